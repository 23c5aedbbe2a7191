"""The map, Theorem 1/2, caption and inverse claims as data: parts read by the checks, cells, n_scope.

Each test feeds a deliberately wrong part (a swapped convention, a flipped sign, a perturbed
constant) through the claim's own check and asserts that the check sees it -- or, for the
caption constants, that it honestly cannot see a change below the printed precision.
"""
import mpmath as mp
import numpy as np
import pytest
import sympy as sp

from symbt.claims import REGISTRY, _flow, load_all
from symbt.claims.theorem2 import samples

MODULES = ("composed_map", "theorem1", "theorem2", "captions", "inverse")


@pytest.fixture(scope="module", autouse=True)
def _claims():
    load_all()


def _mine(include_deep=False):
    return [c for c in REGISTRY.values() if c.func is not None and c.func.__module__.split(".")[-1] in MODULES
            and (include_deep or not c.deep)]


def test_every_claim_exposes_parts():
    claims = _mine(include_deep=True)
    assert len(claims) >= 34
    for c in claims:
        assert c.parts is not None and c.run_parts is not None, c.id
        parts = c.parts()
        assert parts.printed, c.id


@pytest.mark.parametrize("cid", ["l1l2.n2", "xy.branches.n3", "x.newkmu.n2", "eqdisc.n2", "linearcomb.n3", "Hdis",
                                 "inverse.attainable.n3"])
def test_sampled_claims_sample_every_cell_with_a_generated_scope(cid):
    out = REGISTRY[cid].run()
    assert out.status in ("verified", "erratum"), out.detail
    assert out.evidence == "sampled" and out.n_scope
    assert len(out.cells) >= 4 and all(cell["n"] >= 16 for cell in out.cells)
    assert out.scope.startswith("printed statement")
    # no hand-written scope in the statements reported as holding
    assert "only for" not in (out.corrected or "") and "only for" not in out.detail


@pytest.mark.parametrize("cid, side, name, value", [
    ("lam0mu.n2", "printed", "gamma_signs", (1, -1)),          # the mixed pattern is not connected to the identity
    ("lam0mu.n2", "printed", "mixed_signs", (-1, -1)),          # b(-1,-1) is the other branch: it is connected
    ("xy.branches.n2", "printed", "inverse_branch", 1),        # T_b does not invert itself
    ("xy.branches.n2", "printed", "mu_reflection", (1, -1)),
    ("x.n2", "printed", "hamilton", (1, 1)),                    # dp/dmu = +dPhi/dq is the wrong sign
    ("eqdisc.n2", "printed", "flow_sign", -sp.Symbol("branch", real=True)),
    ("Hdiscr.n2", "printed", "time", -1),
    ("inverse.n2", "printed", "signed_mu", -sp.Symbol("branch", real=True) * sp.Symbol("mu", real=True)),
])
def test_a_swapped_convention_is_killed(cid, side, name, value):
    c = REGISTRY[cid]
    base = c.run().status
    out = c.run_with(c.parts().replace(side, name, value))
    assert out.status != base, (cid, name, out.detail)


def test_hdis_dropping_the_absolute_value_is_seen():
    """sgn(tr) arccosh(tr/2) has the same tr-derivative as sgn(tr) arccosh(|tr|/2) (same flow) but is complex
    where tr < -2: the corrected statement asserts a real H; the AA2 comparison reads the parts."""
    c = REGISTRY["Hdis"]
    parts = c.parts()
    tr, b = sp.Symbol("tr", real=True), sp.Symbol("branch", real=True)
    wrong = parts.replace("corrected", "integrand", -b * sp.sign(tr) * sp.acosh(tr / 2))
    assert c.run_with(wrong).status == "failed"
    assert c.run_with(parts.replace("corrected", "AA2_upper", sp.Symbol("lambda0", real=True))).status == "failed"


def test_caption_precision_is_what_the_check_can_decide():
    c = REGISTRY["caption.fig:2"]
    parts = c.parts()
    assert c.run().status == "erratum"
    vals = parts.corrected["mu=2"]
    tiny = parts.replace("corrected", "mu=2", (vals[0] * (1 + 1e-6),) + vals[1:])
    assert c.run_with(tiny).status == "erratum"       # below half a unit of the last printed decimal
    off = parts.replace("corrected", "mu=2", (vals[0] + 1e-4,) + vals[1:])
    assert c.run_with(off).status == "failed"         # one unit of the last printed decimal


def test_flow_routes_agree():
    s = samples(3, 16)[5]
    c = s["b"] * _flow.moments(s["H"], s["l0"], s["mu"], range(3))
    fast = _flow.time_flow(s["p"], s["q"], c, 1.0)
    assert _flow.rel_diff(fast[0] + fast[1], s["image"]) < 1e-12
    route = _flow.flow_route
    try:
        _flow.flow_route = lambda: "taylor"
        slow = _flow.time_flow(s["p"], s["q"], c, 1.0)
    finally:
        _flow.flow_route = route
    assert _flow.rel_diff(slow[0] + slow[1], s["image"]) < 1e-12


def test_two_constants_do_not_determine_the_parameters():
    """A finding of the deep sampling: two parameter pairs share (c_1, c_2) on one orbit (N = 3)."""
    with mp.workdps(30):
        p = [mp.mpf(v) for v in ("-1.165532", "1.129229", "0.576715")]
        q = [mp.mpf(v) for v in ("0.878405", "-0.062172", "-0.487181")]
    H = _flow.hamiltonians_float(p, q)
    a = _flow.moments(H, 0.609376, 0.533544, range(3))
    l0, m, _ = _flow.solve_signed(H, a, mode="exact", indices=(1, 2))
    b = _flow.moments(H, l0, m, range(3))
    assert abs(l0 - 0.609376) > 0.05 and np.allclose(a[1:], b[1:], rtol=1e-12, atol=0)
    assert abs(a[0] - b[0]) > 1e-2
    l0d, md, _ = _flow.solve_signed(H, a, mode="direction", indices=(0, 1, 2))
    assert abs(l0d - 0.609376) < 1e-9 and abs(md - 0.533544) < 1e-9


def test_gl_integral_refines_until_converged():
    val = _flow.gl_integral(lambda x: 1 / np.sqrt(x), 1e-2, 1.0, rtol=1e-13)
    assert abs(val - 1.8) < 1e-12
    with pytest.raises(_flow.QuadratureNotConverged):
        _flow.gl_integral(lambda x: 1 / np.sqrt(x), 1e-12, 1.0, max_panels=8)
