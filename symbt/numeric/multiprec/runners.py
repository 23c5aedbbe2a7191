r"""High precision, fast: the step and the orbit of each backend for mpmath input, on a validated problem.

Which backend runs is decided by the table of :mod:`symbt.numeric.backends` (``"auto"``: ``"qd"`` if
numba is there, the precision fits and the quad-double orbit is compiled --
:func:`~symbt.numeric.multiprec.qd.qd_ready`, ``python -m symbt.numeric.multiprec.qd`` -- else ``"flint"``
if python-flint is there, else ``"mpmath"``); this module only runs them:

* ``"qd"`` (:func:`qd_step`, :func:`qd_orbit`): the same step in compiled quad-double arithmetic
  (:mod:`symbt.numeric.multiprec.qd`, 209 bits), all ``n`` steps in one compiled call; real states
  only; inputs or states outside the double exponent range raise :class:`NumericRangeError`, after
  which ``"auto"`` continues on the next backend.
* ``"flint"`` (:func:`flint_step`, :func:`flint_orbit`): :func:`~symbt.numeric.core.step.step_core`
  on Arb balls (:data:`~symbt.numeric.multiprec.arb.ARB_MID`, decisions on midpoints) at
  ``mp.prec + guard`` bits, the state kept in Arb between the steps of an orbit as exact midpoints
  (the radii are dropped after every step: this is midpoint arithmetic, a wide ball would make Arb
  trim its midpoint); results are the midpoints rounded to the caller's ``mp.prec``.
  ``allow_complex`` uses complex balls (``acb``).
* ``"mpmath"`` (:func:`mpmath_step`, :func:`mpmath_orbit`): the same step on mpmath numbers (mpmath
  itself uses gmpy2 when installed: ``mpmath.libmp.BACKEND == 'gmpy'``), and on ``mpmath.iv`` intervals.

Guard bits: ``40`` for a step (like the mpmath path's 12 digits) and
``40 + 2 log2(n)`` for an ``n``-step orbit (the orbit error grows like
``n**2`` ulps).  Both paths agree to the working precision
(``tests/test_numeric_mpfast.py``, against ``reference_step`` at more digits).

Example
-------
>>> import mpmath
>>> from symbt.numeric import bt_orbit
>>> with mpmath.workdps(50):
...     P, Q = bt_orbit([-20, 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, 10, every=10)
...     print(mpmath.nstr(Q[-1][0], 20))
0.49085150918338141214
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeAlias

import mpmath

from ..core.context import MPValue
from ..core.errors import NoRealMapError, NumericRangeError, importable
from ..core.inputs import check_branch, mp_output
from ..core.problem import Problem
from ..core.step import mp_step, step_core
from ..float64.kernels import stored_steps

__all__ = ["flint_available", "arb_step", "qd_step", "qd_orbit", "flint_step", "flint_orbit", "mpmath_step",
           "mpmath_orbit", "GUARD_BITS"]

GUARD_BITS = 40

if TYPE_CHECKING:
    from flint import acb, arb

#: the stored states of an orbit: one list of N mpmath numbers per stored step
MPOrbit: TypeAlias = "list[list[MPValue]]"
#: a division of Arb balls (plain ``/``, or :func:`_div` with a projective infinity)
BallDivision: TypeAlias = "Callable[[arb, arb], arb]"


def flint_available() -> bool:
    """True if python-flint can be imported (imported once, on first call).

    >>> isinstance(flint_available(), bool)
    True
    """
    return importable("flint")


def _mpf(x: arb, _fme: Callable[..., tuple[int, int, int, int]] = mpmath.libmp.from_man_exp,
         _make: Callable[[tuple[int, int, int, int]], MPValue] = mpmath.mp.make_mpf) -> MPValue:
    """The midpoint of an Arb ball as an mpf rounded (to nearest) to the current ``mp.prec``."""
    if not x.is_finite():
        return mpmath.mpf(x)
    man, exp = x.mid().man_exp()
    return _make(_fme(int(man), int(exp), mpmath.mp.prec, "n"))


def _mpf_exact(x: arb, prec: int, _fme: Callable[..., tuple[int, int, int, int]] = mpmath.libmp.from_man_exp,
               _make: Callable[[tuple[int, int, int, int]], MPValue] = mpmath.mp.make_mpf) -> MPValue:
    """:func:`_mpf` for a finite ball of radius zero (no ``mid()`` needed)."""
    man, exp = x.man_exp()
    return _make(_fme(int(man), int(exp), prec, "n"))


def _to_mp(x: arb | acb) -> MPValue:
    """An Arb ball (or complex ball) as an mpmath number at the current precision (its midpoint)."""
    from flint import acb

    if isinstance(x, acb):
        if x.imag.is_zero():
            return _mpf(x.real)
        return mpmath.mpc(_mpf(x.real), _mpf(x.imag))
    return _mpf(x)


class _Retry(ArithmeticError):
    """Internal: the fast step met a division by an exact zero."""


def _div(a: arb, b: arb) -> arb:
    if b.is_zero():                      # projective infinity, as every context (rare)
        from .arb import ARB_MID

        return ARB_MID.div(a, b)
    return a / b


# Any: N balls followed by the trace's sign (a bool) in one list, as the fused step has always passed them
def _slopes(a: list[arb], r: list[arb], s: int, name: str, dv: BallDivision) -> list[Any]:
    """:func:`~symbt.numeric.core.step.eigen_slopes` for real Arb midpoints, fused (same operations, same order).

    Returns the ``N`` slopes followed by the trace's sign (``True`` for ``tr < 0``)."""
    N = len(a)
    # m_2 m_1 written out: a_1 (-1) - 0 = -a_1 and r_1 (-1) = -r_1 exactly, as step_core computes them
    A, B, C, D = a[1] * a[0] - r[0], -a[1], r[1] * a[0], -r[1]
    for j in range(2, N):
        A, B, C, D = a[j] * A - C, a[j] * B - D, r[j] * A, r[j] * B
    t = A + D
    disc = (t - 2.0) * (t + 2.0)
    if not disc.mid() > 0:
        raise NoRealMapError("no real Bäcklund map: |tr L(%s)| <= 2, the spectral parameter lies in a band"
                             % name, condition="trace")
    g = disc.sqrt()                      # g > 0: the sign tests with g reduce to those of t and dl
    tg = t.mid() >= 0
    fwd = (not tg) if s > 0 else tg
    dl = A - D
    plus = dl.mid() >= 0
    k = dl + (g if plus else -g)
    u1 = dv(k, 2 * B) if (plus if s > 0 else not plus) else dv(-2 * C, k)
    u: list[Any] = [u1]
    if fwd:
        for j in range(N - 1):
            u.append(dv(-r[j], a[j] + u[j]))
        return u + [not tg]
    u += [None] * (N - 1)
    nxt = u1
    for j in range(N - 1, 0, -1):
        nxt = u[j] = -a[j] - dv(r[j], nxt)
    return u + [not tg]


def arb_step(P: list[arb], Q: list[arb], lam0: arb, mu: arb, branch: int,
             dv: BallDivision = operator.truediv) -> tuple[list[arb], list[arb]]:
    """One step on real Arb balls with midpoint decisions: ``step_core(ARB_MID, ...)`` fused.

    Performs exactly the operations of :func:`~symbt.numeric.core.step.step_core` in the same order
    (bit-identical midpoints, ``tests/test_numeric_mpfast.py``) without the context indirection;
    raises the same :class:`NoRealMapError` (and :class:`InvalidInputError` for a branch other
    than +-1).  ``dv`` divides: plain division (fast; a division by an exact zero gives a
    non-finite result) or :func:`_div` (a projective infinity, as ``ARB_MID.div``) -- callers
    redo a non-finite step with ``dv=_div``.

    >>> from flint import arb
    >>> P, Q = arb_step([arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb("0.9")], arb(10), arb(5), 1)
    >>> P[0].str(8, radius=False)
    '-19.996568'
    """
    branch = check_branch(branch)        # _slopes reads only the sign of +-branch
    N = len(P)
    r = [(Q[(j + 1) % N] - Q[j]).exp() for j in range(N)]
    lam1, lam2 = lam0 + mu, lam0 - mu
    u = _slopes([lam1 + pj for pj in P], r, branch, "lam1 = lam0 + mu", dv)
    w = _slopes([lam2 + pj for pj in P], r, -branch, "lam2 = lam0 - mu", dv)
    if u[-1] != w[-1]:     # the traces' signs (step_core): lam1, lam2 in different spectral gaps
        raise NoRealMapError("no real Bäcklund map: tr L(lam1) and tr L(lam2) have opposite signs (lam1 and "
                             "lam2 lie in different spectral gaps)", condition="positivity")
    u, w = u[:-1], w[:-1]
    two_mu = 2 * mu
    dn = [u[j] - w[j] for j in range(N)]
    xr = [dv(two_mu, dn[j]) for j in range(N)]
    if not all((x + 1).mid() > 0 for x in xr):
        if dv is not _div and not all(x.is_finite() for x in xr):
            raise _Retry                     # a division by an exact zero: redo with projective division
        raise NoRealMapError("no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 lie in "
                             "different spectral gaps)", condition="positivity")
    Qn = [Q[j] + xr[j].log1p() for j in range(N)]
    gq = [dv(u[j], dn[j]) for j in range(N)]
    Pn = [P[j] + two_mu * (gq[(j + 1) % N] - gq[j]) for j in range(N)]
    return Pn, Qn


def _safe_step(P: list[arb], Q: list[arb], lam0: arb, mu: arb, branch: int) -> tuple[list[arb], list[arb]]:
    """:func:`arb_step` with plain division, redone with projective division if not finite;
    :class:`NumericRangeError` if still not finite."""
    try:
        Pn, Qn = arb_step(P, Q, lam0, mu, branch)
        ok = all(x.is_finite() for x in Pn + Qn)
    except _Retry:
        ok = False
    if not ok:
        Pn, Qn = arb_step(P, Q, lam0, mu, branch, _div)
        if not all(x.is_finite() for x in Pn + Qn):
            raise NumericRangeError("non-finite result in the Arb step (degenerate eigenvector?)")
    return Pn, Qn


def _flint_step(P: list[MPValue], Q: list[MPValue], lam0: MPValue, mu: MPValue, branch: int,
                allow_complex: bool) -> tuple[list[MPValue], list[MPValue]]:
    from flint import acb, arb

    from .arb import ACB, flint_prec

    with flint_prec(mpmath.mp.prec + GUARD_BITS):
        Pa, Qa, l0, m = [arb(x) for x in P], [arb(x) for x in Q], arb(lam0), arb(mu)
        try:
            Pn, Qn = _safe_step(Pa, Qa, l0, m, branch)
        except NoRealMapError:
            if not allow_complex:
                raise
            Pn, Qn, _ = step_core(ACB, [acb(x) for x in Pa], [acb(x) for x in Qa], acb(l0), acb(m), branch,
                                  check_real=False)
        if not all(x.is_finite() for x in Pn + Qn):
            raise NumericRangeError("non-finite result in the Arb step (degenerate eigenvector?)")
    return [_to_mp(x) for x in Pn], [_to_mp(x) for x in Qn]


def qd_step(pr: Problem, allow_complex: bool) -> tuple[list[MPValue], list[MPValue]]:
    """One quad-double step (raises where the Arb path would, and :class:`NumericRangeError` outside the
    quad-double range: the table's fallback takes over)."""
    from .qd import qd_orbit_mp

    Pn, Qn = qd_orbit_mp(pr.p, pr.q, pr.lam0, pr.mu, 1, branch=pr.branch, every=1)
    return Pn[-1], Qn[-1]


def qd_orbit(pr: Problem) -> tuple[MPOrbit, MPOrbit]:
    """The orbit in quad-double (:func:`~symbt.numeric.multiprec.qd.qd_orbit_mp`)."""
    from .qd import qd_orbit_mp

    return qd_orbit_mp(pr.p, pr.q, pr.lam0, pr.mu, pr.n, branch=pr.branch, every=pr.every)


def flint_step(pr: Problem, allow_complex: bool) -> tuple[list[MPValue], list[MPValue]]:
    """One step on Arb midpoints at ``mp.prec + GUARD_BITS`` (complex balls where ``allow_complex`` needs them)."""
    return _flint_step(pr.p, pr.q, pr.lam0, pr.mu, pr.branch, allow_complex)


def mpmath_step(pr: Problem, allow_complex: bool) -> tuple[list[MPValue], list[MPValue]]:
    """One step on mpmath numbers (or intervals) at ``mp.dps`` plus guard digits."""
    return mp_step(pr.ctx, pr.p, pr.q, pr.lam0, pr.mu, pr.branch, allow_complex)


def mpmath_orbit(pr: Problem) -> tuple[MPOrbit, MPOrbit]:
    """The orbit on mpmath numbers (or intervals), one :func:`mpmath_step` after the other.

    >>> import mpmath
    >>> from symbt.numeric.core.problem import prepare
    >>> with mpmath.workdps(40):
    ...     P, Q = mpmath_orbit(prepare([-20, 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, n=2))
    >>> len(P), mpmath.nstr(P[1][0], 10)
    (3, '-19.99656766')
    """
    keep = set(stored_steps(pr.n, pr.every))
    outP, outQ = [mp_output(pr.p)], [mp_output(pr.q)]
    pc, qc = pr.p, pr.q
    for i in range(1, pr.n + 1):
        pc, qc = mp_step(pr.ctx, pc, qc, pr.lam0, pr.mu, pr.branch, False)
        if i in keep:
            outP.append(pc)
            outQ.append(qc)
    return outP, outQ


def flint_orbit(pr: Problem) -> tuple[MPOrbit, MPOrbit]:
    """The orbit on Arb midpoints, the state kept in Arb between the steps (``GUARD_BITS + 2 log2(n)`` guard
    bits: the orbit error grows like ``n**2`` ulps).

    >>> import mpmath
    >>> from symbt.numeric.core.problem import prepare
    >>> with mpmath.workdps(50):
    ...     P, Q = flint_orbit(prepare([-20, 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, n=10, every=10))
    ...     print(mpmath.nstr(Q[-1][0], 20))
    0.49085150918338141214
    """
    P, Q, lam0, mu, branch, n = pr.p, pr.q, pr.lam0, pr.mu, pr.branch, pr.n
    keep = set(stored_steps(n, pr.every))
    outP, outQ = [mp_output(P)], [mp_output(Q)]
    from flint import arb

    from .arb import flint_prec

    with flint_prec(mpmath.mp.prec + GUARD_BITS + 2 * n.bit_length()):
        Pa, Qa, l0, m = [arb(x) for x in P], [arb(x) for x in Q], arb(lam0), arb(mu)
        for i in range(1, n + 1):
            Pa, Qa = _safe_step(Pa, Qa, l0, m, branch)
            # midpoint arithmetic: drop the radii, else they grow with the steps and Arb trims the
            # midpoints to the accuracy the radius justifies
            Pa, Qa = [x.mid() for x in Pa], [x.mid() for x in Qa]
            if i in keep:
                prec = mpmath.mp.prec
                outP.append([_mpf_exact(x, prec) for x in Pa])
                outQ.append([_mpf_exact(x, prec) for x in Qa])
    return outP, outQ
