r"""What the samples of seeds 23 and 24 found unread (issue 21).

* ``checker.relation_degree`` -- :func:`symbt.proof.reduce_modulo` refuses (``ValueError``) a relation that is not a
  polynomial of degree 1 or more in its own symbol (``{x: y - 1}``, ``{x: 2}``): the remainder of a division by
  something constant in ``x`` is 0, so such a relation would "prove" any statement, ``x y = 0`` included; a
  relation of degree 2 reduces ``x^3 + y`` to ``x y + y`` (written out by hand).  Seed 23: a degree test at ``< 0``
  let the constant relation through.
* ``checker.inclusive_bounds`` -- the tolerances are inclusive, as their docstrings say: a sampled
  :class:`~symbt.proof.verdict.Verdict` whose residual and estimated error both *equal* the tolerance holds; a
  :class:`~symbt.proof.cells.CellTable` sample at the tolerance counts as holding, and a cell whose residuals are all
  exactly 0 still names a sample as its worst point (seed 23: the last two as strict comparisons).
* ``library.source_lines`` -- the rewritten kernels keep their source's place, so tracebacks (and the line map
  ``symbt mutate --source`` traces) name the source's lines: the plain-Python block kernels of
  :mod:`symbt.numeric.float64.block_python` and a function rewritten by
  :func:`symbt.numeric.core.inline.inlined` start at their source function's first line in its file.  And the
  inliner spreads a body's tuple read by constant index, ``t[0]`` included, into one local per element: the inlined
  code subscripts nothing and gives the plain call's value (seed 23: index 0 left the tuple built).
"""
from __future__ import annotations

import dis
import inspect
from typing import Any

import sympy as sp

from .base import Outcome, claim, failed


@claim("checker.relation_degree", equation="checker", scene="checker",
       where="symbt.proof.exact.reduce_modulo: the relations' degree in their own symbols",
       statement="reduce_modulo(x y, {x: y - 1}) and reduce_modulo(x y, {x: 2}) raise ValueError (a division by "
                 "something constant in x leaves remainder 0: it would prove x y = 0); reduce_modulo(x^3 + y, "
                 "{x: x^2 - y}) = x y + y")
def relation_degree() -> Outcome:
    from ..proof import reduce_modulo

    x, y = sp.symbols("x y")
    got: dict[str, Any] = {}
    for name, rel in (("y - 1", y - 1), ("2", sp.Integer(2))):
        try:
            got[name] = f"reduced to {reduce_modulo(x * y, {x: rel})}"
        except ValueError:
            got[name] = "ValueError"
    got["x^2 - y"] = sp.expand(reduce_modulo(x ** 3 + y, {x: x ** 2 - y}) - (x * y + y)) == 0
    want: dict[str, Any] = {"y - 1": "ValueError", "2": "ValueError", "x^2 - y": True}
    if got != want:
        return failed("exact: relations written out by hand", detail=f"got {got}, want {want}")
    return Outcome("verified", "exact: relations written out by hand", evidence="proof", n_scope="all",
                   detail=f"{got}")


@claim("checker.inclusive_bounds", equation="checker", scene="checker",
       where="symbt.proof.verdict.Verdict.sampled, symbt.proof.cells.CellTable.add: the tolerance's edge",
       statement="Verdict.sampled(1e-20, tol=1e-20, error=1e-20) holds; a CellTable sample with residual equal "
                 "to the tolerance holds; a cell whose residuals are all exactly 0 names a sample as its worst")
def inclusive_bounds() -> Outcome:
    from ..proof.cells import CellTable
    from ..proof.verdict import Verdict

    tol = 1e-20
    got: dict[str, Any] = {"verdict at tol": Verdict.sampled(tol, tol=tol, error=tol).holds}
    table = CellTable(tol=tol)
    table.add({"s": 1}, printed=tol, point={"x": "1"})
    got["cell at tol"] = (table.rows[(("s", 1),)].printed_holds, table.printed_holds_everywhere())
    zeros = CellTable(tol=tol)
    for k in range(3):
        zeros.add({"s": -1}, printed=0, point={"x": str(k)})
    worst, point = zeros.worst()
    got["all-zero cell's worst"] = (worst, (point or {}).get("x") in ("0", "1", "2"))
    want: dict[str, Any] = {"verdict at tol": True, "cell at tol": (1, True), "all-zero cell's worst": (0.0, True)}
    if got != want:
        return failed("exact: values at the tolerance written by hand", detail=f"got {got}, want {want}")
    return Outcome("verified", "exact: values at the tolerance written by hand", evidence="proof", n_scope="all",
                   detail=f"{got}")


def _pair(a: float, b: float) -> tuple[float, float]:
    return a + b, a - b


def _reads_pair(a: float, b: float) -> float:
    t = _pair(a, b)
    return t[0] * t[1]


def _subscripts(fn: Any) -> int:
    return sum(i.opname == "BINARY_SUBSCR" for i in dis.get_instructions(fn))


@claim("library.source_lines", equation="checker", scene="library",
       where="symbt.numeric.float64.block_python.kernel, symbt.numeric.core.inline.inlined",
       statement="every plain-Python block kernel and an inlined function start at their source function's first "
                 "line in its file (tracebacks name the source); a body's tuple read as t[0], t[1] is spread: the "
                 "inlined code subscripts nothing and gives (a + b)(a - b)")
def source_lines() -> Outcome:
    from ..numeric.core.inline import inlined
    from ..numeric.float64 import block_python
    from ..numeric.float64 import kernels_block as KB

    bad = []
    # the functions rewritten from source (the others are the module's own, bound as they are)
    names = [n for n, f in block_python._KERNELS.items() if inspect.isfunction(f) and f is not getattr(KB, n, f)]
    for name in names:
        made, src = block_python._KERNELS[name].__code__, getattr(KB, name).__code__
        if (made.co_firstlineno, made.co_filename) != (src.co_firstlineno, src.co_filename):
            bad.append(f"block kernel {name}: line {made.co_firstlineno} of {made.co_filename}, source at "
                       f"{src.co_firstlineno} of {src.co_filename}")
    g = inlined(_reads_pair, "reads_pair_inline", {"_pair": "body"}, {"_pair": _pair})
    src = _reads_pair.__code__
    if (g.__code__.co_firstlineno, g.__code__.co_filename) != (src.co_firstlineno, src.co_filename):
        bad.append(f"inlined: line {g.__code__.co_firstlineno}, source at {src.co_firstlineno}")
    if _subscripts(_reads_pair) == 0 or _subscripts(g) != 0:
        bad.append(f"subscripts: {_subscripts(_reads_pair)} in the source, {_subscripts(g)} inlined (want 0)")
    if g(3.0, 1.0) != 8.0:
        bad.append(f"inlined value {g(3.0, 1.0)!r} at (3, 1), want 8.0")
    if bad:
        return failed(f"{len(bad)} of {len(names) + 3} facts", detail="; ".join(bad))
    return Outcome("verified", f"{len(names)} block kernels and an inlined function at their source's lines; "
                   "the tuple spread", evidence="proof", n_scope="all")
