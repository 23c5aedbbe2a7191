"""Theorems 1, 2 and the inverse problem (symbt.reference.taylor, symbt.claims.theorem1/theorem2/captions/inverse)."""
import random

import mpmath as mp
import pytest

from symbt.claims import REGISTRY, load_all
from symbt.claims.captions import caption_constants
from symbt.claims.theorem2 import compare_iterates_with_flow
from symbt.reference.inverse import solve_parameters
from symbt.reference.literal import spectral_trace_mp
from symbt.reference.samples import admissible_states, paper_state
from symbt.reference.spectral import flow_coefficients_mp
from symbt.reference.taylor import hamiltonian_flow
from symbt.reference.trace import hamiltonians, trace, trace_gap, trace_gradient


@pytest.fixture(scope="module", autouse=True)
def _claims():
    load_all()


@pytest.mark.parametrize("N", [2, 3, 4, 5])
def test_trace_polynomial_matches_lax_product(N):
    rng = random.Random(N)
    with mp.workdps(30):
        p = [mp.mpf(rng.uniform(-2, 2)) for _ in range(N)]
        q = [mp.mpf(rng.uniform(-1, 1)) for _ in range(N)]
        for lam in (mp.mpf("0.3"), mp.mpf("-1.7")):
            assert abs(trace(lam, p, q) - spectral_trace_mp(lam, p, q)) < mp.mpf(10) ** -25
        assert hamiltonians(p, q)[N] == 1
        dp, dq = trace_gradient(mp.mpf("0.3"), p, q)
        f = lambda x: spectral_trace_mp(mp.mpf("0.3"), p, q[:1] + [x] + q[2:])
        assert abs(mp.diff(f, q[1]) - dq[1]) < mp.mpf(10) ** -25


def test_flow_is_reversible_and_trivial_flows():
    with mp.workdps(30):
        p, q = [mp.mpf("0.5"), mp.mpf("-0.3"), mp.mpf("0.1")], [mp.mpf("0.2"), mp.mpf("-0.1"), mp.mpf("0.3")]
        c = [mp.mpf("0.3"), mp.mpf("-0.7"), mp.mpf("0.4")]
        pt, qt = hamiltonian_flow(p, q, c, 2)
        pb, qb = hamiltonian_flow(pt, qt, c, -2)
        assert max(abs(a - b) for a, b in zip(pb + qb, p + q)) < mp.mpf(10) ** -25
        # G = H_2 = p1 + p2 + p3: q_j -> q_j + t, p fixed
        pt, qt = hamiltonian_flow(p, q, [0, 0, 1], mp.mpf("1.5"))
        assert max(abs(a - b) for a, b in zip(pt + qt, p + [v + mp.mpf("1.5") for v in q])) < mp.mpf(10) ** -25
        # the integrals are conserved
        H0, H1 = hamiltonians(p, q), hamiltonians(*hamiltonian_flow(p, q, c, 3))
        assert max(abs(a - b) for a, b in zip(H0, H1)) < mp.mpf(10) ** -25


@pytest.mark.parametrize("N", [2, 3])
@pytest.mark.parametrize("branch", [1, -1])
def test_one_step_is_time_one_flow_and_wrong_sign_is_caught(N, branch):
    with mp.workdps(30):
        for sign in (1, -1):
            p, q, l0, mu = admissible_states(N, sign, 1)[0]
            assert trace_gap(p, q, l0 - mu, l0 + mu) > 0
            good, _ = compare_iterates_with_flow(p, q, l0, mu, branch, (1, 3))
            bad, _ = compare_iterates_with_flow(p, q, l0, mu, branch, (1,), sign=-1)
            assert max(good.values()) < mp.mpf(10) ** -25
            assert bad[1] > mp.mpf(10) ** -3


def test_paper_example_five_steps():
    with mp.workdps(30):
        p, q, l0, mu = paper_state("2")
        res, _ = compare_iterates_with_flow(p, q, l0, mu, 1, (5,))
        assert res[5] < mp.mpf(10) ** -24


def test_caption_constants():
    c5, c2 = caption_constants("5"), caption_constants("2")
    assert [mp.nstr(v, 12) for v in c5] == ["-0.00504544110287", "-0.048548178092", "-0.512050368038"]
    assert [mp.nstr(v, 12) for v in c2] == ["-0.00184505963817", "-0.0183446307667", "-0.184877067007"]


@pytest.mark.parametrize("N", [2, 3])
def test_solve_parameters_round_trip(N):
    with mp.workdps(30):
        for sign, b in ((1, 1), (-1, -1)):
            p, q, l0, mu = admissible_states(N, sign, 1)[0]
            c = flow_coefficients_mp(p, q, l0, mu, b)
            modes = [("exact", (0, 1))] + ([("direction", None), ("lstsq", None)] if N == 3 else [])
            for mode, idx in modes:
                s = solve_parameters(p, q, c, mode=mode, indices=idx)
                assert s["branch"] == b
                assert abs(s["lam0"] - l0) < mp.mpf(10) ** -22 and abs(s["mu"] - mu) < mp.mpf(10) ** -22


def test_solve_parameters_paper_orbit_and_unattainable_target():
    with mp.workdps(30):
        p, q, l0, mu = paper_state("5")
        c = flow_coefficients_mp(p, q, l0, mu, 1)
        s = solve_parameters(p, q, c, mode="exact", indices=(1, 2))
        assert abs(s["lam0"] - 10) < mp.mpf(10) ** -22 and abs(s["mu"] - 5) < mp.mpf(10) ** -22
        # the time step kappa: a scaled target has the same direction, found with kappa = 1/2
        s = solve_parameters(p, q, [2 * v for v in c], mode="direction")
        assert abs(s["lam0"] - 10) < mp.mpf(10) ** -20 and abs(s["kappa"] - mp.mpf(1) / 2) < mp.mpf(10) ** -20
        # c_0 c_2 < c_1^2 is never attained: Newton finds no admissible parameters
        with pytest.raises(ValueError):
            solve_parameters(p, q, [c[0], 2 * c[1], c[2]], mode="direction")


@pytest.mark.parametrize("cid", ["x.n2", "Hdiscr.n2", "eqdisc.n2", "linearcomb.n2", "inverse.n2"])
def test_fast_claims_verified(cid):
    out = REGISTRY[cid].run()
    assert out.status == "verified", out.detail


@pytest.mark.parametrize("cid", ["x.newkmu.n2", "Hdis", "caption.fig:1", "caption.fig:2"])
def test_expected_errata(cid):
    out = REGISTRY[cid].run()
    assert out.status == "erratum", out.detail
    assert out.corrected


def test_deep_claims_are_marked_deep():
    assert REGISTRY["Hdiscr.deep.n3"].deep and REGISTRY["inverse.deep.n3"].deep
    assert not REGISTRY["Hdiscr.n3"].deep
