"""The claims of the scene ``numeric-paths`` kill the bugs they were written for (issue 21, item 4).

Each test plants one single-point bug of ``symbt mutate --source``'s kind in :mod:`symbt.numeric` (the survivors
and uncovered lines of its run, docs/mutation.md) with ``monkeypatch`` and requires the claim to fail; unpatched,
every claim verifies.  The claims memoise only their samples and references (computed by
:mod:`symbt.reference`, which no patch here touches), so a planted bug cannot leak between tests.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from planting import planted as _planted

from symbt.claims import REGISTRY, load_all
from symbt.numeric.float64 import kernels, kernels_block
from symbt.numeric.float64 import orbit as orbit_module
from symbt.numeric.flow import coefficients
from symbt.numeric.multiprec import qd, qd_arith, qd_step

load_all()

NUMERIC_PATHS = sorted(cid for cid, c in REGISTRY.items() if c.scene == "numeric-paths")


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


def test_the_scene_has_the_claims_named_here():
    assert NUMERIC_PATHS == ["paths.abs_products.n2", "paths.abs_products.n3", "paths.acosh_edge", "paths.anchored.n3",
                             "paths.ball_prec.n3", "paths.ball_schedule.n3", "paths.band_edge.n3",
                             "paths.batch_range.n3", "paths.block_driver.n3", "paths.block_slopes.n3",
                             "paths.certified_nomap.n3", "paths.coefficients_mp.n3", "paths.complex.n3",
                             "paths.compress.n3", "paths.contexts", "paths.dask.n3", "paths.decimal_input.n3",
                             "paths.device.n3", "paths.dq_edge.n3", "paths.dq_edge.n9", "paths.dq_range.n3",
                             "paths.edges.n3", "paths.enclosure_poly.n3", "paths.enclosures.n3",
                             "paths.error_bounds.n3", "paths.escalation.n3", "paths.existence_iv.n3",
                             "paths.failing_rows.n3", "paths.failure_text.n3", "paths.field_far.n3",
                             "paths.field_ivp.n3", "paths.field_nomap.n3", "paths.frame.n13", "paths.frame_inverse.n13",
                             "paths.growth.n3", "paths.growth_law", "paths.hook_rules", "paths.idle_rows.n3",
                             "paths.ill_member.n3", "paths.inline_boolop", "paths.inline_globals", "paths.inline_lines",
                             "paths.inline_rule.n3", "paths.jacobian.n3", "paths.jacobian_dual.n3",
                             "paths.kappa_cells.n2", "paths.kappa_cells.n3", "paths.kappa_cells.n5",
                             "paths.kappa_cells.n6", "paths.kappa_cells_rows.n2", "paths.kappa_cells_rows.n3",
                             "paths.kappa_cells_rows.n5", "paths.kappa_edge.n2", "paths.kappa_rows.n2",
                             "paths.kernels.n3", "paths.kernels.n5", "paths.lohner_box.n3", "paths.lohner_reorth.n13",
                             "paths.lohner_reorth.n3", "paths.lohner_unsound.n3", "paths.many_rows.n3",
                             "paths.members.n3", "paths.mixed_block.n3", "paths.mp_verdict.n3", "paths.next_prec.n3",
                             "paths.panels", "paths.python_kernel.n3", "paths.q_low.n3", "paths.qd.n2", "paths.qd.n3",
                             "paths.qd_decompose", "paths.qd_tables", "paths.range_edge.n2", "paths.renorm_top.n2",
                             "paths.root_slope", "paths.rows_apart.n3", "paths.rows_out.n3", "paths.scaled_trace.n4",
                             "paths.scaled_trace.n5", "paths.side_by_side.n3", "paths.spectral_overflow.n3",
                             "paths.step_core.n3", "paths.stored.n3", "paths.symmetric_monodromy.n2",
                             "paths.threshold.n3", "paths.tiny_mu.n3", "paths.track_hooks",
                             "paths.transfer_gradient.n4", "paths.transfer_gradient.n5", "paths.zero_radius.n3"]


@pytest.mark.parametrize("cid", NUMERIC_PATHS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.qd

def test_qd_log1p_in_double_double(monkeypatch):
    # the read-out log1p carried to 106 bits only: a result right to 1e-32, far outside 2^-209
    def short(x):
        hi = math.log1p(x[0])
        return qd_arith.renorm4(hi, 0.0, 0.0, 0.0)
    monkeypatch.setattr(qd_step, "log1p", short)
    assert status("paths.qd.n3") == "failed"


def test_qd_sub_sign_of_a_limb(monkeypatch):
    # qd_arith.sub with the sign of the second limb lost (mutant qd_arith:216 unary-minus)
    monkeypatch.setattr(qd_step, "sub", lambda a, b: qd_arith.add(a, (-b[0], b[1], -b[2], -b[3])))
    assert status("paths.qd.n2") == "failed"


def test_qd_range_limit_lifted(monkeypatch):
    # no range check: a neighbour distance of 310 is stepped instead of given back to the Arb path
    monkeypatch.setattr(qd_step, "MAX_DQ_QD", 1e9)
    assert status("paths.qd.n2") == "failed"


def test_qd_negative_input(monkeypatch):
    # to_qd loses the sign of its input (the conversion of negative values)
    real = qd.to_qd
    monkeypatch.setattr(qd, "to_qd", lambda values: None if (x := real(values)) is None else np.abs(x))
    assert status("paths.qd.n2") == "failed"


def test_qd_decomposition_shift(monkeypatch):
    # from_qd's decomposition: the shift of an absent component 1 instead of 0 (mutant qd:272)
    real = qd._decompose

    def wrong(x, out):
        real(x, out)
        out[:, 6] = np.where(out[:, 3] == 0, 1, out[:, 6])
    monkeypatch.setattr(qd, "_decompose", wrong)
    assert status("paths.qd.n2") == "failed"


def test_qd_fits_rule(monkeypatch):
    # the quad-double admission rule off by one guard bit
    monkeypatch.setattr(qd, "qd_need", lambda prec, n: prec + 15 + 2 * int(n).bit_length())
    assert status("paths.qd.n2") == "failed"


# --------------------------------------------------------------------------- paths.kernels

def _rebuild_python_orbit(monkeypatch, hooks=None):
    """The plain-Python orbit (what ``backend="python"`` runs) rebuilt after a planted change: its hooks are
    written inline when it is built, so a patched module global (``KAPPA_MAX``) or hook reaches it only
    through a rebuild -- as a mutant of the source does, in the fresh process ``symbt mutate`` runs."""
    monkeypatch.setattr(kernels, "python_orbit", kernels.python_orbit_with(hooks or {}))


def test_fused_kernel_gives_moderate_states_back(monkeypatch):
    # the fused kernel's condition test refuses everything: the general path (right too) takes over,
    # which bt_step cannot show (mutant kernels:174/182)
    monkeypatch.setattr(kernels, "KAPPA_MAX", 0.0)
    _rebuild_python_orbit(monkeypatch)
    assert status("paths.kernels.n3") == "failed"


def test_block_kernel_gives_moderate_states_back(monkeypatch):
    # the same in the block kernel (mutant kernels_block:67/118/247)
    monkeypatch.setattr(kernels_block, "KAPPA_MAX", 0.0)
    assert status("paths.kernels.n5") == "failed"


def test_kernels_finish_ill_conditioned_states(monkeypatch):
    # no condition test: a state at a band edge stays in the fused kernel (mutant kernels:182)
    monkeypatch.setattr(kernels, "KAPPA_MAX", math.inf)
    _rebuild_python_orbit(monkeypatch)
    assert status("paths.kernels.n3") == "failed"


def test_block_kernel_misses_opposite_traces(monkeypatch):
    # the block kernel's positivity statuses lost: a state without a real map reported OK (mutant kernels_block:237)
    monkeypatch.setattr(kernels_block, "POSITIVITY", kernels_block.OK)
    assert status("paths.kernels.n3") == "failed"


# --------------------------------------------------------------------------- paths.failing_rows

def test_where_names_the_wrong_member(monkeypatch):
    # raise_for_status reports the batch indices shifted by one (mutants orbit:271, step:262)
    real = orbit_module.raise_for_status

    def shifted(status_, step, shape):
        real(np.roll(status_, 1), np.roll(step, 1), shape)
    monkeypatch.setattr(orbit_module, "raise_for_status", shifted)
    assert status("paths.failing_rows.n3") == "failed"


def test_where_text_default_offset(monkeypatch):
    # where_text's documented default offset 0 becomes 1 (mutant step:262)
    from symbt.numeric.core import step as step_module

    monkeypatch.setattr(step_module.where_text, "__defaults__", (1, None))
    assert status("paths.failing_rows.n3") == "failed"


def test_retry_skipped(monkeypatch):
    # the ensemble's members the block kernel gives back are not recomputed by the general path
    monkeypatch.setattr(orbit_module, "general_orbit",
                        lambda pa, qa, lam0, mu, branch, n, every, P, Q, rows: (np.zeros(rows.size, np.int64),
                                                                                 np.zeros(rows.size, np.int64)))
    assert status("paths.failing_rows.n3") == "failed"


def test_complex_member_from_the_neighbours_q(monkeypatch):
    # float_rows_step continues the member without a real map from the next row's q (mutant rows:213)
    import inspect
    import textwrap

    from symbt.numeric.float64 import rows as rows_module
    from symbt.numeric.float64 import step as step64

    src = textwrap.dedent(inspect.getsource(rows_module.float_rows_step))
    old = "_complex_rows(pa[nomap], qa[nomap],"
    assert src.count(old) == 1
    ns: dict = {}
    exec(compile(src.replace(old, "_complex_rows(pa[nomap], qa[nomap + 1],"), rows_module.__file__, "exec"),
         rows_module.float_rows_step.__globals__, ns)
    monkeypatch.setattr(step64, "float_rows_step", ns["float_rows_step"])
    assert status("paths.failing_rows.n3") == "failed"


# --------------------------------------------------------------------------- paths.tiny_mu

def test_tiny_mu_sign_of_odd_powers(monkeypatch):
    # lam0^k's sign at lam0 < 0 lost in the tiny-mu branch (mutant coefficients:396)
    real = coefficients._log2_rows
    monkeypatch.setattr(coefficients, "_log2_rows", lambda lam, li, ks: (real(lam, li, ks)[0],
                                                                         np.abs(real(lam, li, ks)[1])))
    assert status("paths.tiny_mu.n3") == "failed"


# --------------------------------------------------------------------------- paths.complex

def test_complex_continuation_other_eigenvector(monkeypatch):
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import arb

    # the complex Arb context's square root on the other branch: the continuation follows the other eigenvector
    monkeypatch.setattr(arb.ACB, "sqrt", lambda x: -x.sqrt())
    assert status("paths.complex.n3") == "failed"


# --------------------------------------------------------------------------- paths.growth

def test_growth_record_smallest_radius(monkeypatch):
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner

    # the record's log2 radius of the smallest component instead of the largest (mutant lohner:375)
    monkeypatch.setattr(lohner, "_lograd", lambda xs: math.log2(min(float(x.rad()) for x in xs) or 2.0 ** -2000))
    assert status("paths.growth.n3") == "failed"


def test_growth_record_without_degree(monkeypatch):
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner

    # the growth law's fit skipped (mutant lohner:430): degree None
    real = lohner.growth_law
    monkeypatch.setattr(lohner, "growth_law", lambda lograd, first=100: dict(real(lograd, first), degree=None))
    assert status("paths.growth.n3") == "failed"


# --------------------------------------------------------------------------- paths.frame (2N > 24)

def test_frame_path_without_rounding_errors(monkeypatch):
    # the Lohner set of N = 13 without the step's rounding errors and the Jacobian's radius (the documented
    # unsound variant): the literal orbit leaves the returned balls
    from symbt.numeric.multiprec import lohner
    real = lohner.LohnerSet.__init__

    def unsound(self, *args, **kwargs):
        kwargs["unsound"] = True
        real(self, *args, **kwargs)
    monkeypatch.setattr(lohner.LohnerSet, "__init__", unsound)
    assert status("paths.frame.n13") == "failed"



# --------------------------------------------------------------------------- paths.jacobian, paths.lohner_box

def test_jacobian_slopes_shifted(monkeypatch):
    # the cyclic closure of the slopes' gradients off by one index (mutants lohner:120/170): the enclosure is
    # still rigorous after the intersection with the ball image, only the Jacobian is wrong
    from symbt.numeric.multiprec import lohner
    real = lohner._slope_rows
    monkeypatch.setattr(lohner, "_slope_rows", lambda *args: (lambda out: out[1:] + out[:1])(real(*args)))
    assert status("paths.jacobian.n3") == "failed"


def test_lohner_box_without_the_input_radius(monkeypatch):
    # the C r0 term of the set dropped (mutant lohner:342): the hull is narrower than the box's image
    from symbt.numeric.multiprec import lohner
    real = lohner.LohnerSet.__init__

    def no_r0(self, *args, **kwargs):
        real(self, *args, **kwargs)
        self.has_r0 = False
    monkeypatch.setattr(lohner.LohnerSet, "__init__", no_r0)
    assert status("paths.lohner_box.n3") == "failed"


def test_lohner_box_loose(monkeypatch):
    # the centre step enclosed as at ~116 bits instead of 200 (a too cautious enclosure): rigorous, not sharp
    from flint import arb

    from symbt.numeric.multiprec import lohner
    real = lohner.arb_step
    monkeypatch.setattr(lohner, "arb_step", lambda *a: tuple([x + arb(0, 1e-35) for x in v] for v in real(*a)))
    assert status("paths.lohner_box.n3") == "failed"


def test_lohner_box_wider_by_a_tenth_of_a_micro(monkeypatch):
    # every radius of the set widened by 1e-7 relative -- 100 radius roundings of Arb (2^-30 each) more than the
    # read-out makes: within the old bound (1 + 1e-6, a measured value x 100), outside the derived one
    from flint import arb

    from symbt.numeric.multiprec import lohner
    real = lohner.LohnerSet.step

    def wider(self, *args):
        real(self, *args)
        self.hull = [h + arb(0, float(h.rad()) * 1e-7) for h in self.hull]
    monkeypatch.setattr(lohner.LohnerSet, "step", wider)
    assert status("paths.lohner_box.n3") == "failed"


# --------------------------------------------------------------------------- paths.stored

def test_orbit_stores_every_step(monkeypatch):
    # the storage test `i % every == 0 or i == n` taken at every step (mutant kernels:330): the first rows hold
    # steps 0, 1, 2, ... instead of 0, 3, 6, ...
    real = kernels.orbit

    def every_step(p0, q0, lam1, lam2, two_mu, branch, n, every, anchor, outP, outQ):
        P, Q = np.empty((n + 1, len(p0))), np.empty((n + 1, len(p0)))
        st = real(p0, q0, lam1, lam2, two_mu, branch, n, 1, anchor, P, Q)
        outP[:] = P[:len(outP)]
        outQ[:] = Q[:len(outQ)]
        return st
    monkeypatch.setattr(kernels, "orbit", every_step)
    assert status("paths.stored.n3") == "failed"


# --------------------------------------------------------------------------- paths.threshold, anchored, edges

def test_threshold_fused_estimate_without_the_read_out_term(monkeypatch):
    # the fused kernel's read-out factor (|1 + x| + |x|) taken as (|1 + x| - |x|) (mutant kernels:232): it keeps
    # states the block kernel hands back; the results of either are right, only the decision differs
    def trusted(kt, u, w, dn, x):
        return kt * (abs(u) + abs(w)) * (abs(x + 1.0) - abs(x)) <= kernels.KAPPA_MAX * abs(dn) * abs(x + 1.0)
    hooks = {**kernels.OPERATIONS, **kernels.HOOKS, "trusted": trusted}
    bad = kernels.instantiate(kernels.SOURCE, hooks, tag="f64_planted", jit=False, extra=kernels._EXTRA)
    monkeypatch.setattr(kernels, "step", bad["step"])
    _rebuild_python_orbit(monkeypatch, {"trusted": trusted})
    assert status("paths.threshold.n3") == "failed"


def test_threshold_block_estimate_signed(monkeypatch):
    # the block kernel's cancellation estimate with p_j's sign kept (mutant kernels_block:77): seen only where the
    # cancellation in lam + p_j falls on a negative p_j -- the mirrored state of the scan
    import inspect
    import textwrap

    src = textwrap.dedent(inspect.getsource(kernels_block._slopes))
    assert src.count("cn = abs(lam[k]) + abs(p[j, k])") == 1
    ns = dict(vars(kernels_block))
    exec(compile(src.replace("cn = abs(lam[k]) + abs(p[j, k])", "cn = abs(lam[k]) + p[j, k]"), "planted", "exec"),
         ns)
    monkeypatch.setattr(kernels_block, "_slopes", ns["_slopes"])
    assert status("paths.threshold.n3") == "failed"


def test_anchored_flush_off_by_an_ulp(monkeypatch):
    # the fused kernel's re-anchoring r = exp(dq) one ulp off (as mutant kernels:282, a low part of the wrong
    # neighbour): within every accuracy bound, but the two kernels no longer give the same bits
    real = kernels._anchor1

    def anchor(qh, ql, fh, fl, r, p):
        st = real(qh, ql, fh, fl, r, p)
        r[0] = np.nextafter(r[0], np.inf)
        return st
    monkeypatch.setattr(kernels, "_anchor1", anchor)
    assert status("paths.anchored.n3") == "failed"


def test_edges_growth_law_from_one_point(monkeypatch):
    # a degree made up from a single usable point (the documented answer is None)
    from symbt.numeric.multiprec import lohner
    real = lohner.growth_law
    monkeypatch.setattr(lohner, "growth_law", lambda *a, **k: {**real(*a, **k), "degree": real(*a, **k)["degree"]
                                                              or 0.0})
    assert status("paths.edges.n3") == "failed"


def test_edges_out_of_range_on_the_real_part(monkeypatch):
    # out_of_range judging a complex entry by its real part (as mutant context:215): -2^501 i passes unseen
    from symbt.numeric.core.context import FloatContext
    real = FloatContext.out_of_range
    monkeypatch.setattr(FloatContext, "out_of_range", lambda self, *xs: real(self, *[np.real(x) for x in xs]))
    assert status("paths.edges.n3") == "failed"


def test_edges_range_check_lost(monkeypatch):
    # neighbour_ratios without its range test on float64 (as mutant monodromy:59, which tests the smallest
    # |q_{j+1} - q_j|): a distance of 700.1 next to small ones goes through, and invariants and phi return finite
    # numbers past the documented limit
    from symbt.numeric.core import monodromy
    real = monodromy.neighbour_ratios

    def unchecked(ctx, q):
        if ctx.is_exact_scale:
            return real(ctx, q)
        return [ctx.exp(q[(j + 1) % len(q)] - q[j]) for j in range(len(q))]
    for mod in ("symbt.numeric.flow.invariants", "symbt.numeric.flow.phi"):
        monkeypatch.setattr(mod + ".neighbour_ratios", unchecked)
    assert status("paths.edges.n3") == "failed"


def test_ill_member_escalated_one_site_off(monkeypatch):
    # the escalated momenta written one site off (as mutant orbit:212, Pn[j - 1][ill]): the band-edge member's
    # orbit is no longer the literal one
    real = orbit_module.escalate_rows
    monkeypatch.setattr(orbit_module, "escalate_rows",
                        lambda *a, **k: (lambda r: (np.roll(r[0], 1, axis=1), r[1], r[2]))(real(*a, **k)))
    assert status("paths.ill_member.n3") == "failed"


# ----------------------------------------------------------- paths.kappa_cells (the paper's state, the chains)

def test_sharp_kappa_renormalised_with_the_wrong_sign(monkeypatch):
    # the prefix's B scaled by 2**+f instead of 2**-f at a renormalisation (mutant condition:106)
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "sharp_trace_kappa", _planted(condition.sharp_trace_kappa, "math.ldexp(B, -f)",
                                                                 "math.ldexp(B, f)"))
    assert status("paths.kappa_cells.n6") == "failed"


def test_sharp_kappa_exponent_stored_one_site_early(monkeypatch):
    # the prefix's exponent stored at the previous site (mutant condition:109)
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "sharp_trace_kappa", _planted(condition.sharp_trace_kappa, "        pe[j] = e",
                                                                 "        pe[j - 1] = e"))
    assert status("paths.kappa_cells.n6") == "failed"


def test_sharp_kappa_cancellation_factor_kept_at_the_first_site(monkeypatch):
    # the max over sites of (|lam| + |p_j|) / |a_j| taken as a min (mutant condition:98's kind)
    from symbt.numeric.core import condition

    monkeypatch.setattr(condition, "sharp_trace_kappa", _planted(condition.sharp_trace_kappa,
                                                                 "if cn * kd > kn * abs(a):",
                                                                 "if cn * kd < kn * abs(a):"))
    assert status("paths.kappa_cells.n3") == "failed"


# --------------------------------------------------------------------------- paths.coefficients_mp

def test_coefficients_mp_probes_reflected(monkeypatch):
    # the scale probes a + (b + a) f instead of a + (b - a) f (mutant coefficients:444): outside the interval, in a
    # band for [-5.5, -4.056] of the paper's state
    monkeypatch.setattr(coefficients, "_coefficients_mp", _planted(coefficients._coefficients_mp,
                                                                   "a + (b - a) * mpmath.mpf(f)",
                                                                   "a + (b + a) * mpmath.mpf(f)"))
    assert status("paths.coefficients_mp.n3") == "failed"


# --------------------------------------------------------------------------- paths.threshold (numpy rows)

def test_threshold_numpy_rows_positivity_with_the_smaller_condition(monkeypatch):
    # float_status' positivity test with min(k1, k2) for max (mutant step:313): the numpy rows keep states the
    # kernels hand back
    from symbt.numeric.core import step as step_module

    monkeypatch.setattr(step_module, "float_status", _planted(step_module.float_status, "kt = np.maximum(k1, k2)",
                                                              "kt = np.minimum(k1, k2)"))
    assert status("paths.threshold.n3") == "failed"


def test_qd_orbit_mp_inputs_joined_wrongly(monkeypatch):
    # qd_orbit_mp's `list(P) + list(Q) + [lam0, mu]` with a minus (mutant qd:383): a TypeError, not the documented
    # NumericRangeError for an input beyond 2**600
    monkeypatch.setattr(qd, "qd_orbit_mp", _planted(qd.qd_orbit_mp, "list(Q) + [lam0, mu]", "list(Q) - [lam0, mu]"))
    assert status("paths.qd.n2") == "failed"


def test_ill_member_numpy_rows_escalated_from_the_previous_row(monkeypatch):
    # _float_block escalates the ILLCOND rows with the previous row's momenta (mutant rows:122)
    from symbt.numeric.float64 import rows as rows_module

    monkeypatch.setattr(rows_module, "_float_block", _planted(rows_module._float_block, "escalate_rows(pa[ill],",
                                                              "escalate_rows(pa[ill - 1],"))
    assert status("paths.ill_member.n3") == "failed"


# --------------------------------------------------------------------------- paths.certified_nomap

def test_certified_positivity_accepts_a_negative_ball(monkeypatch):
    # ARB_CERTAIN.positive returns True for a ball certainly <= 0 (mutant arb:109)
    from symbt.numeric.multiprec import arb

    monkeypatch.setattr(arb.ArbContext, "positive", _planted(arb.ArbContext.positive,
                                                             "if x <= 0:\n        return False",
                                                             "if x <= 0:\n        return True"))
    assert status("paths.certified_nomap.n3") == "failed"


# --------------------------------------------------------------------------- paths.frame_inverse

def test_frame_inverse_beta_without_abs(monkeypatch):
    # beta = max X_ij instead of max |X_ij| (mutant lohner:231): a frame whose large entries are negative gets a
    # radius below the lemma's
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "frame_inverse", _planted(lohner.frame_inverse, "max(abs(x) for x in Xa.entries())",
                                                          "max(x for x in Xa.entries())"))
    assert status("paths.frame_inverse.n13") == "failed"


def test_frame_inverse_radius_doubled(monkeypatch):
    # a radius twice the lemma's (the upper side: an enclosure that is rigorous but not the documented one)
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "frame_inverse", _planted(lohner.frame_inverse, "(beta * d / (1 - d))",
                                                          "(2 * beta * d / (1 - d))"))
    assert status("paths.frame_inverse.n13") == "failed"


# --------------------------------------------------------------------------- paths.next_prec

def test_next_prec_without_extrapolation(monkeypatch):
    # _next_prec skips the extrapolation to step n (mutant lohner:449 `i1 > n`)
    from symbt.numeric.multiprec import lohner

    monkeypatch.setattr(lohner, "_next_prec", _planted(lohner._next_prec, "if i1 < n:", "if i1 > n:"))
    assert status("paths.next_prec.n3") == "failed"


# --------------------------------------------------------------------------- paths.field_far

def test_field_renormalised_sweep_with_the_previous_ratio(monkeypatch):
    # the renormalised forward sweep's C' = r_{j-1} A for r_j A (mutant field:110)
    from symbt.numeric.flow import field

    monkeypatch.setattr(field, "_gradient_renormalised", _planted(field._gradient_renormalised,
                                                                  "r[j] * f00, r[j] * f01\n        f00",
                                                                  "r[j - 1] * f00, r[j] * f01\n        f00"))
    assert status("paths.field_far.n3") == "failed"


# --------------------------------------------------------------------------- paths.dask

def test_dask_chunks_swap_lam0_and_mu(monkeypatch):
    # the chunk reads mu's column as lam0 and lam0's as mu
    pytest.importorskip("dask")
    from symbt.numeric.float64 import dask_orbit as mod

    monkeypatch.setattr(mod, "_chunk", _planted(mod._chunk, "block[:, 2 * N], block[:, 2 * N + 1]",
                                                "block[:, 2 * N + 1], block[:, 2 * N]"))
    assert status("paths.dask.n3") == "failed"


def test_dask_shape_test_inverted(monkeypatch):
    # `p.ndim != 2` -> `==` (mutant dask_orbit:97): every well-formed ensemble refused
    pytest.importorskip("dask")
    from symbt.numeric.float64 import dask_orbit as mod

    monkeypatch.setattr(mod, "dask_orbit", _planted(mod.dask_orbit, "p.ndim != 2", "p.ndim == 2"))
    monkeypatch.setattr("symbt.numeric.dask_orbit", mod.dask_orbit)
    assert status("paths.dask.n3") == "failed"


def test_dask_chunks_of_p_from_the_wrong_axis(monkeypatch):
    # p rechunked with its column chunks as row chunks (mutant dask_orbit:110)
    pytest.importorskip("dask")
    from symbt.numeric.float64 import dask_orbit as mod

    monkeypatch.setattr(mod, "dask_orbit", _planted(mod.dask_orbit, "p.rechunk((p.chunks[0], N))",
                                                    "p.rechunk((p.chunks[1], N))"))
    monkeypatch.setattr("symbt.numeric.dask_orbit", mod.dask_orbit)
    assert status("paths.dask.n3") == "failed"


def test_dask_where_offset_of_the_chunk_lost(monkeypatch):
    # NoRealMapError.where with the chunk's offset subtracted (a member of the second chunk named by its index
    # in the chunk's kind): the no-map member 4 of paths.dask is reported elsewhere
    pytest.importorskip("dask")
    from symbt.numeric.float64 import dask_orbit as mod

    monkeypatch.setattr(mod, "_chunk", _planted(mod._chunk, "(w[0] + start,)", "(w[0] - start,)"))
    assert status("paths.dask.n3") == "failed"


def test_dask_chunk_offset_default_is_equivalent(monkeypatch):
    # mutants-equivalent.toml, dask_orbit:60: `... if block_info else 0` -> `else 1`.  dask_orbit calls _chunk only
    # through map_blocks, which passes a non-empty block_info to every block it computes; the default is read only
    # in the NoRealMapError branch, which a block without block_info (dask's meta inference on an empty block)
    # never reaches.  Mechanically: every call that computes members gets a non-empty block_info, and with the
    # mutant planted paths.dask (member 4 without a real map, named by where) still verifies.
    pytest.importorskip("dask")
    from symbt.numeric.float64 import dask_orbit as mod

    mutant = _planted(mod._chunk, 'if block_info else 0', 'if block_info else 1')
    seen = []

    def spy(block, *args, block_info=None):
        seen.append((block.shape[0], bool(block_info)))
        return mutant(block, *args, block_info=block_info)
    monkeypatch.setattr(mod, "_chunk", spy)
    assert status("paths.dask.n3") == "verified"
    assert any(rows > 0 for rows, _ in seen)
    assert all(info for rows, info in seen if rows > 0)


def test_members_compacted_buffer_of_the_wrong_width(monkeypatch):
    # _ensemble's compacted Q buffer with Q.shape[0] (the rows) for Q.shape[-1] (mutant orbit:394): only an
    # ensemble with an idle member (mu = 0) compacts
    monkeypatch.setattr(orbit_module, "_ensemble", _planted(orbit_module._ensemble, "Q.shape[-1]))",
                                                            "Q.shape[-0]))"))
    assert status("paths.members.n3") == "failed"


def test_invariants_unit_coefficient_sign_of_zero_is_equivalent():
    # mutants-equivalent.toml, invariants:82: `A = [P[0], 1.0 + zero]` -> `1.0 - zero`.  zero = 0.0 * P[0] is
    # +0.0 or -0.0 (float64: inputs are validated real and finite), mpf 0 or the interval [0, 0]; 1.0 -+ (+-0.0) is
    # exactly 1.0 in IEEE 754, and 1 - 0 is 1 in mpmath and in its interval arithmetic.  Checked bit for bit on
    # states with P[0] negative (zero = -0.0), positive, +0.0 and -0.0, single, batched, mpmath and interval.
    import mpmath

    from symbt.numeric.flow import invariants as inv_module

    mutant = _planted(inv_module._invariants, "A = [P[0], 1.0 + zero]", "A = [P[0], 1.0 - zero]")
    states = [([-1.5, 2.0, 0.25], [0.1, -0.3, 0.2]), ([3.0, -2.0, 1.0], [0.0, 1.0, -1.0]),
              ([0.0, 1.0, -1.0], [0.5, 0.0, 0.0]), ([-0.0, 1.0, -1.0], [0.5, 0.0, 0.0]),
              ([[-1.5, 2.0, 0.25], [-0.0, 4.0, 1e-300]], [[0.1, -0.3, 0.2], [2.0, 1.0, 0.0]])]
    for p, q in states:
        a, b = inv_module._invariants(p, q), mutant(p, q)
        assert np.asarray(a).dtype == np.asarray(b).dtype
        assert np.array_equal(np.asarray(a), np.asarray(b))
        assert np.array_equal(np.signbit(np.asarray(a, dtype=float)), np.signbit(np.asarray(b, dtype=float)))
    with mpmath.workdps(40):
        p, q = [mpmath.mpf(-1.5), mpmath.mpf(2), mpmath.mpf("0.25")], [mpmath.mpf("0.1"), 0, mpmath.mpf("0.2")]
        assert list(inv_module._invariants(p, q)) == list(mutant(p, q))
        pi, qi = [mpmath.iv.mpf(v) for v in (-1.5, 2, 0.25)], [mpmath.iv.mpf(v) for v in (0.1, 0, 0.2)]
        ai, bi = inv_module._invariants(pi, qi), mutant(pi, qi)
        assert [(x.a, x.b) for x in ai] == [(x.a, x.b) for x in bi]


def test_members_block_with_one_forward_member(monkeypatch):
    # the block kernel's forward sweep skipped when exactly one member of the block is transported forward
    # (`nf > 0` -> `nf > 1` at the forward sweep): a one-member ensemble of a forward state keeps stale slopes
    monkeypatch.setattr(kernels_block, "_slopes", _planted(kernels_block._slopes, "    if nf > 0:\n        for j",
                                                           "    if nf > 1:\n        for j"))
    assert status("paths.members.n3") == "failed"


def test_members_active_by_mu_one(monkeypatch):
    # orbit:370 (seed 8): members active where mu != 1 (not mu != 0): the member at mu = 1 exactly is neither active
    # nor idle, and its rows are never written
    from symbt.numeric.float64 import orbit as orbit_module

    monkeypatch.setattr(orbit_module, "validated_float_orbit", _planted(
        orbit_module.validated_float_orbit, "act = np.flatnonzero(muv != 0) if n else np.arange(0)",
        "act = np.flatnonzero(muv != 1) if n else np.arange(0)"))
    assert status("paths.members.n3") == "failed"


def test_members_backward_slopes_not_copied_with_one_forward_member(monkeypatch):
    # the backward members' slopes not copied from tmp when exactly one member is transported forward (mutant
    # kernels_block:157 `nf > 0` -> `nf > 1`): the far member of the two-member block keeps its forward slopes
    monkeypatch.setattr(kernels_block, "_slopes", _planted(kernels_block._slopes,
                                                           "        if nf > 0:\n            for j in range(1, N):",
                                                           "        if nf > 1:\n            for j in range(1, N):"))
    assert status("paths.members.n3") == "failed"


# --------------------------------------------------------------------------- paths.step_core

def test_step_core_opposite_traces_test_on_arrays_flipped(monkeypatch):
    # _opposite on arrays with `real(t1) > 0` for `real(t1) < 0` (mutant step:333): traces of one sign reported
    # opposite, so step_core(FLOAT) with check_real refuses states that have a real map
    from symbt.numeric.core import step as step_module

    monkeypatch.setattr(step_module, "_opposite", _planted(step_module._opposite, "np.real(t1) < 0, np.real(t2)",
                                                           "np.real(t1) > 0, np.real(t2)"))
    assert status("paths.step_core.n3") == "failed"


def test_step_core_where_of_the_opposite_traces(monkeypatch):
    # the rows named by where taken from `opp` instead of its negation: the rows with a real map are named
    from symbt.numeric.core import step as step_module

    monkeypatch.setattr(step_module, "step_core", _planted(step_module.step_core,
                                                           "where_text(np.logical_not(opp), shape",
                                                           "where_text(opp, shape"))
    assert status("paths.step_core.n3") == "failed"


# --------------------------------------------------------------------------- equivalent: kernels:424

def test_orbit_store_range_test_on_the_previous_site_is_equivalent():
    # mutants-equivalent.toml, kernels:424: the stored row's test `abs(p[j]) < 1e300` -> `abs(p[j - 1]) < 1e300`.
    # Over the loop j = 0..N-1, j - 1 runs over the same sites (p[-1] = p[N-1]), so RANGE is returned iff some
    # |y_j| or some |p_j| fails, as before: the same status for every input, the same rows when it is OK; only the
    # entries of the failing row written before the return differ, and no caller reads a failed state's rows
    # (documented: the drivers recompute it with the general path).  Checked on every pattern of sites with a
    # p~ beyond 1e300 or NaN (a stub step sets p~), positions in and out of range, N = 2, 3.
    import inspect
    import itertools
    import textwrap

    src = textwrap.dedent(inspect.getsource(kernels.orbit))
    old, new = "abs(p[j]) < 1e300)", "abs(p[j - 1]) < 1e300)"
    assert src.count(old) == 1
    for N in (2, 3):
        for pattern in itertools.product((1.5, 2e300, math.nan, -3e300), repeat=N):
            for q0 in (np.linspace(0.0, 1.0, N), np.full(N, 2e300)):
                runs = []
                for text in (src, src.replace(old, new)):
                    def stub(p, *args, _pattern=pattern):
                        p[:] = _pattern
                        return kernels.OK
                    ns: dict = {}
                    exec(compile(text, "orbit", "exec"), {**kernels.__dict__, "step": stub}, ns)
                    P, Q = np.full((3, N), -1.0), np.full((3, N), -1.0)
                    st = ns["orbit"](np.ones(N), q0.copy(), 1.0, -1.0, 2.0, 1, 2, 1, kernels.ANCHOR, P, Q)
                    runs.append((st, P, Q))
                (s0, P0, Q0), (s1, P1, Q1) = runs
                assert s0 == s1
                if s0 == kernels.OK:
                    assert np.array_equal(P0, P1) and np.array_equal(Q0, Q1)
    assert s0 == kernels.RANGE     # the last pattern fails the test (the loop did reach it)


# --------------------------------------------------------------------------- paths.device

def test_device_inlines_the_helpers_of_other_modules(monkeypatch):
    # inline._helper takes the functions of *other* modules for the callee's own (mutant inline:154): the rewrite
    # of python_orbit_with tries to inline condition.sharp_trace_kappa and refuses it
    from symbt.numeric.core import inline

    monkeypatch.setattr(inline, "_helper", _planted(inline._helper, "v.__module__ == fn.__module__",
                                                    "v.__module__ != fn.__module__"))
    assert status("paths.device.n3") == "failed"


# --------------------------------------------------------------------------- paths.enclosures

def test_enclosures_states_counted_from_zero(monkeypatch):
    # common_invariants' `enumerate(H[1:], 1)` -> `enumerate(H[1:], 0)` (mutant lohner_checks:236): the message
    # names the wrong states, or no earlier state is found (StopIteration)
    pytest.importorskip("flint")
    from symbt.numeric.multiprec import lohner_checks

    monkeypatch.setattr(lohner_checks, "common_invariants", _planted(lohner_checks.common_invariants,
                                                                     "enumerate(H[1:], 1)", "enumerate(H[1:], 0)"))
    assert status("paths.enclosures.n3") == "failed"
