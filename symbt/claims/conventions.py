r"""The conventions the library computes with, and one verdict through the numeric screen.

* ``intdis.poisson`` (N = 2, 3): the paper's canonical brackets, :math:`\{p_i, q_j\} = \delta_{ij}`,
  :math:`\{p_i, p_j\} = \{q_i, q_j\} = 0` (Sec. 1, the display before eq. ``Hj``), computed with the
  library's one bracket, :meth:`symbt.symbolic.toda.TodaModel.poisson`; and the flow of eq. ``intdis``,
  :math:`\dot x = \{H, x\}`, agrees with Hamilton's equations :math:`\dot q = \partial H/\partial p`,
  :math:`\dot p = -\partial H/\partial q` for the Toda Hamiltonian
  :math:`H = \tfrac12\sum_j p_j^2 + \sum_j e^{q_{j+1}-q_j}` -- the partial derivatives taken by SymPy
  in the variables :math:`q_j` themselves, not through the bracket's :math:`E_j\,\partial/\partial E_j`.
  :meth:`~symbt.symbolic.toda.TodaModel.hamiltonian_vector_field` is checked against the same
  equations.  Every involution claim compares brackets with 0, which a bracket of the wrong sign
  passes; this claim fixes the sign.  Decided exactly.
* ``newkmu.screen`` (N-free): the real :math:`\Phi` of the traces (the library's
  :func:`symbt.reference.literal.phi_from_traces`) equals
  :math:`\ln|v(\lambda_1)| + \ln|v(\lambda_2)|`, :math:`v = (\operatorname{tr} - b\sqrt{\operatorname{tr}^2-4})/2`
  (eq. ``spec`` with real logarithms), in every cell branch :math:`b = \pm1` times sign of
  :math:`\operatorname{tr}` (:math:`\operatorname{tr}_i = s(2 + a_i)`, :math:`a_i > 0`).  Logarithms
  and ``acosh`` leave the exact layer nothing to reduce, so the verdict is the **numeric screen's**
  (:func:`symbt.proof.decide`, 50 digits); the claim also asks the screen to refute the same identity
  off by a relative :math:`10^{-40}` (above its tolerance :math:`10^{-42}`), so a screen that stops
  seeing small errors fails this claim instead of passing everything.

>>> out = canonical_brackets(2, _parts_poisson(2))
>>> out.status, out.evidence
('verified', 'proof')
"""
from __future__ import annotations

from dataclasses import replace

import sympy as sp

from ..proof import Verdict, decide
from ..reference.literal import phi_from_traces
from ..symbolic.toda import toda_model
from .base import Outcome, Parts, claim, failed, from_decision, scene

scene("conventions", "the library's conventions ({p_i, q_j} = delta_ij, xdot = {H, x}) and a verdict of the "
                     "numeric screen (real Phi = ln|v(l1)| + ln|v(l2)|) with its sensitivity control")

SIZES = (2, 3)


def _sized(out: Outcome, N: int) -> Outcome:
    out = replace(out, n_scope=[N])
    return out


# --------------------------------------------------------------------------- {p_i, q_j} = delta_ij; xdot = {H, x}

def _parts_poisson(N: int) -> Parts:
    return Parts(printed={"brackets": sp.Matrix.hstack(sp.eye(N), sp.zeros(N, N), sp.zeros(N, N)), "hamilton": (1, -1)},
                 context={"brackets": "row i: {p_i, q_j}, then {p_i, p_j}, then {q_i, q_j} (j = 1..N)",
                          "hamilton": "(s_q, s_p): xdot = {H, x} gives qdot = s_q dH/dp, pdot = s_p dH/dq"})


def toda_hamiltonian(N: int) -> tuple[sp.Expr, tuple, tuple]:
    """``(H, p, q)``: :math:`H = \\frac12\\sum p_j^2 + \\sum_j e^{q_{j+1}-q_j}` in the model's symbols ``p_j``, ``q_j``.

    >>> H, p, q = toda_hamiltonian(2)
    >>> H
    p1**2/2 + p2**2/2 + exp(-q1 + q2) + exp(q1 - q2)
    """
    m = toda_model(N)
    H = sp.Add(*[x ** 2 for x in m.p]) / 2 + sp.Add(*[sp.exp(m.q[(j + 1) % N] - m.q[j]) for j in range(N)])
    return H, m.p, m.q


@claim("intdis.poisson", equation="intdis", scene="conventions", sizes=SIZES, parts=_parts_poisson,
       where="Sec. 1: the canonical brackets before eq. Hj, and eq. intdis",
       statement="with the library's bracket (TodaModel.poisson): {p_i, q_j} = delta_ij, {p_i, p_j} = {q_i, q_j} = 0; "
                 "and xdot = {H, x} is Hamilton's qdot = dH/dp, pdot = -dH/dq for H = sum p^2/2 + sum "
                 "e^{q_{j+1}-q_j} (N={N})")
def canonical_brackets(N: int, parts: Parts) -> Outcome:
    m = toda_model(N)
    P = parts.printed
    qs = [sp.log(E) for E in m.E]                       # q_j as a function of E_j = e^{q_j}
    pairs = ((m.p, qs), (m.p, m.p), (qs, qs))         # {p_i, q_j}, {p_i, p_j}, {q_i, q_j}
    got = sp.Matrix.hstack(*(sp.Matrix(N, N, lambda i, j, f=f, g=g: m.poisson(f[i], g[j])) for f, g in pairs))
    d = decide(got, P["brackets"])
    if not d.holds:
        return _sized(from_decision(d, detail="{p_i, q_j}, {p_i, p_j}, {q_i, q_j} of TodaModel.poisson are not the "
                                              "printed canonical brackets"), N)
    # H is the Toda Hamiltonian of the model: H_{N-1}^2/2 - H_{N-2} (coefficients of tr L)
    Hq, p, q = toda_hamiltonian(N)
    HE = m.to_E(Hq)
    hs = m.hamiltonians
    d = decide(HE, hs[N - 1] ** 2 / 2 - hs[N - 2])
    if not d.holds:
        return _sized(from_decision(d, detail="H is not H_{N-1}^2/2 - H_{N-2} of tr L"), N)
    s_q, s_p = P["hamilton"]
    # Hamilton's equations, derivatives in q itself (SymPy), then written in E
    hamilton = sp.Matrix([s_q * m.to_E(sp.diff(Hq, x)) for x in p] + [s_p * m.to_E(sp.diff(Hq, x)) for x in q])
    bracket = sp.Matrix([m.poisson(HE, x) for x in qs] + [m.poisson(HE, x) for x in m.p])
    d = decide(bracket, hamilton)
    if not d.holds:
        return _sized(from_decision(d, detail="xdot = {H, x} (TodaModel.poisson) differs from Hamilton's equations"),
                      N)
    qdot, pdot = m.hamiltonian_vector_field(HE)
    d = decide(sp.Matrix(list(qdot) + list(pdot)), hamilton)
    return _sized(from_decision(d, detail=f"exactly in E_j = e^(q_j): the {3 * N * N} canonical brackets; "
                                          "xdot = {H, x} and TodaModel.hamiltonian_vector_field against Hamilton's "
                                          "equations with dH/dq_j taken in q_j (SymPy), for the Toda H = "
                                          "H_{N-1}^2/2 - H_{N-2}" + ("" if d.holds else
                                                                     "; hamiltonian_vector_field differs")), N)


# --------------------------------------------------------------------------- a verdict of the numeric screen

tr1, tr2, branch = sp.symbols("tr1 tr2 branch", real=True)
a1, a2 = sp.symbols("a1 a2", positive=True)
DIGITS = 50
#: the relative error the control plants: 100 times the screen's tolerance 10^-(DIGITS - 8)
CONTROL = sp.Integer(10) ** -(DIGITS - 10)


def _v_log(t, b):
    return sp.log(sp.Abs((t - b * sp.sqrt(t ** 2 - 4)) / 2))


def _parts_screen() -> Parts:
    return Parts(printed={"Phi": phi_from_traces(tr1, tr2, branch, ns=sp),
                          "rhs": _v_log(tr1, branch) + _v_log(tr2, branch)},
                 context={"Phi": "the library's real Phi of the traces (symbt.reference.literal.phi_from_traces)",
                          "rhs": "ln|v(l1)| + ln|v(l2)|, v = (tr - b sqrt(tr^2 - 4))/2 (eq. spec, real logs)"})


def _cell(b: int, s: int) -> dict:
    """The screen's keywords for the cell {branch=b, sign_tr=s}: tr_i = s (2 + a_i) as degree-1 relations
    (solved numerically by the screen; no substitution into the expression) and the branch pinned."""
    return {"relations": {tr1: tr1 - s * (2 + a1), tr2: tr2 - s * (2 + a2)}, "fixed": {branch: b}}


@claim("newkmu.screen", equation="newkmu", scene="conventions", parts=_parts_screen,
       where="eqs. spec and newkmu (real form): the logarithms of the eigenvalues v(l_i) and the arccosh form",
       statement="real Phi = -b (sgn(tr1) arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2)) = ln|v(l1)| + ln|v(l2)|, "
                 "v(l_i) = (tr_i - b sqrt(tr_i^2 - 4))/2, for |tr_i| > 2 of one sign and b = +-1 (decided by the "
                 "numeric screen)")
def phi_screen(parts: Parts) -> Outcome:
    P = parts.printed
    last: Verdict | None = None
    for b in (1, -1):
        for s in (1, -1):
            lhs, rhs, cell = P["Phi"], P["rhs"], _cell(b, s)
            # logarithms and acosh: the exact layer has nothing to reduce, the screen decides
            d = decide(lhs, rhs, exact=False, digits=DIGITS, seed=1729 + 2 * b + s, **cell)
            if not d.holds:
                return from_decision(d, detail=f"cell branch={b:+d}, sign_tr={s:+d}")
            outside = [pt for pt in d.points for t in ("tr1", "tr2") if not s * float(pt[t]) > 2]
            if outside or not d.points:
                return failed(d.method, detail=f"the screen's points are not in the cell sign_tr={s:+d}: {outside[:1]}")
            control = decide(lhs, rhs * (1 + CONTROL), exact=False, digits=DIGITS, seed=1729 + 2 * b + s, **cell)
            if control.holds or control.inconclusive or not control.counterexample:
                return failed(control.method, residual=control.residual,
                              detail=f"the numeric screen did not refute the identity off by a relative "
                                     f"{float(CONTROL):.0e} (cell branch={b:+d}, sign_tr={s:+d}): its tolerance "
                                     f"is not 10^-{DIGITS - 8} at {DIGITS} digits, so its verdicts mean nothing")
            last = d
    assert last is not None
    out = from_decision(last, detail=f"decided by the numeric screen ({DIGITS} digits, exact layer skipped: log, "
                                     f"acosh) in each of the 4 cells branch x sign(tr), tr_i = s (2 + a_i), a_i > 0; "
                                     f"control: the same identity off by a relative {float(CONTROL):.0e} is refuted "
                                     f"with a counterexample in every cell")
    out = replace(out, n_scope="all")
    return out
