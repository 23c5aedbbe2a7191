"""The exact claims of Sections 2-3 and Appendix A as data: parts, scopes, and checks that can fail.

Each test feeds a claim a deliberately wrong statement part (through ``Claim.run_with``) and asserts
that its own check rejects it -- the property ``symbt mutate`` measures over all mutants.
"""
from __future__ import annotations

import inspect

import pytest
import sympy as sp

from symbt.claims import REGISTRY, load_all

PER_SITE = ["dj", "alphabeta", "ptp", "daj", "xyqqt", "imptransf"]
GENERIC_2X2 = ["d1", "v1", "hd", "v11", "tiltil", "D1D2", "Dapp"]


@pytest.fixture(scope="module", autouse=True)
def _load():
    load_all()


def run(cid, side=None, name=None, value=None):
    c = REGISTRY[cid]
    if side is None:
        return c.run()
    return c.run_with(c.parts().replace(side, name, value))


@pytest.mark.parametrize("cid", PER_SITE + GENERIC_2X2)
def test_local_and_2x2_statements_hold_for_every_n_with_the_argument(cid):
    out = run(cid)
    assert out.status == "verified" and out.evidence == "proof"
    assert out.n_scope == "all"
    assert "every N:" in out.detail and ("telescope" in out.detail or "2x2" in out.detail)


def test_size_families_record_their_size_and_deep_sizes_exist():
    for stem in ("lax", "tra", "Hj", "newgf", "vqqtmu"):
        assert not REGISTRY[f"{stem}.n4"].deep
        assert REGISTRY[f"{stem}.n5"].deep and REGISTRY[f"{stem}.n5"].N == 5
    assert not REGISTRY["nlocal.n4"].deep and REGISTRY["nlocal.n5"].deep and REGISTRY["GF.n4"].deep
    assert run("lax.n4").n_scope == [4]
    assert run("Hj.n2").n_scope == [2]


def test_tiltil_depends_on_the_order_of_the_factors():
    c = REGISTRY["tiltil"]
    ctx = c.parts().context
    swapped = (ctx["D1"] * ctx["Dhat2"]).applyfunc(sp.expand)
    assert run("tiltil", "printed", "composition", swapped).status == "failed"
    # D(l2) instead of its adjugate is not an intertwiner of L~ and L~~ either
    from symbt.symbolic.darboux import single_darboux

    x2, y2 = sp.symbols("x_2 y_2")
    not_adj = (single_darboux(x2, y2, sp.Symbol("lambda2", real=True)) * ctx["D1"]).applyfunc(sp.expand)
    assert run("tiltil", "printed", "composition", not_adj).status == "failed"
    assert run("tiltil").status == "verified"


def test_hj_rejects_a_symmetric_bracket_even_for_n2():
    fp, fq, gp, gq = sp.symbols("f_p f_q g_p g_q")
    assert run("Hj.n2", "printed", "bracket", fp * gq + fq * gp).status == "failed"
    assert run("Hj.n2", "printed", "bracket", fp * gq).status == "failed"


def test_tra_reads_the_trace_degree_and_leading_coefficient():
    A, D = sp.symbols("A D")
    assert run("tra.n3", "printed", "trace", A - D).status == "failed"
    assert run("tra.n3", "printed", "degree", sp.Integer(4)).status == "failed"
    assert run("tra.n3", "printed", "H_N", sp.Integer(2)).status == "failed"


def test_single_bt_parts_are_read_in_exponential_form():
    qt = sp.Symbol("qt_j", real=True)
    assert run("alphabeta", "printed", "beta_jp1", sp.exp(-2 * qt)).status == "failed"
    p = REGISTRY["ptp"].parts().printed["pt"]
    assert run("ptp", "printed", "pt", p - 1).status == "failed"


def test_v1_elimination_must_give_the_printed_quadratic():
    A, B, C, D, b1 = sp.symbols("A B C D beta_1")
    assert run("v1", "printed", "quad", b1 ** 2 * B + b1 * (A - D) - C).status == "failed"


def test_newgf_and_vqqtmu_read_the_summand():
    eta, q, qt = sp.symbols("eta_k q_k qt_k", real=True)
    mu, lam0 = sp.symbols("mu lambda0", real=True)
    wrong = mu * sp.log((eta + mu) / (eta - mu)) - 3 * eta - lam0 * (q - qt)
    assert run("newgf.n2", "printed", "summand", wrong).status == "failed"
    assert run("vqqtmu.n2", "printed", "summand", sp.log((eta + 2 * mu) / (eta - mu))).status == "failed"


def test_nlocal_is_a_proof_in_lambda_on_sampled_states():
    out = run("nlocal.n2")
    assert out.status == "verified" and out.evidence == "sampled" and out.n_scope == [2]
    assert "proof in lambda" in out.method and len(out.cells) == 4
    assert all(c["n"] >= 16 for c in out.cells)
    x, y = sp.symbols("x_j y_j")
    d = REGISTRY["nlocal.n2"].parts().printed["d"]
    assert run("nlocal.n2", "printed", "d", d.subs(x, -x)).status == "failed"


def test_gf_sign_convention_and_form_are_checked():
    out = run("GF.n2")
    assert out.status == "verified" and out.evidence == "sampled" and len(out.cells) == 4
    assert run("GF.n2", "printed", "b", sp.Integer(1)).status == "failed"
    assert run("GF.n2", "printed", "omega", sp.Matrix([[0, 1], [1, 0]])).status == "failed"


def test_n3_hamiltonians_erratum_reads_the_corrected_relabelling():
    k = sp.Symbol("k", integer=True)
    assert run("n3-hamiltonians.tra").status == "erratum"
    assert run("n3-hamiltonians.tra", "corrected", "power", k).status == "failed"


def test_generating_does_not_import_composed_map():
    import symbt.claims.generating as g
    import symbt.claims.generating_map as gm

    for mod in (g, gm):
        assert "composed_map" not in inspect.getsource(mod)
