"""Planting a bug for the killer tests: a function rebuilt from its source with one edit."""
# the rebuilt source is compiled with this module's future flags: its annotations stay unevaluated, as in symbt
from __future__ import annotations

import importlib
import inspect
import textwrap
import types
from pathlib import Path


def planted(func, old: str, new: str):
    """``func`` rebuilt from its source with the one edit ``old -> new`` (a mutant of `symbt mutate --source`'s
    kind), in its module's namespace; the edit must match exactly once.

    A method that calls ``super()`` gets its class back: the rebuilt source is not in a class body, so the
    zero-argument form would find no ``__class__`` cell (every call would raise ``RuntimeError``, and a test
    requiring a claim to fail would pass without the mutant doing anything); it is compiled inside a factory
    whose parameter ``__class__`` is the method's class, with ``super()`` spelled ``super(__class__, self)``."""
    src = textwrap.dedent(inspect.getsource(func))
    assert src.count(old) == 1, (func.__name__, old)
    src = src.replace(old, new)
    ns: dict = {}
    code = func.__code__
    if "__class__" in code.co_freevars:
        cls = func.__closure__[code.co_freevars.index("__class__")].cell_contents
        src = src.replace("super()", f"super(__class__, {code.co_varnames[0]})")
        src = "def _planted_factory(__class__):\n" + textwrap.indent(src, "    ") + f"    return {func.__name__}\n"
        exec(compile(src, inspect.getsourcefile(func), "exec"), func.__globals__, ns)
        return ns["_planted_factory"](cls)
    exec(compile(src, inspect.getsourcefile(func), "exec"), func.__globals__, ns)
    return ns[func.__name__]


def mutated(module: str, before: str, after: str, *, same_classes: bool = False) -> types.ModuleType:
    """A copy of ``module`` with the one mutant of ``symbt mutate --source`` whose line reads ``before`` and,
    mutated, ``after`` (found by its text, not its line number); ``same_classes``: the copy's classes replaced
    by the module's own (so that its values pass the ``isinstance`` checks of other modules -- only when the
    mutant is not inside a class)."""
    from symbt.engine.mutants import find_mutants

    mod = importlib.import_module(module)
    data = Path(mod.__file__).read_bytes()
    hits = [m for m in find_mutants(data, module)
            if m.line_text.strip() == before.strip() and m.mutated_line.strip() == after.strip()]
    assert len(hits) == 1, f"{len(hits)} mutants of {module} match {before!r} -> {after!r}"
    copy = types.ModuleType(module + "_mutant")
    copy.__dict__.update(__name__=module, __package__=mod.__package__, __file__=mod.__file__)
    exec(compile(hits[0].apply(data), mod.__file__, "exec"), copy.__dict__)   # noqa: S102 -- symbt's own source
    if same_classes:
        for name, value in list(copy.__dict__.items()):
            if isinstance(value, type) and value.__module__ == module and isinstance(getattr(mod, name, None), type):
                setattr(copy, name, getattr(mod, name))
    return copy


def claim_fails(cid: str, *, crash: bool = False) -> bool:
    """The claim ``cid`` fails -- by its own comparison, unless ``crash`` (the planted bug raises where the claim
    runs it, which ``symbt mutate`` also counts as a kill)."""
    from symbt.claims import REGISTRY, load_all

    load_all()
    out = REGISTRY[cid].run()
    return out.status == "failed" and (crash or out.method != "exception")
