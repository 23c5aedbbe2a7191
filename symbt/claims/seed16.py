r"""Lines the claims did not reach (issue 21, seed 16: ``codegen.kernels:166``, ``context:178``, ``step:367``,
``kernels:320``, and the input validation no claim ran).

* ``shipped.loop_phi_grad.n5`` -- the loop form's (``N >= 4``) gradient of the real :math:`\Phi`, ``phi_grad``
  (float64) and ``phi_grad_mp`` (mpmath, 30 digits), against central differences of
  :func:`symbt.reference.spectral.phi_real` (the literal traces) at 40 digits -- not the formula
  :math:`\partial_x\Phi = -b\,(t_{1,x}/\sqrt{t_1^2-4} + t_{2,x}/\sqrt{t_2^2-4})` the loop form prints.  The
  reference is checked against itself (:func:`~symbt.reference.spectral.phi_gradient`, the trace's exact
  gradient: another route, within ``1e-30``).  Only the closed forms (``N = 2, 3``) had their gradient checked by
  a default claim (``codegen.phi_grad``).

  float64's bound, per component ``x``: each term ``T_i = t_{i,x}/\sqrt{t_i^2-4}`` carries the rounding of two
  products of ``2 x 2`` matrices over ``N`` sites, ``(4N + 1) u`` times their absolute form -- ``|t_x|_abs <=
  |t|_abs/|a_j|`` for ``x = p_j`` (the derivative replaces ``a_j`` by 1 in one factor), ``<= 2 |t|_abs`` for
  ``x = q_j`` (two ratios ``r``) -- and of the square root of ``t^2 - 4``, amplified by ``t^2/(t^2 - 4)``; then
  ``4 u |d_x Phi|`` for the quotients and the sum:

  .. math:: |\mathrm{err}_x| \le u \Big(\sum_i (4N+1)\Big(\frac{|t_{i,x}|_{abs}}{\sqrt{t_i^2-4}}
            + |T_i| \frac{t_i^2}{t_i^2-4}\frac{|t_i|_{abs}}{|t_i|}\Big)\Big) + 4u\,|\partial_x\Phi|.
* ``paths.symmetric_monodromy.n2`` -- a state whose monodromy has ``A = D`` *exactly in float64* at one spectral
  parameter, so ``A - D``, whose sign picks the root formula without cancellation (``k = (A - D) + sgn(A - D) g``),
  is zero: ``p = (1, r_1 - r_2)``, ``q = (1/4, 0)``, ``r_1 = e^{-1/4}``, ``r_2 = e^{1/4}`` (doubles; ``r_1 - r_2``
  is exact by Sterbenz's lemma) at ``lam = 0``, where ``A = (r_1 - r_2) 1 - r_1 = -r_2 = D`` in floating point and
  ``tr = -2 r_2`` (a gap); ``lam0 = -1/4``, ``mu = +-1/4`` puts ``lam1`` or ``lam2`` there and the other at
  ``-1/2`` (the same gap), both branches.  Every float64 route -- ``bt_step`` with ``backend="python"``,
  ``"numpy"``, ``"auto"`` (the fused kernel, numba-free), a batch of two, ``bt_orbit`` one state and an ensemble
  (the block kernel, in plain Python) -- returns the same bits (documented: one order of operations) and is the
  literal map within ``16 N u S_i`` (``shipped.step``'s bound), as is the general path of the orbit (numpy rows;
  its positions in double-double, so other last bits).
* ``shipped.guard_boundary.n{2,3}`` -- the shipped closed form's conditioning guard against the estimate it
  prints, written separately in :func:`~symbt.numeric.float64.kernels.cheap_kernels` (the fused step without the
  sharp tier): on the free chain (``p = q = 0``, a band edge at ``lam = 2``) the kernel's status flips from
  ``ILLCOND`` to ``OK`` at some ``lam2 = 2 + delta`` (bisection); ``toda{N}.bt_step`` refuses at ``delta / 1.02``
  and at ``delta 1.02`` returns the literal map within ``16 N u S_i`` (the two estimates round differently; the
  estimate moves ~2 % over that margin).
* ``library.input_kinds`` -- the public numeric entry points (``bt_step``, ``bt_orbit``, ``phi``,
  ``spectral_trace``, ``invariants``, ``flow_coefficients``, ``FlowField``) on malformed input: text in every
  form (str, numpy strings, bytes, an object array or a nested list holding text), complex input in every form,
  dates (numpy would cast them to day counts), a NaN or an inf in one member of a batch of 100 -- each refused
  with :class:`~symbt.numeric.InvalidInputError` naming the cause; object, int and float32 arrays and int lists
  of the same numbers give the float arrays' result bit for bit, an object array of mpf the mpf lists'
  (``bt_step``, ``flow_coefficients``, which gives zeros at ``mu = 0`` in either arithmetic).
  ``certified_orbit``, which takes its input exactly, reads decimal strings and Fractions as the numbers they
  name (the float result bit for bit), refuses bytes, dates, nesting, complex and non-finite values, one site and
  unequal lengths by name, and at two sites encloses the literal step.
"""
from __future__ import annotations

import math
from typing import Any

import mpmath as mp
import numpy as np

from ._shipped import scale_parts, scaled
from .base import Outcome, Parts, claim, failed
from .seed13 import LOOP_STATE, _abs_trace

#: shipped.loop_phi_grad: (lam0, mu) with lam0 +- mu in the state's outer gaps (|tr| >= 3 there), of both signs
#: of the traces and both orders of the pair
PHI_PAIRS = ((8.5, 2.5), (-5.0, 2.0), (1.25, -9.75), (-0.5, 7.5))


def _reference_gradient(p: Any, q: Any, lam0: float, mu: float, b: int) -> list[mp.mpf]:
    """``d Phi / d(p, q)`` by central differences of ``phi_real`` (current precision)."""
    from ..reference.spectral import phi_real

    xs = [mp.mpf(v) for v in p + q]
    N = len(p)

    def phi(*x: Any) -> Any:
        return phi_real(list(x[:N]), list(x[N:]), mp.mpf(lam0), mp.mpf(mu), b)

    return [mp.diff(phi, xs, tuple(int(i == k) for i in range(2 * N))) for k in range(2 * N)]


@claim("shipped.loop_phi_grad", equation="toda{N}.phi_grad", source_equation="newkmu", scene="shipped",
       sizes=(5,), parts=scale_parts,
       where="symbt codegen --n {N}: toda{N}.py (loop form): phi_grad, phi_grad_mp",
       statement="the loop form's gradient of the real Phi (N={N}; float64, and mpmath at 30 digits) at 4 pairs "
                 "(lam0, mu) in the outer gaps, both branches = central differences of phi_real (the literal "
                 "traces) at 40 digits: float64 within the products' condition carried through the square roots "
                 "(module docstring), mpmath within 1e-25 of the largest term; the reference = phi_gradient to 1e-30")
def loop_phi_grad(N: int, parts: Parts) -> Outcome:
    from ..reference.literal import literal_trace
    from ..reference.spectral import phi_gradient
    from ..reference.trace import trace_gradient
    from .shipped_emitted import emitted_module

    mod = emitted_module(N)
    p, q = (list(v) for v in LOOP_STATE)
    u = mp.mpf(2) ** -53
    s = parts.printed["scale"]                      # route output x scale = reference (scale = 1)
    bad: list[str] = []
    worst = mp.mpf(0)
    for lam0, mu in PHI_PAIRS:
        for b in (1, -1):
            gp, gq = mod.phi_grad(np.array(p), np.array(q), lam0, mu, b)
            got64 = [float(v) * s for v in list(gp) + list(gq)]
            with mp.workdps(30):
                P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
                mp_p, mp_q = mod.phi_grad_mp(P, Q, mp.mpf(lam0), mp.mpf(mu), b)
                got_mp = scaled(list(mp_p) + list(mp_q), s)
            with mp.workdps(40):
                ref = _reference_gradient(p, q, lam0, mu, b)
                ep, eq = phi_gradient(p, q, mp.mpf(lam0), mp.mpf(mu), b)
                if not max(abs(a - c) for a, c in zip(ref, ep + eq)) <= mp.mpf(10) ** -30 * max(map(abs, ref)):
                    bad.append(f"(lam0, mu, b) = ({lam0}, {mu}, {b}): the reference disagrees with phi_gradient")
                    continue
                terms, bound = [mp.mpf(0)] * (2 * N), [mp.mpf(0)] * (2 * N)
                for lam in (lam0 + mu, lam0 - mu):
                    t = literal_trace(lam, p, q)
                    g = mp.sqrt(t * t - 4)
                    tabs = _abs_trace(lam, p, q)
                    dp, dq = trace_gradient(lam, p, q)      # the polynomial's: a scale for the bound only
                    dt = dp + dq
                    for k in range(2 * N):
                        dabs = tabs / abs(lam + p[k]) if k < N else 2 * tabs
                        T = abs(dt[k]) / g
                        terms[k] = max(terms[k], T)
                        bound[k] += (4 * N + 1) * (dabs / g + T * t * t / (t * t - 4) * tabs / abs(t))
                for k in range(2 * N):
                    tol = u * (bound[k] + 4 * abs(ref[k]))
                    err = abs(mp.mpf(got64[k]) - ref[k])
                    worst = max(worst, err / tol)
                    if not err <= tol:
                        bad.append(f"float64 (lam0, mu, b) = ({lam0}, {mu}, {b}), component {k}: "
                                   f"{mp.nstr(err, 3)} (bound {mp.nstr(tol, 3)})")
                    if not abs(got_mp[k] - ref[k]) <= mp.mpf(10) ** -25 * terms[k]:
                        bad.append(f"mpmath (lam0, mu, b) = ({lam0}, {mu}, {b}), component {k}: "
                                   f"{mp.nstr(got_mp[k], 12)} vs {mp.nstr(ref[k], 12)}")
    detail = (f"{len(PHI_PAIRS)} pairs x 2 branches x {2 * N} components; worst float64 error "
              f"{mp.nstr(worst, 3)} of its bound.")
    if bad:
        return failed("the loop form's phi_grad vs central differences of phi_real",
                      detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", "numeric: the emitted loop form's phi_grad vs central differences of phi_real "
                   "(literal traces, 40 digits)", evidence="sampled", n_scope=[N], detail=detail,
                   printed="within the products' condition")


def _tie_state() -> tuple:
    """``(p, q)``: ``A = D`` exactly in float64 at ``lam = 0`` (module docstring)."""
    r1, r2 = math.exp(-0.25), math.exp(0.25)
    return (1.0, r1 - r2), (0.25, 0.0)


@claim("paths.symmetric_monodromy", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       sizes=(2,),
       where="symbt/numeric/core/context.py: FLOAT.align at A - D = 0; the float64 routes of bt_step and bt_orbit",
       statement="at p = (1, r1 - r2), q = (1/4, 0), r1 = e^(-1/4), r2 = e^(1/4) (N={N}), whose monodromy at "
                 "lam = 0 has A = D exactly in float64, lam0 = -1/4, mu = +-1/4, both branches: bt_step's python, "
                 "numpy and fused routes, a batch, bt_orbit and the block kernel's ensemble return the same bits, "
                 "the literal map within 16 N u S_i, as is the general orbit's (numpy) result")
def symmetric_monodromy(N: int) -> Outcome:
    from ..numeric import bt_orbit, bt_step
    from ..numeric.core.context import FLOAT
    from ..numeric.core.step import monodromy
    from ._shipped import EPS, ratios, step_constant, step_ref, without_numba

    p, q = _tie_state()
    r = [np.exp(q[1] - q[0]), np.exp(q[0] - q[1])]
    A, _, _, D, _ = monodromy(FLOAT, [0.0 + v for v in p], r)
    if not A == D:
        return failed("the tie state", detail=f"A = {A!r}, D = {D!r} at lam = 0: not a tie in float64")
    pa, qa = np.array(p), np.array(q)
    bad: list[str] = []
    worst = 0.0
    with without_numba():
        for mu in (0.25, -0.25):
            for b in (1, -1):
                outs: dict[str, tuple] = {}
                for be in ("python", "numpy", "auto"):
                    P, Q = bt_step(pa, qa, -0.25, mu, branch=b, backend=be)
                    outs[be] = tuple(P) + tuple(Q)
                P, Q = bt_step(np.array([pa, pa]), np.array([qa, qa]), -0.25, mu, branch=b, backend="numpy")
                outs["batch"] = tuple(P[1]) + tuple(Q[1])
                P, Q = bt_orbit(pa, qa, -0.25, mu, 1, branch=b)
                outs["orbit"] = tuple(P[-1]) + tuple(Q[-1])
                P, Q = bt_orbit(np.array([pa, pa]), np.array([qa, qa]), -0.25, mu, 1, branch=b, backend="python")
                outs["ensemble"] = tuple(P[-1][1]) + tuple(Q[-1][1])
                differ = [k for k, v in outs.items() if v != outs["python"]]
                if differ:
                    bad.append(f"mu = {mu}, b = {b}: {', '.join(differ)} differ from the python route")
                # the general path of the orbit (numpy rows, double-double positions: other bits, the same bound)
                P, Q = bt_orbit(np.array([pa, pa]), np.array([qa, qa]), -0.25, mu, 1, branch=b, backend="numpy")
                ref = step_ref((p, q, -0.25, mu), b)
                for name, x in (("python", outs["python"]), ("general orbit", tuple(P[-1][1]) + tuple(Q[-1][1]))):
                    ratio, _ = ratios(x, ref.x, ref.S, EPS / 2, step_constant(N))
                    worst = max(worst, ratio)
                    if not ratio <= 1.0:
                        bad.append(f"mu = {mu}, b = {b}, {name}: {ratio:.3g} of the bound from the literal map")
    detail = f"2 (lam0, mu) x 2 branches x 7 routes; worst error {worst:.3g} of 16 N u S_i."
    if bad:
        return failed("the float64 routes at A = D", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: every float64 route at an exact A = D, bit for bit (consistency) and vs "
                   "the literal map", evidence="sampled", n_scope=[N], residual=worst, detail=detail)


#: shipped.guard_boundary: mu, and the relative margin in delta = lam2 - 2 on either side of the kernel's flip (the
#: two estimates round differently; the estimate moves ~2 % there, far above the rounding of either)
GUARD_MU, GUARD_MARGIN = 0.5, 1.02


def _cheap_status(N: int, delta: float) -> int:
    """The status of the fused float64 step with the cheap condition estimate only (``cheap_kernels``: the
    estimate the emitted guard prints) on the free chain ``p = q = 0``, ``lam2 = 2 + delta`` (a band edge at 2),
    ``lam1 = lam2 + 2 mu``, branch +1."""
    from ..numeric.float64.kernels import cheap_kernels

    lam2 = 2.0 + delta
    w = [np.empty(N) for _ in range(4)]
    return int(cheap_kernels()["step"](np.zeros(N), np.ones(N), (np.ones(N), np.zeros(N)), lam2 + 2 * GUARD_MU,
                                       lam2, 2 * GUARD_MU, 1, *w, np.zeros(4)))


def cheap_flip(N: int) -> float | None:
    """``delta`` where :func:`_cheap_status` turns from ``ILLCOND`` (nearer the band edge) to ``OK``, by 60
    bisections in log between 1e-12 and 1e-2; ``None`` if the ends do not straddle it (no flip there)."""
    from ..numeric.core.limits import ILLCOND, OK

    lo, hi = 1e-12, 1e-2
    if (_cheap_status(N, lo), _cheap_status(N, hi)) != (ILLCOND, OK):
        return None
    for _ in range(60):
        mid = float(np.sqrt(lo * hi))
        lo, hi = (mid, hi) if _cheap_status(N, mid) == ILLCOND else (lo, mid)
    return hi


@claim("shipped.guard_boundary", equation="toda{N}.bt_step", source_equation="imptransf", scene="shipped",
       sizes=(2, 3), parts=scale_parts,
       where="symbt/generated/toda{N}.py: bt_step's conditioning guard; symbt/numeric/float64/kernels.py: "
             "cheap_kernels (the same estimate, written separately)",
       statement="on the free chain (p = q = 0, N={N}, lam2 = 2 + delta, mu = 1/2) the cheap estimate of the fused "
                 "float64 step flips from ILLCOND to OK at delta with delta KAPPA_MAX in (1e-9, 1e3); the shipped "
                 "toda{N}.bt_step refuses (IllConditionedError) at delta / 1.02 and at delta 1.02 returns the "
                 "literal map within 16 N u S_i")
def guard_boundary(N: int, parts: Parts) -> Outcome:
    import importlib

    from ..numeric.core.limits import ILLCOND, KAPPA_MAX, OK
    from ._shipped import EPS, ratios, step_constant, step_ref

    flip = cheap_flip(N)
    if flip is None:
        ends = (_cheap_status(N, 1e-12), _cheap_status(N, 1e-2))
        return failed("the cheap estimate on the free chain", detail=f"statuses {ends} at delta = 1e-12, 1e-2 "
                      f"(want ILLCOND = {ILLCOND}, OK = {OK}: the estimate must flip in between)")
    mod = importlib.import_module(f"symbt.generated.toda{N}")     # the shipped file (codegen.check: = its render)
    bad: list[str] = []
    if not 1e-9 < flip * KAPPA_MAX < 1e3:
        bad.append(f"the flip delta = {flip:.3g} is not the 2**24 limit's (delta KAPPA_MAX = {flip * KAPPA_MAX:.3g})")
    z = (0.0,) * N
    inside = (z, z, 2.0 + flip * GUARD_MARGIN + GUARD_MU, GUARD_MU)
    outside = (z, z, 2.0 + flip / GUARD_MARGIN + GUARD_MU, GUARD_MU)
    try:
        mod.bt_step(np.array(outside[0]), np.array(outside[1]), outside[2], outside[3], 1)
        bad.append(f"bt_step stepped at delta = {flip / GUARD_MARGIN:.4g} (want IllConditionedError)")
    except mod.IllConditionedError:
        pass
    ratio = float("nan")            # no step inside (refused: reported above)
    try:
        P, Q = mod.bt_step(np.array(inside[0]), np.array(inside[1]), inside[2], inside[3], 1)
        ref = step_ref(inside, 1)
        ratio, _ = ratios(scaled(list(P) + list(Q), parts.printed["scale"]), ref.x, ref.S, EPS / 2,
                          step_constant(N))
    except mod.NumericRangeError as exc:
        bad.append(f"bt_step refused at delta = {flip * GUARD_MARGIN:.4g}: {exc}")
    if not math.isnan(ratio) and not ratio <= 1.0:
        bad.append(f"bt_step at delta = {flip * GUARD_MARGIN:.4g}: {ratio:.3g} of 16 N u S_i from the literal map")
    detail = f"flip at delta = {flip:.4g} (delta KAPPA_MAX = {flip * KAPPA_MAX:.3g}); inside: {ratio:.3g} of the bound."
    if bad:
        return failed("the emitted guard vs the cheap estimate's flip", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the emitted guard at the cheap estimate's flip (consistency of two "
                   "implementations), the step inside vs the literal map", evidence="sampled", n_scope=[N],
                   residual=ratio, detail=detail, printed="refused outside, the literal map inside")


#: library.input_kinds: the paper's state as each kind of input the public entry points refuse
_P, _Q = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)


def _refused_kinds() -> list[tuple[str, Any, str]]:
    """``(kind, p, words)``: malformed ``p`` and the words the refusal must contain."""
    text, cplx = "not text or a mapping", "complex input is not supported"
    return [("a list of str", [str(v) for v in _P], text), ("a numpy str array", np.array([str(v) for v in _P]), text),
            ("bytes in a list", [b"-20", 10.0, 1.0], text),
            ("an object array holding str", np.array(["-20", 10.0, 1.0], dtype=object), text),
            ("a nested list holding str", [[-20.0, "10", 1.0]], text),
            ("a Python complex", [-20 + 0j, 10.0, 1.0], cplx),
            ("a numpy complex array", np.array(_P, dtype=complex), cplx), ("mpc", [mp.mpc(v) for v in _P], cplx),
            ("an object array holding complex", np.array([-20 + 1j, 10.0, 1.0], dtype=object), cplx)]


def _entry_points() -> dict[str, Any]:
    """The public numeric entry points as functions of ``(p, q)`` (the paper's lam0 = 10, mu = 5)."""
    from ..numeric import FlowField, bt_orbit, bt_step, flow_coefficients, invariants, phi, spectral_trace

    return {"bt_step": lambda p, q: bt_step(p, q, 10.0, 5.0), "bt_orbit": lambda p, q: bt_orbit(p, q, 10.0, 5.0, 2),
            "phi": lambda p, q: phi(p, q, 10.0, 5.0), "spectral_trace": lambda p, q: spectral_trace(15.0, p, q),
            "invariants": invariants, "flow_coefficients": lambda p, q: flow_coefficients(p, q, 10.0, 5.0),
            "FlowField": lambda p, q: FlowField(p, q, 10.0, 5.0)}


def _certified_inputs(dates: np.ndarray) -> list[str]:
    """certified_orbit takes its input exactly: decimal strings and Fractions are numbers there (its docstring);
    bytes, dates, nesting, complex and non-finite values, one site and unequal lengths are refused, each by name;
    two sites enclose the literal step."""
    from fractions import Fraction

    from ..numeric import InvalidInputError, certified_orbit

    def run(p: Any) -> Any:
        return certified_orbit(p, list(_Q), 10.0, 5.0, 1)

    bad = []
    cplx = "complex input is not supported"
    for kind, p, words in (("bytes in a list", [b"-20", 10.0, 1.0], "unsupported number type bytes"),
                           ("a datetime64 array", dates, "unsupported number type"),
                           ("a nested list", [list(_P)], "flat sequence"),
                           ("a Python complex", [-20 + 0j, 10.0, 1.0], cplx), ("mpc", [mp.mpc(v) for v in _P], cplx),
                           ("an mpf inf", [mp.mpf(-20), mp.inf, mp.mpf(1)], "non-finite"),
                           ("a float nan", [-20.0, math.nan, 1.0], "non-finite")):
        try:
            run(p)
            bad.append(f"certified_orbit accepted {kind}")
        except InvalidInputError as exc:
            if words not in str(exc):
                bad.append(f"certified_orbit on {kind}: {exc}")
    for kind, p, q, words in (("one site", [1.0], [0.0], "N >= 2"), ("unequal lengths", list(_P), [0.0, 1.0],
                                                                            "equal lengths")):
        try:
            certified_orbit(p, q, 10.0, 5.0, 1)
            bad.append(f"certified_orbit accepted {kind}")
        except InvalidInputError as exc:
            if words not in str(exc):
                bad.append(f"certified_orbit on {kind}: {exc}")
    # two sites, the smallest lattice: an enclosure of the literal step (60 digits)
    from ..reference.literal import reference_step

    P2, Q2, Pr, Qr = certified_orbit([0.5, -0.25], [0.0, 0.5], 3.0, 0.5, 1)
    with mp.workdps(60):
        ref = reference_step([0.5, -0.25], [0.0, 0.5], 3.0, 0.5)
        if not all(abs(m - x) <= r for m, x, r in zip(list(P2[-1]) + list(Q2[-1]), ref[0] + ref[1],
                                                        list(Pr[-1]) + list(Qr[-1]))):
            bad.append("certified_orbit at N = 2 does not enclose the literal step")
    want = run(list(_P))
    for kind, p in (("decimal strings", [str(int(v)) for v in _P]), ("Fractions", [Fraction(int(v)) for v in _P]),
                    ("a numpy str array", np.array([str(int(v)) for v in _P]))):
        got = run(p)
        if any(list(a) != list(b) for a, b in zip(got, want)):
            bad.append(f"certified_orbit on {kind} differs from the same numbers as floats")
    # no precision admitted (prec above max_prec): "lohner" says so by name; "auto" records why Lohner gave up,
    # then the ball path (its own refusal)
    from ..numeric import NumericRangeError

    for method in ("lohner", "auto"):
        info: dict = {}
        try:
            certified_orbit(list(_P), list(_Q), 10.0, 5.0, 1, prec=200, max_prec=100, method=method, info=info)
            bad.append(f"certified_orbit(method={method!r}) with prec 200 > max_prec 100 returned")
        except NumericRangeError as exc:
            lohner_named = str(exc).startswith("certified orbit (Lohner):")
            fell_back = (info.get("method"), "max_prec = 100" in str(info.get("fallback", "")), info["passes"])
            if (lohner_named, fell_back) != ((True, (None, False, [])) if method == "lohner"
                                             else (False, ("ball", True, []))):
                bad.append(f"method={method!r}, no precision admitted: {exc}; info {info}")
    return bad


@claim("library.input_kinds", equation="bt_step", source_equation="imptransf", scene="library",
       where="symbt/numeric/core/inputs.py: float_array, _has_text, _is_complex, _kind, the finiteness test of "
             "prepare's batches; every public entry point",
       statement="bt_step, bt_orbit, phi, spectral_trace, invariants, flow_coefficients and FlowField refuse text "
                 "(str, numpy strings, bytes, an object array or a nested list holding text) and complex input "
                 "(Python, numpy, mpc, object) with InvalidInputError naming it; the batch entry points refuse a "
                 "NaN or an inf anywhere in a batch of 100 states; dates (datetime64) are refused, not as text; "
                 "certified_orbit takes decimal strings and Fractions exactly, refuses bytes, dates, nesting, "
                 "complex and non-finite values, one site and unequal lengths by name, and at N = 2 encloses the "
                 "literal step; with prec above max_prec it raises NumericRangeError, by the Lohner method's name "
                 "for method='lohner', after recording Lohner's refusal and trying the ball path for 'auto'; "
                 "object, int, float32 arrays and a list of int holding the same numbers give the float array's "
                 "result bit for bit, an object array of mpf the mpf list's (bt_step, flow_coefficients); "
                 "flow_coefficients at mu = 0 is zeros in either arithmetic; bt_orbit on mpf input repeats the "
                 "input at mu = 0 and is the literal orbit at mu = 1")
def input_kinds() -> Outcome:
    from ._shipped import without_numba

    with without_numba():               # the default run compiles no numba kernel (seconds on a cold cache)
        return _input_kinds()


def _input_kinds() -> Outcome:
    from ..numeric import InvalidInputError

    bad: list[str] = []
    entries = _entry_points()
    kinds = _refused_kinds()
    for name, f in entries.items():
        for kind, p, words in kinds:
            q = [list(_Q)] if kind.startswith("a nested") else list(_Q)
            try:
                f(p, q)
                bad.append(f"{name} accepted {kind}")
            except InvalidInputError as exc:
                if words not in str(exc):
                    bad.append(f"{name} on {kind}: {exc}")
            except Exception as exc:            # noqa: BLE001 -- an untyped error is what this claim looks for
                bad.append(f"{name} on {kind}: {type(exc).__name__}: {exc}")
    # dates are no numbers (numpy would cast them to days): refused as such, not as text
    dates = np.array(["2026-11-27"] * 3, dtype="datetime64[D]")
    for name, f in entries.items():
        for kind, p in (("a datetime64 array", dates), ("a list of datetime64", list(dates))):
            try:
                f(p, list(_Q))
                bad.append(f"{name} accepted {kind}")
            except InvalidInputError as exc:
                if "real numeric array" not in str(exc) or "text" in str(exc):
                    bad.append(f"{name} on {kind}: {exc}")
    P, Q = np.tile(_P, (100, 1)), np.tile(_Q, (100, 1))
    for bad_value in (math.inf, math.nan, -math.inf):
        Pb = P.copy()
        Pb[71, 2] = bad_value
        for name in ("bt_step", "bt_orbit", "phi", "spectral_trace", "invariants"):
            try:
                entries[name](Pb, Q)
                bad.append(f"{name} accepted {bad_value} in a batch of 100")
            except InvalidInputError as exc:
                if "finite" not in str(exc):
                    bad.append(f"{name} on {bad_value} in a batch: {exc}")
    bad += _certified_inputs(dates)
    floats = entries["bt_step"](np.array(_P), np.array(_Q))
    for kind, p in (("object", np.array(_P, dtype=object)), ("int", np.array(_P, dtype=np.int64)),
                    ("float32", np.array(_P, dtype=np.float32)), ("list of int", [int(v) for v in _P])):
        got = entries["bt_step"](p, np.array(_Q))
        if not all(np.array_equal(a, b) for a, b in zip(floats, got)):
            bad.append(f"bt_step on an {kind} array of the same numbers differs from the float arrays")
    with mp.workdps(30):
        mps = [mp.mpf(v) for v in _P], [mp.mpf(v) for v in _Q]
        objs = np.array(mps[0], dtype=object), np.array(mps[1], dtype=object)
        # mpmath orbits: mu = 0 repeats the input; mu = 1 moves it (the literal orbit, 1e-25)
        from ..numeric import bt_orbit
        from ..reference.literal import reference_step

        P0, _ = bt_orbit(*mps, mp.mpf(10), mp.mpf(0), 2)
        P1, Q1 = bt_orbit(*mps, mp.mpf(10), mp.mpf(1), 2)
        a, b = mps
        for _ in range(2):
            a, b = reference_step(a, b, mp.mpf(10), mp.mpf(1))
        if P0[-1] != mps[0] or not max(abs(x - y) for x, y in zip(P1[-1] + Q1[-1], a + b)) <= mp.mpf(10) ** -25:
            bad.append("bt_orbit on mpf input: mu = 0 does not repeat the input, or mu = 1 is not the literal orbit")
        for name in ("bt_step", "flow_coefficients"):
            want, got = entries[name](*mps), entries[name](*objs)
            flat_w, flat_g = np.ravel(np.array(want, dtype=object)), np.ravel(np.array(got, dtype=object))
            if not (isinstance(flat_g[0], mp.mpf) and flat_g.tolist() == flat_w.tolist()):
                bad.append(f"{name} on object arrays of mpf differs from the mpf lists' result")
    # flow_coefficients documents zeros at mu = 0, in either arithmetic
    from ..numeric import flow_coefficients

    for args in ((list(_P), list(_Q), 10.0, 0.0), ([mp.mpf(v) for v in _P], [mp.mpf(v) for v in _Q], mp.mpf(10), 0)):
        c = flow_coefficients(*args)
        if len(c) != len(_P) or any(v != 0 for v in c):
            bad.append(f"flow_coefficients at mu = 0 ({type(args[0][0]).__name__}): {list(c)}")
    detail = (f"{len(entries)} entry points x {len(kinds) + 2} malformed kinds; 3 non-finite values in batches of "
              "100 for 5 batch entry points; object, int, float32 arrays, int lists, object arrays of mpf.")
    if bad:
        return failed("the documented input rules", detail="; ".join(bad[:5]) + ". " + detail)
    return Outcome("verified", "numeric: the public entry points on malformed and object inputs vs their documented "
                   "rules", evidence="sampled", n_scope=[3], detail=detail)
