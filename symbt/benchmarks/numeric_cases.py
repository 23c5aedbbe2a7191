"""Error metric and well-conditioned random cases for the tests and benchmarks of :mod:`symbt.numeric`.

(Moved here from ``symbt.numeric.testing``: it is not part of the integrator that ships.)

``state_error`` is the normwise relative error used throughout the tests::

    ||(p - p_ref, q - q_ref)||_2 / ||(p_ref, q_ref - mean(q_ref))||_2

computed in mpmath from the exact binary values of the float64 result.  The
centre of mass of ``q`` is removed from the *denominator* because a common
shift of ``q`` is a symmetry (the error must not look small just because
``|q| ~ 800``); the numerator is not centred, so the unavoidable rounding of
the output ``q~ = fl(q + increment)`` (``<= ulp(|q|)/2`` per entry) is included.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import mpmath
import numpy as np

from ..numeric import NoRealMapError, bt_step, spectral_trace

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["state_error", "gap_intervals", "random_gap_case", "outer_gap_case"]


def state_error(p: Any, q: Any, p_ref: Sequence[Any], q_ref: Sequence[Any]) -> float:
    """Normwise relative error of a float state against an mpmath reference.

    >>> state_error([1.0, 2.0], [0.0, 0.0], [1, 2], [0, 0])
    0.0
    """
    with mpmath.workdps(max(40, mpmath.mp.dps)):
        P = [mpmath.mpf(float(v)) for v in np.ravel(p)]
        Qv = [mpmath.mpf(float(v)) for v in np.ravel(q)]
        num = mpmath.fsum([(a - b) ** 2 for a, b in zip(P + Qv, list(p_ref) + list(q_ref))])
        mq = mpmath.fsum(q_ref) / len(q_ref)
        den = mpmath.fsum([a**2 for a in p_ref]) + mpmath.fsum([(b - mq) ** 2 for b in q_ref])
        return float(mpmath.sqrt(num / den))


def gap_intervals(p: Any, q: Any, ngrid: int = 4001, margin: float = 2.5) -> list[tuple[float, float]]:
    """Intervals of a grid where ``|tr L| > margin`` (candidate spectral gaps).

    >>> [(round(float(a), 1), round(float(b), 1)) for a, b in gap_intervals([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9])]
    [(-10.3, -0.8), (-0.8, 20.1)]
    """
    p = np.asarray(p, float)
    q = np.asarray(q, float)
    dq = np.diff(np.r_[q, q[0]])
    R = np.max(np.abs(p)) + 2 * np.max(np.exp(dq / 2)) + 1
    lam = np.linspace(-R, R, ngrid)
    tr = spectral_trace(lam, np.broadcast_to(p, (ngrid, p.size)), np.broadcast_to(q, (ngrid, p.size)))
    ok = np.abs(tr) > margin
    sgn = np.sign(tr)
    out, i = [], 0
    while i < ngrid:
        if ok[i]:
            j = i
            # a sign change of tr means a (possibly unresolved, narrow) band in between
            while j + 1 < ngrid and ok[j + 1] and sgn[j + 1] == sgn[i]:
                j += 1
            if 0 < i and j < ngrid - 1:
                out.append((lam[i], lam[j]))
            i = j + 1
        else:
            i += 1
    return out


def random_gap_case(rng: np.random.Generator, N: int, pscale: float = 5.0, qscale: float = 1.0,
                    mu: float | None = None, tries: int = 200) -> tuple[npt.NDArray[np.float64],
                                                                           npt.NDArray[np.float64], float, float]:
    """Random ``(p, q, lam0, mu)`` with ``lam0 +- mu`` inside one *inner* gap.

    Points stay 10 % of the gap width away from its (grid) edges; the case is
    accepted only if the real map exists for both branches.  ``mu`` (if given)
    is capped at 0.3 gap widths; its sign is random.

    >>> p, q, lam0, mu = random_gap_case(np.random.default_rng(0), 3)
    >>> p.shape, isinstance(lam0, float)
    ((3,), True)
    """
    for _ in range(tries):
        p = rng.normal(size=N) * pscale
        q = rng.normal(size=N) * qscale
        G = [g for g in gap_intervals(p, q) if g[1] - g[0] > 1e-2 * pscale]
        if not G:
            continue
        lo, hi = G[rng.integers(len(G))]
        w = hi - lo
        if mu is None:
            l1, l2 = np.sort(rng.uniform(lo + 0.1 * w, hi - 0.1 * w, 2))
            lam0, m = 0.5 * (l1 + l2), 0.5 * (l2 - l1)
        else:
            m = min(mu, 0.3 * w)
            lam0 = rng.uniform(lo + 0.1 * w + m, hi - 0.1 * w - m)
        m = m if rng.random() < 0.5 else -m
        try:
            bt_step(p, q, lam0, m)
            bt_step(p, q, lam0, m, branch=-1)
        except NoRealMapError:
            continue
        return p, q, float(lam0), float(m)
    raise RuntimeError("no case found")


def outer_gap_case(rng: np.random.Generator, N: int, pscale: float = 5.0, qscale: float = 1.0,
                   side: int = 1) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], float, float]:
    """Random case with ``lam0 +- mu`` beyond the spectrum (unbounded gap).

    >>> p, q, lam0, mu = outer_gap_case(np.random.default_rng(0), 4)
    >>> abs(lam0) > abs(mu) > 0
    True
    """
    p = rng.normal(size=N) * pscale
    q = rng.normal(size=N) * qscale
    dq = np.diff(np.r_[q, q[0]])
    R = np.max(np.abs(p)) + 2 * np.max(np.exp(dq / 2)) + 1
    a, b = np.sort(rng.uniform(R, 3 * R, 2))
    lam0, m = 0.5 * (a + b), 0.5 * (b - a)
    if rng.random() < 0.5:
        m = -m
    return p, q, side * float(lam0), float(m)
