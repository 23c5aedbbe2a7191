r"""Samples of the explicit map shared by the map and Theorem 1 claims (cached per process).

:func:`images` runs the paper's route (:func:`symbt.reference.literal.literal_step`) on every
sample of :func:`symbt.claims._common.map_cells` at ``DPS`` digits.  :func:`theorem1_data`
adds what Theorem 1 needs at the image :math:`(\tilde p,\tilde q)`, all by central
differences of step ``H`` at ``DPS`` digits (error about ``H**2``, far below the claims'
tolerance ``10**-25``):

* :math:`\partial_\mu(\tilde p,\tilde q)` of the map at fixed :math:`(p, q, \lambda_0)`;
* the :math:`\eta_k` of the inverse map (branch -b) at :math:`(\tilde p,\tilde q)` and at the
  :math:`4N` points :math:`\tilde p_j\pm H`, :math:`\tilde q_j\pm H` (so any function of the
  :math:`\eta_k`, e.g. :math:`\hat\Phi = \sum_k\ln\frac{\eta_k+\mu}{\eta_k-\mu}`, has its
  gradient without re-running the map);
* :math:`\operatorname{tr}L(\lambda_0\pm\mu)` and their gradients (closed form,
  :func:`symbt.reference.trace.trace_gradient`).
"""
from __future__ import annotations

from functools import cache
from typing import Any

import mpmath as mp

from ..reference.literal import literal_step
from ..reference.trace import trace_gradient
from ._common import DPS, eta_from_states, literal_image, map_cells

__all__ = ["images", "theorem1_data", "inverse_etas", "H", "fd_gradient"]

H = mp.mpf(10) ** -20  # finite-difference step (at DPS = 60 digits)


@cache
def images(N: int, count: int) -> tuple:
    """``(cell, state, branch, p~, q~, info)`` for every sample of ``map_cells(N, count)``."""
    out = []
    with mp.workdps(DPS):
        for cell, state, b in map_cells(N, count):
            pt, qt, info = literal_image(state, b)
            out.append((cell, state, b, pt, qt, info))
    return tuple(out)


def _etas(P: list, Q: list, l0: Any, mu: Any, b: int) -> list:
    p, q, _ = literal_step(P, Q, l0, mu, -b)
    return eta_from_states(p, q, P, Q, l0)


@cache
def theorem1_data(N: int, count: int) -> tuple:
    """Per sample a dict: cell, state, b, P, Q, dP, dQ (d/dmu), tr1, tr2, grad1, grad2 (``(d tr/dp~, d tr/dq~)``
    at lam0 + mu, lam0 - mu)."""
    out = []
    with mp.workdps(DPS):
        for cell, state, b, P, Q, info in images(N, count):
            p, q, l0, mu = state
            plus = literal_step(p, q, l0, mu + H, b)
            minus = literal_step(p, q, l0, mu - H, b)
            dP = [(a - c) / (2 * H) for a, c in zip(plus[0], minus[0])]
            dQ = [(a - c) / (2 * H) for a, c in zip(plus[1], minus[1])]
            out.append(dict(cell=cell, state=state, b=b, P=P, Q=Q, dP=dP, dQ=dQ,
                            tr1=mp.re(info["tr1"]), tr2=mp.re(info["tr2"]),
                            grad1=trace_gradient(l0 + mu, P, Q), grad2=trace_gradient(l0 - mu, P, Q)))
    return tuple(out)


@cache
def inverse_etas(N: int, count: int) -> tuple:
    """Per sample of :func:`theorem1_data`: ``(eta, eta_pm)`` -- the eta_k of the inverse map at the image and
    ``eta_pm[i] = (eta at coordinate i + H, eta at coordinate i - H)`` (coordinates p~ then q~)."""
    out = []
    with mp.workdps(DPS):
        for d in theorem1_data(N, count):
            P, Q, (_, _, l0, mu), b = d["P"], d["Q"], d["state"], d["b"]
            eta_pm = []
            for i in range(2 * N):
                pair = []
                for s in (1, -1):
                    Pv, Qv = list(P), list(Q)
                    if i < N:
                        Pv[i] += s * H
                    else:
                        Qv[i - N] += s * H
                    pair.append(_etas(Pv, Qv, l0, mu, b))
                eta_pm.append(tuple(pair))
            out.append((_etas(P, Q, l0, mu, b), tuple(eta_pm)))
    return tuple(out)


def fd_gradient(f: Any, t1: Any, t2: Any, b: int) -> tuple:
    """``(df/dtr1, df/dtr2)`` of ``f(tr1, tr2, b)`` by central differences (complex values kept)."""
    d1 = (f(t1 + H, t2, b) - f(t1 - H, t2, b)) / (2 * H)
    d2 = (f(t1, t2 + H, b) - f(t1, t2 - H, b)) / (2 * H)
    return d1, d2
