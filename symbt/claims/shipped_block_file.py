r"""What ships, 4m: the float64 kernels observed function by function (scene ``numeric-paths``; issue 21 item 4,
docs/mutation.md "Fresh samples of symbt/numeric/float64/kernels_block.py and kernels.py").

Fresh mutation samples of :mod:`symbt.numeric.float64.kernels` and :mod:`~symbt.numeric.float64.kernels_block` left
the hooks and double-double helpers the plain-Python kernel writes *inline* (the line map never sees their lines
run; both kernels share them, so comparing the kernels cannot see a slip there) and outputs of the block kernel that
no claim compared (its condition estimate, slopes, scale, a member's neighbours in a block of unlike members):

* ``paths.hook_rules`` -- every hook of :data:`~symbt.numeric.float64.kernels.HOOKS` that ``track_hooks`` leaves
  out, and ``_logf``, ``_dd_add``, ``_dd_position``, ``_dd_low``, called directly on inputs reaching each branch,
  against their documented rules with exact rationals (the sharp tier's value is ``sharp_trace_kappa``'s: wiring).
* ``paths.block_slopes.n3`` -- ``kernels_block._slopes`` member by member against the definition at 50 digits.
* ``paths.block_driver.n3`` -- the block ensemble against the single-state orbit (bit for bit, every status code),
  the literal traces and the literal map.

Shown to fail on planted bugs in ``tests/test_killers_block.py``.
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed

F = Fraction
EPS = 2.0 ** -53          # the unit roundoff of a double


def _rel(got: float, want: Fraction) -> float:
    """``|got - want| / |want|`` with exact rationals (``inf`` for a non-finite ``got``)."""
    if not math.isfinite(got):
        return math.inf
    return float(abs(F(got) - want) / abs(want)) if want else float(abs(F(got)))


def _failed(method: str, bad: list[str], detail: str) -> Outcome:
    """``failed`` with the first findings (and how many more) before ``detail``."""
    more = f" (and {len(bad) - 6} more)" if len(bad) > 6 else ""
    return failed(method, detail="; ".join(bad[:6]) + more + ". " + detail)


def _track_rules(H: dict, bad: list[str]) -> None:
    """``track``: the absolute product's next factor (``|a| Aa + Ca``, ``|a| Ba + Da``, ``r Aa``, ``r Ba``: two
    roundings at most, all terms positive) and ``kn / kd`` the larger of the old ratio and ``(|lam| + |p_j|) / |a|``."""
    aux0 = (3.0, 0.75, 2.5, 1.25, 5.0, 4.0, 0.5)          # kn / kd = 1.25, scale 1/2
    for lam, pj, rj in ((-3.0, 1.0, 0.5), (-3.0, 2.5, 2.0), (3.0, 0.5, 1.5), (-0.5, -2.0, 0.25), (2.0, -1.9, 3.0)):
        a = lam + pj
        Aa, Ba, Ca, Da, kn, kd, sc = H["track"](aux0, lam, pj, a, rj)
        aa = abs(F(a))
        want = (aa * F(aux0[0]) + F(aux0[2]), aa * F(aux0[1]) + F(aux0[3]), F(rj) * F(aux0[0]), F(rj) * F(aux0[1]))
        errs = [_rel(g, w) for g, w in zip((Aa, Ba, Ca, Da), want)]
        ratio = max(F(aux0[4]) / F(aux0[5]), (abs(F(lam)) + abs(F(pj))) / aa)
        if max(errs) > 2 * EPS or _rel(kn / kd, ratio) > 2 * EPS or sc != aux0[6]:
            bad.append(f"track at lam = {lam}, p_j = {pj}: {(Aa, Ba, Ca, Da, kn, kd, sc)}, kn/kd wanted "
                       f"{float(ratio)!r}")


def _rescale_last_rules(H: dict, bad: list[str]) -> None:
    """``rescale_last``: shrinks by ``2**-400`` exactly where ``Ca`` or ``Da`` is past ``2**400`` (the tracked matrix
    over its scale unchanged); ``Aa``, ``Ba`` past it do not count here."""
    big, S = 2.0 ** 400, 2.0 ** -400
    ABCD = (5.0 * big, -big, 0.25 * big, 3.0)
    for name, aux, shrink in (("Ca past", (1.0, 1.0, 2.0 * big, 1.0, 1.0, 1.0, 1.0), True),
                              ("Da past", (1.0, 1.0, 1.0, 3.0 * big, 2.0, 1.0, 0.25), True),
                              ("Aa, Ba past, Ca = Da = 2**400", (4.0 * big, 4.0 * big, big, big, 1.0, 1.0, 1.0),
                               False)):
        A, B, C, D, aux2 = H["rescale_last"](*ABCD, aux)
        if shrink:
            ok = ((A, B, C, D) == tuple(x * S for x in ABCD) and aux2[:4] == tuple(x * S for x in aux[:4])
                  and aux2[4:6] == aux[4:6] and aux2[6] == aux[6] * S)
        else:
            ok = (A, B, C, D) == ABCD and tuple(aux2) == aux
        if not ok:
            bad.append(f"rescale_last, {name}: {(A, B, C, D)}, {aux2} (wanted {'shrunk' if shrink else 'kept'})")


def _range_rules(H: dict, bad: list[str]) -> None:
    """``in_range``: every entry below ``1e290`` in magnitude and an entry of the first row strictly above
    ``1e-290``; ``disc_fits``: ``disc < 1e300``; ``two_of``: ``2 sc``."""
    top, inside = 1e290, math.nextafter(1e290, 0.0)
    low, above = 1e-290, math.nextafter(1e-290, 1.0)
    cases = []
    for i in range(4):
        for v, want in ((top, False), (-top, False), (inside, True), (-inside, True)):
            e = [1.0, 1.0, 1.0, 1.0]
            e[i] = v
            cases.append((tuple(e), want))
    for a, b, want in ((low, low, False), (-low, 0.0, False), (0.0, -low, False), (above, 0.0, True),
                       (0.0, -above, True), (-above, low, True), (low, above, True)):
        cases.append(((a, b, 1.0, 1.0), want))
    for entries, want in cases:
        got = bool(H["in_range"](*entries, 0.0))
        if got != want:
            bad.append(f"in_range{entries} = {got}, the rule gives {want}")
    for d, want in ((1e300, False), (math.nextafter(1e300, 0.0), True), (math.inf, False), (-1.0, True)):
        if bool(H["disc_fits"](d)) != want:
            bad.append(f"disc_fits({d!r}) = {not want}")
    for sc in (1.0, 2.0 ** -400, 2.0 ** -800):
        if H["two_of"]((0.0, 0.0, 0.0, 0.0, 1.0, 1.0, sc)) != 2.0 * sc:
            bad.append(f"two_of at scale {sc!r}")


def _decided_rules(H: dict, bad: list[str]) -> None:
    """``decided``: with the cheap bound ``T (|t| + 2 sc) <= KAPPA_MAX |disc|`` (``T = Aa + Da``) the estimate
    ``T (|t| + 2 sc) / |disc| * kn / kd`` goes to ``tt[i + 2]``; where it fails, the smaller of it and the sharp
    ``k_t`` decides (``<= KAPPA_MAX``), nothing written when refused; ``step_kappa`` is ``max(tt[2], tt[3])`` and
    ``sharpen`` lowers each of ``tt[2]``, ``tt[3]`` to its sharp value where that is smaller."""
    from ..numeric.core.condition import sharp_trace_kappa
    from ..numeric.core.limits import KAPPA_MAX

    # the cheap tier decides: a scaled trace t = -6 sc (either sign of t, scales 1 and 2**-400)
    p3, r3 = np.zeros(3), np.ones(3)
    for i, t, sc in ((0, -6.0, 1.0), (1, 6.0, 2.0 ** -400), (0, 6.0 * 2.0 ** -400, 2.0 ** -400)):
        aux = (7.0 * sc, 0.5, 0.25, 3.0 * sc, 9.0, 4.0, sc)
        disc = (t - 2 * sc) * (t + 2 * sc)
        tt = np.full(4, -1.0)
        ok = bool(H["decided"](aux, t, disc, tt, i, p3, r3, 3.0, 0.0))
        want = (F(aux[0]) + F(aux[3])) * (abs(F(t)) + 2 * F(sc)) / abs(F(disc)) * F(9, 4)
        others = [tt[k] for k in range(4) if k != i + 2]
        if not (ok and _rel(tt[i + 2], want) <= 4 * EPS and others == [-1.0] * 3):
            bad.append(f"decided (cheap tier) at t = {t!r}, slot {i}: {ok}, tt = {tt.tolist()}, k_t wanted "
                       f"{float(want)!r}")
    # the cheap tier fails, the sharp k_t decides: the free chain (N = 8) 1e-6 outside the band edge lam = 2
    p8, r8 = np.zeros(8), np.ones(8)
    for lam, accept in ((2.0 + 1e-6, True), (2.0 + 1e-13, False)):
        ks = sharp_trace_kappa(p8, r8, lam, 0.0)
        t = 2.0 * math.cosh(8 * math.acosh(lam / 2))          # the free chain's trace, 2 T_8(lam / 2)
        disc = (t - 2.0) * (t + 2.0)
        T = 2.0 ** 14                                          # far above KAPPA_MAX |disc| / (|t| + 2)
        aux = (T / 2, 1.0, 1.0, T / 2, 1.0, 1.0, 1.0)
        tt = np.full(4, -1.0)
        ok = bool(H["decided"](aux, t, disc, tt, 1, p8, r8, lam, 0.0))
        cheap = T * (abs(t) + 2.0) / abs(disc)
        if cheap <= KAPPA_MAX or (ks <= KAPPA_MAX) != accept:
            bad.append(f"decided (sharp tier) at lam = {lam!r}: the premise does not hold (cheap {cheap:.3g}, "
                       f"sharp {ks:.3g})")
        elif ok != accept or (accept and tt[3] != min(ks, cheap)) or (not accept and tt[3] != -1.0) \
                or [tt[0], tt[1], tt[2]] != [-1.0] * 3:
            bad.append(f"decided (sharp tier) at lam = {lam!r}: {ok}, tt = {tt.tolist()}; sharp k_t {ks!r}")
    # step_kappa and sharpen: one slot above its sharp value, the other below
    pa, ra = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    k1, k2 = sharp_trace_kappa(pa, ra, 15.0, 0.0), sharp_trace_kappa(pa, ra, 5.0, 0.0)
    for tt0 in ((0.0, 0.0, 2 * k1, 0.5 * k2), (0.0, 0.0, 0.5 * k1, 3 * k2), (7.0, 8.0, 4 * k1, 4 * k2)):
        tt = np.array(tt0)
        got = H["sharpen"](tt, pa, ra, 15.0, 0.0, 5.0, 0.0)
        w2, w3 = min(tt0[2], k1), min(tt0[3], k2)
        if tt.tolist() != [tt0[0], tt0[1], w2, w3] or got != max(w2, w3):
            bad.append(f"sharpen from {tt0}: {tt.tolist()}, returned {got!r} (sharp {k1!r}, {k2!r})")
        for a, b in ((tt0[2], tt0[3]), (tt0[3], tt0[2])):
            if H["step_kappa"](np.array([9.0, 9.0, a, b])) != max(a, b):
                bad.append(f"step_kappa of ({a!r}, {b!r})")


def _trusted_rules(H: dict, bad: list[str]) -> None:
    """``trusted``: ``kt (|u| + |w|) (|x + 1| + |x|) <= KAPPA_MAX |u - w| |x + 1|`` (its comment), on both sides of
    the bound by 10 % for every sign of ``u``, ``w`` and ``x + 1`` and of ``x``."""
    from ..numeric.core.limits import KAPPA_MAX

    for u, w in ((3.0, 1.0), (-3.0, 1.0), (1.0, -3.0), (-1.0, -3.0), (3.0, -0.5), (-0.25, 2.0)):
        dn = u - w
        for x in (-0.5, 0.25, -1.5, -4.0, 3.0):
            q = (abs(F(u)) + abs(F(w))) * (abs(F(x) + 1) + abs(F(x))) / (F(KAPPA_MAX) * abs(F(dn)) * abs(F(x) + 1))
            for factor, want in ((F(9, 10), True), (F(11, 10), False)):
                kt = float(factor / q)
                if bool(H["trusted"](kt, u, w, dn, x)) != want:
                    bad.append(f"trusted(kt = {kt:.6g}, u = {u}, w = {w}, x = {x}) = {not want}")


def _advance_rules(H: dict, bad: list[str]) -> None:
    """``advance`` at site ``j``: ``r_j <- r_j (1 + x_{j+1}) / (1 + x_j)`` (three roundings) and the factor
    ``F_j = fh_j + fl_j <- F_j (1 + x_j)`` in double-double -- error within ``eps |x| |F|`` (the rounding of
    ``fh x``), not ``eps |F|`` -- every other site untouched."""
    for j in (0, 1, 2):
        for x, xn in ((1e-5, -3e-6), (-0.3, 0.7), (2.5e-9, 4e-9)):
            r, fh, fl = np.array([0.5, 2.0, 7.0]), np.array([1.25, 0.75, 3.0]), np.array([3e-13, -2e-17, 1e-10])
            r0, fh0, fl0 = r.copy(), fh.copy(), fl.copy()
            H["advance"](r, (fh, fl), j, x, xn, 0.0)
            want_r = F(r0[j]) * (1 + F(xn)) / (1 + F(x))
            want_f = (F(fh0[j]) + F(fl0[j])) * (1 + F(x))
            got_f = F(fh[j]) + F(fl[j])
            ferr = float(abs(got_f - want_f) / want_f)
            others = [k for k in range(3) if k != j]
            if (_rel(r[j], want_r) > 4 * EPS or ferr > 2 * EPS * abs(x) + 2.0 ** -100
                    or any(r[k] != r0[k] or fh[k] != fh0[k] or fl[k] != fl0[k] for k in others)):
                bad.append(f"advance at j = {j}, x = {x!r}: r {r.tolist()}, F error {ferr:.3g} relative, "
                           f"fh {fh.tolist()}, fl {fl.tolist()}")


def _double_double_rules(bad: list[str]) -> None:
    """``_logf`` is ``log(fh + fl)`` inside ``(1e-300, 1e300)`` (two ulps of the 40-digit value; NaN at and beyond
    the ends); ``_dd_add`` returns ``(hi + lo) + s`` as a renormalised pair to ``2**-104`` relative;
    ``_dd_position`` rounds ``qh + ql + log F`` once (within an ulp); ``_dd_low`` is what that dropped."""
    from ..numeric.float64 import kernels as K

    lo_edge, hi_edge = 1e-300, 1e300
    for fh, fl in ((math.nextafter(lo_edge, 1.0), 0.0), (1e-200, 3e-217), (1e-150, 0.0), (0.75, 1e-17),
                   (1.0, -2e-17), (1e150, 1e133), (math.nextafter(hi_edge, 0.0), 0.0)):
        got = K._logf(fh, fl)
        with mp.workdps(40):
            want = mp.log(mp.mpf(fh) + mp.mpf(fl))
            ok = math.isfinite(got) and abs(mp.mpf(got) - want) <= 2 * EPS * max(abs(want), mp.mpf(2) ** -1000)
        if not ok:
            bad.append(f"_logf({fh!r}, {fl!r}) = {got!r}, log = {mp.nstr(want, 17)}")
    for fh in (lo_edge, -1.0, 0.0, hi_edge, math.inf, math.nan):
        if not math.isnan(K._logf(fh, 0.0)):
            bad.append(f"_logf({fh!r}, 0) = {K._logf(fh, 0.0)!r}, NaN wanted")
    for hi, lo, s in ((1.0, 2.0 ** -60, 2.0 ** -55), (1e3, -3e-14, -999.75), (-7.0, 1e-16, 3.5 + 2.0 ** -40),
                      (0.0, 0.0, 1.5), (2.0 ** 60, 1.0, -(2.0 ** 60))):
        h2, l2 = K._dd_add(hi, lo, s)
        exact = F(hi) + F(lo) + F(s)
        pair = F(h2) + F(l2)
        scale = max(abs(F(hi)) + abs(F(lo)) + abs(F(s)), F(1, 2 ** 1000))
        if abs(pair - exact) > scale * F(1, 2 ** 104) or (h2 != 0 and abs(F(l2)) > abs(F(h2)) * F(1, 2 ** 53)):
            bad.append(f"_dd_add({hi!r}, {lo!r}, {s!r}) = ({h2!r}, {l2!r})")
    for qh, ql, fh, fl in ((3.0, 1e-16, 1.5, 2e-17), (-250.0, -2e-14, 0.25, 0.0), (1e-3, 1e-20, 1.0, 1e-17)):
        y = K._dd_position(qh, ql, fh, fl)
        low = K._dd_low(qh, ql, fh, fl, y)
        want = F(qh) + F(ql) + F(K._logf(fh, fl))         # the position the double-double carries
        if abs(F(y) - want) > F(math.ulp(y)) / 2 * (1 + F(1, 2 ** 40)) or \
                abs(F(y) + F(low) - want) > abs(want) * F(1, 2 ** 104):
            bad.append(f"_dd_position/_dd_low at q = {qh!r} + {ql!r}, F = {fh!r} + {fl!r}: {y!r}, {low!r}; "
                       f"{float(want)!r}")


@claim("paths.hook_rules", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/float64/kernels.py: the hooks track, rescale_last, in_range, two_of, decided, "
             "disc_fits, step_kappa, sharpen, trusted, advance and _logf, _dd_add, _dd_position, _dd_low",
       statement="the fused kernel's hooks and the orbit's double-double helpers, called directly on inputs that "
                 "reach each branch (every entry at each range edge, both tiers of the trace's condition, both "
                 "signs of every operand of the read-out test, every site of advance), against their documented "
                 "rules evaluated with exact rationals (mpmath at 40-50 digits for the logarithms)")
def hook_rules() -> Outcome:
    from ..numeric.float64.kernels import HOOKS

    bad: list[str] = []
    for rules in (_track_rules, _rescale_last_rules, _range_rules, _decided_rules, _trusted_rules, _advance_rules):
        rules(HOOKS, bad)
    _double_double_rules(bad)
    detail = "track, rescale_last, in_range, disc_fits, two_of, decided, sharpen, step_kappa, trusted, advance; _logf."
    if bad:
        return _failed("numeric: the fused kernel's hooks and helpers vs their documented rules", bad, detail)
    return Outcome("verified", "numeric: the fused kernel's hooks and double-double helpers vs their documented rules "
                   "(exact rationals)", evidence="sampled", n_scope="all", detail=detail,
                   printed="every hook's documented rule on every branch")


# --------------------------------------------------------------------------- paths.block_slopes

#: paths.block_slopes: (p, q, lam, lo) per member -- the paper's state on both sides of its gaps (traces of both
#: signs: both transport directions in one block), far from the spectrum (the monodromy rescaled by 2**-400), with a
#: low part, in a band (|tr| < 2), the free chain where only the sharp condition decides (cheap estimate ~1.9e7, sharp
#: ~1.6e7 against KAPPA_MAX ~1.7e7) and where neither does; the last two last, so that a neighbour's index past the
#: block cannot wrap round.  At lam = 1e100 the monodromy (~1e300) fits only rescaled; at lam = -1e200 it overflows
#: (RANGE).  The low part 2**95 at lam = 1e45 (half its ulp) is far from its neighbour's: a member reading another's
#: low part is seen
SLOPE_MEMBERS = (((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 15.0, 0.0), ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 21.0, 0.0),
                 ((20.0, -10.0, -1.0), (1.0, 0.0, 0.9), -25.0, 2.0 ** -50),
                 ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), -5.0, -(2.0 ** -51)),
                 ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 1e45, 2.0 ** 95),
                 ((0.5, -0.25, 0.0), (0.0, 0.5, -1.0), 9.0, 0.0),
                 ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 0.5, 0.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 2.0 + 8e-8, 0.0),
                 ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 1e100, 0.0), ((1.0, 0.0, -2.0), (0.0, 0.0, 0.0), -1e200, 0.0),
                 ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 2.0 + 8e-8, 0.0),
                 ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 2.0 + 1e-10, 0.0))


def _slope_reference(p: tuple, r: list[float], lam: float, lo: float, s: int) -> dict:
    """The definition at 50 digits from the member's doubles: the monodromy ``m_{N-1} ... m_0`` of
    ``m_j = [[lam + lo + p_j, -1], [r_j, 0]]``, its trace, the trace of the product of the entrywise absolute values
    ``T``, the cheap estimate ``T (|t| + 2) / |t**2 - 4| max_j (|lam| + |p_j|) / |lam + lo + p_j|`` and the slopes:
    ``u_0 = (A - D + s sqrt(t**2 - 4)) / (2 B)``, ``u_{j+1} = -r_j / (a_j + u_j)`` (exact arithmetic has no
    direction: the transport loses at most ``log10`` of the eigenvalue ratio, ``2 log10 |t|``, so the digits are
    50 plus that)."""
    with mp.workdps(20):
        m = mp.eye(2)
        for j in range(len(p)):
            m = mp.matrix([[mp.mpf(lam) + p[j], -1], [r[j], 0]]) * m
        extra = 2 * int(mp.log10(abs(m[0, 0] + m[1, 1]) + 10))
    with mp.workdps(50 + extra):
        a = [mp.mpf(lam) + mp.mpf(lo) + mp.mpf(x) for x in p]
        M = mp.eye(2)
        Mabs = mp.eye(2)
        for j in range(len(p)):
            M = mp.matrix([[a[j], -1], [r[j], 0]]) * M
            Mabs = mp.matrix([[abs(a[j]), 1], [r[j], 0]]) * Mabs
        t = M[0, 0] + M[1, 1]
        T = Mabs[0, 0] + Mabs[1, 1]
        # the documented rescaling: after each site j >= 1 the tracked matrix and its absolute product are multiplied
        # by 2**-400 where Aa or Ba is past 2**400 (kernels._rescale), after the last where Ca or Da is
        # (_rescale_last): the scale from the absolute product carried the same way, exactly
        big, ab, sc, over = mp.mpf(2) ** 400, [abs(a[0]), mp.mpf(1), mp.mpf(r[0]), mp.mpf(0)], mp.mpf(1), False
        for j in range(1, len(p)):
            ab = [abs(a[j]) * ab[0] + ab[2], abs(a[j]) * ab[1] + ab[3], r[j] * ab[0], r[j] * ab[1]]
            over = over or max(ab) > 2 ** 1023          # an intermediate past the doubles
            if ab[0] > big or ab[1] > big:
                ab, sc = [x / big for x in ab], sc / big
        if ab[2] > big or ab[3] > big:
            sc = sc / big
        cancel = max((abs(mp.mpf(lam)) + abs(mp.mpf(x))) / abs(aj) for x, aj in zip(p, a))
        cheap = T * (abs(t) + 2) / abs(t * t - 4) * cancel
        u = None
        if abs(t) > 2:
            u = [(M[0, 0] - M[1, 1] + s * mp.sqrt(t * t - 4)) / (2 * M[0, 1])]
            for j in range(len(p) - 1):
                u.append(-r[j] / (a[j] + u[j]))
        return {"t": t, "T": T, "cheap": cheap, "u": u, "sc": sc, "over": over}


@claim("paths.block_slopes", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/kernels_block.py: _slopes (traces, condition estimates, slopes, statuses)",
       statement="the block kernel's slopes (N={N}) on a block of twelve unlike members -- traces of both signs "
                 "(both transport directions in one block), rescaled by 2**-400 and 2**-800, overflowing, in a band, "
                 "decided only by the sharp condition, by neither, one already failed -- for s = +-1, and on "
                 "sub-blocks with 0, 1, B - 1 and B members transported forward: each member's trace, condition "
                 "estimate, scale, status and every slope against the definition at 50 digits from its doubles, "
                 "within 16 N eps of the trace's rounding scale, 4 N eps of the estimate, 32 N eps (1 + k_t) of each "
                 "slope")
def block_slopes(N: int) -> Outcome:
    from ..numeric.core.condition import sharp_trace_kappa
    from ..numeric.core.limits import ILLCOND, KAPPA_MAX, OK, RANGE, TRACE1, TRACE2
    from ..numeric.float64.kernels_block import _slopes

    bad: list[str] = []
    members = [(np.array(p[:N]), [math.exp(q[(j + 1) % N] - q[j]) for j in range(N)], lam, lo)
               for p, q, lam, lo in SLOPE_MEMBERS]
    refs = {s: [_slope_reference(tuple(p), r, lam, lo, s) for p, r, lam, lo in members] for s in (1, -1)}
    with np.errstate(all="ignore"):
        sharp = [sharp_trace_kappa(p, np.array(r), lam, lo) for p, r, lam, lo in members]
    preset = 6                              # a member already failed (TRACE2): its status stays
    ran = 0
    for s in (1, -1):
        fwd = [k for k in range(len(members)) if (refs[s][k]["t"] < 0) == (s > 0)]
        back = [k for k in range(len(members)) if k not in fwd]
        # the whole block; forward-only and backward-only; every forward member and one backward (B - 1 forward),
        # one forward member and every backward one (1 forward)
        for block in (list(range(len(members))), fwd, back, fwd + back[:1], fwd[:1] + back):
            B = len(block)
            P, R = (np.array([members[k][i] for k in block]).T.copy() for i in (0, 1))
            lam, lo = (np.array([members[k][i] for k in block]) for i in (2, 3))
            u, tmp, Ab = np.full((N, B), np.nan), np.empty((N, B)), np.empty((4, B))
            A, Bm, C, D, u1, tt, kt, Kn, Kd, sc = (np.empty(B) for _ in range(10))
            fw = np.empty(B, np.int64)
            status = np.array([TRACE2 if k == preset else OK for k in block], np.int64)
            with np.errstate(all="ignore"):
                _slopes(P, R, lam, lo, s, u, tmp, A, Bm, C, D, u1, fw, status, TRACE1, Ab, tt, kt, Kn, Kd, sc)
            ran += 1
            for i, k in enumerate(block):
                ref = refs[s][k]
                tag = f"s = {s}, member {k} (block of {B})"
                scale = sc[i]
                if ref["over"]:                         # the scaled monodromy overflows: a range problem
                    if int(status[i]) != RANGE:
                        bad.append(f"{tag}: status {int(status[i])} where the monodromy overflows, RANGE wanted")
                    continue
                if mp.mpf(scale) != ref["sc"]:
                    bad.append(f"{tag}: scale {scale!r}, the rescaling rule gives {mp.nstr(ref['sc'], 6)}")
                    continue
                tr = mp.mpf(tt[i]) / mp.mpf(scale)
                if not abs(tr - ref["t"]) <= 16 * N * EPS * ref["T"]:
                    bad.append(f"{tag}: trace {mp.nstr(tr, 17)}, definition {mp.nstr(ref['t'], 17)}")
                cheap, inband = float(ref["cheap"]), abs(ref["t"]) <= 2   # the band, else the two tiers decide
                want_kt = cheap if inband or cheap <= KAPPA_MAX else min(cheap, sharp[k])
                want_status = TRACE2 if k == preset else TRACE1 if inband else OK if want_kt <= KAPPA_MAX else ILLCOND
                if int(status[i]) != want_status:
                    bad.append(f"{tag}: status {int(status[i])}, the definition gives {want_status}")
                if not abs(kt[i] - want_kt) <= 4 * N * EPS * want_kt * (1 + (want_kt if not inband else 0)):
                    bad.append(f"{tag}: condition estimate {kt[i]!r}, definition {want_kt!r}")
                if want_status == OK:
                    tol = 32 * N * EPS * (1 + want_kt)
                    errs = [abs(mp.mpf(u[j, i]) - ref["u"][j]) / abs(ref["u"][j]) if math.isfinite(u[j, i])
                            else mp.inf for j in range(N)]
                    if not max(errs) <= tol:
                        bad.append(f"{tag}: slopes {u[:, i].tolist()}, definition "
                                   f"{[mp.nstr(x, 12) for x in ref['u']]} (relative {mp.nstr(max(errs), 3)})")
    detail = f"{len(members)} members, {ran} calls; traces {', '.join(mp.nstr(r['t'], 4) for r in refs[1])}."
    if bad:
        return _failed("numeric: the block kernel's _slopes vs the definition at 50 digits", bad, detail)
    return Outcome("verified", "numeric: the block kernel's _slopes vs the definition at 50 digits (member by "
                   "member)", evidence="sampled", detail=detail,
                   printed="every member's trace, estimate, status and slopes as defined")


# --------------------------------------------------------------------------- paths.block_driver

_PAPER_P, _PAPER_Q = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
#: paths.block_driver: (p, q, lam0, mu) per member, in blocks of four: a block of unlike members (OK, lam1 in a
#: band -- the free chain --, lam1 and lam2 in different gaps, lam2 in a band), a block of four OK members (the
#: paper's state, its mirror, far left, a small mu; parameters whose sums are not exact, so that the low parts of
#: the spectral parameters differ), and a last, partial block of failing ones (ill-conditioned, p_1 = -1e300,
#: q_2 - q_1 = -701 with every other distance within 700); every mu differs from its neighbours'
DRIVER_MEMBERS = ((_PAPER_P, _PAPER_Q, 10.0, 5.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), -2.5, 3.0),
                  (_PAPER_P, _PAPER_Q, -15.0, 5.0), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), 2.5, 2.0),
                  (_PAPER_P, _PAPER_Q, 10.1, 4.9), ((20.0, -10.0, -1.0), _PAPER_Q, -10.3, 4.7),
                  (_PAPER_P, _PAPER_Q, -30.1, 2.2), (_PAPER_P, _PAPER_Q, 25.0, 0.3),
                  (_PAPER_P, _PAPER_Q, 15.0, 5.0), ((-1e300, 0.0, 0.0), (0.0, 0.0, 0.0), 10.0, 5.5),
                  (_PAPER_P, (0.0, -701.0, -1.0), 10.0, 5.2))


def _literal_codes(p: tuple, q: tuple, lam0: float, mu: float) -> str:
    """What the definitions say of a member before any step (30 digits): ``RANGE`` where a neighbour distance
    passes ``MAX_DQ_FLOAT64`` or some ``|p_j|``, ``|q_j|`` is at least ``1e300`` (the kernels' range, their module
    docstring), ``TRACE1`` / ``TRACE2`` where ``|tr L(lam0 +- mu)| <= 2``, ``POSITIVITY`` where the two traces
    differ in sign, else ``open`` (OK or ill-conditioned: the estimate decides)."""
    from ..numeric.core.limits import MAX_DQ_FLOAT64
    from ..reference.literal import literal_trace

    N = len(p)
    if any(abs(q[(j + 1) % N] - q[j]) > MAX_DQ_FLOAT64 or abs(p[j]) >= 1e300 or abs(q[j]) >= 1e300
           for j in range(N)):
        return "RANGE"
    with mp.workdps(30):
        t1 = literal_trace(mp.mpf(lam0) + mu, p, q)
        t2 = literal_trace(mp.mpf(lam0) - mu, p, q)
    if abs(t1) <= 2:
        return "TRACE1"
    if abs(t2) <= 2:
        return "TRACE2"
    return "POSITIVITY" if (t1 < 0) != (t2 < 0) else "open"


@claim("paths.block_driver", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/kernels_block.py: run_block, ensemble, _anchor (the block driver); kernels.py: "
             "orbit, _anchor1 (the single-state driver)",
       statement="the block ensemble (backend 'python', N={N}) of eleven members in blocks of four -- every "
                 "status code, a block of unlike members, one of OK members, a partial one of failing members -- "
                 "ANCHOR + 1 steps stored every 2nd step with the low parts, both branches: each member's status "
                 "is the single-state orbit's and the definitions' "
                 "(codes 1-4 from the literal traces and distances at 30 digits), every stored row of an OK "
                 "member equals the single-state orbit's bit for bit (also with N columns of Q: no low parts), and "
                 "the paper's member's first stored state (branch 1) (step 2) is the literal map's at 40 digits within "
                 "16 N n eps S")
def block_driver(N: int) -> Outcome:
    from ..numeric.core import limits
    from ..numeric.float64.jit import kernel
    from ..numeric.float64.kernels import ANCHOR, orbit_rows, python_orbit, stored_steps
    from ..reference.literal import reference_step

    ensemble, _ = kernel("ensemble", "python")
    n, every, block = ANCHOR + 1, 2, 4
    M = len(DRIVER_MEMBERS)
    P0, Q0, lam0, mu = (np.array([m[i] for m in DRIVER_MEMBERS]) for i in range(4))
    rows = orbit_rows(n, every)
    codes = [_literal_codes(*m) for m in DRIVER_MEMBERS]
    bad, seen = [], []
    for b in (1, -1):
        P, Q = np.full((rows, M, N), np.nan), np.full((rows, M, 2 * N), np.nan)
        status = np.full(M, -1, np.int64)
        with np.errstate(all="ignore"):
            ensemble(P0, Q0, lam0 + mu, lam0 - mu, 2 * mu, b, n, every, ANCHOR, block, P, Q, status)
        for k, (p, q, l0, m) in enumerate(DRIVER_MEMBERS):
            Ps, Qs = np.full((rows, N), np.nan), np.full((rows, 2 * N), np.nan)
            st = python_orbit(np.array(p), np.array(q), l0 + m, l0 - m, 2 * m, b, n, every, ANCHOR, Ps, Qs)
            want = codes[k]
            tag = f"branch {b}, member {k} ({want})"
            if int(status[k]) != st or (want != "open" and st != getattr(limits, want)) or \
                    (want == "open" and st not in (limits.OK, limits.ILLCOND)):
                bad.append(f"{tag}: block status {int(status[k])}, single-state {st}")
                continue
            if not (np.array_equal(P[0, k], p) and np.array_equal(Q[0, k, :N], q) and not Q[0, k, N:].any()):
                bad.append(f"{tag}: the first stored row is not the initial state")
            if st != limits.OK:
                continue
            if not (np.array_equal(P[:, k], Ps) and np.array_equal(Q[:, k], Qs)):
                diff = [s for i, s in enumerate(stored_steps(n, every))
                        if not (np.array_equal(P[i, k], Ps[i]) and np.array_equal(Q[i, k], Qs[i]))]
                bad.append(f"{tag}: the stored rows of steps {diff[:5]} differ from the single-state orbit's")
                continue
            if k != 0 or b != 1:    # the literal map for the first member (the single-state orbit: paths.kernels)
                continue
            with mp.workdps(40):
                pr, qr = list(p), list(q)
                for _ in range(every):
                    pr, qr = reference_step(pr, qr, l0, m, branch=b)
                S = max(1.0, *(abs(float(x)) for x in pr + qr))
                err = max(abs(mp.mpf(P[1, k, j]) - pr[j]) for j in range(N))
                err = max(err, *(abs(mp.mpf(Q[1, k, j]) + mp.mpf(Q[1, k, N + j]) - qr[j]) for j in range(N)))
            if not err <= 16 * N * every * EPS * S:
                bad.append(f"{tag}: step {every} off the literal map by {mp.nstr(err, 3)} (bound "
                           f"{16 * N * every * EPS * S:.3g})")
            seen.append(f"b = {b}, member {k}: {mp.nstr(err, 2)}")
        if b == 1:
            # outQ of N columns: no low parts, the positions the same bits (orbit's docstring), first block only
            Pn, Qn, sn = np.full((rows, block, N), np.nan), np.full((rows, block, N), np.nan), np.zeros(block, np.int64)
            with np.errstate(all="ignore"):
                ensemble(P0[:block], Q0[:block], (lam0 + mu)[:block], (lam0 - mu)[:block], 2 * mu[:block], b, n,
                         every, ANCHOR, block, Pn, Qn, sn)
            ok = [k for k in range(block) if status[k] == limits.OK]
            if not (np.array_equal(sn, status[:block]) and np.array_equal(Pn[:, ok], P[:, ok])
                    and np.array_equal(Qn[:, ok], Q[:, ok, :N])):
                bad.append("the ensemble without low parts differs from the one with them")
        seen.append(f"branch {b} statuses {status.tolist()}")
    detail = "; ".join(seen) + "."
    if bad:
        return _failed("numeric: the block ensemble vs the single-state orbit and the literal map", bad, detail)
    return Outcome("verified", "numeric: the block ensemble's driver vs the single-state orbit (bit for bit) and the "
                   "literal map (40 digits)", evidence="sampled", detail=detail,
                   printed="every member's status and stored rows as the single-state orbit's")
