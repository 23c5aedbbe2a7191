r"""What ships, 4k: three documented rules of the numeric routes at their edges (scene ``numeric-paths``, issue 21).

* ``paths.renorm_top.n2`` -- :func:`~symbt.numeric.core.condition.sharp_trace_kappa`'s backward pass renormalises
  the suffix product by a power of two taken from the *largest magnitude* of its four entries.  After the first
  backward site the suffix is ``[[a_N, -1], [r_N, 0]]``; at ``p = (+-1, 0)``, ``q = (0, 416)``,
  ``lam = +-1e-300`` its entry ``S12 = -1`` is the largest and negative, the others are below ``2**-200``
  (``a_2 = lam``, ``r_2 = e**-416 ~ 2**-600``).  Renormalised by the largest magnitude (1) nothing moves; by a
  smaller one the suffix is scaled up by ``~2**599`` and its product with ``r_1 = e**416 ~ 2**600`` at the next
  site leaves the double range (``inf``), though the exponent bookkeeping is exact either way.  Checked as
  ``paths.kappa_cells`` checks the value: against the docstring's definition with exact 2x2 products at 60
  digits (checked at 80), within a relative ``16 u N``.
* ``paths.kappa_edge.n2`` -- the float64 kernels decide a trace where its condition estimate is *at most*
  ``KAPPA_MAX = 2**24`` (``kernels._decided``'s docstring, docs/numeric.md "Conditioned decisions and
  escalation": ``k_t <= KAPPA_MAX``).  A state built so that the estimate is the double ``2**24`` exactly:
  ``p = (0, 0)``, ``q = (0, d)``, ``lam = L`` with the low part ``lo = 1.5 * 2**-52`` (so ``a_j = L + lo``
  rounds one ulp above ``|lam| + |p_j|`` and the cancellation factor is the double below 1), ``L`` and ``d``
  found offline so that the cheap tier's ``T (|t| + 2) / |t**2 - 4|`` is the double above ``2**24``: the cheap
  test fails, the sharp estimate (N = 2: ``T_s = T (1 + 2**-48)``) is larger, and the estimate is
  ``fl(fl(T ta / |disc|) * fl(kn / kd)) = 2**24``.  The premise is recomputed with exact rationals and one
  correct rounding per documented operation (not with the kernels' doubles); at ``d`` one ulp up the estimate is
  above ``2**24``, one ulp down below.  The block kernel's trace decision (``kernels_block._slopes``, three
  members) and the fused kernel's hook ``HOOKS["decided"]`` are called directly (as ``paths.range_edge`` calls
  ``in_range``): the edge decided (status unchanged, estimate ``2**24``), above refused (``ILLCOND``), below
  decided.  (Through ``run_block``, ``lam2 = L + 1``, the read-out test hands this state back either way: its
  ``kappa >= k_t = 2**24`` is above ``2**24`` there; the rule is visible in the trace decision itself.)
* ``paths.inline_rule.n3`` -- :func:`~symbt.numeric.core.inline.inlined` writes a body that writes to an array
  inline only at the root of its statement (``x = f(...)``, ``f(...)``, ``if not f(...):``) and refuses it
  anywhere else with ``ValueError`` (its module docstring: the statements of a nested call are placed before its
  statement, which would change what runs -- ``u[0] + f(u, x)`` would read ``u[0]`` after ``f`` wrote it).
  Checked: three nested positions (an operand, an argument of ``abs``, an ``if`` test's comparison) refused, the
  three root positions rewritten with results equal to the plain calls bit for bit (including ``u``).

Shown to fail on planted bugs in ``tests/test_killers_numeric3.py``.
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed

# --------------------------------------------------------------------------- paths.renorm_top

#: paths.renorm_top: (p, q, lam): S12 = -1 the largest suffix entry, the others below 2**-200
RENORM_CASES = (((1.0, 0.0), (0.0, 416.0), 1e-300), ((-1.0, 0.0), (0.0, 416.0), -1e-300))


def renorm_inputs(p: tuple, q: tuple, lam: float) -> tuple[tuple, tuple]:
    """``(p, r)`` as ``sharp_trace_kappa`` takes them: ``r_j = exp(q_{j+1} - q_j)`` rounded once.

    >>> p, r = renorm_inputs((1.0, 0.0), (0.0, 416.0), 1e-300)
    >>> r[0] > 2.0 ** 599, r[1] < 2.0 ** -599
    (True, True)
    """
    return p, tuple(math.exp(q[(j + 1) % len(q)] - q[j]) for j in range(len(q)))


@claim("paths.renorm_top", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2,),
       where="symbt/numeric/core/condition.py: sharp_trace_kappa's backward renormalisation (the largest |S_ij|)",
       statement="sharp_trace_kappa (N={N}) at p = (+-1, 0), q = (0, 416), lam = +-1e-300, where the first "
                 "suffix product's largest entry is S12 = -1 and the others are below 2**-200: its documented k_t "
                 "evaluated with exact 2x2 products at 60 digits (checked at 80), within a relative 16 u N (a "
                 "renormalisation by a smaller entry overflows at the next site, r_1 = e**416)")
def renorm_top(N: int) -> Outcome:
    from ..numeric.core.condition import SHARP_UNIT
    from .shipped_condition import sharp_against_definition

    bad, seen = [], []
    for p, q, lam in RENORM_CASES:
        p, r = renorm_inputs(p, q, lam)
        # the premise: after the first backward site S = [[lam, -1], [r_2, 0]], S12 the largest, the rest tiny
        if not (max(abs(lam), r[1]) < 2.0 ** -200 and r[0] > 2.0 ** 512):
            bad.append(f"lam = {lam:g}: the construction does not hold")
            continue
        compared = sharp_against_definition(p, r, lam)
        if compared is None:
            bad.append(f"lam = {lam:g}: the reference disagrees with itself at 80 digits")
            continue
        got, ref, dev = compared
        seen.append(f"lam = {lam:g}: k_t = {got!r}, definition {mp.nstr(ref, 17)}")
        if not dev <= SHARP_UNIT * N:
            bad.append(f"lam = {lam:g}: k_t = {got!r}, by the definition {mp.nstr(ref, 12)}")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: sharp_trace_kappa at the top of the range vs its definition (60 digits)",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: sharp_trace_kappa at the top of the range vs its definition (exact "
                   "products, 60 digits)", evidence="sampled", detail=detail,
                   printed="k_t = its definition within 16 u N")


# --------------------------------------------------------------------------- paths.kappa_edge

#: paths.kappa_edge: lam = L (high part), its low part, and q_2 - q_1 = d (found offline: the estimate is 2**24)
EDGE_L, EDGE_LO, EDGE_D = 2.9343643216262145, 1.5 * 2.0 ** -52, 1.8649461929027753
#: the ratios (r_1, r_2) = (e**d, e**-d) as the kernels' re-anchoring rounds them (math.exp) at d, at d one ulp up and
#: one ulp down: written as the doubles themselves, so that the premise depends on IEEE arithmetic alone
EDGE_RATIOS = {"at 2**24": ("0x1.9d285cc0a3293p+2", "0x1.3d3e9809506fbp-3"),
               "one ulp above": ("0x1.9d285cc0a3294p+2", "0x1.3d3e9809506fap-3"),
               "one ulp below": ("0x1.9d285cc0a3291p+2", "0x1.3d3e9809506fcp-3")}


def kappa_estimate(L: float, lo: float, r: tuple[float, float]) -> tuple[float, bool, float, float]:
    """The kernels' condition estimate of the trace at ``lam = L + lo`` for ``p = (0, 0)`` and the ratios ``r``,
    each documented operation computed with exact rationals and rounded once (``float`` of a ``Fraction`` is
    correctly rounded): ``(estimate, cheap test failed, t, disc)`` -- ``a_j = fl(L + lo)`` (``lam_add`` with
    ``p_j = 0``), ``t = fl(fl(fl(a a) - r_1) - r_2)``, ``T = fl(fl(fl(a a) + r_1) + r_2)``,
    ``disc = fl(fl(t - 2) fl(t + 2))``, ``ta = fl(|t| + 2)``, the estimate ``fl(fl(fl(T ta) / |disc|) fl(kn / kd))``
    with ``kn = |L|``, ``kd = |a|``.

    >>> kappa_estimate(EDGE_L, EDGE_LO, edge_ratios("at 2**24"))[:2] == (2.0 ** 24, True)
    True
    """
    def fl(x: Fraction) -> float:
        return float(x)
    F = Fraction
    r1, r2 = r
    a = fl(F(L) + F(lo))
    P = fl(F(a) * F(a))
    t = fl(F(fl(F(P) - F(r1))) - F(r2))
    T = fl(F(fl(F(P) + F(r1))) + F(r2))
    disc = fl(F(fl(F(t) - 2)) * F(fl(F(t) + 2)))
    ta = fl(abs(F(t)) + 2)
    Tta = fl(F(T) * F(ta))
    est = fl(F(fl(F(Tta) / abs(F(disc)))) * F(fl(F(abs(L)) / F(abs(a)))))
    return est, Tta > F(2) ** 24 * abs(F(disc)), t, disc


def edge_ratios(name: str) -> tuple[float, float]:
    """``(r_1, r_2)`` of the state ``name`` of :data:`EDGE_RATIOS` (the edge, ``d`` one ulp up, one ulp down).

    >>> [round(v, 6) for v in edge_ratios("at 2**24")]
    [6.455589, 0.154905]
    """
    r1, r2 = EDGE_RATIOS[name]
    return float.fromhex(r1), float.fromhex(r2)


@claim("paths.kappa_edge", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(2,),
       where="symbt/numeric/float64/kernels_block.py (_slopes), kernels.py (_decided): the trace decision at "
             "KAPPA_MAX",
       statement="the float64 kernels' trace decision (N={N}): at p = (0, 0), q = (0, d), lam = L + 1.5 2**-52 "
                 "built so that the condition estimate is 2**24 = KAPPA_MAX exactly (exact rationals, one rounding "
                 "per documented operation; the cheap test fails, the sharp estimate is larger), the block "
                 "kernel's _slopes and the fused hook decide the trace (the documented rule k_t <= KAPPA_MAX) "
                 "with estimate 2**24; at d one ulp up (estimate above) both refuse it (ILLCOND), one ulp down "
                 "both decide it")
def kappa_edge(N: int) -> Outcome:
    from ..numeric.core.condition import sharp_trace_kappa
    from ..numeric.core.limits import ILLCOND, KAPPA_MAX, OK, TRACE1
    from ..numeric.float64.kernels import HOOKS
    from ..numeric.float64.kernels_block import _slopes

    states = list(EDGE_RATIOS)
    bad, seen = [], []
    want = []
    for name in states:
        est, cheap_failed, t, disc = kappa_estimate(EDGE_L, EDGE_LO, edge_ratios(name))
        want.append(est <= KAPPA_MAX)
        r = np.array(edge_ratios(name))
        ks = sharp_trace_kappa(np.zeros(2), r, EDGE_L, EDGE_LO)
        seen.append(f"{name}: estimate {est!r} (sharp {ks!r})")
        premise = {"at 2**24": est == KAPPA_MAX and cheap_failed and ks > est,
                   "one ulp above": est > KAPPA_MAX, "one ulp below": est < KAPPA_MAX}[name]
        if not premise:
            bad.append(f"{name}: the construction does not hold (estimate {est!r}, cheap test failed "
                       f"{cheap_failed}, sharp {ks!r})")
        # the fused kernel's hook, on the track its own hooks build (site 1, then site 2)
        a = HOOKS["lam_add"](EDGE_L, EDGE_LO, 0.0)
        aux = HOOKS["track"](HOOKS["track_init"](EDGE_L, 0.0, a, r[0]), EDGE_L, 0.0, a, r[1])
        tt = np.zeros(4)
        fused = bool(HOOKS["decided"](aux, t, disc, tt, 0, np.zeros(2), r, EDGE_L, EDGE_LO))
        if fused != want[-1] or (fused and tt[2] != est):
            bad.append(f"{name}: the fused hook decides {fused} with k_t {tt[2]!r}; the rule gives "
                       f"{want[-1]} with {est!r}")
    # the block kernel's trace decision, the three states as one block of members
    B = len(states)
    p, r = np.zeros((N, B)), np.array([edge_ratios(name) for name in states]).T.copy()
    lam, lo = np.full(B, EDGE_L), np.full(B, EDGE_LO)
    u, tmp, Ab = np.empty((N, B)), np.empty((N, B)), np.empty((4, B))
    A, Bm, C, D, u1, tt, kt, Kn, Kd, sc = (np.empty(B) for _ in range(10))
    fw, status = np.empty(B, np.int64), np.full(B, OK, np.int64)
    with np.errstate(all="ignore"):
        _slopes(p, r, lam, lo, 1, u, tmp, A, Bm, C, D, u1, fw, status, TRACE1, Ab, tt, kt, Kn, Kd, sc)
    for k, name in enumerate(states):
        est = kappa_estimate(EDGE_L, EDGE_LO, edge_ratios(name))[0]
        code = OK if want[k] else ILLCOND
        seen.append(f"{name}: block status {int(status[k])}")
        if int(status[k]) != code or (code == OK and kt[k] != est):
            bad.append(f"{name}: the block kernel's status {int(status[k])}, estimate {kt[k]!r}; the rule gives "
                       f"{code} with {est!r}")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: the kernels' trace decision at KAPPA_MAX vs the documented rule (exact rationals)",
                      detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the kernels' trace decision at KAPPA_MAX vs the documented rule "
                   "(exact rationals)", evidence="sampled", detail=detail,
                   printed="decided at k_t = 2**24 exactly, refused one ulp above")


# --------------------------------------------------------------------------- paths.inline_rule

def store_first(u: list[float], x: float) -> float:      # a body for the inliner: writes to an array
    u[0] = x
    return x


def nested_operand(u: list[float], x: float) -> float:     # u[0] is read before store_first writes it
    y = u[0] + store_first(u, x)
    return y


def nested_argument(u: list[float], x: float) -> float:
    y = abs(store_first(u, x))
    return y


def nested_test(u: list[float], x: float) -> float:
    if store_first(u, x) > 0.0:
        return u[0]
    return -u[0]


def root_assign(u: list[float], x: float) -> float:
    y = store_first(u, x)
    return y + u[0]


def root_statement(u: list[float], x: float) -> float:
    store_first(u, x)
    return u[0]


def root_not_test(u: list[float], x: float) -> float:
    if not store_first(u, x):
        return u[0]
    return -u[0]


#: (function, refused): the nested calls of the impure body must be refused, the root ones written inline
INLINE_CASES = ((nested_operand, True), (nested_argument, True), (nested_test, True),
                (root_assign, False), (root_statement, False), (root_not_test, False))


@claim("paths.inline_rule", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/core/inline.py: inlined's refusal of an impure body away from the root of its statement",
       statement="inlined (the plain-Python kernels' rewrite) with a body that writes to an array: refused with "
                 "ValueError where the call is an operand, an argument or inside an if test's comparison (its "
                 "statements would run before the statement: its module docstring); written inline at the root "
                 "of its statement (x = f(...), f(...), if not f(...)), with results and the written array equal "
                 "to the plain call's, bit for bit")
def inline_rule(N: int) -> Outcome:
    from ..numeric.core.inline import FLOAT64_INLINE, inlined

    kinds, env = {**FLOAT64_INLINE, "store_first": "body"}, {"store_first": store_first}
    bad, seen = [], []
    for fn, refused in INLINE_CASES:
        try:
            g = inlined(fn, fn.__name__ + "_inline", kinds, env)
        except ValueError as exc:
            seen.append(f"{fn.__name__}: refused")
            if not refused:
                bad.append(f"{fn.__name__}: refused at the root of its statement ({str(exc)[:80]})")
            continue
        if refused:
            bad.append(f"{fn.__name__}: written inline, the documented rule refuses it")
            continue
        if "store_first" in g.__code__.co_names:
            bad.append(f"{fn.__name__}: the body is still called")
        for x in (2.5, -1.25, 0.0):
            u0, u1 = [7.0, 1.0], [7.0, 1.0]
            plain, got = fn(u0, x), g(u1, x)
            if not (repr(plain) == repr(got) and u0 == u1):
                bad.append(f"{fn.__name__}({x}): {got!r}, u = {u1}; the plain call {plain!r}, u = {u0}")
        seen.append(f"{fn.__name__}: written inline")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: inlined vs its documented rule for impure bodies", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: inlined vs its documented rule for impure bodies (the plain calls)",
                   evidence="sampled", detail=detail, printed="refused away from the root, bit for bit at it")
