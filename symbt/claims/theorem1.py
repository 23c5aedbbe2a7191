r"""Theorem 1 on the Toda BT (eq. ``x``) and the sentence after eq. ``newkmu`` (N = 2, 3).

As functions of :math:`\mu` the images :math:`(\tilde p,\tilde q)` of the map follow Hamilton's
equations :math:`\partial_\mu\tilde q = \partial\Phi/\partial\tilde p`,
:math:`\partial_\mu\tilde p = -\partial\Phi/\partial\tilde q`.  Two independent routes meet:
the :math:`\mu`-derivative of the explicit map (central differences of
:func:`symbt.reference.literal.literal_step`) and the gradient of :math:`\Phi` at the image --
either :math:`\hat\Phi = \partial F/\partial\mu = \sum_k\ln\frac{\eta_k+\mu}{\eta_k-\mu}` (eq.
``vqqtmu``, the :math:`\eta_k` of the inverse map at the image) or the trace formula
:math:`\Phi = -b\,(\operatorname{sgn}\operatorname{tr}_1\operatorname{arccosh}\frac{|\operatorname{tr}_1|}2
+ \operatorname{sgn}\operatorname{tr}_2\operatorname{arccosh}\frac{|\operatorname{tr}_2|}2)`
(gradient by the chain rule through :math:`\operatorname{tr}L(\lambda_0\pm\mu)`).

Printed formulas are evaluated as printed with principal branches (complex where the argument
leaves the real domain, see :mod:`symbt.claims._common`); a constant imaginary part does not
change a Hamiltonian vector field, so eq. ``newkmu``'s
:math:`-\operatorname{arccosh}(\cdot)-\operatorname{arccosh}(\cdot)` generates the map exactly in the
cells where its derivative :math:`\mp 1/\sqrt{\operatorname{tr}^2-4}` has the branch's sign -- the
cells are listed by the generated scope.
"""
from __future__ import annotations

from dataclasses import replace

import mpmath as mp
import sympy as sp

from ..proof.cells import CellTable
from ..reference.literal import phi_from_traces
from ._bt import H, fd_gradient, inverse_etas, theorem1_data
from ._common import DPS, fmt_state, judge_cells, lambdified, per_cell
from .base import Outcome, Parts, claim, scene

scene("theorem1", "Theorem 1 (eq. x): mu-derivative of the BT image = Hamiltonian vector field of Phi (N=2,3)")

eta, mu_ = sp.symbols("eta mu", real=True)
tr1, tr2, branch = sp.symbols("tr1 tr2 branch", real=True)


def phi_real() -> sp.Expr:
    """The real Phi of branch ``branch`` in the traces (the one implementation, in :mod:`symbt.reference.literal`;
    built when a claim runs, so the claims check the library's formula as it is now)."""
    return phi_from_traces(tr1, tr2, branch, ns=sp)


PHI_PRINTED = -sp.acosh(tr1 / 2) - sp.acosh(tr2 / 2)
TOL1 = 1e-25


def _hamilton_residual(d: dict, gp: list, gq: list, signs: tuple = (1, -1)) -> mp.mpf:
    """|dq~/dmu - s_q dPhi/dp~|, |dp~/dmu - s_p dPhi/dq~| relative to the size of the vector field."""
    lhs = d["dQ"] + d["dP"]
    rhs = [signs[0] * v for v in gp] + [signs[1] * v for v in gq]
    return max(abs(a - c) for a, c in zip(lhs, rhs)) / max(1, max(abs(v) for v in rhs))


def _trace_gradient_of(f, d: dict) -> tuple[list, list]:
    """Gradient at the image of ``f(tr1, tr2, b)`` by the chain rule through tr L(lam0 +- mu)."""
    d1, d2 = fd_gradient(f, d["tr1"], d["tr2"], d["b"])
    (p1, q1), (p2, q2) = d["grad1"], d["grad2"]
    return [d1 * a + d2 * c for a, c in zip(p1, p2)], [d1 * a + d2 * c for a, c in zip(q1, q2)]


def _parts_x(N: int) -> Parts:
    return Parts(printed={"dFdmu_term": sp.log((eta + mu_) / (eta - mu_)), "Phi": phi_real(), "hamilton": (1, -1)},
                 context={"Phi_hat": "sum over sites k of dFdmu_term at eta = eta_k (eq. vqqtmu)",
                          "hamilton": "(s_q, s_p): dq~/dmu = s_q dPhi/dp~, dp~/dmu = s_p dPhi/dq~"})


@claim("x", equation="x", scene="theorem1", sizes=(2, 3), parts=_parts_x,
       statement="Theorem 1: as functions of mu the image (p~, q~) of the BT satisfies dq~/dmu = dPhi/dp~, "
                 "dp~/dmu = -dPhi/dq~ at (p~, q~), with Phi^(p~,q~,mu) = dF/dmu = sum_k ln((eta_k+mu)/(eta_k-mu)) "
                 "(eq. vqqtmu, principal logarithms) at q = q(p~,q~,mu) -- equivalently with Phi = -b(sgn tr1 "
                 "arccosh|tr1|/2 + sgn tr2 arccosh|tr2|/2) at lam0 +- mu, which is real and equals "
                 "sum_k ln|(eta_k+mu)/(eta_k-mu)| (N={N})")
def theorem1_check(N: int, parts: Parts, deep: bool = False) -> Outcome:
    P = parts.printed
    term = lambdified((eta, mu_), P["dFdmu_term"])
    phi = lambdified((tr1, tr2, branch), P["Phi"])
    table = CellTable(tol=TOL1)
    worst_hat = worst_tr = worst_val = mp.mpf(0)
    with mp.workdps(DPS):
        for d, (etas, eta_pm) in zip(theorem1_data(N, per_cell(deep)), inverse_etas(N, per_cell(deep))):
            m = d["state"][3]

            def phi_hat(etas):
                return mp.fsum(term(e, m) for e in etas)

            g = [(phi_hat(a) - phi_hat(c)) / (2 * H) for a, c in eta_pm]
            r_hat = _hamilton_residual(d, g[:N], g[N:], P["hamilton"])
            r_tr = _hamilton_residual(d, *_trace_gradient_of(phi, d), P["hamilton"])
            value = phi(d["tr1"], d["tr2"], d["b"])
            real = mp.fsum(mp.log(abs((e + m) / (e - m))) for e in etas)
            r_val = max(abs(value - real) / max(1, abs(real)), abs(mp.im(value)))
            worst_hat, worst_tr, worst_val = max(worst_hat, r_hat), max(worst_tr, r_tr), max(worst_val, r_val)
            table.add(d["cell"], printed=max(r_hat, r_tr, r_val),
                      point=fmt_state(d["state"], d["b"], tr1=d["tr1"], tr2=d["tr2"]))
    out = judge_cells(table, method=f"numeric: mpmath {DPS} digits; d/dmu of the explicit map vs the Hamiltonian "
                                    f"vector field of Phi at the image (central differences, step {mp.nstr(H, 1)})",
                      printed="dq~/dmu = dPhi/dp~, dp~/dmu = -dPhi/dq~ with Phi^ = dF/dmu and with the trace formula",
                      dps=DPS,
                      detail=f"worst residuals: with Phi^ = dF/dmu (eta_k of the inverse map at the image) "
                             f"{mp.nstr(worst_hat, 3)}; with the trace formula {mp.nstr(worst_tr, 3)}; trace formula "
                             f"vs sum_k ln|(eta_k+mu)/(eta_k-mu)| and its imaginary part {mp.nstr(worst_val, 3)};")
    out = replace(out, n_scope=[N])
    return out


def _parts_newkmu(N: int) -> Parts:
    return Parts(printed={"Phi": PHI_PRINTED}, corrected={"Phi": phi_real()})


@claim("x.newkmu", equation="x", scene="theorem1", sizes=(2, 3), parts=_parts_newkmu, uses=("newkmu",),
       where="Sec. 3.2, sentence after eq. newkmu: 'According to Theorem 1, the BTs given by (D) are the "
             "integral curves of the Hamiltonian system given by (newkmu)'",
       statement="the BTs are the integral curves (in mu) of the Hamiltonian Phi of eq. newkmu, "
                 "Phi = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2) (principal arccosh) (N={N})")
def theorem1_newkmu(N: int, parts: Parts, deep: bool = False) -> Outcome:
    f_pr = lambdified((tr1, tr2, branch), parts.printed["Phi"])
    f_co = lambdified((tr1, tr2, branch), parts.corrected["Phi"])
    table = CellTable(tol=TOL1)
    with mp.workdps(DPS):
        for d in theorem1_data(N, per_cell(deep)):
            rp = _hamilton_residual(d, *_trace_gradient_of(f_pr, d))
            rc = max(_hamilton_residual(d, *_trace_gradient_of(f_co, d)),
                     abs(mp.im(f_co(d["tr1"], d["tr2"], d["b"]))))
            table.add(d["cell"], printed=rp, corrected=rc,
                      point=fmt_state(d["state"], d["b"], tr1=d["tr1"], tr2=d["tr2"]))
    out = judge_cells(table, method=f"numeric: mpmath {DPS} digits; d/dmu of the explicit map vs the Hamiltonian "
                                    "vector field of Phi (principal arccosh, complex; gradient through tr L)",
                      printed="Phi = -arccosh(tr L(l1)/2) - arccosh(tr L(l2)/2) generates the BT in mu",
                      corrected="the BT of branch b (gamma = b sqrt(tr^2-4)) is generated by the real Phi = -b "
                                "(sgn(tr1) arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2))",
                      dps=DPS)
    out = replace(out, n_scope=[N])
    return out
