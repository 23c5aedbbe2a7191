"""Planting a bug for the killer tests: a function rebuilt from its source with one edit."""
# the rebuilt source is compiled with this module's future flags: its annotations stay unevaluated, as in symbt
from __future__ import annotations

import inspect
import textwrap


def planted(func, old: str, new: str):
    """``func`` rebuilt from its source with the one edit ``old -> new`` (a mutant of `symbt mutate --source`'s
    kind), in its module's namespace; the edit must match exactly once."""
    src = textwrap.dedent(inspect.getsource(func))
    assert src.count(old) == 1, (func.__name__, old)
    ns: dict = {}
    exec(compile(src.replace(old, new), inspect.getsourcefile(func), "exec"), func.__globals__, ns)
    return ns[func.__name__]
