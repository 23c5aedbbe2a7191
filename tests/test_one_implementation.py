"""One implementation of each thing, and the claims see it (issue 21, item 2).

The implicit derivative of the generating function (:func:`symbt.symbolic.generating.implicit_derivative`,
behind ``GeneratingFunction.total_derivative``), the real Phi of the traces
(:func:`symbt.reference.literal.phi_from_traces`) and the Poisson bracket (``TodaModel.poisson``) each
exist once; the claims call them.  Each test plants a realistic single-point bug in the library
function -- by swapping the function's code object, so that every caller, whatever name it imported,
runs the bug, as after an edit of the source -- runs the relevant claims in-process through the
engine (no cache: ``conftest`` gives each test its own cache directory, and ``use_cache=False``) and
asserts that a claim is no longer verified.  Without the bug the same claims are verified.
"""
from __future__ import annotations

import mpmath as mp
import pytest
import sympy as sp

import symbt
from symbt.claims import load_all
from symbt.reference import literal
from symbt.symbolic import generating
from symbt.symbolic.toda import TodaModel

OK = ("verified", "erratum")


def statuses(ids):
    """Run the claims ``ids`` in this process (no workers, no cache), ``{id: status}``."""
    load_all()
    return {r.claim.id: r.status for r in symbt.verify(list(ids), use_cache=False, budget=None)}


def plant(monkeypatch, target, buggy):
    """Give ``target`` the body of ``buggy`` (same signature): every reference to it runs the bug."""
    monkeypatch.setattr(target, "__code__", buggy.__code__)


# --------------------------------------------------------------------------- the implicit derivative of F

GF_CLAIMS = ("newgf.n2", "PoincareCartan")


def _lost_half(expr, var, etas, mu_):
    # the planted bug: d eta/d var = (d w/d var)/eta, the factor 1/2 of eta^2 = mu^2 + w lost
    out = sp.diff(expr, var)
    for e, w in etas.items():
        de = sp.diff(expr, e)
        if de == 0:
            continue
        deta = mu_ / e if var == mu_ else sp.diff(w, var) / e
        if deta != 0:
            out += de * deta
    return out


def test_generating_function_claims_hold_with_the_library():
    assert statuses(GF_CLAIMS) == {c: "verified" for c in GF_CLAIMS}


def test_a_lost_half_in_the_implicit_derivative_fails_claims(monkeypatch):
    plant(monkeypatch, generating.implicit_derivative, _lost_half)
    got = statuses(GF_CLAIMS)
    assert got["newgf.n2"] not in OK and got["PoincareCartan"] not in OK, got


def test_a_lost_half_in_total_derivative_fails_newgf(monkeypatch):
    # the bug, in the method itself (the old body, without the 1/2)
    def total_derivative(self, expr, var):
        out = sp.diff(expr, var)
        for j, e in enumerate(self.eta):
            de = sp.diff(expr, e)
            if de != 0:
                out += de * (self.mu if var == self.mu else sp.diff(self.w(j), var)) / e
        return out

    monkeypatch.setattr(generating.GeneratingFunction, "total_derivative", total_derivative)
    assert statuses(["newgf.n2"])["newgf.n2"] not in OK


def test_the_implicit_derivative_against_a_closed_form():
    # eta = sqrt(mu^2 + w) explicitly: the implicit derivative must equal the explicit one
    g = generating.generating_function(2)
    explicit = {e: sp.sqrt(g.mu ** 2 + g.w(j)) for j, e in enumerate(g.eta)}
    for var in (g.E[0], g.Et[1], g.mu):
        implicit = g.total_derivative(g.F, var).xreplace(explicit)
        direct = sp.diff(g.F.xreplace(explicit), var)
        at = {g.E[0]: sp.Rational(3, 2), g.E[1]: sp.Rational(2, 3), g.Et[0]: sp.Rational(1, 2),
              g.Et[1]: sp.Rational(5, 4), g.mu: sp.Rational(7, 3), g.lam0: sp.Rational(1, 5)}
        a, b = complex(implicit.subs(at).evalf(40)), complex(direct.subs(at).evalf(40))
        assert abs(a - b) <= 1e-30 * max(1.0, abs(b)), var


# --------------------------------------------------------------------------- the real Phi of the traces

PHI_CLAIMS = ("x.n2", "newkmu.n2", "x.newkmu.n2", "newkmu.screen")


def _flipped_phi(tr1, tr2, branch, *, ns=mp):
    # the planted bug: the overall sign of Phi flipped
    return branch * (ns.sign(tr1) * ns.acosh(abs(tr1) / 2) + ns.sign(tr2) * ns.acosh(abs(tr2) / 2))


def test_phi_claims_hold_with_the_library():
    assert statuses(PHI_CLAIMS) == {"x.n2": "verified", "newkmu.n2": "erratum", "x.newkmu.n2": "erratum",
                                   "newkmu.screen": "verified"}


def test_a_flipped_sign_of_phi_fails_claims(monkeypatch):
    plant(monkeypatch, literal.phi_from_traces, _flipped_phi)
    got = statuses(PHI_CLAIMS)
    assert all(s not in OK for s in got.values()), got


def _flipped_branch(T, *, ns=mp):
    # the planted bug: the real branch of arccosh(T/2) loses its sign
    return ns.acosh(abs(T) / 2)


def test_a_lost_sign_in_the_real_arccosh_fails_claims(monkeypatch):
    # signed_arccosh_half is Phi's building block and the density of H in eqs. Hdis, AA2
    plant(monkeypatch, literal.signed_arccosh_half, _flipped_branch)
    got = statuses(("x.n2", "Hdis"))
    assert all(s not in OK for s in got.values()), got


def test_phi_one_formula_for_every_namespace():
    # the SymPy expression (claims, codegen) and the mpmath numbers are the same formula
    from symbt.codegen.derive import branch, phi_of

    t1, t2 = sp.symbols("t1 t2", real=True)
    assert phi_of(t1, t2) == literal.phi_from_traces(t1, t2, branch, ns=sp)
    f = sp.lambdify((t1, t2, branch), phi_of(t1, t2), "mpmath")
    with mp.workdps(40):
        for a, c, b in ((3, 5, 1), (-2.5, -7, 1), (4, 9, -1), (-3, -2.01, -1)):
            x, y = mp.mpf(a), mp.mpf(c)
            assert abs(f(x, y, b) - literal.phi_from_traces(x, y, b)) < mp.mpf(10) ** -35


# --------------------------------------------------------------------------- the Poisson bracket

BRACKET = ("intdis.poisson.n2", "intdis.poisson.n3")


def _flipped_poisson(self, f, g):
    # the planted bug: {f, g} = sum f_q g_p - f_p g_q, i.e. {p_i, q_j} = -delta_ij
    return sp.Add(*[self.d_q(f, i) * self.d_p(g, i) - self.d_p(f, i) * self.d_q(g, i) for i in range(self.N)])


def _flipped_field(self, H):
    # the planted bug: pdot = +H_q
    return ([self.d_p(H, i) for i in range(self.N)], [self.d_q(H, i) for i in range(self.N)])


def test_the_convention_claim_holds():
    assert statuses(BRACKET) == {c: "verified" for c in BRACKET}


@pytest.mark.parametrize("method, buggy", [("poisson", _flipped_poisson),
                                           ("hamiltonian_vector_field", _flipped_field)])
def test_a_flipped_bracket_fails_the_convention_claim(monkeypatch, method, buggy):
    plant(monkeypatch, getattr(TodaModel, method), buggy)
    got = statuses(BRACKET + ("Hj.n2",))
    assert got["intdis.poisson.n2"] not in OK and got["intdis.poisson.n3"] not in OK, got
    # the involution claims compare brackets with 0 and cannot see the sign: why the convention claim exists
    assert got["Hj.n2"] == "verified"
