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
    kind), in its module's namespace; the edit must match exactly once."""
    src = textwrap.dedent(inspect.getsource(func))
    assert src.count(old) == 1, (func.__name__, old)
    ns: dict = {}
    exec(compile(src.replace(old, new), inspect.getsourcefile(func), "exec"), func.__globals__, ns)
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
