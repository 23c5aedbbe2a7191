r"""The single-parameter BT as an explicit map on the lattice: eqs. ``local`` and ``LhDhDL``.

The claims of :mod:`.single_bt` and :mod:`.appendix_a` prove the relations for generic symbols;
here they are read on the actual map (:func:`symbt.claims._maps.single_bt`: :math:`\beta_1` from
the quadratic of eq. ``v1`` with root sign ``r``, then eq. ``ptp`` site by site), sampled in the
cells ``{root = +-1}`` (for real maps :math:`\zeta < -\max_j p_j`, and the sign of
:math:`\operatorname{tr}L(\zeta)` is :math:`(-1)^N`, so it is no cell of its own).

* ``local``: :math:`l_j(\lambda,\tilde p_j,\tilde q_j)\,d_j(\lambda) = d_{j+1}(\lambda)\,l_j(\lambda,p_j,q_j)` at
  every site, with :math:`d_j` of eq. ``dj``, :math:`\alpha_j = e^{q_j}`, :math:`\beta_j = e^{-\tilde q_{j-1}}`
  (eq. ``alphabeta``) and :math:`d_{N+1} = d_1` (periodicity);
* ``LhDhDL``: :math:`L(\lambda,p,q)\,\hat D(\lambda) = \hat D(\lambda)\,L(\lambda,\tilde p,\tilde q)` with the printed
  :math:`\hat D` (eq. ``hd``), and the inverse is the root :math:`w = v^{-1}`: the kernel
  :math:`(\alpha_1,-1)` of :math:`\hat D(\zeta)` is an eigenvector of :math:`\tilde L(\zeta)` with eigenvalue
  :math:`w` and :math:`w\,v = 1`, :math:`v` the eigenvalue of :math:`L(\zeta)` on :math:`(1,-\beta_1)`.

>>> out = local.claims[0].run()
>>> out.status, out.n_scope, [c["cell"] for c in out.cells]
('verified', [2], [{'root': 1}, {'root': -1}])
"""
from __future__ import annotations

from dataclasses import replace

import mpmath as mp
import sympy as sp

from ..proof.cells import CellTable
from ..symbolic.toda import lam
from ._common import DPS, TOL, fmt_state, judge_cells, lambdified, per_cell
from ._maps import lax, local_lax, mat_mul, mat_norm, mat_sub, single_cells
from .base import Outcome, Parts, claim, scene

scene("single-bt-map", "the single BT as an explicit map: local relation, intertwining of its inverse (N=2,3)")

zeta = sp.Symbol("zeta")
alpha_j, beta_j, alpha, beta = sp.symbols("alpha_j beta_j alpha beta")
LAMBDAS = ("1.7", "0.3", "-2.1")   # offsets from zeta / values of lambda besides zeta itself


def _lambdas(z) -> list:
    return [z, z + mp.mpf(LAMBDAS[0]), mp.mpf(LAMBDAS[1]), mp.mpf(LAMBDAS[2])]


def _relation(left: tuple, M: tuple, right: tuple) -> mp.mpf:
    """|left M - M right| relative to |left| |M|."""
    return mat_norm(mat_sub(mat_mul(left, M), mat_mul(M, right))) / (mat_norm(left) * max(1, mat_norm(M)))


def _parts_local(N: int) -> Parts:
    return Parts(printed={"d": sp.Matrix([[lam - zeta - alpha_j * beta_j, -alpha_j], [beta_j, 1]])},
                 context={"alpha_j": "e^{q_j}", "beta_j": "e^{-q~_{j-1}}"})


@claim("local", equation="local", scene="single-bt-map", sizes=(2, 3), parts=_parts_local,
       statement="on the explicit single BT: l_j(lambda, p~_j, q~_j) d_j(lambda) = d_{j+1}(lambda) "
                 "l_j(lambda, p_j, q_j) at every site, d_j = [[lambda-zeta-alpha_j beta_j, -alpha_j],[beta_j, 1]], "
                 "alpha_j = e^{q_j}, beta_j = e^{-q~_{j-1}}, d_{N+1} = d_1 (N={N})")
def local(N: int, parts: Parts, deep: bool = False) -> Outcome:
    d = lambdified((lam, zeta, alpha_j, beta_j), parts.printed["d"])
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, (p, q, z), r, pt, qt in single_cells(N, per_cell(deep)):
            worst = mp.mpf(0)
            for lv in _lambdas(z):
                ds = [tuple(d(lv, z, mp.exp(q[j]), mp.exp(-qt[j - 1]))) for j in range(N)]
                for j in range(N):
                    lt, lo = local_lax(lv, pt[j], qt[j]), local_lax(lv, p[j], q[j])
                    res = mat_sub(mat_mul(lt, ds[j]), mat_mul(ds[(j + 1) % N], lo))
                    worst = max(worst, mat_norm(res) / (mat_norm(lt) * max(1, mat_norm(ds[j]))))
            table.add(cell, printed=worst, point=fmt_state((p, q, z, mp.mpf(0)), r, zeta=z))
    out = judge_cells(table, method=f"numeric: mpmath {DPS} digits, every site, 4 values of lambda (one = zeta)",
                      printed="l_j(p~, q~) d_j = d_{j+1} l_j(p, q), d_{N+1} = d_1")
    out = replace(out, n_scope=[N])
    return out


def _parts_lhdhdl(N: int) -> Parts:
    return Parts(printed={"Dhat": sp.Matrix([[1, alpha], [-beta, lam - zeta - alpha * beta]]), "wv": 1},
                 context={"alpha": "e^{q_1}", "beta": "e^{-q~_N}"})


@claim("LhDhDL", equation="LhDhDL", scene="single-bt-map", sizes=(2, 3), parts=_parts_lhdhdl,
       statement="on the explicit single BT: L(lambda, p, q) D^(lambda) = D^(lambda) L(lambda, p~, q~) with D^ = "
                 "[[1, alpha_1],[-beta_1, lambda-zeta-alpha_1 beta_1]], alpha_1 = e^{q_1}, beta_1 = e^{-q~_N}; the "
                 "kernel (alpha_1, -1) of D^(zeta) is an eigenvector of L~(zeta) with eigenvalue w, w v = 1 (N={N})")
def lhdhdl(N: int, parts: Parts, deep: bool = False) -> Outcome:
    Dh = lambdified((lam, zeta, alpha, beta), parts.printed["Dhat"])
    wv = parts.printed["wv"]
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, (p, q, z), r, pt, qt in single_cells(N, per_cell(deep)):
            a, b = mp.exp(q[0]), mp.exp(-qt[N - 1])
            worst = max(_relation(lax(lv, p, q), tuple(Dh(lv, z, a, b)), lax(lv, pt, qt)) for lv in _lambdas(z))
            L, Lt = lax(z, p, q), lax(z, pt, qt)
            v = L[0] - b * L[1]                         # L(zeta)(1, -beta_1) = v (1, -beta_1)
            w = Lt[3] - a * Lt[2]                       # L~(zeta)(alpha_1, -1) = w (alpha_1, -1)
            eig = max(abs(L[2] - b * L[3] + v * b), abs(Lt[0] * a - Lt[1] - w * a)) / max(1, mat_norm(L), mat_norm(Lt))
            worst = max(worst, eig, abs(w * v - wv) / max(1, abs(w * v)))
            table.add(cell, printed=worst, point=fmt_state((p, q, z, mp.mpf(0)), r, zeta=z, v=v, w=w))
    out = judge_cells(table, method=f"numeric: mpmath {DPS} digits, 4 values of lambda (one = zeta); eigenvectors at "
                                    "zeta", printed="L D^ = D^ L~; L~(zeta)(alpha_1, -1) = w (alpha_1, -1), w v = 1")
    out = replace(out, n_scope=[N])
    return out
