r"""The Bäcklund step and orbit in quad-double arithmetic (:mod:`symbt.numeric.multiprec.qd_arith`).

The step is the fused scalar step of :mod:`symbt.numeric.core.fused` (the one
the float64 kernels run), instantiated here with the quad-double operations of
:mod:`~symbt.numeric.multiprec.qd_arith` and the quad-double hooks: decisions
taken on the leading component (the sign of a renormalised quad-double),
finiteness as the range test, no condition estimate (the precision rule of
:mod:`symbt.numeric.multiprec.qd` covers it), and the positions carried as
themselves (``q_j <- q_j + log1p(xr_j)``, the ratios ``r_j = exp(q_{j+1} - q_j)``
recomputed at every step).  :func:`qd_orbit` runs ``n`` steps in one call and
writes the stored states (steps ``0, every, ...`` and ``n``) into its output
arrays.  A state is an ``(N, 4)`` float64 array (row ``j``: the components of
site ``j``).

Status codes (those of :mod:`symbt.numeric.core.limits`; the first failure wins): ``0`` ok, ``1``/``2``
``|tr L(lam1/lam2)| <= 2``, ``3`` some ``1 + x_j <= 0`` or traces of opposite signs, ``4`` range: a
neighbour distance ``|q_{j+1} - q_j| > MAX_DQ_QD = 300`` (the squared trace must stay inside the
range of the quad-double product, :mod:`symbt.numeric.core.limits`) or a
non-finite value (an overflow, a division by an exact zero).  The caller
(:mod:`symbt.numeric.multiprec.qd`) turns them into the typed errors of
:mod:`symbt.numeric.core.errors`, or for ``4`` falls back to the Arb path.

Example (plain Python, slow; numba compiles the same functions):

>>> import numpy as np
>>> from symbt.numeric.multiprec.qd_step import qd_orbit
>>> P, Q = np.zeros((3, 4)), np.zeros((3, 4))
>>> P[:, 0], Q[:, 0] = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]
>>> Q[2, :2] = 0.9, -2.2204460492503132e-17           # 0.9 to 106 bits
>>> spec = np.array([[10.0, 0, 0, 0], [5.0, 0, 0, 0]])
>>> outP, outQ = np.empty((2, 3, 4)), np.empty((2, 3, 4))
>>> qd_orbit(P, Q, spec, 1, 1, 1, outP, outQ)
(0, 1)
>>> round(float(outP[1, 0, 0]), 8)
-19.99656766
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import limits
from ..core.compile import instantiate
from ..core.fused import SOURCE
from ..core.limits import MAX_DQ_QD, OK, RANGE
from . import qd_arith
from .qd_arith import add, div, exp, log1p, mul_pwr2, renorm4, sub

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]

__all__ = ["qd_orbit", "python_kernels", "HOOKS", "OPERATIONS"]

QD = tuple[float, float, float, float]
# the limits are frozen into the compiled step: their file belongs to its cache key (core/compile.py)
_EXTRA = (Path(limits.__file__),)


def _row(a: F64, j: int) -> QD:
    return a[j, 0], a[j, 1], a[j, 2], a[j, 3]


def _put(a: F64, j: int, x: QD) -> None:
    a[j, 0] = x[0]
    a[j, 1] = x[1]
    a[j, 2] = x[2]
    a[j, 3] = x[3]


def _finite(x: QD) -> bool:
    return math.isfinite(x[0]) and math.isfinite(x[3])


# the hooks of the fused step (core/fused.py) in quad-double: what float64 tracks (condition, rescaling)
# the precision rule of qd.py replaces; the range test is finiteness
def _hi(x: QD) -> float:
    return x[0]


def _track_init(lam: QD, p0: QD, a0: QD, r0: QD) -> float:
    return 0.0


def _track(aux: float, lam: QD, pj: QD, a: QD, rj: QD) -> float:
    return aux


def _rescale(A: QD, B: QD, C: QD, D: QD, aux: float) -> tuple[QD, QD, QD, QD, float]:
    return A, B, C, D, aux


def _in_range(A: QD, B: QD, C: QD, D: QD, t: QD) -> bool:
    return _finite(A) and _finite(B) and _finite(C) and _finite(D) and _finite(t)


def _two_of(aux: float) -> float:
    return 2.0


def _decided(aux: float, t: QD, disc: QD, tt: F64, i: int, p: F64, r: F64, lam: QD, lo: float) -> bool:
    return True


def _disc_fits(disc: QD) -> bool:
    return True


def _step_kappa(tt: F64) -> float:
    return 0.0


def _sharpen(tt: F64, p: F64, r: F64, lam1: QD, lo1: float, lam2: QD, lo2: float) -> float:
    return 0.0


def _trusted(kt: float, u: QD, w: QD, dn: QD, x: QD) -> bool:
    return True


def _lam_add(lam: QD, lo: float, pj: QD) -> QD:
    # lam1 = lam0 + mu and lam2 = lam0 - mu are quad-double sums of the given numbers: consistent with
    # two_mu already (the float64 low parts of core/spectral_sum.py are not needed)
    return add(lam, pj)


def _lam_split(lam1: QD, lam2: QD, two_mu: QD) -> tuple[float, float]:
    return 0.0, 0.0


def _root_slope(A: QD, D: QD, dl: QD, g: QD, B: QD, C: QD, two: float, plus: bool, wantk: bool) -> QD:
    # k = dl +- g has no cancellation; the wanted root is k / (2B) or -2C / k (float64 rounds it once instead)
    k = add(dl, g) if plus else sub(dl, g)
    return div(k, mul_pwr2(B, 2.0)) if wantk else div(mul_pwr2(C, -2.0), k)


def _advance(r: F64, Q: F64, j: int, x: QD, xn: QD, pj: QD) -> bool:
    """``q_j <- q_j + log1p(xr_j)``; False if it or ``p_j`` is not finite."""
    q = add(_row(Q, j), log1p(x))
    _put(Q, j, q)
    return _finite(pj) and _finite(q)


#: the hooks of the quad-double arithmetic (compiled with ``inline="always"`` by :mod:`.qd`)
HOOKS: dict[str, Callable[..., Any]] = {
    "hi": _hi, "track_init": _track_init, "track": _track, "rescale": _rescale, "rescale_last": _rescale,
         "in_range": _in_range, "two_of": _two_of, "decided": _decided, "disc_fits": _disc_fits,
         "step_kappa": _step_kappa, "sharpen": _sharpen, "bounded": _finite, "trusted": _trusted, "advance": _advance,
         "ld": _row, "st": _put, "lam_add": _lam_add, "lam_split": _lam_split, "root_slope": _root_slope}
#: the operations: names of :mod:`.qd_arith` (``add_d`` adds a double, ``mul2`` is ``mul_pwr2``)
OPERATIONS = {"add": "add", "sub": "sub", "mul": "mul", "div": "div", "neg": "neg", "sqrt": "sqrt",
              "add_d": "add_d", "mul2": "mul_pwr2"}


@cache
def python_kernels() -> dict[str, Callable[..., Any]]:
    """The fused step (:mod:`symbt.numeric.core.fused`) in quad-double, plain Python (slow; the doctests
    and the tests of the limits run it).

    >>> sorted(python_kernels())
    ['slopes', 'step']
    """
    ops = {name: getattr(qd_arith, fn) for name, fn in OPERATIONS.items()}
    return instantiate(SOURCE, {**ops, **HOOKS}, tag="qd", jit=False, extra=_EXTRA)


def qd_orbit(P0: F64, Q0: F64, spec: F64, branch: int, n: int, every: int, outP: F64, outQ: F64
             ) -> tuple[int, int]:
    """``n`` steps from ``(P0, Q0)`` (``(N, 4)``, any non-overlapping components: renormalised here);
    ``spec`` rows ``lam0, mu``.  Writes the stored states into ``outP, outQ`` (``(rows, N, 4)``) and
    returns ``(status, step)`` (``(0, n)``, or the failing step)."""
    N = P0.shape[0]
    P, Q = np.empty((N, 4)), np.empty((N, 4))
    r, u, w, xr, gq = np.empty((N, 4)), np.empty((N, 4)), np.empty((N, 4)), np.empty((N, 4)), np.empty((N, 4))
    tt = np.zeros(4)
    for j in range(N):
        _put(P, j, renorm4(P0[j, 0], P0[j, 1], P0[j, 2], P0[j, 3]))
        _put(Q, j, renorm4(Q0[j, 0], Q0[j, 1], Q0[j, 2], Q0[j, 3]))
    lam0 = renorm4(spec[0, 0], spec[0, 1], spec[0, 2], spec[0, 3])
    mu = renorm4(spec[1, 0], spec[1, 1], spec[1, 2], spec[1, 3])
    lam1, lam2, two_mu = add(lam0, mu), sub(lam0, mu), mul_pwr2(mu, 2.0)
    outP[0] = P
    outQ[0] = Q
    row = 1
    for i in range(1, n + 1):
        for j in range(N):
            dq = sub(_row(Q, (j + 1) % N), _row(Q, j))
            if not abs(dq[0]) <= MAX_DQ_QD:
                return RANGE, i
            _put(r, j, exp(dq))
        st = step(P, r, Q, lam1, lam2, two_mu, branch, u, w, xr, gq, tt)
        if st != OK:
            return st, i
        if i % every == 0 or i == n:
            outP[row] = P
            outQ[row] = Q
            row += 1
    return OK, n


# the plain-Python step :func:`qd_orbit` calls (qd.py compiles ``qd_orbit`` with the numba instance)
step = python_kernels()["step"]
