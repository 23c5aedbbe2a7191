r"""The composed map sampled by domain cells: eqs. ``nlocal`` (site-by-site factorisation) and ``GF``
(canonicity): nlocal for N = 2, 3, 4 (5 under ``--deep``), GF for N = 2, 3 (4, 5 under ``--deep``).

``nlocal``: on the map (the literal route of :mod:`symbt.reference.literal`, which finds :math:`x_j, y_j` by
transporting kernels, Appendix B), every site satisfies
:math:`l_j(\lambda,\tilde p_j,\tilde q_j)\,\mathfrak d_j(\lambda) = \mathfrak d_{j+1}(\lambda)\,l_j(\lambda,p_j,q_j)`
with :math:`\mathfrak d_j` the printed matrix of eq. ``daj`` and :math:`\mathfrak d_{N+1} = \mathfrak d_1`.  The
residual is a matrix polynomial in :math:`\lambda` of degree at most :math:`1 + \deg_\lambda\mathfrak d_j`; checking
it at one more value of :math:`\lambda` than that degree proves it in :math:`\lambda` at each sampled state, while
the states themselves are sampled cell by cell (``map_cells``: branch x sign of tr L), so the evidence is
"sampled".

``GF``: a generating function :math:`F(q,\tilde q)` with :math:`p = a\,\partial F/\partial q`,
:math:`\tilde p = b\,\partial F/\partial\tilde q` (printed: :math:`a = 1`, :math:`b = -1`) exists iff
:math:`dF = p\,dq/a + \tilde p\,d\tilde q/b` is closed, i.e. the Jacobian :math:`J` of the map satisfies
:math:`J^T\Omega J = -(b/a)\,\Omega` with :math:`\Omega = \omega\otimes\mathbb 1_N` (:math:`\omega` the form on one pair
:math:`(p_j, q_j)`), and :math:`(q,\tilde q)` are coordinates (:math:`\det\partial\tilde q/\partial p \ne 0`).  J is
taken from the literal map by the complex step :math:`J e_i = \operatorname{Im} T(z + i h e_i)/h`, which has no
subtractive cancellation: at 40 digits with :math:`h = 10^{-20}` its truncation error is
:math:`O(h^2) = 10^{-40}` (relative); the rounding of the literal route (its forward transport loses about
:math:`2\log_{10}|\operatorname{tr}L|` digits) stays below :math:`10^{-35}` on the samples (N <= 5), so the
tolerance :math:`10^{-28}` keeps seven digits of margin while any wrong form or sign gives a residual of order one.

>>> out = GF(2, _parts_gf(2))
>>> out.status, out.evidence, [c["n"] for c in out.cells]
('verified', 'sampled', [16, 16, 16, 16])
"""
from __future__ import annotations

from dataclasses import replace
from functools import cache

import mpmath as mp
import sympy as sp

from ..proof.cells import CellTable
from ..reference.literal import literal_step
from ..symbolic.darboux import composed_darboux, lam1, lam2
from ..symbolic.toda import lam
from ._common import DPS, TOL, fmt_state, judge_cells, lambdified, map_cells, per_cell
from .base import Parts, claim

x_s, y_s = sp.symbols("x_j y_j")
GF_DPS = 40
GF_STEP = mp.mpf(10) ** -20
GF_TOL = mp.mpf(10) ** -28


def _sized(out, N: int):
    out = replace(out, n_scope=[N])
    return out


def _local(lv, pj, qj):
    return mp.matrix([[lv + pj, -mp.exp(qj)], [mp.exp(-qj), 0]])


# --------------------------------------------------------------------------- eq. nlocal

@cache
def _images(N: int, count: int) -> tuple:
    """Per sample: cell, state, branch, and the image p~, q~ with the x_j, y_j of the literal route (DPS digits)."""
    out = []
    with mp.workdps(DPS):
        for cell, state, b in map_cells(N, count):
            pv, qv, l0, m = state
            ptv, qtv, info = literal_step(pv, qv, l0, m, b)
            out.append((cell, state, b, tuple(ptv), tuple(qtv), tuple(info["x"]), tuple(info["y"])))
    return tuple(out)


def _parts_nlocal(N: int) -> Parts:
    return Parts(printed={"d": composed_darboux(x_s, y_s)})


NLOCAL = ("the composed map factorizes site by site: l_j(p~,q~) d_j = d_{j+1} l_j(p,q) with d_j of eq. daj, "
          "d_{N+1} = d_1 = D (N={N})")


@claim("nlocal", equation="nlocal", scene="generating", sizes=(5,), deep=True, parts=_parts_nlocal, statement=NLOCAL)
@claim("nlocal", equation="nlocal", scene="generating", sizes=(2, 3, 4), parts=_parts_nlocal, statement=NLOCAL)
def nlocal(N: int, parts: Parts, deep: bool = False):
    d = parts.printed["d"]
    degree = 1 + max(sp.degree(e, lam) for e in d if e.has(lam))   # deg l_j + deg d_j
    lams = [mp.mpf(v) for v in ("0.3", "-2.2", "1.7", "-0.45", "3.1", "-4.6")][:degree + 1]
    f = lambdified((lam, lam1, lam2, x_s, y_s), d)
    table = CellTable(tol=float(TOL))
    with mp.workdps(DPS):
        for cell, state, b, ptv, qtv, xs, ys in _images(N, per_cell(deep)):
            pv, qv, l0, m = state
            worst = mp.mpf(0)
            for lv in lams:
                ds = [mp.matrix(f(lv, l0 + m, l0 - m, xs[j], ys[j])) for j in range(N)]
                for j in range(N):
                    lt, lo, dj, dn = _local(lv, ptv[j], qtv[j]), _local(lv, pv[j], qv[j]), ds[j], ds[(j + 1) % N]
                    scale = mp.mnorm(lt, 1) * mp.mnorm(dj, 1) + mp.mnorm(dn, 1) * mp.mnorm(lo, 1)
                    worst = max(worst, mp.mnorm(lt * dj - dn * lo, 1) / scale)
            table.add(cell, printed=worst, point=fmt_state(state, b))
    out = judge_cells(table, printed="l_j(p~,q~) d_j = d_{j+1} l_j(p,q) at every site, d_{N+1} = d_1",
                      method=f"numeric: mpmath {DPS} digits on the map, every site; the residual is a polynomial of "
                             f"degree {degree} in lambda, checked at {len(lams)} values per state: a proof in lambda "
                             f"at each sampled state")
    return _sized(out, N)


# --------------------------------------------------------------------------- eq. GF

@cache
def _jacobians(N: int, count: int) -> tuple:
    """Per sample: cell, state, branch, the Jacobian of (p, q) -> (p~, q~) by the complex step (GF_DPS digits)."""
    out = []
    with mp.workdps(GF_DPS):
        for cell, state, b in map_cells(N, count):
            pv, qv, l0, m = state
            z0 = [mp.mpc(v) for v in list(pv) + list(qv)]
            J = mp.matrix(2 * N, 2 * N)
            for i in range(2 * N):
                z = list(z0)
                z[i] += mp.mpc(0, GF_STEP)
                ptv, qtv, _ = literal_step(z[:N], z[N:], l0, m, b)
                for r, val in enumerate(list(ptv) + list(qtv)):
                    J[r, i] = mp.im(val) / GF_STEP
            out.append((cell, state, b, J))
    return tuple(out)


def _parts_gf(N: int) -> Parts:
    return Parts(printed={"a": sp.Integer(1), "b": sp.Integer(-1), "omega": sp.Matrix([[0, 1], [-1, 0]])})


GF_STATEMENT = ("the composed BT is canonical (a generating function F(q, q~) with p = dF/dq, p~ = -dF/dq~ exists): "
                "its Jacobian J satisfies J^T Omega J = Omega and (q, q~) are coordinates (N={N})")


@claim("GF", equation="GF", scene="generating", sizes=(4, 5), deep=True, parts=_parts_gf, statement=GF_STATEMENT)
@claim("GF", equation="GF", scene="generating", sizes=(2, 3), parts=_parts_gf, statement=GF_STATEMENT)
def GF(N: int, parts: Parts, deep: bool = False):
    P = parts.printed
    a, b_, om = complex(P["a"]), complex(P["b"]), [[complex(P["omega"][r, c]) for c in range(2)] for r in range(2)]
    table = CellTable(tol=float(GF_TOL))
    with mp.workdps(GF_DPS):
        Om = mp.matrix(2 * N, 2 * N)
        for i in range(N):
            for r in range(2):
                for c in range(2):
                    Om[r * N + i, c * N + i] = mp.mpc(om[r][c])
        factor = -mp.mpc(b_) / mp.mpc(a)
        for cell, state, b, J in _jacobians(N, per_cell(deep)):
            res = mp.mnorm(J.T * Om * J - factor * Om, 1) / (mp.mnorm(J, 1) ** 2 * max(mp.mnorm(Om, 1), 1e-30))
            dqdp = mp.matrix([[J[N + r, c] for c in range(N)] for r in range(N)])
            nondeg = abs(mp.det(dqdp)) / mp.mnorm(J, 1) ** N
            table.add(cell, printed=res if nondeg > mp.mpf(10) ** -20 else 1,
                      point=fmt_state(state, b, det_dqt_dp=mp.det(dqdp)))
    out = judge_cells(table, dps=GF_DPS,
                      printed="J^T Omega J = -(b/a) Omega = Omega for p = dF/dq, p~ = -dF/dq~, and "
                              "det(dq~/dp) != 0",
                      method=f"numeric: complex-step Jacobian of the literal map at {GF_DPS} digits (h = 1e-20, "
                             f"tolerance 1e-28)")
    return _sized(out, N)
