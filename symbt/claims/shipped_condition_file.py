r"""What ships, 4m: the whole of :mod:`symbt.numeric.core.condition` against independent routes, cell by cell
(scene ``numeric-paths``; issue 21 item 4, docs/mutation.md "Fresh samples of symbt/numeric/core/condition.py").

The earlier claims on this module each observed one state or one branch (``paths.sharp_kappa``, now part of
``paths.kappa_cells``: no cancellation, ``lam`` of one sign per state family; ``paths.renorm_top``: one backward
renormalisation; ``paths.kappa_rows`` and ``paths.side_by_side``: the numpy forms against the scalar ones, bit for
bit).  A fresh mutation sample showed that a slip in any other branch went unseen.  These claims observe each
function over the cells of its branches, against a route that shares no code with it.

* ``paths.kappa_cells.n{2,3,5,6}`` -- :func:`~symbt.numeric.core.condition.sharp_trace_kappa` against its docstring's
  definition with exact 2x2 products at 60 digits (checked at 80; the one reference of
  :func:`~symbt.claims.shipped_condition.kappa_by_definition`), on a grid of states:
  ``lam`` of both signs with a nonzero low part ``lo``, at moderate values (bands, gaps, outside), at ``+-1e40``
  (prefix and suffix products past ``2**200``), at steep ``q`` (``r_j = e**+-300``: renormalised up and down) and at
  tiny ``lam, p`` with ``q`` falling (products below ``2**-200``), and with ``a_j`` cancelling to ``2**-20`` of
  ``|lam| + |p_j|`` at the first and at the last site (the cancellation factor's maximum at either end); and the
  states of :func:`~symbt.claims.shipped_condition.kappa_cases` (the paper's state and its mirror, N = 3; chains
  at ``lam = +-1e25``, N = 6).
  Accepted: ``|k_t / k_ref - 1| <= 16 u N (1 + k_ref)`` -- ``16 u N`` the docstring's allowance for the routine's
  own rounding, ``16 u N k_ref`` the first-order error of the computed trace (``|delta t| <= 3 N u T_s``)
  carried through ``(|t| + 2) / |t**2 - 4|``, whose log-derivative is at most ``3 / ||t| - 2|``.  And the
  documented ``inf``: at ``t = +-2`` exactly (``p = 0``, ``r = 1``, ``lam = +-2``: ``t = 2 T_N(+-1)``) and where
  some ``a_j = 0`` exactly (``lam = -p_j``, at the first and at the last site); ``inf`` or NaN ("not trusted"),
  never an exception, where the products leave the double range (``p_j = +-1.5 * 2**780``).
* ``paths.kappa_cells_rows.n{2,3,5}`` -- :func:`~symbt.numeric.core.condition.sharp_trace_kappa_rows` on the same
  states stacked, in both of its forms (the first ``FEW_ROWS`` rows: the scalar source on Python floats; all rows:
  numpy operations over the rows), every row against the same reference and bound (and ``inf`` where documented);
  and bit for bit the scalar call (its docstring; a consistency check, the reference above is the independent one).
* ``paths.abs_products.n{2,3}`` -- :func:`~symbt.numeric.core.condition.abs_trace_rows` and
  :func:`~symbt.numeric.core.condition.monodromy_and_abs` in each of their regimes (1, 7 and 16 rows: Python floats --
  one batch whose every large entry is negative;
  17, 20 and 40 rows: the two products side by side, with no row, some rows and every row renormalised; 2049 rows
  at N = 2: the separate calls; sites of different shapes), rows at moderate scale, past ``2**500``, past the double
  range (the unscaled product overflows), below ``2**-500``, with the largest entry negative (``a_1 = -1e300``),
  and at N = 3 a row whose product of absolute values is past ``2**500`` while the monodromy itself is
  ``[[0, 1], [-1, 0]]`` (only the second product renormalised) and one whose largest entry after the second site is
  a negative ``C`` with the others ``2**-1023`` below it; at N = 2, 3 a row whose largest entry after the last site
  is a negative ``D`` (about ``-2**600``, every other entry far smaller: renormalised by the wrong one, the entries
  and the exponent come out other bits, seed 21).  Against the exact
  rational products of the double inputs: ``2**e (A, B; C, D)`` within ``3 N u |m_N| ... |m_1|`` entrywise plus
  ``2**-500`` of its largest entry (underflow in the scaled arithmetic, whose largest entry is at least
  ``2**-500``), the trace of the absolute product within a relative ``3 N u`` plus the same; and
  ``monodromy_and_abs`` bit for bit ``monodromy(FLOAT)`` and ``abs_trace_rows`` (its docstring; consistency).

Shown to fail on planted bugs in ``tests/test_killers_condition.py``.
"""
from __future__ import annotations

import math
from fractions import Fraction
from functools import cache

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed
from .shipped_condition import kappa_by_definition, kappa_cases

U = 2.0 ** -53
#: the digits of the reference and of its check
REF_DPS, CHECK_DPS = 60, 80

Case = tuple[tuple[float, ...], tuple[float, ...], float, float]      # (p, r, lam, lo)


def _ratios(q: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(math.exp(q[(j + 1) % len(q)] - q[j]) for j in range(len(q)))


@cache
def kappa_grid(N: int) -> tuple[tuple[Case, ...], tuple[Case, ...], tuple[Case, ...]]:
    """``(finite, infinite, untrusted)``: the states ``(p, r, lam, lo)`` of ``paths.kappa_cells`` -- those whose
    ``k_t`` is compared with the reference, those where the docstring says ``inf`` (``t = +-2``, some ``a_j = 0``),
    and those where a product leaves the double range (``inf`` or NaN, "not trusted").

    >>> fin, inf, untrusted = kappa_grid(3)
    >>> len(fin) > 16, len(inf), len(untrusted)
    (True, 6, 4)
    """
    rng = np.random.default_rng(20261127 + N)
    fin: list[Case] = []

    def add(p: np.ndarray, q: tuple[float, ...], lam: float) -> None:
        lo = lam * 2.0 ** -60 * (1 if len(fin) % 2 else -1)
        fin.append((tuple(float(x) for x in p), _ratios(q), float(lam), float(lo)))

    for sign in (1.0, -1.0):
        for mag in (0.7, 2.5, 6.0, 40.0):                           # bands, gaps, outside
            add(rng.uniform(-3, 3, N), tuple(rng.uniform(-1, 1, N)), sign * mag)
        add(rng.uniform(-3, 3, N), tuple(rng.uniform(-1, 1, N)), sign * 1e40)   # products past 2**200
        steep = tuple(300.0 * (j % 2) - 40.0 * j for j in range(N))           # r = e**+-300: up and down
        add(rng.uniform(-3, 3, N), steep, sign * 3.5)
        fall = min(150.0, 700.0 / (N - 1))                          # the wrap-around ratio e**(fall (N-1)) a double
        add(rng.uniform(-1, 1, N) * 1e-70, tuple(-fall * j for j in range(N)), sign * 1e-70)  # below 2**-200
        for site in (0, N - 1):                                     # a_j cancels to 2**-20 of |lam| + |p_j|
            p = rng.uniform(1, 3, N) * np.where(rng.uniform(size=N) < 0.5, -1.0, 1.0)
            add(p, tuple(rng.uniform(-1, 1, N)), -float(p[site]) * (1 + 2.0 ** -20))
    fin += [(p, r, lam, 0.0) for p, r, lam in kappa_cases(N)]      # the paper's state (N = 3), the chains (N = 6)
    inf: list[Case] = []
    for lam in (2.0, -2.0):                                         # t = 2 T_N(+-1) = +-2 exactly
        inf.append(((0.0,) * N, (1.0,) * N, lam, 0.0))
    for site in (0, N - 1):                                         # a_j = 0 exactly
        for sign in (1.0, -1.0):
            pz = tuple(sign * (1.5 + j) for j in range(N))
            inf.append((pz, _ratios(tuple(0.3 * j for j in range(N))), -pz[site], 0.0))
    untrusted: list[Case] = []
    for sign in (1.0, -1.0):                                        # a_j a_{j+1} past 2**1024: the products overflow
        for lam in (1.0, -3.0):
            pf = tuple(sign * (-1) ** j * 1.5 * 2.0 ** 780 for j in range(N))
            untrusted.append((pf, _ratios(tuple(0.3 * j for j in range(N))), lam, 0.0))
    return tuple(fin), tuple(inf), tuple(untrusted)


@cache
def kappa_references(N: int) -> tuple[tuple[float, ...], int]:
    """The reference ``k_t`` (as a double) of every finite state of :func:`kappa_grid`, and how many states'
    references disagree with themselves at ``CHECK_DPS`` digits (those are ``nan``)."""
    out, unsure = [], 0
    for p, r, lam, lo in kappa_grid(N)[0]:
        ref, check = kappa_by_definition(p, r, lam, REF_DPS, lo), kappa_by_definition(p, r, lam, CHECK_DPS, lo)
        if abs(ref - check) <= abs(check) * mp.mpf(10) ** (5 - REF_DPS):
            out.append(float(ref))
        else:
            unsure += 1
            out.append(math.nan)
    return tuple(out), unsure


def judge_kappas(N: int, got: list[float], label: str) -> list[str]:
    """What is wrong with ``got`` (the values at every state of :func:`kappa_grid`, in order): a finite state's
    deviation from :func:`kappa_references` beyond ``16 u N (1 + k_ref)``, a documented-``inf`` state not ``inf``,
    an untrusted state neither ``inf`` nor NaN."""
    refs, unsure = kappa_references(N)
    bad = [f"{unsure} references disagree with themselves at {CHECK_DPS} digits"] if unsure else []
    fin, inf, untrusted = kappa_grid(N)
    for (p, _r, lam, _lo), k, ref in zip(fin, got, refs):
        dev = abs(k / ref - 1) if math.isfinite(k) else math.inf
        if not dev <= 16 * U * N * (1 + ref):
            bad.append(f"{label} at lam = {lam:.6g}, p0 = {p[0]:.4g}: k_t = {k:.8g}, by the definition {ref:.8g}")
    for (p, _r, lam, _lo), k in zip(inf, got[len(fin):]):
        if k != math.inf:
            bad.append(f"{label} at lam = {lam:g}, p = {p} (t = +-2 or some a_j = 0): {k!r}, documented inf")
    for (p, _r, lam, _lo), k in zip(untrusted, got[len(fin) + len(inf):]):
        if math.isfinite(k):
            bad.append(f"{label} at lam = {lam:g}, p0 = {p[0]:.4g} (products past the double range): {k!r}, "
                       "documented inf or NaN")
    return bad


def _worst(N: int, got: list[float]) -> float:
    refs = kappa_references(N)[0]
    return max(abs(k / ref - 1) / (16 * U * N * (1 + ref)) for k, ref in zip(got, refs))


def _scalar_kappas(cases: tuple[Case, ...]) -> tuple[list[float], str]:
    """``sharp_trace_kappa`` at every state, and the first exception's text ('' if none: the docstring promises
    a value, ``inf`` or NaN where not trusted)."""
    from ..numeric.core import condition

    out, err = [], ""
    with np.errstate(all="ignore"):
        for p, r, lam, lo in cases:
            try:
                out.append(condition.sharp_trace_kappa(np.array(p), np.array(r), lam, lo))
            except (ArithmeticError, ValueError) as exc:
                err = err or f"lam = {lam:g}, p0 = {p[0]:.4g}: {type(exc).__name__}: {exc}"
                out.append(math.nan)
    return out, err


@claim("paths.kappa_cells", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       sizes=(2, 3, 5, 6), where="symbt/numeric/core/condition.py: sharp_trace_kappa (every branch)",
       statement="sharp_trace_kappa (N={N}) = its documented k_t with exact 2x2 products at 60 digits (checked at "
                 "80) within 16 u N (1 + k_t) on a grid: lam of both signs with a low part, in bands, gaps and "
                 "outside, at +-1e40, at steep q (r = e**+-300), at tiny lam and falling q, a_j cancelling at the "
                 "first and the last site; the paper's state and its mirror at 7 spectral parameters (N = 3), chains "
                 "at lam = +-1e25, 3e24 through the renormalised path (N = 6); inf at t = +-2 and at a_j = 0 (first "
                 "and last site); inf or NaN, no exception, where the products leave the double range")
def kappa_cells(N: int) -> Outcome:
    fin, inf, untrusted = kappa_grid(N)
    got, err = _scalar_kappas(fin + inf + untrusted)
    bad = judge_kappas(N, got, "scalar") + ([f"raised at {err}"] if err else [])
    detail = (f"{len(fin)} states against the definition (worst {_worst(N, got):.3g} x the bound), "
              f"{len(inf)} documented inf, {len(untrusted)} past the range.")
    if bad:
        return failed("numeric: sharp_trace_kappa vs its definition (exact products, 60 digits), every cell",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: sharp_trace_kappa vs its definition (exact products, 60 digits), every cell",
                   evidence="sampled", detail=detail, printed="k_t = its definition within 16 u N (1 + k_t)")


@claim("paths.kappa_cells_rows", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       sizes=(2, 3, 5), where="symbt/numeric/core/condition.py: sharp_trace_kappa_rows (both forms)",
       statement="sharp_trace_kappa_rows (N={N}) on paths.kappa_cells' states stacked -- the first FEW_ROWS rows "
                 "(Python floats) and all rows (numpy over the rows) -- = the documented k_t with exact products "
                 "within 16 u N (1 + k_t), inf (or NaN) where documented, and bit for bit the scalar "
                 "sharp_trace_kappa")
def kappa_cells_rows(N: int) -> Outcome:
    from ..numeric.core.condition import FEW_ROWS, sharp_trace_kappa_rows

    fin, inf, untrusted = kappa_grid(N)
    cases = fin + inf + untrusted
    P, R = np.array([c[0] for c in cases]), np.array([c[1] for c in cases])
    L, O = np.array([c[2] for c in cases]), np.array([c[3] for c in cases])
    scalar, err = _scalar_kappas(cases)
    bad = [f"the scalar raised at {err}"] if err else []
    with np.errstate(all="ignore"):
        forms = {"numpy rows": sharp_trace_kappa_rows(P, R, L, O)}
        few = [sharp_trace_kappa_rows(P[k:k + FEW_ROWS], R[k:k + FEW_ROWS], L[k:k + FEW_ROWS], O[k:k + FEW_ROWS])
               for k in range(0, len(cases), FEW_ROWS)]
        forms["few rows"] = np.concatenate(few)
    if not len(cases) > FEW_ROWS:
        bad.append(f"only {len(cases)} rows: the numpy form is not reached")
    for label, got in forms.items():
        bad += judge_kappas(N, got.tolist(), label)
        if not np.array_equal(got, np.array(scalar), equal_nan=True):
            bad.append(f"{label}: not bit for bit the scalar sharp_trace_kappa")
    detail = (f"{len(cases)} rows (FEW_ROWS = {FEW_ROWS}); worst {_worst(N, forms['numpy rows'].tolist()):.3g} "
              "x the bound.")
    if bad:
        return failed("numeric: sharp_trace_kappa_rows vs the definition (exact products) and the scalar",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: sharp_trace_kappa_rows vs the definition (exact products, 60 digits) and "
                   "the scalar (bit for bit)", evidence="sampled", detail=detail,
                   printed="each row's k_t = its definition within 16 u N (1 + k_t)")


# --------------------------------------------------------------------------- paths.abs_products

@cache
def product_rows(N: int) -> tuple[tuple[tuple[float, ...], tuple[float, ...], str], ...]:
    """``(a, r, label)``: the distinct rows of ``paths.abs_products`` (site values ``a_j`` and ``r_j``).

    >>> [label for _a, _r, label in product_rows(3)][4:]
    ['below 2**-500', 'largest entry negative', 'absolute part only', 'C the largest', 'D the largest']
    """
    rng = np.random.default_rng(7 + N)

    def signs() -> np.ndarray:
        return np.where(rng.uniform(size=N) < 0.5, -1.0, 1.0)

    rows = []
    for _ in range(2):
        rows.append((rng.uniform(-4, 4, N), np.exp(rng.uniform(-1, 1, N)), "moderate"))
    rows.append((signs() * rng.uniform(1, 2, N) * 10.0 ** (200 / N), np.exp(rng.uniform(-1, 1, N)), "past 2**500"))
    rows.append((signs() * rng.uniform(1, 2, N) * 10.0 ** (400 / N), np.exp(rng.uniform(-1, 1, N)),
                 "past the double range"))
    rows.append((signs() * rng.uniform(1, 2, N) * 1e-160, rng.uniform(1, 2, N) * 1e-160, "below 2**-500"))
    neg = np.concatenate([[-1e300, 1e10], rng.uniform(1, 2, N - 2)])     # the largest entry negative, then overflow
    rows.append((neg, np.ones(N), "largest entry negative"))
    if N == 3:
        rows.append((np.array([1e160, 0.0, -1e160]), np.ones(3), "absolute part only"))
        # after the second site C = -0.94 is the largest entry, the others below 2**-1022: renormalised by a
        # smaller one, C becomes -0.94 * 2**1023 and the third site's a_3 A - C leaves the double range
        rows.append((np.array([-1.7e308, 2.0 ** -1023, -1.5e308]), np.array([1e-20, 1.0, 1.0]), "C the largest"))
    # after the last site D = -2**600 (N = 2: -2**599) is the largest entry, the largest positive one far below it:
    # renormalised by that one's power of two instead of D's, the entries and the exponent come out other bits
    a_d, r_d = {2: ((0.25, 1.0), (1.0, 2.0 ** 600)), 3: ((1.0, 1.0, 0.5), (1.0, 1.0, 2.0 ** 600))}[N]
    rows.append((np.array(a_d), np.array(r_d), "D the largest"))
    return tuple((tuple(float(x) for x in a), tuple(float(x) for x in r), lab) for a, r, lab in rows)


def exact_products(a: tuple[float, ...], r: tuple[float, ...]) -> tuple[list[Fraction], list[Fraction]]:
    """The exact monodromy ``m_N ... m_1`` (``m_j = [[a_j, -1], [r_j, 0]]``) and the product of the entrywise
    absolute values, as four Fractions each (A, B, C, D)."""
    M = [Fraction(1), Fraction(0), Fraction(0), Fraction(1)]
    T = list(M)
    for aj, rj in zip(a, r):
        fa, fr = Fraction(aj), Fraction(rj)
        A, B, C, D = M
        M = [fa * A - C, fa * B - D, fr * A, fr * B]
        A, B, C, D = T
        T = [abs(fa) * A + C, abs(fa) * B + D, fr * A, fr * B]
    return M, T


def _scaled(x: float, e: int) -> Fraction:
    return Fraction(x) * Fraction(2) ** e


def judge_row(a: tuple, r: tuple, got: tuple[float, float, float, float, int], trace: float, ea: int) -> str:
    """'' if ``2**e (A, B, C, D)`` and ``2**ea trace`` are within the bounds of the module docstring, else why."""
    M, T = exact_products(a, r)
    N = len(a)
    floor = max(T) * Fraction(2) ** -500
    if not all(math.isfinite(x) for x in got[:4]) or not math.isfinite(trace):
        return f"non-finite entries {got[:4]}, trace {trace}"
    for name, x, m, t in zip("ABCD", got[:4], M, T):
        if not abs(_scaled(x, got[4]) - m) <= 3 * N * Fraction(U) * t + floor:
            return f"{name}: 2**e {name} = {float(_scaled(x, got[4])):.6g}, exact {float(m):.6g}"
    tr = T[0] + T[3]
    if not abs(_scaled(trace, ea) - tr) <= 3 * N * Fraction(U) * tr + floor:
        return f"2**ea T = {float(_scaled(trace, ea)):.6g}, exact {float(tr):.6g}"
    return ""


def _row_exp(e: int | np.ndarray, k: int) -> int:
    return int(np.asarray(e)[k]) if np.ndim(e) else int(e)


@claim("paths.abs_products", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2, 3),
       where="symbt/numeric/core/condition.py: abs_trace_rows and monodromy_and_abs (every regime)",
       statement="abs_trace_rows and monodromy_and_abs (N={N}) with 1, 7, 16, 17, 20, 40 rows (and 2049 at N = 2), "
                 "rows moderate, past 2**500, past the double range, below 2**-500 (and at N = 3 a row renormalised "
                 "in the absolute product only) = the exact rational products within 3 N u of the absolute product "
                 "plus 2**-500 of its largest entry; monodromy_and_abs bit for bit the separate calls, also beside a "
                 "row with an infinite a_1, and (N = 2) a row whose largest entry is 2**500 exactly beside one below "
                 "2**-500")
def abs_products(N: int) -> Outcome:
    from ..numeric.core.condition import abs_trace_rows, monodromy_and_abs
    from ..numeric.core.context import FLOAT
    from ..numeric.core.monodromy import monodromy

    rows = product_rows(N)
    far = [k for k, (_a, _r, lab) in enumerate(rows) if lab in ("past 2**500", "past the double range")]
    neg = [k for k, (_a, _r, lab) in enumerate(rows) if lab == "largest entry negative"]
    big_d = [k for k, (_a, _r, lab) in enumerate(rows) if lab == "D the largest"]
    batches = [[0], neg, big_d, [k % len(rows) for k in range(7)], [k % len(rows) for k in range(16)],
               [0, 1] * 8 + [1], [far[k % 2] for k in range(20)], [k % len(rows) for k in range(40)]]
    if N == 2:
        batches.append([k % len(rows) for k in range(2049)])
    bad, checked, exps = [], 0, set()
    for batch in batches:
        a = [np.array([rows[k][0][j] for k in batch]) for j in range(N)]
        r = [np.array([rows[k][1][j] for k in batch]) for j in range(N)]
        with np.errstate(all="ignore"):
            T, ea = abs_trace_rows(a, r)
            (A, B, C, D, e), (T2, ea2) = monodromy_and_abs(a, r)
            sep = (*monodromy(FLOAT, a, r), T, ea)
        both = (A, B, C, D, e, T2, ea2)
        if not all(np.array_equal(np.asarray(x), np.asarray(y)) for x, y in zip(both, sep)):
            bad.append(f"{len(batch)} rows: monodromy_and_abs differs from monodromy(FLOAT) and abs_trace_rows")
        look = range(len(batch)) if len(batch) <= 40 else [*range(len(rows)), *range(len(batch) - len(rows),
                                                                                      len(batch))]
        for k in look:
            ent = (float(A[k]), float(B[k]), float(C[k]), float(D[k]), _row_exp(e, k))
            exps.add(ent[4])
            why = judge_row(*rows[batch[k]][:2], ent, float(T2[k]), _row_exp(ea2, k))
            why = why or judge_row(*rows[batch[k]][:2], ent, float(T[k]), _row_exp(ea, k))
            checked += 1
            if why:
                bad.append(f"{len(batch)} rows, row {k} ({rows[batch[k]][2]}): {why}")
    # sites of different shapes (every r_j one value for all rows; the moderate rows, whose products stay in
    # range): the general form, broadcast
    a = [np.array([rows[k % 2][0][j] for k in range(5)]) for j in range(N)]
    r = [np.array([rows[0][1][j]]) for j in range(N)]
    with np.errstate(all="ignore"):
        T, ea = abs_trace_rows(a, r)
        (A, B, C, D, e), (T2, ea2) = monodromy_and_abs(a, r)
    A, B, C, D, T, T2 = np.broadcast_arrays(A, B, C, D, T, T2)          # (site lists broadcast: B, D may be one)
    for k in range(5):
        ent = (float(A[k]), float(B[k]), float(C[k]), float(D[k]), _row_exp(e, k))
        why = judge_row(rows[k % 2][0], rows[0][1], ent, float(T[k]), _row_exp(ea, k))
        why = why or judge_row(rows[k % 2][0], rows[0][1], ent, float(T2[k]), _row_exp(ea2, k))
        checked += 1
        if why:
            bad.append(f"5 rows, r broadcast, row {k}: {why}")
    # a row with an infinite a_1 beside a moderate one: the few-rows float form gives the entries and exponents of
    # monodromy(FLOAT) bit for bit (NaN where it has NaN; the exponent of a non-finite row is 0, as np.frexp's)
    a = [np.array([rows[0][0][j], np.inf if j == 0 else rows[0][0][j]]) for j in range(N)]
    r = [np.array([rows[0][1][j]] * 2) for j in range(N)]
    with np.errstate(all="ignore"):
        (A, B, C, D, e), _ = monodromy_and_abs(a, r)
        ref = monodromy(FLOAT, a, r)
    if not all(np.array_equal(np.asarray(x), np.asarray(y), equal_nan=True) for x, y in zip((A, B, C, D, e), ref)):
        bad.append(f"a row with a_1 = inf: monodromy_and_abs gives exponents {e}, monodromy(FLOAT) {ref[4]}")
    if N == 2:
        # the range test's edge: a row whose largest entry is 2**500 exactly (a1 a2 = 2**500, r1 below its ulp:
        # in range, "below 2**500" fails for the batch) beside a row whose largest is 2**-510 (renormalised): the
        # few-rows form decides per row as monodromy(FLOAT) does, bit for bit
        a = [np.array([2.0 ** 250, 2.0 ** -510])] * 2
        r = [np.array([2.0 ** -1000, 2.0 ** -600]), np.array([1.0, 2.0 ** -520])]
        with np.errstate(all="ignore"):
            (A, B, C, D, e), _ = monodromy_and_abs(a, r)
            ref = monodromy(FLOAT, a, r)
        if not (float(A[0]) == 2.0 ** 500 and all(np.array_equal(np.asarray(x), np.asarray(y))
                                                  for x, y in zip((A, B, C, D, e), ref))):
            bad.append(f"a row at 2**500 exactly beside one below 2**-500: exponents {e}, monodromy(FLOAT) {ref[4]}")
    detail = (f"{len(batches) + 1} batches, {checked} rows against exact rationals; exponents seen "
              f"{min(exps)}..{max(exps)}.")
    if bad:
        return failed("numeric: abs_trace_rows and monodromy_and_abs vs exact rational products",
                      detail="; ".join(bad[:3]) + ". " + detail)
    return Outcome("verified", "numeric: abs_trace_rows and monodromy_and_abs vs exact rational products, every "
                   "regime", evidence="sampled", detail=detail,
                   printed="the products within 3 N u of the absolute product")
