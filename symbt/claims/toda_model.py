r"""Claims about the Toda model itself: eqs. ``eq:lax``, ``tra``, ``Hj``, ``tn2``, ``th1th2`` and the
three N=3 Hamiltonians printed in the Numerics subsection.

.. math:: L(\lambda) = l_N\cdots l_1,\quad l_j = \begin{pmatrix}\lambda+p_j & -e^{q_j}\\ e^{-q_j} & 0\end{pmatrix},
          \qquad \det(v - L) = v^2 - (A+D)\,v + 1,\qquad A + D = \sum_{k=0}^N H_k\lambda^k,\ H_N = 1,

and :math:`\{H_i,H_j\} = 0` for the bracket :math:`\{f,g\} = \sum_i f_{p_i}g_{q_i} - f_{q_i}g_{p_i}`
(:math:`\{p_i,q_j\}=\delta_{ij}`).  The printed pieces (the local Lax matrix, the trace ``A + D``, the
bracket, the Hamiltonians) are :class:`~symbt.claims.base.Parts` read by the checks; everything is
decided exactly in :math:`E_j = e^{q_j}`, with an independent 50-digit comparison against the literal
matrix product of :mod:`symbt.reference.literal`.  Sizes N = 2, 3, 4 run by default, N = 5 under ``--deep``.

>>> out = lax(3, _parts_lax(3))
>>> out.status, out.evidence, out.n_scope
('verified', 'proof', [3])
"""
from __future__ import annotations

import itertools
import random
from dataclasses import replace

import mpmath as mp
import sympy as sp

from ..proof import Verdict, decide
from ..reference.literal import lax_matrix, literal_trace
from ..symbolic.toda import lam, toda_model
from ._common import lambdified
from ._site import to_E
from .base import Outcome, Parts, claim, failed, from_decision, judge, scene

scene("toda", "Toda model: Lax matrix, spectral invariants, involution (N=2,3,4; N=5 under --deep)")

p_j, q_j = sp.symbols("p_j q_j", real=True)
E_j = sp.Symbol("E_j", positive=True)
A, B, C, D = sp.symbols("A B C D")                 # entries of L(lambda)
fp, fq, gp, gq = sp.symbols("f_p f_q g_p g_q")     # partial derivatives in one canonical pair
k = sp.Symbol("k", integer=True)
DEFAULT, DEEP = (2, 3, 4), (5,)


def _sized(out: Outcome, N: int) -> Outcome:
    out = replace(out, n_scope=[N])
    return out


def _random_points(N: int, count: int = 4):
    rng = random.Random(N)
    for _ in range(count):
        yield ([mp.mpf(rng.uniform(-3, 3)) for _ in range(N)], [mp.mpf(rng.uniform(-2, 2)) for _ in range(N)],
               mp.mpf(rng.uniform(-3, 3)))


# --------------------------------------------------------------------------- eq. eq:lax

def _parts_lax(N: int) -> Parts:
    return Parts(printed={"l_j": sp.Matrix([[lam + p_j, -sp.exp(q_j)], [sp.exp(-q_j), 0]])})


LAX = "L = l_N...l_1 with l_j = [[lambda+p_j, -e^q_j],[e^-q_j, 0]]; det l_j = 1 and det L = 1 (N={N})"


@claim("lax", equation="eq:lax", scene="toda", sizes=DEEP, deep=True, parts=_parts_lax, statement=LAX)
@claim("lax", equation="eq:lax", scene="toda", sizes=DEFAULT, parts=_parts_lax, statement=LAX)
def lax(N: int, parts: Parts):
    m = toda_model(N)
    lj = to_E(parts.printed["l_j"], {q_j: E_j})
    d0 = decide(lj.det(), 1)
    if not d0.holds:
        return _sized(from_decision(d0, detail="det l_j != 1"), N)
    L = sp.eye(2)
    for j in range(N):
        L = lj.subs({p_j: m.p[j], E_j: m.E[j], q_j: m.q[j]}, simultaneous=True) * L
    L = L.applyfunc(sp.expand)
    # independent route: the printed product at 50 digits against the literal mpmath product
    f = lambdified([lam, *m.p, *m.q, *m.E], L)
    worst = mp.mpf(0)
    with mp.workdps(50):
        for pv, qv, lv in _random_points(N):
            ref = lax_matrix(lv, pv, qv)
            got = mp.matrix(f(lv, *pv, *qv, *[mp.exp(v) for v in qv]))
            worst = max(worst, mp.mnorm(got - ref, 1) / max(1, mp.mnorm(ref, 1)))
    if worst > mp.mpf(10) ** -40:
        return _sized(failed("numeric: printed product vs literal product at 50 digits", residual=float(worst),
                             detail="the printed l_N...l_1 differs from the reference product"), N)
    same = decide(L, m.L)
    if not same.holds:
        return _sized(from_decision(same, detail="printed l_N...l_1 differs from the model's L"), N)
    return _sized(from_decision(decide(L.det(), 1),
                                detail=f"det l_j = 1 exactly; the printed product equals the model's L and the "
                                       f"literal 50-digit product (residual {mp.nstr(worst, 3)})"), N)


# --------------------------------------------------------------------------- eq. tra

def _parts_tra(N: int) -> Parts:
    return Parts(printed={"trace": A + D, "H_N": sp.Integer(1), "degree": sp.Integer(N)})


TRA = "tr L(lambda) = A + D = sum_{{k=0}}^N H_k lambda^k with H_N = 1 (N={N})"


@claim("tra", equation="tra", scene="toda", sizes=DEEP, deep=True, parts=_parts_tra, statement=TRA)
@claim("tra", equation="tra", scene="toda", sizes=DEFAULT, parts=_parts_tra, statement=TRA)
def tra(N: int, parts: Parts):
    m = toda_model(N)
    L = m.L
    tr = sp.expand(parts.printed["trace"].subs({A: L[0, 0], B: L[0, 1], C: L[1, 0], D: L[1, 1]}))
    v = sp.Symbol("v")
    # the trace of the spectral curve det(v - L) = v^2 - tr L v + 1 (det L = 1: claim lax)
    curve = decide((v * sp.eye(2) - L).det(), v ** 2 - tr * v + 1)
    if not curve.holds:
        return _sized(from_decision(curve, detail="the printed trace is not the trace of the spectral curve"), N)
    poly = sp.Poly(tr, lam)
    if poly.degree() != parts.printed["degree"]:
        return _sized(Outcome("failed", "exact: Poly degree", evidence="proof",
                              detail=f"degree {poly.degree()} != {parts.printed['degree']}"), N)
    lead = decide(poly.LC(), parts.printed["H_N"])
    if not lead.holds:
        return _sized(from_decision(lead, detail="leading coefficient H_N"), N)
    coeffs = decide(sum(h * lam ** i for i, h in enumerate(m.hamiltonians)), tr)
    if not coeffs.holds:
        return _sized(from_decision(coeffs, detail="the model's H_k are not the coefficients"), N)
    # independent route: sum H_k lambda^k against the literal trace at 50 digits
    f = lambdified([lam, *m.p, *m.E], sum(h * lam ** i for i, h in enumerate(m.hamiltonians)))
    worst = mp.mpf(0)
    with mp.workdps(50):
        for pv, qv, lv in _random_points(N):
            ref = literal_trace(lv, pv, qv)
            worst = max(worst, abs(f(lv, *pv, *[mp.exp(x) for x in qv]) - ref) / max(1, abs(ref)))
    out = from_decision(coeffs, detail=f"det(v - L) = v^2 - (A+D) v + 1; degree {N} in lambda, leading coefficient "
                                       f"1; sum H_k lambda^k vs the literal trace at 50 digits: {mp.nstr(worst, 3)}")
    if worst > mp.mpf(10) ** -40:
        out = replace(out, status="failed")
    return _sized(out, N)


# --------------------------------------------------------------------------- eq. Hj

def _parts_hj(N: int) -> Parts:
    return Parts(printed={"bracket": fp * gq - fq * gp})


HJ = "{{H_i, H_j}} = 0 for all coefficients H_k of tr L, with {{p_i, q_j}} = delta_ij (N={N})"


def _bracket(m, form):
    """The printed bracket summed over the canonical pairs (q_j-derivatives as E_j d/dE_j)."""
    def br(f, g):
        return sp.Add(*[form.subs({fp: m.d_p(f, i), fq: m.d_q(f, i), gp: m.d_p(g, i), gq: m.d_q(g, i)})
                        for i in range(m.N)])
    return br


@claim("Hj", equation="Hj", scene="toda", sizes=DEEP, deep=True, parts=_parts_hj, statement=HJ)
@claim("Hj", equation="Hj", scene="toda", sizes=DEFAULT, parts=_parts_hj, statement=HJ)
def Hj(N: int, parts: Parts):
    m = toda_model(N)
    br = _bracket(m, parts.printed["bracket"])
    qs = [sp.log(E) for E in m.E]
    # the printed canonical brackets {p_i, q_j} = delta_ij, {p_i, p_j} = {q_i, q_j} = 0, and the
    # antisymmetry of any Poisson bracket, {q_j, p_i} = -delta_ij (sites 1, 2: i = j and i != j; the
    # bracket is one formula summed over the sites)
    S = range(2)
    canon = sp.Matrix([[br(m.p[i], qs[j]) for j in S] + [br(qs[j], m.p[i]) for j in S]
                       + [br(m.p[i], m.p[j]) for j in S] + [br(qs[i], qs[j]) for j in S] for i in S])
    want = sp.Matrix([[int(i == j) for j in S] + [-int(i == j) for j in S] + [0] * 4 for i in S])
    d = decide(canon, want)
    if not d.holds:
        return _sized(from_decision(d, detail="the bracket does not give {p_i, q_j} = -{q_j, p_i} = delta_ij"), N)
    H = m.hamiltonians[:N]
    for i, j in itertools.combinations(range(N), 2):
        d = decide(br(H[i], H[j]), 0)
        if not d.holds:
            return _sized(from_decision(d, detail=f"{{H_{i}, H_{j}}} != 0"), N)
    # the bracket is not trivially zero: {H_{N-1}, e^q1} = e^q1 (H_{N-1} = sum p)
    d = decide(br(H[N - 1], m.E[0]), m.E[0])
    return _sized(from_decision(d, detail=f"canonical brackets; all {N * (N - 1) // 2} pairs; bracket sanity "
                                          f"{{sum p, e^q1}} = e^q1"), N)


# --------------------------------------------------------------------------- N = 2

def _parts_tn2() -> Parts:
    m = toda_model(2)
    (p1, p2), (q1, q2) = m.p, m.q
    return Parts(printed={"trace": lam ** 2 + (p1 + p2) * lam + p1 * p2 - 2 * sp.cosh(q1 - q2)})


@claim("tn2", equation="tn2", scene="toda", N=2, parts=_parts_tn2,
       statement="N=2: A+D = lambda^2 + (p1+p2) lambda + p1 p2 - 2 cosh(q1-q2)")
def tn2(parts: Parts):
    m = toda_model(2)
    return _sized(from_decision(decide(m.to_E(parts.printed["trace"]), m.trace)), 2)


I1s, I2s = sp.symbols("I_1 I_2", real=True)


def _parts_th1th2() -> Parts:
    m = toda_model(2)
    (p1, p2), (q1, q2) = m.p, m.q
    return Parts(printed={"I1": (p1 + p2) / 2, "I2": 2 * sp.cosh(q1 - q2) + ((p1 - p2) / 2) ** 2,
                          "trace": (lam + I1s) ** 2 - I2s})


@claim("th1th2.trace", equation="th1th2", scene="toda", N=2, parts=_parts_th1th2,
       statement="N=2 with I1 = (p1+p2)/2, I2 = 2cosh(q1-q2) + ((p1-p2)/2)^2: A+D = (lambda+I1)^2 - I2")
def th1th2_trace(parts: Parts):
    m = toda_model(2)
    P = parts.printed
    return _sized(from_decision(decide(m.to_E(P["trace"].subs({I1s: P["I1"], I2s: P["I2"]})), m.trace)), 2)


# --------------------------------------------------------------------------- the printed N = 3 Hamiltonians

def _n3_hamiltonians(typo: bool) -> dict:
    m = toda_model(3)
    (p1, p2, p3), (q1, q2, q3) = m.p, m.q
    e = sp.exp
    return {"H1": p1 + p2 + p3,
            "H2": p1 * p2 + (p2 * p2 if typo else p2 * p3) + p3 * p1 - e(q1 - q3) - e(q2 - q1) - e(q3 - q2),
            "H3": p1 * p2 * p3 - p2 * e(q1 - q3) - p3 * e(q2 - q1) - p1 * e(q3 - q2)}


def _parts_n3_tra() -> Parts:
    return Parts(printed=dict(_n3_hamiltonians(True), power=k),
                 corrected=dict(_n3_hamiltonians(False), power=3 - k))


def _is_coefficient(m, hs: dict) -> Verdict:
    """Each H_kk equals the coefficient of lambda^power(kk) in tr L (the first failure, else the last)."""
    out = None
    for kk in (1, 2, 3):
        e = sp.sympify(hs["power"]).subs(k, kk)
        if not (e.is_Integer and 0 <= int(e) <= 3):
            return Verdict(False, "proof", f"exact: power {e} is not an integer in 0..3", residual=1.0, definite=True,
                           counterexample={"k": kk, "power": str(e)})
        out = decide(m.to_E(hs[f"H{kk}"]), m.hamiltonians[int(e)])
        if not out.holds:
            return out
    assert out is not None
    return out


@claim("n3-hamiltonians.tra", equation="n3-hamiltonians", scene="toda", N=3, parts=_parts_n3_tra,
       where="Numerics subsection, unnumbered display after eq. eqdisc",
       statement="printed H_1, H_2, H_3 of the N=3 lattice are the coefficients H_k of tr L (eq. tra)")
def n3_hamiltonians_tra(parts: Parts):
    m = toda_model(3)
    relabelled = dict(parts.printed, power=3 - k)
    typo = decide(m.to_E(parts.printed["H2"]), m.hamiltonians[1])
    out = judge(_is_coefficient(m, parts.printed),
                printed="H_1 = p1+p2+p3 = coeff of lambda^1, H_2 = p1p2+p2p2+p3p1-..., H_3 = p1p2p3-...",
                corrected="printed H_k is the coefficient of lambda^(3-k) in tr L (H_1 = coeff of lambda^2, "
                          "H_2 = coeff of lambda^1 with p2*p2 -> p2*p3, H_3 = coeff of lambda^0); tra's H_3 = 1",
                corrected_check=lambda: _is_coefficient(m, parts.corrected),
                detail=f"relabelling alone leaves printed H_2 - coeff(lambda^1) nonzero (p2*p2 typo): "
                       f"{typo.verdict}, residual {typo.residual:.3g}; relabelled printed set: "
                       f"{_is_coefficient(m, relabelled).verdict}")
    return _sized(out, 3)


def _parts_n3_inv() -> Parts:
    return Parts(printed=_n3_hamiltonians(True), corrected=_n3_hamiltonians(False))


def _involutive(m, hs: dict):
    """{H_a, H_b} = 0 for the three given H's, and each commutes with every H_k of tr L (the Toda integrals)."""
    H = {kk: m.to_E(hs[f"H{kk}"]) for kk in (1, 2, 3)}
    d = None
    pairs = [(H[a], H[b]) for a, b in itertools.combinations((1, 2, 3), 2)]
    pairs += [(H[a], h) for a in (1, 2, 3) for h in m.hamiltonians[:3]]
    for f, g in pairs:
        d = decide(m.poisson(f, g), 0)
        if not d.holds:
            return d
    return d


@claim("n3-hamiltonians.involution", equation="n3-hamiltonians", scene="toda", N=3, parts=_parts_n3_inv,
       where="Numerics subsection, unnumbered display after eq. eqdisc",
       statement="the printed N=3 Hamiltonians H_1, H_2, H_3 are in involution (eq. Hj)")
def n3_hamiltonians_involution(parts: Parts):
    m = toda_model(3)
    out = judge(_involutive(m, parts.printed),
                printed="{H_i, H_j} = 0 for the printed H_1, H_2 (with p2*p2), H_3",
                corrected="{H_i, H_j} = 0 with H_2 = p1p2 + p2p3 + p3p1 - e^(q1-q3) - e^(q2-q1) - e^(q3-q2)",
                corrected_check=lambda: _involutive(m, parts.corrected),
                detail="pairwise, and each H_k also commutes with the coefficients of tr L (the Toda integrals)")
    return _sized(out, 3)
