r"""Shared pieces of the claims about what ships (scene ``shipped``): states per cell, the reference, the bounds.

The *independent* route is the paper's map computed literally (:func:`symbt.reference.literal.reference_step`:
the 2x2 Lax products, eq. ``xy``, the transport of Appendix B, with guard digits chosen from the traces) --
it shares no code with :mod:`symbt.numeric` (which is reformulated on neighbour ratios and projective
slopes) nor with the emitted modules.  For every sample it is computed at ``REF_DPS`` and at ``CHECK_DPS``
digits: a reference that disagrees with itself beyond ``10**-(REF_DPS - 5)`` of the state's size makes the
sample fail (the guard was not enough), never pass.

**Acceptance, two-sided and from the conditioning.**  For an output component :math:`\tilde x_i` and the
inputs :math:`x = (p, q, \lambda_0, \mu)`, the *condition scale* is

.. math:: S_i = |\tilde x_i| + \sum_j \max(|x_j|, 1)\,|\partial\tilde x_i/\partial x_j|,

the change of :math:`\tilde x_i` under relative-or-absolute input perturbations of one unit, by forward
differences of the reference at ``FD_DPS`` digits plus its guard (step :math:`10^{-12}\max(|x_j|,1)`:
truncation and rounding far below the 1 % that a bound needs).  A route accurate to its working precision ``u`` (``eps``
for float64, ``2**-mp.prec`` for mpmath) is within ``C u S_i`` where ``C`` counts the roundings a
component goes through (:func:`step_constant`: ``16 N``, the ``O(N)`` operations of the transport around the
ring, each contributing at most ``u S_i``).  A sample passes iff ``|route - reference| <= C u S_i`` for every
component **and** the reference agrees with itself; a sample whose bound would let through a relative error
above ``INFORMATIVE`` (an ill-conditioned state: the bound could hide a grossly wrong result) is reported,
and makes the claim ``inconclusive``, never ``verified``.

Orbits: an error ``delta_k`` made at step ``k`` reaches step ``n`` through :math:`J_{n\leftarrow k}`; the
map is integrable, its Jacobians grow polynomially and depend (to first order) on the elapsed steps only, so
``|x_n - ref_n|_i <= C u sum_{k<n} max_{m<=n} S^{(m)}_i <= C u n max_m S^{(m)}_i`` with
:math:`S^{(m)}_i = |x_{m,i}| + \sum_j \max(|x_{0,j}|,1)|\partial x_{m,i}/\partial x_{0,j}|` (forward
differences of the reference orbit; ``m`` at 1, n/2 and n).

Cells (:func:`ship_cells`): branch ``b = +-1`` x sign of ``mu`` x sign of ``tr L(lambda_1) = tr L(lambda_2)``
(equal wherever the real map exists; states with opposite signs, where no real map exists, are the claim
``shipped.nomap``).  ``mu < 0`` is the state of ``mu > 0`` with ``mu -> -mu`` (``lambda_1 <-> lambda_2``).

>>> C = step_constant(3); C
48
>>> cells = ship_cells(2, 1)
>>> sorted({tuple(sorted(c.items())) for c, _, _ in cells})[0]
(('branch', -1), ('sign_mu', -1), ('sign_tr', -1))
"""
from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import cache
from typing import Any

import mpmath as mp
import numpy as np

from ..proof.cells import CellTable
from ..reference.literal import literal_step, literal_trace
from ..reference.samples import admissible_states
from ._common import fmt_state
from .base import Outcome, Parts, inconclusive, judge_cells

__all__ = ["EPS", "REF_DPS", "CHECK_DPS", "FD_DPS", "INFORMATIVE", "step_constant", "ship_cells", "wide_states",
           "StepRef", "step_ref", "OrbitRef", "orbit_ref", "ratios", "Tally", "State", "step_outputs",
           "literal_state", "range_error", "guard_digits", "literal_orbit",
           "without_numba", "scale_parts", "scaled"]

EPS = float(np.finfo(np.float64).eps)
REF_DPS, CHECK_DPS, FD_DPS = 50, 75, 30
#: a sample whose bound allows a relative error above this is not informative (ill-conditioned)
INFORMATIVE = 1e-7
State = tuple  # (p, q, lam0, mu): tuples of floats (exact binary numbers, the same for every route)


def step_constant(N: int) -> int:
    """``C`` of the bound ``C u S``: 16 roundings per site of the transport (see the module docstring)."""
    return 16 * N


@cache
def ship_cells(N: int, per_cell: int, seed: int = 11) -> tuple:
    """``(cell, state, branch)``: ``per_cell`` float64 states per cell ``{branch, sign_mu, sign_tr}``."""
    out = []
    for sign in (1, -1):
        with mp.workdps(30):
            states = admissible_states(N, sign, per_cell, seed=seed)
        for p, q, l0, m in states:
            base = (tuple(float(v) for v in p), tuple(float(v) for v in q), float(l0), float(m))
            for smu in (1, -1):
                st = (base[0], base[1], base[2], smu * base[3])
                for b in (1, -1):
                    out.append(({"branch": b, "sign_mu": smu, "sign_tr": sign}, st, b))
    return tuple(out)


@cache
def wide_states(N: int) -> tuple:
    """``(cell, state, branch)`` with q spread over ~1000 (large |q_i - q_j|) where the real map exists:
    for N = 3 the state of issue 21 (branch -1), and seeded states found by rejection (both branches)."""
    out: list[tuple[dict[str, Any], State, int]] = []
    if N == 3:
        st = ((-6.670844734995089, 6.749416383837502, 9.945390979638757),
              (999.5531082492741, 351.51762457052644, 699.0759141727409), -179.0, 155.0)
        out.append(({"branch": -1, "sign_mu": 1, "sign_tr": 1, "q": "wide"}, st, -1))
    rng = np.random.default_rng(4242 + N)
    found, tries = 0, 0
    while found < 2 and tries < 400:
        tries += 1
        q = tuple(float(v) for v in np.round(rng.uniform(0, 1000, N), 6))
        if max(abs(q[(j + 1) % N] - q[j]) for j in range(N)) > 690:   # float64 range: documented NumericRangeError
            continue
        p = tuple(float(v) for v in np.round(rng.uniform(-10, 10, N), 6))
        l0, m = float(np.round(rng.uniform(-200, 200), 3)), float(np.round(rng.uniform(20, 200), 3))
        if _exists((p, q, l0, m), 1) and _exists((p, q, l0, m), -1):
            found += 1
            sign = 1 if _traces((p, q, l0, m))[0] > 0 else -1
            for b in (1, -1):
                out.append(({"branch": b, "sign_mu": 1, "sign_tr": sign, "q": "wide"}, (p, q, l0, m), b))
    return tuple(out)


def _traces(st: State) -> tuple:
    p, q, l0, m = st
    with mp.workdps(40):
        return literal_trace(mp.mpf(l0) + mp.mpf(m), p, q), literal_trace(mp.mpf(l0) - mp.mpf(m), p, q)


def _exists(st: State, b: int) -> bool:
    """The real map exists (decided at REF_DPS with guard digits: traces of one sign beyond 2, every E~_j > 0)."""
    t1, t2 = _traces(st)
    if not (abs(t1) > 2.2 and abs(t2) > 2.2 and t1 * t2 > 0):
        return False
    return all(isinstance(v, mp.mpf) for v in _ref(st, b, REF_DPS))


def guard_digits(st: State) -> int:
    """Guard digits of the literal route (as :func:`~symbt.reference.literal.reference_step` chooses them): the
    forward transport loses about ``2 log10 |tr|`` digits."""
    t1, t2 = _traces(st)
    return 20 + 2 * int(mp.log10(max(abs(t1), abs(t2), mp.mpf(10)))) + 2 * len(st[0])


def _ref(st: State, b: int, dps: int, guard: int | None = None) -> list:
    """The literal map at ``dps`` digits plus ``guard`` (default: :func:`guard_digits`), rounded to ``dps``."""
    p, q, l0, m = st
    g = guard_digits(st) if guard is None else guard
    with mp.workdps(dps + g):
        pt, qt, _ = literal_step([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m), b)
    with mp.workdps(dps):
        return [+v for v in list(pt) + list(qt)]


def _agreement(a: list, c: list) -> float:
    """Relative disagreement of two references (inf when complex: no real map at that precision)."""
    if not all(isinstance(v, mp.mpf) for v in a + c):
        return float("inf")
    scale = max(max(abs(v) for v in c), 1)
    return float(max(abs(x - y) for x, y in zip(a, c)) / scale)


def _inputs(st: State) -> list:
    p, q, l0, m = st
    return list(p) + list(q) + [l0, m]


def _split(x: list, N: int) -> State:
    return (x[:N], x[N:2 * N], x[2 * N], x[2 * N + 1])


@dataclass(frozen=True)
class StepRef:
    """The reference image of one sample: ``x`` (mpf at REF_DPS), ``S`` (condition scales), ``agree``."""

    x: tuple
    S: tuple
    agree: float


@cache
def step_ref(st: State, b: int) -> StepRef:
    """The literal map at REF_DPS and CHECK_DPS, and the condition scales by forward differences."""
    N = len(st[0])
    g = guard_digits(st)
    x = _ref(st, b, REF_DPS, g)
    agree = _agreement(x, _ref(st, b, CHECK_DPS, g + 25))
    S = [abs(v) if isinstance(v, mp.mpf) else mp.inf for v in x]
    if agree < 1e-30:
        with mp.workdps(FD_DPS):
            xin = [mp.mpf(v) for v in _inputs(st)]
            x0 = _ref(st, b, FD_DPS, g)
            for j, v in enumerate(xin):
                w = max(abs(v), 1)
                h = mp.mpf(10) ** -12 * w
                hi = list(xin)
                hi[j] = v + h
                fp = _ref(_split(hi, N), b, FD_DPS, g)
                S = [s + w * abs(a - c) / h for s, a, c in zip(S, fp, x0)]
    return StepRef(tuple(x), tuple(S), agree)


@dataclass(frozen=True)
class OrbitRef:
    """The reference orbit: ``xs[k]`` (mpf, k = 0..n), ``S`` (max over checkpoints m of S^(m)), ``agree``."""

    xs: tuple
    S: tuple
    agree: float


def literal_orbit(st: State, b: int, n: int, dps: int, guard: int) -> list:
    """n literal steps at ``dps + guard`` digits (the spectrum, hence the guard, is the same at every step)."""
    p, q, l0, m = st
    out = [list(p) + list(q)]
    with mp.workdps(dps + guard):
        P, Q, L0, M = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m)
        for _ in range(n):
            P, Q, _ = literal_step(P, Q, L0, M, b)
            out.append(list(P) + list(Q))
    return out


@cache
def orbit_ref(st: State, b: int, n: int) -> OrbitRef:
    """The literal orbit at REF_DPS and CHECK_DPS and the scales ``max_m S^(m)`` (m = 1, n/2, n)."""
    N = len(st[0])
    g = guard_digits(st)
    xs = literal_orbit(st, b, n, REF_DPS, g)
    agree = max(_agreement(a, c) for a, c in zip(xs[1:], literal_orbit(st, b, n, CHECK_DPS, g + 25)[1:]))
    marks = sorted({1, max(n // 2, 1), n})
    S = [max(abs(xs[k][i]) for k in marks) for i in range(2 * N)]
    if agree < 1e-30:
        with mp.workdps(FD_DPS):
            xin = [mp.mpf(v) for v in _inputs(st)]
            acc = [[mp.mpf(0)] * (2 * N) for _ in marks]
            x0 = literal_orbit(st, b, n, FD_DPS, g)
            for j, v in enumerate(xin):
                w = max(abs(v), 1)
                h = mp.mpf(10) ** -12 * w
                hi = list(xin)
                hi[j] = v + h
                fp = literal_orbit(_split(hi, N), b, n, FD_DPS, g)
                for r, k in enumerate(marks):
                    acc[r] = [s + w * abs(a - c) / h for s, a, c in zip(acc[r], fp[k], x0[k])]
            S = [max(S[i], *(abs(xs[k][i]) + acc[r][i] for r, k in enumerate(marks))) for i in range(2 * N)]
    return OrbitRef(tuple(tuple(x) for x in xs), tuple(S), agree)


def ratios(values: Any, ref: tuple, S: tuple, u: float, C: float) -> tuple[float, float]:
    """``(max_i |v_i - ref_i| / (C u S_i), bound / scale)``: <= 1 passes; the second is the relative error the
    bound allows (informative iff <= INFORMATIVE).  Non-finite or complex values give ``inf``."""
    worst = 0.0
    for v, r, s in zip(values, ref, S):
        try:
            vm = mp.mpf(v) if not isinstance(v, mp.mpf) else v
        except (TypeError, ValueError):
            return float("inf"), 0.0
        if not mp.isfinite(vm) or not isinstance(r, mp.mpf):
            return float("inf"), 0.0
        worst = max(worst, float(abs(vm - r) / (C * u * s)))
    scale = max(max(abs(r) for r in ref), 1)
    return worst, float(C * u * max(S) / scale)


class Tally:
    """A :class:`CellTable` over ``route x cell`` with tol 1 (residual = error / bound), the worst ratio per
    route, the count of uninformative samples and of references that disagree with themselves."""

    def __init__(self) -> None:
        self.table = CellTable(tol=1.0)
        self.per_route: dict[str, float] = {}
        self.loose = 0
        self.disagree = 0
        self.notes: list[str] = []
        self.declined: dict[str, int] = {}

    def decline(self, route: str, cell: dict, st: State, b: int) -> None:
        """The route said, with its documented ``NumericRangeError``, that the state is beyond float64 range: no
        wrong result (counted and reported; accepted only at the wide states, see :func:`wide_states`)."""
        self.declined[route] = self.declined.get(route, 0) + 1
        self.add(route, cell, st, b, 0.0)

    def add(self, route: str, cell: dict, st: State, b: int, ratio: float, allowed: float = 0.0,
            agree: float = 0.0, agree_tol: float = 10.0 ** (5 - REF_DPS)) -> None:
        if agree > agree_tol:
            self.disagree += 1
            ratio = float("inf")
        if allowed > INFORMATIVE:
            self.loose += 1
        self.per_route[route] = max(self.per_route.get(route, 0.0), ratio)
        self.table.add(dict(route=route, **cell), printed=ratio,
                       point=fmt_state(tuple(mp.mpf(v) if not isinstance(v, tuple) else [mp.mpf(x) for x in v]
                                             for v in st), b))

    def outcome(self, *, method: str, printed: str, detail: str = "") -> Outcome:
        routes = "; ".join(f"{r}: {v:.3g}" for r, v in self.per_route.items())
        text = (f"worst error/bound per route: {routes}. " + " ".join(self.notes) + " " + detail).strip()
        if self.declined:
            text += " Declined with NumericRangeError (a documented range limit) at wide states: " + \
                ", ".join(f"{r} {k}x" for r, k in self.declined.items()) + "."
        if self.disagree:
            text += f" {self.disagree} samples whose reference disagrees with itself at two precisions."
        out = judge_cells(self.table, printed=printed, method=method, dps=REF_DPS, detail=text)
        if out.status == "verified" and self.loose:
            return inconclusive(method, residual=out.residual, evidence="sampled", printed=printed, cells=out.cells,
                                detail=f"{self.loose} samples ill-conditioned: the bound allows a relative error "
                                       f"above {INFORMATIVE:g}. " + text)
        return out


@contextmanager
def without_numba() -> Iterator[None]:
    """Run the numba-free kernels (bit-identical to the compiled ones: ``tests/test_numeric_fast.py``) inside, so a
    claim that calls an entry point whose existence check uses ``backend="auto"`` does not load or compile numba
    (seconds on a cold cache) in the default ``symbt verify``."""
    old = os.environ.get("SYMBT_NO_NUMBA")
    os.environ["SYMBT_NO_NUMBA"] = "1"
    try:
        yield
    finally:
        if old is None:
            del os.environ["SYMBT_NO_NUMBA"]
        else:
            os.environ["SYMBT_NO_NUMBA"] = old


def scale_parts(N: int | None = None) -> Parts:
    """The statement parts of a claim about what ships: ``route output x scale = reference``, ``scale = 1``
    (``symbt mutate`` negates it and perturbs it by 1e-6: the claim must fail on both)."""
    return Parts(printed={"scale": 1.0})


def scaled(values: Any, s: float) -> list:
    """``values`` (numbers, arrays or mpf) times ``s``; mpf at their own precision, not rounded to 53 bits."""
    out = list(values)
    if s == 1.0:
        return out
    with mp.workdps(CHECK_DPS + 30):
        return [v * mp.mpf(s) if isinstance(v, mp.mpf) else v * s for v in out]


def range_error(exc: BaseException) -> bool:
    """A documented range error: :class:`symbt.numeric.NumericRangeError` or an emitted module's own."""
    return type(exc).__name__ == "NumericRangeError"


def step_outputs(x: Any) -> list:
    """Flatten ``(p~, q~)`` (arrays or lists) into one list of components."""
    p, q = x[0], x[1]
    return [v for v in p] + [v for v in q]


def literal_state(st: State, b: int, dps: int = REF_DPS) -> tuple:
    """``literal_step`` at ``dps`` (the raw route, no guard: for the existence decision)."""
    p, q, l0, m = st
    with mp.workdps(dps):
        return literal_step([mp.mpf(v) for v in p], [mp.mpf(v) for v in q], mp.mpf(l0), mp.mpf(m), b)
