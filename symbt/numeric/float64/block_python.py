r"""The block kernel (:mod:`.kernels_block`) in plain Python on lists of Python floats.

What ``backend="python"`` runs for an ensemble (:func:`symbt.numeric.float64.jit.kernel`): the source of
:mod:`.kernels_block` -- the one numba compiles -- rewritten in its syntax tree so that it runs on nested
lists of Python floats (a numpy scalar's arithmetic takes ~3x a float's, BENCHMARKS.md "The plain-Python
kernel"): ``x[j, k]`` is read and written as ``x[j][k]``, a column ``x[:, k]`` is taken as a list, the
arrays are allocated as lists, and every division divides as IEEE arithmetic
(:func:`~symbt.numeric.core.inline.ieee_div0`: ``x / 0`` is ``+-inf`` or NaN, as in numba, where a Python
float raises).  The same operations on the same doubles, so the same bits and statuses as the numba
kernel (``tests/test_numeric_block_python.py``).

Example
-------
>>> import numpy as np
>>> from symbt.numeric.float64.kernels import ANCHOR
>>> M = 3
>>> P, Q, st = np.empty((2, M, 3)), np.empty((2, M, 3)), np.zeros(M, np.int64)
>>> ensemble(np.tile([-20.0, 10, 1], (M, 1)), np.tile([1.0, 0, 0.9], (M, 1)), np.full(M, 15.0),
...          np.full(M, 5.0), np.full(M, 10.0), 1, 1, 1, ANCHOR, 2, P, Q, st)
>>> st.tolist(), np.round(P[1, 0], 8).tolist()
([0, 0, 0], [-19.99656766, 9.78635495, 1.21021272])
"""

from __future__ import annotations

import ast
import inspect
import textwrap
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.condition import SHARP_ON_FLOATS, _Sites
from ..core.inline import _IeeeDivision, ieee_div0
from ..core.spectral_sum import lam_add, lam_split, root_slope
from . import kernels_block as KB

if TYPE_CHECKING:
    from .kernels import F64, I64

__all__ = ["ensemble", "run_block", "kernel"]


class _Arr(list[Any]):
    """A (nested) list of Python floats with the ``shape`` the kernel reads."""

    __slots__ = ("shape",)

    def __init__(self, items: Any = ()) -> None:
        super().__init__(items)
        inner = self[0].shape if self and isinstance(self[0], _Arr) else ()
        self.shape: tuple[int, ...] = (len(self),) + inner


def _arr(x: Any) -> Any:
    """``np.ndarray.tolist()``'s nested lists as :class:`_Arr` (floats and ints stay as they are)."""
    return _Arr(_arr(y) for y in x) if isinstance(x, list) else x


class _Lists:
    """The array constructors of :mod:`.kernels_block` (``np.empty((N, B))`` ...) on lists."""

    int64 = int

    @staticmethod
    def full(shape: int | tuple[int, ...], value: float) -> _Arr:
        dims = shape if isinstance(shape, tuple) else (shape,)
        if len(dims) == 1:
            return _Arr([value] * dims[0])
        return _Arr(_Lists.full(dims[1:], value) for _ in range(dims[0]))

    @staticmethod
    def empty(shape: int | tuple[int, ...], dtype: type = float) -> _Arr:
        return _Lists.full(shape, 0 if dtype in (int, np.int64) else 0.0)

    zeros = empty

    @staticmethod
    def ones(shape: int | tuple[int, ...]) -> _Arr:
        return _Lists.full(shape, 1.0)


def _column(x: list[list[float]], k: int) -> _Sites:
    return _Sites([row[k] for row in x])


class _Subscripts(ast.NodeTransformer):
    """``x[a, b]`` -> ``x[a][b]``; ``x[:, k]`` -> ``_column(x, k)``."""

    def visit_Subscript(self, n: ast.Subscript) -> ast.AST:
        self.generic_visit(n)
        idx = n.slice
        if not isinstance(idx, ast.Tuple):
            return n
        first = idx.elts[0]
        if isinstance(first, ast.Slice) and first.lower is None and first.upper is None and len(idx.elts) == 2:
            return ast.copy_location(ast.Call(ast.Name("_column", ast.Load()), [n.value, idx.elts[1]], []), n)
        if any(isinstance(e, ast.Slice) for e in idx.elts):
            raise ValueError("block_python: a slice the rewrite does not know: %s" % ast.unparse(n))
        out: ast.expr = n.value
        for e in idx.elts[:-1]:
            out = ast.Subscript(out, e, ast.Load())
        return ast.copy_location(ast.Subscript(out, idx.elts[-1], n.ctx), n)


def _rewritten(fn: Callable[..., Any], env: dict[str, Any], subscripts: bool = True) -> Callable[..., Any]:
    tree = ast.parse(textwrap.dedent(inspect.getsource(fn)))
    ast.increment_lineno(tree, fn.__code__.co_firstlineno - 1)      # tracebacks name the source's lines
    if subscripts:
        tree = _Subscripts().visit(tree)
    tree = ast.fix_missing_locations(_IeeeDivision().visit(tree))
    g = {**fn.__globals__, **env, "_inline_ieee_div0": ieee_div0, "_column": _column}
    ns: dict[str, Any] = {}
    exec(compile(tree, inspect.getsourcefile(fn) or "<block_python>", "exec"), g, ns)
    out: Callable[..., Any] = ns[fn.__name__]
    return out


def _build() -> dict[str, Callable[..., Any]]:
    env: dict[str, Any] = {"np": _Lists, "lam_add": lam_add, "lam_split": lam_split,
                           "root_slope": _rewritten(root_slope, {}, subscripts=False),
                           "sharp_trace_kappa": SHARP_ON_FLOATS, "prange": range}
    for name in ("_shrink", "_slopes", "_anchor", "run_block", "ensemble"):
        env[name] = _rewritten(getattr(KB, name), env)
    return env


def _snapshot() -> tuple[tuple[str, int], ...]:
    return tuple((k, id(v)) for k, v in vars(KB).items())


_KERNELS = _build()
_BUILT_FOR = _snapshot()


def kernel(name: str) -> Callable[..., Any]:
    """The plain-Python block kernel ``name`` (``"run_block"`` or ``"ensemble"``): this module's form on
    floats -- or, where a global of :mod:`.kernels_block` was replaced since it was built (a planted bug of
    the tests), :mod:`.kernels_block`'s own function on numpy scalars, which reads the replacement.

    >>> kernel("ensemble") is ensemble
    True
    """
    out: Callable[..., Any] = globals()[name] if _snapshot() == _BUILT_FOR else getattr(KB, name)
    return out


def _on_lists(name: str, P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, *rest: Any) -> None:
    """The kernel ``name`` on the arrays converted to lists once; ``outP, outQ, status`` written back."""
    *head, outP, outQ, status = rest[:-2] if name == "run_block" else rest
    tail = rest[-2:] if name == "run_block" else ()
    oP, oQ, st = _arr(outP.tolist()), _arr(outQ.tolist()), status.tolist()
    _KERNELS[name](_arr(np.asarray(P0, float).tolist()), _arr(np.asarray(Q0, float).tolist()),
                   *(_Arr(np.asarray(x, float).tolist()) for x in (lam1, lam2, two_mu)), *head, oP, oQ, st, *tail)
    outP[...] = oP
    outQ[...] = oQ
    status[...] = st


def run_block(P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, branch: int, n: int, every: int,
              anchor: int, outP: F64, outQ: F64, status: I64, i0: int, i1: int) -> None:
    """:func:`.kernels_block.run_block` on lists of Python floats (arguments and results as there).

    >>> from symbt.numeric.float64.kernels import ANCHOR
    >>> st = np.zeros(1, np.int64)
    >>> run_block(np.zeros((1, 2)), np.zeros((1, 2)), np.ones(1), -np.ones(1), 2 * np.ones(1), 1, 1, 1, ANCHOR,
    ...           np.empty((2, 1, 2)), np.empty((2, 1, 2)), st, 0, 1)
    >>> int(st[0])                      # tr L(1) = 1 - 2 = -1: lam1 = 1 lies in a band
    1
    """
    _on_lists("run_block", P0, Q0, lam1, lam2, two_mu, branch, n, every, anchor, outP, outQ, status, i0, i1)


def ensemble(P0: F64, Q0: F64, lam1: F64, lam2: F64, two_mu: F64, branch: int, n: int, every: int,
             anchor: int, block: int, outP: F64, outQ: F64, status: I64) -> None:
    """:func:`.kernels_block.ensemble` on lists of Python floats (arguments and results as there).

    >>> from symbt.numeric.float64.kernels import ANCHOR
    >>> P, Q, st = np.empty((2, 2, 2)), np.empty((2, 2, 2)), np.zeros(2, np.int64)
    >>> ensemble(np.zeros((2, 2)), np.zeros((2, 2)), np.array([3.0, 1.0]), np.array([2.5, -1.0]),
    ...          np.array([0.5, 2.0]), 1, 1, 1, ANCHOR, 8, P, Q, st)
    >>> st.tolist()                     # the second: lam1 = 1 lies in a band (tr L(1) = -1)
    [0, 1]
    """
    _on_lists("ensemble", P0, Q0, lam1, lam2, two_mu, branch, n, every, anchor, block, outP, outQ, status)
