r"""The paper's explicit Bäcklund map, computed *literally* in mpmath (reference route).

This follows Section 3 word for word and is meant as an independent
high-precision reference for the claims and for :mod:`symbt.numeric` (whose
float64 route is reformulated for stability).  It is sympy-free.

1. Build :math:`L(\lambda_1)`, :math:`L(\lambda_2)` as 2x2 mpmath matrices (eq. ``eq:lax``),
   :math:`\lambda_{1,2} = \lambda_0 \pm \mu` (eq. ``lam0mu``).
2. :math:`\gamma_i = b\,\sqrt{\operatorname{tr}L(\lambda_i)^2-4}` with the branch :math:`b=\pm1`
   (the same at both points: the two maps connected to the identity).
3. :math:`y, x` from eq. ``xy``.
4. Transport to every site (Appendix B): the kernels :math:`(1,-y_j)` of
   :math:`\mathfrak d_j(\lambda_1)` and :math:`(1,-z_j)`, :math:`z_j = y_j + 2\mu/x_j`, of
   :math:`\mathfrak d_j(\lambda_2)` are carried by :math:`l_j` (eq. ``rte``), then
   :math:`e^{\tilde q_j} = e^{q_j} - x_j` (eq. ``xyqqt``),
   :math:`\eta_j = x_j y_j + \mu`, :math:`\tilde p_j = p_j + \eta_j - \eta_{j+1}`
   (difference of the two lines of eq. ``imptransf``).

:func:`reference_step` wraps the same route with automatic guard digits: the
forward transport of step 4 is unstable for one of the two slopes (it runs
against the contracting direction and loses about ``log10(|v_max|**2)`` digits
per period), and ``E - x`` cancels for small ``mu``.  It works at ``mp.dps +
guard`` digits, the guard chosen from the size of the traces, and can verify
itself by re-running with more digits.  It is the slow, independent reference
for :mod:`symbt.numeric` in the tests.

Example
-------
>>> import mpmath as mp
>>> mp.mp.dps = 30
>>> pt, qt, info = literal_step([-20, 10, 1], [1, 0, mp.mpf("0.9")], 10, 5)
>>> mp.nstr(pt[0], 10)
'-19.99656766'
"""
from __future__ import annotations

from collections.abc import Sequence
from types import ModuleType
from typing import Any, TypeAlias

import mpmath as mp
from mpmath import libmp as _libmp

#: a real or complex mpmath number (the literal route continues off the real line where the map is complex)
MPNumber: TypeAlias = "mp.mpf | mp.mpc"
#: what the routes take: mpmath numbers, or numbers and decimal strings ``mpmath.mpmathify`` converts
MPLike: TypeAlias = "mp.mpf | mp.mpc | int | float | str"
#: an mpf as mpmath's ``libmp`` works on it: ``(sign, mantissa, exponent, bitcount)``
RawMPF: TypeAlias = "tuple[int, int, int, int]"
#: ``(p_new, q_new, info)`` of :func:`literal_step`; ``info`` maps names to numbers or lists of them
StepResult: TypeAlias = "tuple[list[MPNumber], list[MPNumber], dict[str, Any]]"

__all__ = ["lax_matrix", "literal_step", "spectral_trace_mp", "phi_from_traces", "signed_arccosh_half",
           "reference_step", "literal_trace"]


def lax_matrix(lam: MPNumber, p: Sequence[MPNumber], q: Sequence[MPNumber]) -> mp.matrix:
    """:math:`L(\\lambda) = l_N \\cdots l_1` as an mpmath matrix (eq. ``eq:lax``).

    The product is written out entry by entry with the operations ``mp.matrix`` multiplication
    performs (``fdot`` of a row and a column, one rounding per entry; a product with the zero entry
    of ``l_j`` is exact), so the result is bit-identical to ``l_N * ... * l_1 * eye(2)`` in
    mpmath matrices at a fraction of the cost -- this routine is the inner loop of the reference
    map that most sampled claims evaluate thousands of times.

    >>> import mpmath as mp
    >>> with mp.workdps(30):
    ...     M = lax_matrix(mp.mpf(2), [mp.mpf(1), mp.mpf(-1)], [mp.mpf(0), mp.mpf("0.5")])
    ...     old = mp.eye(2)
    ...     for pj, qj in zip([1, -1], [0, mp.mpf("0.5")]):
    ...         old = mp.matrix([[2 + mp.mpf(pj), -mp.exp(qj)], [mp.exp(-qj), 0]]) * old
    >>> M == old
    True
    """
    ex = [(mp.exp(qj), mp.exp(-qj)) for qj in q]
    a, b, c, d = _lax_entries(lam, p, ex)
    return mp.matrix([[a, b], [c, d]])


def _lax_entries(lam: MPNumber, p: Sequence[MPNumber],
                 ex: Sequence[tuple[MPNumber, MPNumber]]) -> tuple[MPNumber, MPNumber, MPNumber, MPNumber]:
    """The entries ``(a, b, c, d)`` of :func:`lax_matrix` from ``ex[j] = (exp(q_j), exp(-q_j))``.

    On real mpf the dot products are done as ``mp.fdot`` does them (exact products, one rounded
    sum: ``mpf_sum`` of ``mpf_mul``), without its per-call type dispatch; anything else goes through
    ``mp.fdot`` itself.  Bit-identical either way (``tests/test_reference.py``).
    """
    fdot, mpf = mp.fdot, mp.mpf
    a, b, c, d = mpf(1), mpf(0), mpf(0), mpf(1)
    prec, rnd = mp.mp._prec_rounding
    make, mul, fsum = mp.mp.make_mpf, _libmp.mpf_mul, _libmp.mpf_sum
    for pj, (ej, eij) in zip(p, ex):
        s, e, ei = lam + pj, -ej, eij
        if type(s) is mpf and type(e) is mpf and type(ei) is mpf and type(a) is mpf and type(b) is mpf \
                and type(c) is mpf and type(d) is mpf:
            S, X, I = s._mpf_, e._mpf_, ei._mpf_
            A, B, C, D = a._mpf_, b._mpf_, c._mpf_, d._mpf_
            a, b = make(fsum([mul(S, A), mul(X, C)], prec, rnd)), make(fsum([mul(S, B), mul(X, D)], prec, rnd))
            c, d = make(fsum([mul(I, A)], prec, rnd)), make(fsum([mul(I, B)], prec, rnd))
        else:
            a, b, c, d = fdot(((s, a), (e, c))), fdot(((s, b), (e, d))), fdot(((ei, a),)), fdot(((ei, b),))
    return a, b, c, d


def spectral_trace_mp(lam: MPNumber, p: Sequence[MPNumber], q: Sequence[MPNumber]) -> MPNumber:
    M = lax_matrix(lam, p, q)
    return M[0, 0] + M[1, 1]


def literal_step(p: Sequence[MPLike], q: Sequence[MPLike], lam0: MPLike, mu: MPLike, branch: int = 1, *,
                 gamma_signs: tuple[int, int] | None = None) -> StepResult:
    """One step of the map along the paper's route.

    ``gamma_signs=(s1, s2)`` overrides the branch independently at
    :math:`\\lambda_1` and :math:`\\lambda_2` (to study the mixed choices).
    Returns ``(p_new, q_new, info)``; ``info`` holds ``x, y, eta, tr1, tr2,
    gamma1, gamma2, E_new`` (lists over sites where relevant).  Values may be
    complex where the real map does not exist.  A branch or sign other than +1 or -1 raises ``ValueError``.
    """
    p = [mp.mpmathify(v) for v in p]
    q = [mp.mpmathify(v) for v in q]
    lam0, mu = mp.mpmathify(lam0), mp.mpmathify(mu)
    s1, s2 = gamma_signs if gamma_signs is not None else (branch, branch)
    if s1 not in (1, -1) or s2 not in (1, -1):
        raise ValueError(f"literal_step: the signs of the square roots must be +1 or -1, not {s1}, {s2}")
    if all(type(v) is mp.mpf for v in (*p, *q, lam0, mu)):
        try:
            return _literal_step_real(p, q, lam0, mu, s1, s2)
        except _libmp.ComplexResult:  # a square root or logarithm of a negative number: the complex route below
            pass
    return _literal_step_generic(p, q, lam0, mu, s1, s2)


def _literal_step_generic(p: list[MPNumber], q: list[MPNumber], lam0: MPNumber, mu: MPNumber, s1: int,
                          s2: int) -> StepResult:
    N = len(p)
    l1, l2 = lam0 + mu, lam0 - mu
    # exp(+-q_j) once for both matrices and for E_j: the values lax_matrix and the list below would compute
    ex = [(mp.exp(v), mp.exp(-v)) for v in q]
    A1, B1, _, D1 = _lax_entries(l1, p, ex)
    A2, B2, _, D2 = _lax_entries(l2, p, ex)
    tr1, tr2 = A1 + D1, A2 + D2
    g1 = s1 * mp.sqrt(tr1 ** 2 - 4)
    g2 = s2 * mp.sqrt(tr2 ** 2 - 4)
    # eq. xy
    y = (A1 - D1 + g1) / (2 * B1)
    x = 2 * B1 * B2 * (l2 - l1) / (B2 * (A1 - D1 + g1) - B1 * (A2 - D2 - g2))
    E = [e for e, _ in ex]
    ys, zs = [y], [y + 2 * mu / x]
    for j in range(N - 1):
        ys.append(-1 / (E[j] * (l1 + p[j] + E[j] * ys[-1])))
        zs.append(-1 / (E[j] * (l2 + p[j] + E[j] * zs[-1])))
    xs = [2 * mu / (z - yy) for yy, z in zip(ys, zs)]
    Et = [e - xx for e, xx in zip(E, xs)]
    eta = [xx * yy + mu for xx, yy in zip(xs, ys)]
    pt = [p[j] + eta[j] - eta[(j + 1) % N] for j in range(N)]
    qt = [mp.log(e) for e in Et]
    info = dict(x=xs, y=ys, z=zs, eta=eta, tr1=tr1, tr2=tr2, gamma1=g1, gamma2=g2,
                E=E, E_new=Et, x_formula=x)
    return pt, qt, info


def _literal_step_real(p: list[mp.mpf], q: list[mp.mpf], lam0: mp.mpf, mu: mp.mpf, s1: int, s2: int) -> StepResult:
    """:func:`_literal_step_generic` on real mpf, written on mpmath's ``libmp`` tuples.

    Every line performs the operation the mpf operators perform (the same ``libmp`` function, in
    the same order, at the context's precision and rounding), so the result is bit-identical; only the
    per-operation type dispatch and object creation are gone (tested in ``tests/test_reference_literal.py``).
    A square root or logarithm of a negative number raises ``ComplexResult`` and the caller takes
    the generic (complex) route.
    """
    L = _libmp
    prec, rnd = mp.mp._prec_rounding
    add, sub, mul, div, neg = L.mpf_add, L.mpf_sub, L.mpf_mul, L.mpf_div, L.mpf_neg
    fsum, exp, log, sqrt = L.mpf_sum, L.mpf_exp, L.mpf_log, L.mpf_sqrt
    four = L.from_int(4)
    N = len(p)
    P, Q, l0, m = [v._mpf_ for v in p], [v._mpf_ for v in q], lam0._mpf_, mu._mpf_
    l1, l2 = add(l0, m, prec, rnd), sub(l0, m, prec, rnd)
    ex = [(exp(v, prec, rnd), exp(neg(v, prec, rnd), prec, rnd)) for v in Q]

    def lax(lam: RawMPF) -> tuple[RawMPF, RawMPF, RawMPF]:  # _lax_entries on tuples
        a, b, c, d = L.fone, L.fzero, L.fzero, L.fone
        for pj, (ej, eij) in zip(P, ex):
            s, e = add(lam, pj, prec, rnd), neg(ej, prec, rnd)
            # a one-term fsum is the correctly rounded product: mpf_mul at prec gives the same bits
            a, b, c, d = (fsum([mul(s, a), mul(e, c)], prec, rnd), fsum([mul(s, b), mul(e, d)], prec, rnd),
                          mul(eij, a, prec, rnd), mul(eij, b, prec, rnd))
        return a, b, d

    A1, B1, D1 = lax(l1)
    A2, B2, D2 = lax(l2)
    tr1, tr2 = add(A1, D1, prec, rnd), add(A2, D2, prec, rnd)
    g1 = sqrt(sub(L.mpf_pow_int(tr1, 2, prec, rnd), four, prec, rnd), prec, rnd)
    g2 = sqrt(sub(L.mpf_pow_int(tr2, 2, prec, rnd), four, prec, rnd), prec, rnd)
    g1, g2 = (g1 if s1 == 1 else neg(g1, prec, rnd)), (g2 if s2 == 1 else neg(g2, prec, rnd))
    n1 = add(sub(A1, D1, prec, rnd), g1, prec, rnd)
    y = div(n1, L.mpf_mul_int(B1, 2, prec, rnd), prec, rnd)
    num = mul(mul(L.mpf_mul_int(B1, 2, prec, rnd), B2, prec, rnd), sub(l2, l1, prec, rnd), prec, rnd)
    den = sub(mul(B2, n1, prec, rnd), mul(B1, sub(sub(A2, D2, prec, rnd), g2, prec, rnd), prec, rnd), prec, rnd)
    x = div(num, den, prec, rnd)
    E = [e for e, _ in ex]
    m2 = L.mpf_mul_int(m, 2, prec, rnd)
    ys, zs = [y], [add(y, div(m2, x, prec, rnd), prec, rnd)]
    for j in range(N - 1):
        for lam, seq in ((l1, ys), (l2, zs)):
            inner = add(add(lam, P[j], prec, rnd), mul(E[j], seq[-1], prec, rnd), prec, rnd)
            seq.append(L.mpf_rdiv_int(-1, mul(E[j], inner, prec, rnd), prec, rnd))
    xs = [div(m2, sub(z, yy, prec, rnd), prec, rnd) for yy, z in zip(ys, zs)]
    Et = [sub(e, xx, prec, rnd) for e, xx in zip(E, xs)]
    qt = [log(e, prec, rnd) for e in Et]
    eta = [add(mul(xx, yy, prec, rnd), m, prec, rnd) for xx, yy in zip(xs, ys)]
    pt = [sub(add(P[j], eta[j], prec, rnd), eta[(j + 1) % N], prec, rnd) for j in range(N)]
    mk = mp.mp.make_mpf

    def mks(vs: list[RawMPF]) -> list[mp.mpf]:
        return [mk(v) for v in vs]

    info = dict(x=mks(xs), y=mks(ys), z=mks(zs), eta=mks(eta), tr1=mk(tr1), tr2=mk(tr2), gamma1=mk(g1),
                gamma2=mk(g2), E=mks(E), E_new=mks(Et), x_formula=mk(x))
    return mks(pt), mks(qt), info


# Any: mpmath numbers or SymPy expressions, as the namespace ``ns`` (a module) computes them
def phi_from_traces(tr1: Any, tr2: Any, branch: Any, *, ns: ModuleType = mp) -> Any:
    r"""The real Phi on the map of branch ``b`` from ``tr_i = tr L(lambda_i)`` (corrects eq. ``newkmu``).

    :math:`\Phi = \sum_k \ln|(\eta_k+\mu)/(\eta_k-\mu)| = -b\,(\operatorname{sgn}(tr_1)\operatorname{arccosh}(|tr_1|/2)
    + \operatorname{sgn}(tr_2)\operatorname{arccosh}(|tr_2|/2))` -- arccosh only ever sees arguments >= 1.

    The one implementation of this formula: ``ns`` is the namespace that supplies ``sign`` and
    ``acosh`` -- mpmath by default (numbers at the current precision), or the ``sympy`` module for
    the expression that the claims (``x``, ``newkmu``, ``Hdiscr``, ...) and ``symbt codegen`` use
    (this module never imports SymPy itself).

    >>> mp.nstr(phi_from_traces(mp.mpf(3), mp.mpf(-5), -1), 12)
    '-0.604375586853'
    >>> import sympy as sp
    >>> t1, t2, b = sp.symbols("tr1 tr2 b", real=True)
    >>> phi_from_traces(t1, t2, b, ns=sp)
    -b*(acosh(Abs(tr1)/2)*sign(tr1) + acosh(Abs(tr2)/2)*sign(tr2))
    """
    return -branch * (signed_arccosh_half(tr1, ns=ns) + signed_arccosh_half(tr2, ns=ns))


def signed_arccosh_half(T: Any, *, ns: ModuleType = mp) -> Any:
    r"""The real branch of :math:`\operatorname{arccosh}(T/2)` entering Phi:
    :math:`\operatorname{sgn}(T)\operatorname{arccosh}(|T|/2)` (:math:`|T| \ge 2`); ``ns`` as in
    :func:`phi_from_traces` (the density of H in eqs. ``Hdis``, ``AA2`` is ``-b`` times it).

    >>> mp.nstr(signed_arccosh_half(mp.mpf(-3)), 12)
    '-0.962423650119'
    """
    return ns.sign(T) * ns.acosh(abs(T) / 2)


def literal_trace(lam: MPLike, p: Sequence[MPLike], q: Sequence[MPLike]) -> MPNumber:
    """``tr L(lam)`` from the literal 2x2 product (mpmath, current precision)."""
    return spectral_trace_mp(mp.mpf(lam), [mp.mpf(v) for v in p], [mp.mpf(v) for v in q])


def reference_step(p: Sequence[MPLike], q: Sequence[MPLike], lam0: MPLike, mu: MPLike, *, branch: int = 1,
                   guard: int | None = None, verify: bool = False) -> tuple[list[MPNumber], list[MPNumber]]:
    """:func:`literal_step` with automatic guard digits; returns ``(p_new, q_new)`` as lists at ``mp.dps``.

    ``guard`` extra decimal digits are used internally (default: 20 plus twice
    ``log10`` of the larger trace, which bounds the loss of the unstable
    forward transport).  With ``verify=True`` the computation is repeated with
    25 more digits and an ``AssertionError`` is raised unless both agree to
    ``mp.dps`` digits.  Complex results (no real map) are returned as mpc.
    """
    dps = mp.mp.dps
    with mp.workdps(dps + 30):
        P = [mp.mpf(v) for v in p]
        Q = [mp.mpf(v) for v in q]
        l0, m = mp.mpf(lam0), mp.mpf(mu)
        t1 = literal_trace(l0 + m, P, Q)
        t2 = literal_trace(l0 - m, P, Q)
    if guard is None:
        big = max(abs(t1), abs(t2), mp.mpf(10))
        guard = 20 + 2 * int(mp.log10(big)) + 2 * len(P)
    with mp.workdps(dps + guard):
        P = [mp.mpf(v) for v in p]
        Q = [mp.mpf(v) for v in q]
        pt, qt, _ = literal_step(P, Q, mp.mpf(lam0), mp.mpf(mu), branch)
    if verify:
        with mp.workdps(dps + guard + 25):
            P = [mp.mpf(v) for v in p]
            Q = [mp.mpf(v) for v in q]
            pt2, qt2, _ = literal_step(P, Q, mp.mpf(lam0), mp.mpf(mu), branch)
            scale = max(abs(v) for v in pt + qt) + 1
            diff = max(abs(a - b) for a, b in zip(pt + qt, pt2 + qt2))
            if diff > scale * mp.mpf(10) ** (-dps):
                raise AssertionError("literal reference not converged: %s" % mp.nstr(diff, 5))
    return [+v for v in pt], [+v for v in qt]
