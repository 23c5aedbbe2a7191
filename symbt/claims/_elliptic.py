r"""Shared pieces of the N = 2 claim modules (eqs. ``th1th2``, ``AA2``, ``citn``, ``linBts``, ``addform``).

Domain cells
------------
A state (p, q) with a step (lambda0, mu) falls in a cell ``{regime, branch, sign_q1_q2}``: the regime of
:math:`(\lambda_-, \lambda_+)` (:data:`symbt.reference.elliptic.REGIMES`), the branch ``b = +-1`` of the
map and the sign of :math:`q_1 - q_2` (the printed angle is the global one for :math:`q_1 > q_2` only):
20 cells, :func:`~symbt.claims._common.per_cell` seeded states in each (every state is used with both
branches).  Statements on the phase space alone (no step) use the quadrant of :math:`(P, C)`:
``{sign_q1_q2, sign_p2_p1}``.

Evaluation
----------
States are exact decimal strings; the map (:func:`symbt.reference.elliptic.step2`), the actions, the
Abel images and the angles are computed once per state at :data:`DPS` digits and cached for every
claim in the process.  Statement parts (SymPy) are evaluated by :func:`mp_fn` with mpmath's principal
branches (``ellipf`` with a Carlson fast path that returns the same value where ``|phi| < pi/2``, the
Abel map ``A``), compared as complex numbers (the rule of :mod:`symbt.claims._common`).  Integrals of
eq. ``AA2`` are computed by :func:`quad` (float64 Gauss-Legendre after a cosine substitution on each
piece between the zeros of tr L -+ 2, where the integrands have 1/sqrt singularities) and judged with
the matching tolerance :data:`QTOL`.

>>> cells = {tuple(s.cell.values()) for s in map_samples(1)}
>>> len(cells), sorted(cells)[0]
(20, ('gap', -1, -1))
>>> f = lambda x, a: 1 / np.sqrt(1 - x ** 2 + 0j)      # int_{-1}^{1} dx/sqrt(1-x^2) = pi
>>> bool(abs(quad_many(f, [(-1.0, 1.0, [0.0], (0.0,))])[0] - np.pi) < 1e-11)
True
"""
from __future__ import annotations

import random
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import cache
from typing import Any

import mpmath as mp
import numpy as np
import sympy as sp

from ..proof.cells import CellTable, cell_text
from ..proof.lambdify import plain_lambdify
from ..reference import elliptic as E
from ._common import judge_cells
from .base import Outcome, scene

__all__ = ["DPS", "TOL", "QTOL", "MapSample", "map_samples", "phase_samples", "state", "image", "mp_fn",
           "np_fn", "quad_many", "breaks", "ScopedTable", "outcome", "point", "pq_point", "finite"]

scene("elliptic", "N=2 action-angle variables, their update by the map, linearization and the elliptic "
                  "addition formula, by regime of lambda_+-, branch and sign of q1 - q2")

DPS = 30
TOL = 1e-20
#: tolerance of the float64 quadratures of eq. AA2 (their error is below 1e-11 on every sampled cell)
QTOL = 1e-9

# symbols of the statement parts
p1, p2, q1, q2 = sp.symbols("p1 p2 q1 q2", real=True)
I1, I2 = sp.symbols("I1 I2", real=True)
lam, lam0 = sp.symbols("lambda lambda0", real=True)
mu = sp.Symbol("mu", positive=True)
lam1, lam2 = sp.symbols("lambda1 lambda2", real=True)
branch = sp.Symbol("branch", real=True)
tr1, tr2 = sp.symbols("tr1 tr2", real=True)
A = sp.Function("A")  # the Abel image A(lambda, branch, I1, I2) of the curve point used by the map


def F_sym(z: Any, I2_: Any = I2) -> Any:
    """The paper's F(z, k), k^2 = (I2-2)/(I2+2), read as the incomplete integral (mpmath parameter k^2)."""
    return sp.elliptic_f(sp.asin(z), (I2_ - 2) / (I2_ + 2))


# --------------------------------------------------------------------------- samples

@dataclass(frozen=True)
class MapSample:
    """One sample of a map claim: its cell, the state (decimal strings) and the branch."""

    cell: dict = field(hash=False, compare=False)
    key: tuple
    b: int


def _key(case: tuple) -> tuple:
    p, q, l0, m = case
    return (tuple(p), tuple(q), l0, m)


@cache
def map_samples(per: int, seed: int = 0) -> tuple[MapSample, ...]:
    """``per`` states in each (regime, sign of q1-q2), each with both branches: 20 cells."""
    out = []
    for reg in E.REGIMES:
        for xs in (1, -1):
            rng = random.Random(f"elliptic/{reg}/{xs}/{seed}")
            cases = [E.sample_case(reg, rng, x_sign=xs) for _ in range(per)]
            for b in (1, -1):
                out += [MapSample({"regime": reg, "branch": b, "sign_q1_q2": xs}, _key(c), b) for c in cases]
    return tuple(out)


@cache
def phase_samples(per: int, seed: int = 0) -> tuple[tuple[dict, tuple], ...]:
    """``per`` real states (p, q) in each quadrant {sign_q1_q2, sign_p2_p1} of (P, C)."""
    out = []
    for xs in (1, -1):
        for ps in (1, -1):
            rng = random.Random(f"phase/{xs}/{ps}/{seed}")
            for _ in range(per):
                p, q = E.sample_state(rng, x_sign=xs, p_sign=ps)
                out.append(({"sign_q1_q2": xs, "sign_p2_p1": ps}, (tuple(p), tuple(q))))
    return tuple(out)


# --------------------------------------------------------------------------- per-state data (cached)

@dataclass
class State:
    p: list
    q: list
    E: list
    lam0: Any
    mu: Any
    I1: Any
    I2: Any
    m: Any
    P: Any
    w: Any
    u: Any


@cache
def _state(key: tuple, dps: int) -> State:
    with mp.workdps(dps):
        p, q = [mp.mpf(v) for v in key[0]], [mp.mpf(v) for v in key[1]]
        a1, a2 = E.actions(p, q)
        _, m = E.modulus(a2)
        Ev = [mp.exp(v) for v in q]
        P, w = E.curve_point((p[1] - p[0]) / (2 * mp.sqrt(a2 - 2)), Ev[0], Ev[1], a2)
        return State(p, q, Ev, mp.mpf(key[2]), mp.mpf(key[3]), a1, a2, m, P, w, E.abel(P, w, m))


def state(s: MapSample | tuple, dps: int = DPS) -> State:
    return _state(s.key if isinstance(s, MapSample) else s, dps)


@dataclass
class Image:
    pt: list
    qt: list
    Et: list
    tr: tuple
    Pt: Any
    wt: Any
    ut: Any
    on_curve: Any
    gammas: tuple


def next_state(p: list, q: list, st: State, b: int, gammas: tuple | None = None) -> Image:
    """The image of (p, q) (same level set as ``st``) and its Abel image u~ (branch-free); ``gammas``
    as in :func:`~symbt.reference.elliptic.step2` (iterates keep the curve points of the first step)."""
    pt, qt, info = E.step2(p, q, st.lam0, st.mu, b, gammas=gammas)
    Et = info["E_new"]
    Pt, wt = E.curve_point((pt[1] - pt[0]) / (2 * mp.sqrt(st.I2 - 2)), Et[0], Et[1], st.I2)
    on = abs(wt ** 2 - (1 - Pt ** 2) * (1 - st.m * Pt ** 2)) / max(1, abs(wt) ** 2)
    return Image(pt, qt, Et, (info["tr1"], info["tr2"]), Pt, wt, E.abel(Pt, wt, st.m), on,
                 (info["gamma1"], info["gamma2"]))


@cache
def _image(key: tuple, b: int, dps: int) -> Image:
    st = _state(key, dps)
    with mp.workdps(dps):
        return next_state(st.p, st.q, st, b)


def image(s: MapSample, dps: int = DPS) -> Image:
    return _image(s.key, s.b, dps)


# --------------------------------------------------------------------------- evaluating parts

def _F_principal(z: Any, m: Any) -> Any:
    """mpmath's ellipf(asin z, m), the printed F.  Off the real cuts |z| > 1, asin z has |Re| < pi/2 and
    mpmath computes z R_F(1 - z^2, 1 - m z^2, 1), which :func:`~symbt.reference.elliptic._F_m` evaluates
    (memoised, shared with the Abel map; tested equal).  On the cuts mpmath itself is called."""
    if isinstance(m, mp.mpf) and 0 <= m < 1 and (isinstance(z, mp.mpc) or (isinstance(z, mp.mpf) and abs(z) < 1)):
        return E._F_m(z, m)
    return _ellipf_cut(z, m, mp.mp.prec)


@cache
def _ellipf_cut(z: Any, m: Any, prec: int) -> Any:
    return mp.ellipf(mp.asin(z), m)


def _abel(lv: Any, b: Any, a1: Any, a2: Any) -> Any:
    return _abel_at(lv, b, a1, a2, mp.mp.prec)


@cache
def _abel_at(lv: Any, b: Any, a1: Any, a2: Any, prec: int) -> Any:
    s, w, _, _ = E.spectral_point(lv, a1, a2, b)
    return E.abel(s, w, (a2 - 2) / (a2 + 2))


Fp = sp.Function("Fp")  # elliptic_f(asin(z), m) is evaluated by _F_principal
MP_NAMESPACE = {"Fp": _F_principal, "A": _abel}


def _nested(f: Callable[[Any], Any], e: Any) -> Any:
    """``f`` applied to every SymPy leaf of ``e`` (a nested list or tuple, returned as lists)."""
    return [_nested(f, x) for x in e] if isinstance(e, (list, tuple)) else f(sp.sympify(e))


def _principal_F(e: Any) -> Any:
    return e.replace(lambda x: isinstance(x, sp.elliptic_f) and isinstance(x.args[0], sp.asin),
                     lambda x: Fp(x.args[0].args[0], x.args[1]))


def mp_fn(args: list, expr: Any):
    """``expr`` (SymPy, or a nested list) as an mpmath function of ``args`` (principal branches; A = Abel image)."""
    return plain_lambdify(args, _nested(_principal_F, expr), [MP_NAMESPACE, "mpmath"])


def _cplx(x: Any) -> np.ndarray:
    x = np.asarray(x)
    if not np.iscomplexobj(x):
        return x.astype(complex)
    return np.where(x.imag == 0, x.real + 0j, x)  # on a cut: the upper side, as mpmath for real input


NP_NAMESPACE = {"sqrt": lambda x: np.sqrt(_cplx(x)), "acosh": lambda x: np.arccosh(_cplx(x)),
                "log": lambda x: np.log(_cplx(x)), "DiracDelta": lambda *a: 0.0}


def np_fn(args: list, expr: Any):
    """``expr`` as a vectorised numpy function with mpmath's principal branches on real input."""
    return plain_lambdify(args, _nested(lambda x: x, expr), [NP_NAMESPACE, "numpy"])


_XG, _WG = np.polynomial.legendre.leggauss(96)
_TH = (_XG + 1) * np.pi / 2
_WTH = _WG * np.pi / 2 * np.sin(_TH) / 2
_S2 = np.sin(_TH / 2) ** 2  # (1 - cos t)/2 without cancellation


def breaks(a1: float, a2: float) -> list[float]:
    """The lambda where tr L = (lambda + I1)^2 - I2 is -2, 0 or 2 (singular points of the AA2 integrands)."""
    return [-a1 + s * np.sqrt(a2 + c) for s in (1, -1) for c in (2.0, 0.0, -2.0) if a2 + c > 0]


def quad_many(f, jobs: list[tuple[float, float, list[float], tuple]]) -> np.ndarray:
    """``[int_a^b f(lambda, *params) dlambda for (a, b, pts, params) in jobs]`` (oriented), one vectorised call.

    Each [a, b] is cut at the ``pts`` inside it; every piece gets Gauss-Legendre nodes after
    lambda = c + (d-c)(1-cos t)/2, which makes 1/sqrt singularities at the ends smooth.
    """
    xs, ws, seg, par = [], [], [], []
    for i, (a, b, pts, params) in enumerate(jobs):
        sgn = 1.0
        if a > b:
            a, b, sgn = b, a, -1.0
        cuts = [a] + sorted(x for x in pts if a < x < b) + [b]
        for c, d in zip(cuts[:-1], cuts[1:]):
            xs.append(c + (d - c) * _S2)
            ws.append(sgn * (d - c) * _WTH)
            seg.append(np.full(_TH.shape, i))
            par.append(np.tile(np.asarray(params, dtype=float), (_TH.size, 1)))
    X, W, S, Pm = np.concatenate(xs), np.concatenate(ws), np.concatenate(seg), np.concatenate(par)
    with np.errstate(all="ignore"):
        v = np.broadcast_to(np.asarray(f(X, *Pm.T), dtype=complex), X.shape)
    n = len(jobs)
    return np.bincount(S, weights=W * v.real, minlength=n) + 1j * np.bincount(S, weights=W * v.imag, minlength=n)


def finite(x: Any) -> Any:
    """|x| if finite, else +inf (a residual that is nan or infinite does not hold)."""
    try:
        r = abs(x)
        return r if mp.isfinite(r) else mp.inf
    except (TypeError, ValueError):
        return mp.inf


# --------------------------------------------------------------------------- tables and outcomes

@dataclass
class ScopedTable(CellTable):
    """A :class:`CellTable` with explicit *not applicable* cells (the statement's premise is false there,
    computed at every sample); they are listed in ``cells`` and in the generated scope."""

    na: dict = field(default_factory=dict)

    def add_na(self, cell: dict, reason: str) -> None:
        key = tuple(cell.items())
        row = self.na.setdefault(key, {"cell": dict(cell), "n": 0, "applies": False, "reason": reason})
        row["n"] += 1

    def cells(self) -> list[dict]:
        return super().cells() + [dict(r) for r in self.na.values()]

    def scope(self) -> str:
        txt = super().scope()
        reasons: dict[str, list] = {}
        for r in self.na.values():
            reasons.setdefault(r["reason"], []).append(r)
        for why, rows in reasons.items():
            n = sum(r["n"] for r in rows)
            txt += (f"; does not apply in {len(rows)} cells ({why}, at {n}/{n} samples): "
                    + ", ".join(cell_text(r["cell"]) for r in rows))
        return txt


def outcome(table: CellTable, *, dps: int = DPS, **kw: Any) -> Outcome:
    """:func:`~symbt.claims._common.judge_cells` (digits capped at ``dps``), for N = 2."""
    out = judge_cells(table, dps=dps, **kw)
    out = replace(out, n_scope=[2])
    return out


def pq_point(p: list, q: list, **extra: Any) -> dict:
    """A phase-space sample (p, q) for a counterexample."""
    d: dict[str, Any] = {"p": [mp.nstr(v, 15) for v in p], "q": [mp.nstr(v, 15) for v in q]}
    d.update({k_: mp.nstr(v, 12) for k_, v in extra.items()})
    return d


def point(s: MapSample, **extra: Any) -> dict:
    """The sample (its exact decimal inputs, branch and cell) with ``extra`` values, for a counterexample."""
    p, q, l0, m = s.key
    d: dict[str, Any] = {"p": list(p), "q": list(q), "lambda0": l0, "mu": m, "branch": s.b}
    d.update({k_: (v if isinstance(v, (int, str)) else mp.nstr(v, 12)) for k_, v in extra.items()})
    return d
