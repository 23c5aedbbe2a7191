r"""Private helpers of the claims on Sections 1-2 specialised to the Toda BT (:mod:`.section1`,
:mod:`.intertwining`): images of the composed map by cell, near-identity images, the single BT as
an explicit map, and scalar 2x2 matrices (faster than ``mpmath.matrix`` for the many small products).

* :func:`map_images` -- per sample of :func:`~symbt.claims._common.map_cells`: cell, state, branch and
  the literal image (Section 3 word for word, :func:`symbt.reference.literal.literal_step`), at
  :data:`~symbt.claims._common.DPS` digits; cached per ``(N, count)``.
* :func:`tiny_images` -- the same states moved to :math:`\lambda_0' = \lambda_0+\mu` (where
  :math:`|\operatorname{tr}L| > 2.2` with the cell's sign) with :math:`\mu' = 10^{-30}`, at 90 digits.
* :func:`single_bt` -- the single-parameter BT :math:`\zeta` of eqs. ``dj``, ``alphabeta``, ``ptp``
  as an explicit map: :math:`\beta_1 = e^{-\tilde q_N}` is a root of
  :math:`\beta^2 B(\zeta) - \beta(A(\zeta)-D(\zeta)) - C(\zeta) = 0` (eq. ``v1``),
  :math:`\beta_1 = (A-D+r\sqrt{\operatorname{tr}^2-4})/(2B)` with the root sign ``r = +-1``; then site by
  site :math:`e^{\tilde q_j} = e^{q_j}(-p_j-\zeta-e^{q_j}\beta_j)`, :math:`\beta_{j+1} = e^{-\tilde q_j}`
  (second line of eq. ``ptp``) and :math:`\tilde p_j = -(e^{\tilde q_j-q_j}+e^{q_{j+1}-\tilde q_j}+\zeta)`
  (first line).  The real map exists for both roots when :math:`\zeta` lies below every :math:`-p_j`
  far enough (sampled by :func:`single_cells`).

>>> import mpmath as mp
>>> with mp.workdps(30):
...     pt, qt, beta1 = single_bt([mp.mpf(1), mp.mpf(-0.5)], [mp.mpf(0.2), mp.mpf(-0.1)], mp.mpf(-4), 1)
...     L, Lt = lax(mp.mpf("0.7"), [1, -0.5], [0.2, -0.1]), lax(mp.mpf("0.7"), pt, qt)
...     abs(L[0] + L[3] - (Lt[0] + Lt[3])) < 1e-25           # tr L is invariant
True
"""
from __future__ import annotations

import random
from functools import cache
from typing import Any

import mpmath as mp

from ..reference.literal import literal_step
from ._common import DPS, map_cells

__all__ = ["mat_mul", "mat_sub", "mat_norm", "local_lax", "lax", "map_images", "tiny_images", "single_bt",
           "single_cells", "TINY_DPS", "TINY_MU"]

Mat = tuple[Any, Any, Any, Any]  # (a, b, c, d) = [[a, b], [c, d]]

TINY_DPS = 90
TINY_MU = "1e-30"


def mat_mul(X: Mat, Y: Mat) -> Mat:
    return (X[0] * Y[0] + X[1] * Y[2], X[0] * Y[1] + X[1] * Y[3], X[2] * Y[0] + X[3] * Y[2], X[2] * Y[1] + X[3] * Y[3])


def mat_sub(X: Mat, Y: Mat) -> Mat:
    return (X[0] - Y[0], X[1] - Y[1], X[2] - Y[2], X[3] - Y[3])


def mat_norm(X: Mat) -> Any:
    return max(abs(v) for v in X)


def local_lax(lam: Any, p: Any, q: Any) -> Mat:
    """:math:`l_j(\\lambda) = [[\\lambda+p_j, -e^{q_j}], [e^{-q_j}, 0]]` (eq. ``eq:lax``)."""
    E = mp.exp(q)
    return (lam + p, -E, 1 / E, mp.mpf(0))


def lax(lam: Any, p: list, q: list) -> Mat:
    """:math:`L(\\lambda) = l_N\\cdots l_1` (eq. ``eq:lax``) as a 4-tuple."""
    M: Mat = (mp.mpf(1), mp.mpf(0), mp.mpf(0), mp.mpf(1))
    for pj, qj in zip(p, q):
        M = mat_mul(local_lax(lam, mp.mpmathify(pj), mp.mpmathify(qj)), M)
    return M


@cache
def map_images(N: int, count: int) -> tuple:
    """``(cell, state, branch, p~, q~, info)`` for every sample of ``map_cells(N, count)`` at DPS digits."""
    out = []
    with mp.workdps(DPS):
        for cell, state, b in map_cells(N, count):
            p, q, l0, m = state
            pt, qt, info = literal_step(p, q, l0, m, b)
            out.append((cell, state, b, pt, qt, info))
    return tuple(out)


@cache
def tiny_images(N: int, count: int) -> tuple:
    """``(cell, state', branch, p~, q~)`` with state' = (p, q, lambda0 + mu, 1e-30), at TINY_DPS digits."""
    out = []
    with mp.workdps(TINY_DPS):
        for cell, (p, q, l0, m), b in map_cells(N, count):
            state = ([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0) + mp.mpf(m), mp.mpf(TINY_MU))
            pt, qt, _ = literal_step(state[0], state[1], state[2], state[3], b)
            out.append((cell, state, b, pt, qt))
    return tuple(out)


def single_bt(p: list, q: list, zeta: Any, root: int) -> tuple[list, list, Any] | None:
    """The single BT (parameter ``zeta``, root sign ``root``): ``(p~, q~, beta_1)``, or None if not real."""
    N = len(p)
    A, B, C, D = lax(zeta, p, q)
    disc = (A + D) ** 2 - 4
    if disc <= 0:
        return None
    beta = [((A - D) + root * mp.sqrt(disc)) / (2 * B)]
    E = [mp.exp(v) for v in q]
    Et = []
    for j in range(N):
        Et.append(E[j] * (-p[j] - zeta - E[j] * beta[j]))
        if Et[-1] <= 0:
            return None
        beta.append(1 / Et[-1])
    qt = [mp.log(v) for v in Et]
    pt = [-(Et[j] / E[j] + E[(j + 1) % N] / Et[j] + zeta) for j in range(N)]
    return pt, qt, beta[0]


@cache
def single_cells(N: int, count: int, seed: int = 0) -> tuple:
    """``(cell, (p, q, zeta), root, p~, q~)``: ``count`` states per root sign, each real for both roots.

    p_j ~ U(-3, 3), q_j ~ U(-1.5, 1.5), zeta = -max p - U(0.3, 4) (6 decimals, seeded); at DPS digits.
    """
    rng = random.Random(7000 + 10 * N + seed)
    out: list = []
    with mp.workdps(DPS):
        states: list = []
        while len(states) < count:
            ps = [f"{rng.uniform(-3, 3):.6f}" for _ in range(N)]
            qs = [f"{rng.uniform(-1.5, 1.5):.6f}" for _ in range(N)]
            zs = f"{-max(float(v) for v in ps) - rng.uniform(0.3, 4):.6f}"
            p, q, z = [mp.mpf(v) for v in ps], [mp.mpf(v) for v in qs], mp.mpf(zs)
            images = [single_bt(p, q, z, r) for r in (1, -1)]
            if all(images):
                states.append(((p, q, z), images))
        for r_index, r in enumerate((1, -1)):
            for (p, q, z), images in states:
                pt, qt, _ = images[r_index]
                out.append(({"root": r}, (p, q, z), r, pt, qt))
    return tuple(out)
