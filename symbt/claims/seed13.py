r"""Lines the claims did not reach (issue 21, seeds 12-14: ``literal:276``, ``codegen.cli:81``/``:99``/``:125``,
``coefficients:132``, ``existence:73``, ``field:71``, ``kernels_block:257``, ``codegen.kernels:89``).

* ``library.guard_far_trace`` -- :func:`symbt.reference.literal.reference_step` chooses its guard digits from the
  larger of ``|tr L(lam1)|``, ``|tr L(lam2)|`` (the forward transport loses about twice their ``log10``).  At the
  paper-like state ``p = (0.3, -0.2, 0.1)``, ``q = (0, 0.5, 0.2)`` with ``lam1 = -2.5`` just below the lowest band
  (``|tr| ~ 6``) and ``lam2 = -1e13`` or ``-1e20`` in the same outer gap (``|tr L(lam2)| ~ |lam2|^3``; and the
  other way round, ``lam1 = -1e20``, whose trace ``~ -1e60`` is the larger in modulus and negative), both
  branches, 30 digits: the step with ``verify=True`` (the same computation with 25 more digits agrees to 30
  digits), and within ``1e-28`` of ``bt_step``'s mpmath backend at 60 digits (the scaled formulation of
  ``symbt.numeric``, another route) relative to ``1 + |x|``.  A guard sized from ``lam1`` alone loses every digit
  at ``lam2 = -1e20``.
* ``library.codegen_check`` -- ``symbt codegen --check`` (what CI pipelines run to fail on a drifted generated
  file) on copies of the shipped ``toda2.py`` and ``__init__.py``: exit 0, also written ``symbt codegen --
  --check``; exit 1 naming "edited by hand" after a one-byte edit, and "missing" after the file is deleted; with
  ``--project DIR`` naming a directory that is not a checkout, exit 2 naming it.
* ``paths.scaled_trace.n{4,5}`` -- :func:`symbt.numeric.flow.coefficients.scaled_trace` (the float64 transfer product
  of the flow quadrature, renormalised at every site; and its mpmath form) at 4 and 5 sites -- at N = 3 the
  recurrence's last ``B`` is never read, so no N <= 3 computation sees it -- against the literal trace at 40 digits,
  within ``(4N + 1) u |tr|_abs`` (``|tr|_abs``: the same product with every term positive, the product's condition).
* ``paths.band_edge.n3`` -- ``p = q = 0`` (``tr = lam**3 - 3 lam``, exact in binary) with ``lam0 +- mu`` exactly at a
  band edge (``|tr| = 2``): the interval verdict, ``bt_step`` (python, numpy, one state and a batch, mpmath) and the
  emitted ``toda3.bt_step`` all refuse, as the polynomial decides in exact rationals.
* ``paths.transfer_gradient.n{4,5}`` -- :func:`symbt.numeric.flow.field.transfer_gradient` on mpf entries against
  the exact prefix and suffix products at 70 digits (``shipped.field``'s reference; its prefix's last row and its
  suffix's middle are read only from four sites on).
* ``shipped.loop_integrand.n5`` -- the loop form's ``ck_integrand`` (float64 and mpmath; only ``bt_step`` of the loop
  form was checked by a default claim) against ``lam^k / sqrt(tr^2 - 4)`` with the literal trace, within the
  product's condition carried through the square root.
* ``paths.mixed_block.n3`` -- the block kernel's per-member condition tracking: ``paths.threshold``'s scans of the
  paper's state and of its mirror interleaved as one block, every member equal to its own in its scan's block and
  in a block of one; the paper's scan with each member beside a state that fails before the read-out (the sharp
  tier of a member must read its own early status, not its neighbour's).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import mpmath as mp
import numpy as np

from ._facts import Facts
from ._facts import facts_failed as _bad
from ._shipped import scale_parts, scaled
from .base import Outcome, Parts, claim, failed
from .shipped_condition_file import exact_products

#: library.guard_far_trace: the state, lam1 below the lowest band, lam2 far in the same outer gap
GUARD_STATE = (("0.3", "-0.2", "0.1"), ("0", "0.5", "0.2"))
GUARD_LAMBDAS = (("-2.5", "-1e13"), ("-2.5", "-1e20"), ("-1e20", "-2.5"))       # (lam1, lam2); the last mu < 0


@claim("library.guard_far_trace", equation="checker", scene="library",
       where="symbt/reference/literal.py: reference_step's guard digits (from both traces)",
       statement="reference_step (30 digits, verify=True) at p = (0.3, -0.2, 0.1), q = (0, 0.5, 0.2), lam1 = -2.5, "
                 "lam2 = -1e13 and -1e20 (|tr L(lam2)| ~ |lam2|^3 far above |tr L(lam1)| ~ 6), and the other way "
                 "round (lam1 = -1e20: tr L(lam1) ~ -1e60, the larger trace negative), both branches: "
                 "converged, and within 1e-28 (1 + |x|) of bt_step's mpmath backend at 60 digits")
def guard_far_trace() -> Outcome:
    from ..numeric import bt_step
    from ..reference.literal import reference_step

    bad, worst = [], mp.mpf(0)
    with mp.workdps(30):
        p, q = ([mp.mpf(v) for v in vs] for vs in GUARD_STATE)
        for l1, l2 in GUARD_LAMBDAS:
            lam1, lam2 = mp.mpf(l1), mp.mpf(l2)
            l0, m = (lam1 + lam2) / 2, (lam1 - lam2) / 2
            for b in (1, -1):
                try:
                    pt, qt = reference_step(p, q, l0, m, branch=b, verify=True)
                except AssertionError as exc:
                    bad.append(f"lam2 = {l2}, branch {b}: {exc}")
                    continue
                with mp.workdps(60):
                    pn, qn = bt_step(p, q, l0, m, branch=b, backend="mpmath")
                err = max(abs(x - y) / (1 + abs(y)) for x, y in zip(list(pt) + list(qt), list(pn) + list(qn)))
                worst = max(worst, err)
                if not err <= mp.mpf("1e-28"):
                    bad.append(f"lam2 = {l2}, branch {b}: {mp.nstr(err, 3)} from the mpmath backend")
    detail = f"{2 * len(GUARD_LAMBDAS)} steps converged; worst difference {mp.nstr(worst, 3)} relative to 1 + |x|."
    if bad:
        return failed("reference_step at a far trace", detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", "reference_step (verify=True) vs bt_step's mpmath backend (60 digits)",
                   evidence="sampled", n_scope=[3], detail=detail, printed="converged, within 1e-28")


@claim("library.codegen_check", equation="checker", scene="library",
       where="symbt codegen --check (symbt.codegen.cli.main on the installed derivations)",
       statement="symbt codegen --check --installed --n 2 --out DIR, DIR holding copies of the shipped toda2.py and "
                 "__init__.py: exit 0 (also after a leading '--'); with toda2.py edited by one byte: exit 1 and a "
                 "message 'edited by hand'; with toda2.py deleted: exit 1 and 'missing'; --project DIR: exit 2 "
                 "naming DIR, not a checkout")
def codegen_check() -> Outcome:
    import contextlib
    import io
    import shutil
    import tempfile
    from pathlib import Path

    from ..codegen.cli import main
    from ..codegen.files import DEFAULT_OUT

    got: Facts = []
    with tempfile.TemporaryDirectory(prefix="symbt-codegen-check-") as tmp:
        for name in ("toda2.py", "__init__.py"):
            shutil.copy(DEFAULT_OUT / name, tmp)
        module = Path(tmp) / "toda2.py"

        def run(*lead: str) -> tuple[int, str]:
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                code = main([*lead, "--check", "--installed", "--n", "2", "--out", tmp])
            return code, err.getvalue()

        got.append(("the shipped files", run()[0], 0))
        got.append(("the shipped files, `symbt codegen -- --check`", run("--")[0], 0))
        module.write_text(module.read_text(encoding="utf-8") + " ", encoding="utf-8")
        code, msg = run()
        got.append(("toda2.py edited by hand", (code, "edited by hand" in msg), (1, True)))
        module.unlink()
        code, msg = run()
        got.append(("toda2.py deleted", (code, "missing" in msg), (1, True)))
        # --project naming a directory that is no checkout: a usage error naming it (exit 2), nothing checked
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = main(["--check", "--project", tmp, "--n", "2"])
        named = f"--project {tmp}: not a symbt checkout" in err.getvalue()
        got.append(("--project DIR, DIR no checkout", (code, named), (2, True)))
    bad = _bad("symbt codegen --check", got)
    return bad or Outcome("verified", "symbt codegen --check on copies of the shipped files, edited and deleted",
                          evidence="proof", n_scope=[2], detail=f"{len(got)} runs, each exit status as documented")


def _abs_trace(lam: float, p: Sequence[float], q: Sequence[float]) -> mp.mpf:
    """``|tr|_abs``: the trace of the 2x2 product of the entrywise absolute values (every term of ``tr L(lam)``
    positive: the product's condition), exactly by ``exact_products`` for the doubles ``a_j = lam + p_j``,
    ``r_j = exp(q_{j+1} - q_j)`` (their rounding moves it by a few ulps: a bound's scale, not a reference)."""
    N = len(p)
    _, T = exact_products(tuple(lam + p[j] for j in range(N)), tuple(math.exp(q[(j + 1) % N] - q[j]) for j in range(N)))
    t = T[0] + T[3]
    return mp.mpf(t.numerator) / t.denominator


#: paths.scaled_trace: nodes (in gaps and bands alike: a trace is a trace), one beyond 2**500 per site product
TRACE_NODES = (-7.5, -1.25, 0.375, 2.0, 6.0, 1e40, -3e60, 1e120)
#: the states' p and q per size (moderate: the product's condition is that of its terms)
TRACE_STATES = {4: ((1.5, -0.75, 2.25, -3.0), (0.0, 0.5, -0.25, 1.0)),
                5: ((-2.0, 1.0, 0.5, -0.25, 3.0), (0.25, 0.0, 1.5, -0.5, 0.75))}


@claim("paths.scaled_trace", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(4, 5),
       where="symbt/numeric/flow/coefficients.py: scaled_trace (float64 nodes, renormalised; one mpmath value)",
       statement="scaled_trace at N={N} (the product's later sites: at N = 3 the last B of the recurrence is never "
                 "read), 8 nodes from -7.5 to 1e120: T 2**e within (4N + 1) u |tr|_abs of the literal trace at 40 "
                 "digits (|tr|_abs: the same product of |a_j| and r_j with every sign positive, the condition of the "
                 "2x2 product; per site the roundings of a_j, r_j, a product and a difference, and the final sum); "
                 "the mpmath form at 30 digits within 10**-25 |tr|_abs; the reference at 40 digits within "
                 "10**-35 |tr|_abs of itself at 60")
def scaled_trace_claim(N: int) -> Outcome:
    import numpy as np

    from ..numeric.flow.coefficients import neighbour_ratios_of, scaled_trace
    from ..reference.literal import literal_trace

    p, q = TRACE_STATES[N]
    r = neighbour_ratios_of(list(q))
    T, e = scaled_trace(np.array(TRACE_NODES), list(p), r)
    u = mp.mpf(2) ** -53
    bad, worst = [], mp.mpf(0)
    with mp.workdps(40):
        for k, lam in enumerate(TRACE_NODES):
            ref = literal_trace(lam, p, q)
            with mp.workdps(60):
                again = literal_trace(lam, p, q)
            # |tr|_abs: the 2x2 product with |a_j| and the r_j entered with a plus sign (every term of tr positive)
            size = _abs_trace(lam, p, q)
            if not abs(again - ref) <= mp.mpf(10) ** -35 * size:
                bad.append(f"lam = {lam:g}: the literal trace at 40 and 60 digits differ")
            err = abs(mp.ldexp(mp.mpf(float(T[k])), int(e[k])) - ref) / size
            worst = max(worst, err / ((4 * N + 1) * u))
            if not err <= (4 * N + 1) * u:
                bad.append(f"float64 lam = {lam:g}: {mp.nstr(err, 3)} of |tr|_abs")
            with mp.workdps(30):
                t_mp, e_mp = scaled_trace(mp.mpf(lam), [mp.mpf(v) for v in p],
                                          neighbour_ratios_of([mp.mpf(v) for v in q]))
            err_mp = abs(mp.ldexp(t_mp, int(e_mp)) - ref) / size
            if not err_mp <= mp.mpf(10) ** -25:
                bad.append(f"mpmath lam = {lam:g}: {mp.nstr(err_mp, 3)} of |tr|_abs")
    detail = (f"{len(TRACE_NODES)} nodes; worst float64 error {mp.nstr(worst, 3)} of the bound (4N + 1) u |tr|_abs; "
              f"exponents {sorted(set(int(x) for x in e))}.")
    if bad:
        return failed("numeric: scaled_trace vs the literal trace", detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: scaled_trace vs the literal trace (40 digits)", evidence="sampled",
                   detail=detail, printed="within (4N + 1) u |tr|_abs")


#: paths.band_edge: (lam0, mu) with lam0 + mu or lam0 - mu exactly at a band edge of p = q = 0 (tr = lam**3 - 3 lam)
EDGE_PARAMS = ((2.25, 0.25), (2.25, -0.25), (-2.25, 0.25), (-2.25, -0.25))


@claim("paths.band_edge", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/existence.py: decide_existence's band test at |t| = 2 exactly; every route",
       statement="p = q = 0 (N={N}: tr L(lam) = lam**3 - 3 lam, exact in binary), lam0 +- mu = 2 or -2 exactly (a band "
                 "edge, |tr| = 2) and the other 2.5 or -2.5 (|tr| = 8.125): no real map (|tr| <= 2, by the "
                 "polynomial in exact rationals) -- decide_existence gives that parameter's trace code at its first "
                 "precision; bt_step (one state and a batch of two, backends python and numpy; mpmath at 30 digits) "
                 "raises NoRealMapError with condition 'trace'; the emitted toda3.bt_step refuses (NoRealMapError or "
                 "IllConditionedError), never a state")
def band_edge(N: int) -> Outcome:
    from fractions import Fraction

    import numpy as np

    from ..numeric import NoRealMapError, bt_step
    from ..numeric.core.limits import TRACE1, TRACE2
    from ..numeric.float64.existence import decide_existence

    p, q = np.zeros(N), np.zeros(N)
    got: Facts = []
    for l0, m in EDGE_PARAMS:
        lams = (Fraction(l0) + Fraction(m), Fraction(l0) - Fraction(m))
        at_edge = [abs(x ** 3 - 3 * x) <= 2 for x in lams]        # the independent decision: which is in a band
        want = TRACE1 if at_edge[0] else TRACE2
        got.append((f"lam0 = {l0}, mu = {m}: the exact polynomial puts one parameter on an edge",
                    sorted(at_edge), [False, True]))
        got.append((f"lam0 = {l0}, mu = {m}: decide_existence", decide_existence(p, q, l0, m, 1)[0], want))
        zero = [mp.mpf(0)] * N
        routes: list[tuple[str, Any, Any, Any, Any, Any]] = [
            (f"bt_step({be}, {what})", P, Q, l0, m, be) for be in ("python", "numpy")
            for what, P, Q in (("one state", p, q), ("a batch of two", np.stack([p, p]), np.stack([q, q])))]
        routes.append(("bt_step(mpmath, 30 digits)", zero, zero, mp.mpf(l0), mp.mpf(m), "mpmath"))
        for name, P, Q, lam0, mu, be in routes:
            try:
                with mp.workdps(30):
                    bt_step(P, Q, lam0, mu, backend=be)
                seen = "a state"
            except NoRealMapError as exc:
                seen = exc.condition
            except Exception as exc:  # noqa: BLE001 -- any other outcome is the finding
                seen = f"{type(exc).__name__}: {exc}"
            got.append((f"lam0 = {l0}, mu = {m}: {name}", seen, "trace"))
        try:
            from ..generated import toda3
            toda3.bt_step(p, q, l0, m, 1)
            seen = "a state"
        except (NoRealMapError, toda3.IllConditionedError):
            seen = "refused"
        except Exception as exc:  # noqa: BLE001 -- any other outcome is the finding
            seen = f"{type(exc).__name__}: {exc}"
        got.append((f"lam0 = {l0}, mu = {m}: toda3.bt_step", seen, "refused"))
    bad = _bad("existence at an exact band edge", got)
    return bad or Outcome("verified", "numeric: every route at |tr| = 2 exactly vs the exact trace polynomial",
                          evidence="sampled", detail=f"{len(got)} facts at {len(EDGE_PARAMS)} parameter pairs")


#: paths.transfer_gradient: a_j, r_j (moderate, mixed signs) and inv_s per size
GRADIENT_CASES = {4: ((2.5, -1.25, 0.75, 3.0), (0.5, 1.75, 0.25, 2.0), 1.0),
                  5: ((1.5, -2.0, 0.5, 2.25, -0.75), (1.25, 0.5, 2.5, 0.75, 1.5), 0.5)}


@claim("paths.transfer_gradient", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       sizes=(4, 5),
       where="symbt/numeric/flow/field.py: transfer_gradient (the prefix and suffix products of FlowField)",
       statement="transfer_gradient at N={N} (at N <= 3 the prefix's last r-row and the suffix's middle are never "
                 "read), mpf entries at 50 digits: d tr/da_j and d tr/dr_j of tr(m_N ... m_1), "
                 "m_j = [[a_j, -inv_s], [r_j, 0]], within 1e-35 (1 + |g|) of the exact prefix and suffix products at "
                 "70 digits (shipped.field's reference)")
def transfer_gradient_claim(N: int) -> Outcome:
    from ..numeric.flow.field import transfer_gradient
    from .shipped_field import trace_gradient

    a0, r0, s0 = GRADIENT_CASES[N]
    bad, worst = [], mp.mpf(0)
    with mp.workdps(50):
        a, r = [mp.mpf(v) for v in a0], [mp.mpf(v) for v in r0]
        da, dr = transfer_gradient(a, r, mp.mpf(s0))
    with mp.workdps(70):                 # the exact prefix and suffix products (lam = 0: a_j = p_j)
        ref = trace_gradient(mp.mpf(0), [mp.mpf(v) for v in a0], [mp.mpf(v) for v in r0], False, mp.mpf(s0))
        for k, (name, got) in enumerate((("da", da), ("dr", dr))):
            for j in range(N):
                want = ref[k * N + j]
                err = abs(got[j] - want) / (1 + abs(want))
                worst = max(worst, err)
                if not err <= mp.mpf(10) ** -35:
                    bad.append(f"{name}[{j}] = {mp.nstr(got[j], 12)}, the exact product's {mp.nstr(want, 12)}")
    detail = f"{2 * N} derivatives; worst {mp.nstr(worst, 3)} relative to 1 + |g|."
    if bad:
        return failed("numeric: transfer_gradient vs the exact products' gradient",
                      detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: transfer_gradient vs the exact products' gradient (70 digits)",
                   evidence="sampled", detail=detail, printed="within 1e-35 (1 + |g|)")


@claim("paths.mixed_block", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/kernels_block.py: _slopes' per-member condition tracking (Kn, Kd)",
       statement="the block kernel (plain Python), N={N}: the scans of paths.threshold across KAPPA_MAX for the "
                 "paper's state and its mirror p -> -p (top edge, branch 1) interleaved as one block of 128 members "
                 "(neighbours with different cancellations in a_j = lam + p_j): every member's status and state = "
                 "its own in the block of its scan alone and in a block of one, bit for bit; likewise the paper's "
                 "scan with each member beside a state that fails before the read-out (lam2 in a band) "
                 "(docs/numeric.md: a member equals its single-state step; a consistency check)")
def mixed_block(N: int) -> Outcome:
    from .shipped_paths import _block_kernel
    from .shipped_routes import threshold_states

    scans = {(label, b): rows for label, b, rows in threshold_states()}
    b = 1
    alone = [_block_kernel(list(scans[(name, b)]), b) for name in ("paper top", "mirror top")]
    rows = [st for pair in zip(scans[("paper top", b)], scans[("mirror top", b)]) for st in pair]
    P, Q, status = _block_kernel(rows, b)
    bad = 0
    for k in range(len(rows)):
        P1, Q1, s1 = alone[k % 2]
        i = k // 2
        same = int(status[k]) == int(s1[i]) and (int(s1[i]) != 0 or (np.array_equal(P[k], P1[i])
                                                                         and np.array_equal(Q[k], Q1[i])))
        # and its block of one (no neighbour at all): the single-state step's status and bits
        P0, Q0, s0 = _block_kernel([rows[k]], b)
        same = same and int(status[k]) == int(s0[0]) and (int(s0[0]) != 0 or (np.array_equal(P[k], P0[0])
                                                                              and np.array_equal(Q[k], Q0[0])))
        bad += 0 if same else 1
    # the scan of the paper's state, each member beside a state that fails before the read-out (lam2 in a band):
    # a member the sharp tier finishes must not read its neighbour's early failure
    in_band = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 0.0, 0.787)
    mixed = [st for m in scans[("paper top", b)] for st in (m, in_band)]
    Pm, Qm, sm = _block_kernel(mixed, b)
    for k in range(0, len(mixed), 2):
        P1, Q1, s1 = alone[0]
        same = int(sm[k]) == int(s1[k // 2]) and (int(s1[k // 2]) != 0 or (np.array_equal(Pm[k], P1[k // 2])
                                                                            and np.array_equal(Qm[k], Q1[k // 2])))
        bad += 0 if same else 1
    early = int(sm[1])
    handed = int(np.sum(status != 0))
    detail = (f"{len(rows)} members, {handed} handed back, {len(rows) - handed} finished; the paper's scan "
              f"interleaved with a state in a band (its status {early}); {bad} differ from their scan's own block "
              "or from their block of one.")
    if bad or not 0 < handed < len(rows) or early == 0:
        return failed("numeric: an interleaved block vs each scan's own block", detail=detail)
    return Outcome("verified", "numeric: an interleaved block vs each scan's own block (consistency)",
                   evidence="sampled", detail=detail, printed="every member = its own, statuses included")


#: shipped.loop_integrand: a moderate N = 5 state and spectral parameters in its outer gaps (|tr| >= 3 there)
LOOP_STATE = ((0.3, -0.2, 0.1, 0.5, -0.4), (0.0, 0.5, 0.2, -0.3, 0.1))
LOOP_LAMS = (6.0, -7.0, 3.5, -4.25, 11.0)


@claim("shipped.loop_integrand", equation="toda{N}.ck_integrand", source_equation="eqdisc", scene="shipped",
       sizes=(5,), parts=scale_parts,
       where="symbt codegen --n {N}: toda{N}.py (loop form): ck_integrand, ck_integrand_mp",
       statement="the loop form's c_k integrand (N={N}; float64 and mpmath at 30 digits) at 5 spectral parameters "
                 "in the outer gaps = lam^k / sqrt(tr^2 - 4), tr the literal trace at 40 digits: float64 within "
                 "(t^2/(t^2 - 4) (4N + 1) |tr|_abs/|tr| + N + 3) u relative (the product's condition carried "
                 "through the square root, then k products), mpmath within 1e-25")
def loop_integrand(N: int, parts: Parts) -> Outcome:
    from ..reference.literal import literal_trace
    from .shipped_emitted import emitted_module

    mod = emitted_module(N)
    p, q = LOOP_STATE
    u = mp.mpf(2) ** -53
    bad, worst = [], mp.mpf(0)
    s = parts.printed["scale"]                      # route output x scale = reference (scale = 1)
    got64 = np.asarray(mod.ck_integrand(np.array(LOOP_LAMS), np.array(p), np.array(q))) * s
    with mp.workdps(30):
        P, Q = [mp.mpf(v) for v in p], [mp.mpf(v) for v in q]
        got_mp = [scaled(mod.ck_integrand_mp(mp.mpf(lam), P, Q), s) for lam in LOOP_LAMS]
    with mp.workdps(40):
        for i, lam in enumerate(LOOP_LAMS):
            t = literal_trace(lam, p, q)
            cond = t * t / (t * t - 4) * (4 * N + 1) * _abs_trace(lam, p, q) / abs(t) + N + 3
            w = 1 / mp.sqrt(t * t - 4)
            for k in range(N):
                ref = mp.mpf(lam) ** k * w
                err = abs(mp.mpf(float(got64[i, k])) - ref) / abs(ref)
                worst = max(worst, err / (cond * u))
                if not err <= cond * u:
                    bad.append(f"float64 lam = {lam}, k = {k}: {mp.nstr(err, 3)} relative "
                               f"(bound {mp.nstr(cond * u, 3)})")
                if not abs(got_mp[i][k] - ref) <= mp.mpf(10) ** -25 * abs(ref):
                    bad.append(f"mpmath lam = {lam}, k = {k}: {mp.nstr(got_mp[i][k], 12)} vs {mp.nstr(ref, 12)}")
    detail = f"{len(LOOP_LAMS)} parameters x {N} moments; worst float64 error {mp.nstr(worst, 3)} of its bound."
    if bad:
        return failed("the loop form's c_k integrand vs the literal trace", detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", "numeric: the emitted loop form's ck_integrand vs lam^k/sqrt(tr^2 - 4), tr literal "
                   "(40 digits)", evidence="sampled", n_scope=[N], detail=detail, printed="within the product's "
                   "condition")
