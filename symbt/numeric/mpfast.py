r"""High precision, fast: mpmath in, mpmath out, quad-doubles (numba) or python-flint's Arb inside.

For mpmath input :func:`~symbt.numeric.bt_step` and :func:`~symbt.numeric.bt_orbit`
pick the fastest backend present (``"auto"``: ``"qd"`` if numba is there, the
precision fits and the quad-double orbit is compiled -- :func:`~symbt.numeric.qd.qd_ready`,
``python -m symbt.numeric.qd`` -- else ``"flint"`` if python-flint is there, else ``"mpmath"``):

* ``"qd"`` (numba installed, ``mp.prec`` small enough for the number of steps:
  :func:`~symbt.numeric.qd.qd_fits`): the same step in compiled quad-double
  arithmetic (:mod:`symbt.numeric.qd`, 209 bits), all ``n`` steps in one
  compiled call; real states only (``allow_complex`` continues on the Arb or
  mpmath path where the real map does not exist); inputs or states outside the
  double exponent range go to the next backend under ``"auto"``
  (:class:`NumericRangeError` for an explicit ``"qd"``).
* ``"flint"`` (python-flint installed): :func:`~symbt.numeric.step.step_core`
  on Arb balls (:data:`~symbt.numeric.arb.ARB_MID`, decisions on midpoints)
  at ``mp.prec + guard`` bits, the state kept in Arb between the steps of an
  orbit as exact midpoints (the radii are dropped after every step: this is
  midpoint arithmetic, a wide ball would make Arb trim its midpoint);
  results are the midpoints rounded to the caller's ``mp.prec``.
  ``allow_complex`` uses complex balls (``acb``).
* ``"mpmath"``: the same step on mpmath numbers (mpmath itself uses gmpy2
  when installed: ``mpmath.libmp.BACKEND == 'gmpy'``).

Guard bits: ``40`` for a step (like the mpmath path's 12 digits) and
``40 + 2 log2(n)`` for an ``n``-step orbit (the orbit error grows like
``n**2`` ulps).  Both paths agree to the working precision
(``tests/test_numeric_mpfast.py``, against ``reference_step`` at more digits).

Example
-------
>>> import mpmath
>>> from symbt.numeric.mpfast import mp_orbit
>>> with mpmath.workdps(50):
...     P, Q = mp_orbit([-20, 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, 10, every=10)
...     print(mpmath.nstr(Q[-1][0], 20))
0.49085150918338141214
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import Any

import mpmath

from ._input import IV, as_state_pair, prepare_spectral_pair, to_output
from .errors import InvalidInputError, MissingDependencyError, NoRealMapError, NumericRangeError, importable
from .kernels import stored_steps
from .step import _mp_step, step_core

__all__ = ["flint_available", "mp_backend", "mp_orbit", "arb_step", "pick_mp_backend", "MP_BACKENDS", "GUARD_BITS"]

#: accepted ``backend`` values for mpmath input
MP_BACKENDS = ("auto", "flint", "qd", "mpmath")
GUARD_BITS = 40


def flint_available() -> bool:
    """True if python-flint can be imported (imported once, on first call).

    >>> isinstance(flint_available(), bool)
    True
    """
    return importable("flint")


def _mpf(x: Any, _fme: Any = mpmath.libmp.from_man_exp, _make: Any = mpmath.mp.make_mpf) -> Any:
    """The midpoint of an Arb ball as an mpf rounded (to nearest) to the current ``mp.prec``."""
    if not x.is_finite():
        return mpmath.mpf(x)
    man, exp = x.mid().man_exp()
    return _make(_fme(int(man), int(exp), mpmath.mp.prec, "n"))


def _mpf_exact(x: Any, prec: int, _fme: Any = mpmath.libmp.from_man_exp, _make: Any = mpmath.mp.make_mpf) -> Any:
    """:func:`_mpf` for a finite ball of radius zero (no ``mid()`` needed)."""
    man, exp = x.man_exp()
    return _make(_fme(int(man), int(exp), prec, "n"))


def _to_mp(x: Any) -> Any:
    """An Arb ball (or complex ball) as an mpmath number at the current precision (its midpoint)."""
    from flint import acb

    if isinstance(x, acb):
        if x.imag.is_zero():
            return _mpf(x.real)
        return mpmath.mpc(_mpf(x.real), _mpf(x.imag))
    return _mpf(x)


class _Retry(ArithmeticError):
    """Internal: the fast step met a division by an exact zero."""


def _div(a: Any, b: Any) -> Any:
    if b.is_zero():                      # projective infinity, as every context (rare)
        from .arb import ARB_MID

        return ARB_MID.div(a, b)
    return a / b


def _slopes(a: list[Any], r: list[Any], s: int, name: str, dv: Callable[[Any, Any], Any]) -> list[Any]:
    """:func:`~symbt.numeric.step.eigen_slopes` for real Arb midpoints, fused (same operations, same order).

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
    u = [u1]
    if fwd:
        for j in range(N - 1):
            u.append(dv(-r[j], a[j] + u[j]))
        return u + [not tg]
    u += [None] * (N - 1)
    nxt = u1
    for j in range(N - 1, 0, -1):
        nxt = u[j] = -a[j] - dv(r[j], nxt)
    return u + [not tg]


def arb_step(P: list[Any], Q: list[Any], lam0: Any, mu: Any, branch: int,
             dv: Callable[[Any, Any], Any] = operator.truediv) -> tuple[list[Any], list[Any]]:
    """One step on real Arb balls with midpoint decisions: ``step_core(ARB_MID, ...)`` fused.

    Performs exactly the operations of :func:`~symbt.numeric.step.step_core` in the same order
    (bit-identical midpoints, ``tests/test_numeric_mpfast.py``) without the context indirection;
    raises the same :class:`NoRealMapError`.  ``dv`` divides: plain division (fast; a division by
    an exact zero gives a non-finite result) or :func:`_div` (a projective infinity, as
    ``ARB_MID.div``) -- callers redo a non-finite step with ``dv=_div``.

    >>> from flint import arb
    >>> P, Q = arb_step([arb(-20), arb(10), arb(1)], [arb(1), arb(0), arb("0.9")], arb(10), arb(5), 1)
    >>> P[0].str(8, radius=False)
    '-19.996568'
    """
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


def _safe_step(P: list[Any], Q: list[Any], lam0: Any, mu: Any, branch: int) -> tuple[list[Any], list[Any]]:
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


def _flint_step(P: list[Any], Q: list[Any], lam0: Any, mu: Any, branch: int,
                allow_complex: bool) -> tuple[list[Any], list[Any]]:
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


def pick_mp_backend(backend: str, n: int = 1) -> str:
    """The backend ``"qd"``, ``"flint"`` or ``"mpmath"`` that runs ``n`` steps at the current ``mp.prec``.

    ``"auto"``: ``"qd"`` if numba is present, :func:`~symbt.numeric.qd.qd_fits` and the compiled
    orbit is ready (:func:`~symbt.numeric.qd.qd_ready`: compiled once, e.g. by
    ``python -m symbt.numeric.qd``), else ``"flint"``
    if python-flint is present, else ``"mpmath"``.  An explicit backend that is missing raises
    :class:`MissingDependencyError`; ``"qd"`` at a precision it cannot carry raises
    :class:`InvalidInputError`.

    >>> pick_mp_backend("mpmath")
    'mpmath'
    >>> with mpmath.workdps(200):
    ...     pick_mp_backend("auto", 10) in ("flint", "mpmath")
    True
    """
    if backend not in MP_BACKENDS:
        raise InvalidInputError("backend for mpmath input must be one of %s, got %r" % (MP_BACKENDS, backend))
    if backend == "mpmath":
        return backend
    from .qd import qd_available, qd_fits, qd_need, qd_ready

    if backend == "qd":
        if not qd_available():
            raise MissingDependencyError("the qd backend needs numba: pip install 'symbt[fast]' "
                                         "(or unset SYMBT_NO_NUMBA)")
        if not qd_fits(mpmath.mp.prec, n):
            raise InvalidInputError("the qd backend carries 209 bits; mp.prec = %d with %d steps needs %d: "
                                    "use backend='flint' (or 'auto')" % (mpmath.mp.prec, n, qd_need(mpmath.mp.prec, n)))
        return backend
    if backend == "auto" and qd_fits(mpmath.mp.prec, n) and qd_ready() and qd_available():
        return "qd"
    if not flint_available():
        if backend == "flint":
            raise MissingDependencyError("the flint backend needs python-flint: pip install 'symbt[certified]'")
        return "mpmath"
    return "flint"


def _qd_step(P: list[Any], Q: list[Any], lam0: Any, mu: Any, branch: int, allow_complex: bool,
             explicit: bool = False) -> tuple[list[Any], list[Any]]:
    """One quad-double step; where the real map does not exist and ``allow_complex``, or (not ``explicit``)
    outside the quad-double range, the Arb (or mpmath) step."""
    from .qd import qd_orbit_mp

    try:
        Pn, Qn = qd_orbit_mp(P, Q, lam0, mu, 1, branch=branch, every=1)
        return Pn[-1], Qn[-1]
    except NoRealMapError:
        if not allow_complex:
            raise
    except NumericRangeError:
        if explicit:
            raise
    if flint_available():
        return _flint_step(P, Q, lam0, mu, branch, allow_complex)
    from ._input import MP

    return _mp_step(MP, P, Q, lam0, mu, branch, allow_complex)


def _qd_step_explicit(P: list[Any], Q: list[Any], lam0: Any, mu: Any, branch: int,
                      allow_complex: bool) -> tuple[list[Any], list[Any]]:
    return _qd_step(P, Q, lam0, mu, branch, allow_complex, explicit=True)


def mp_backend(backend: str = "auto") -> Callable[..., tuple[list[Any], list[Any]]] | None:
    """The fast mpmath step for ``backend`` at the current precision (``None``: use the plain mpmath path).

    >>> mp_backend("mpmath") is None
    True
    """
    name = pick_mp_backend(backend, 1)
    if name == "qd":
        return _qd_step_explicit if backend == "qd" else _qd_step
    return _flint_step if name == "flint" else None


def mp_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, branch: int = 1, every: int = 1,
             backend: str = "auto") -> tuple[list[list[Any]], list[list[Any]]]:
    """``n`` steps from one mpmath state; lists of the stored states (mpf at ``mp.dps``).

    Stored states as for float64 orbits (steps ``0, every, ...`` and ``n``).

    >>> with mpmath.workdps(40):
    ...     P, Q = mp_orbit([-20, 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, 2, backend="mpmath")
    >>> len(P), mpmath.nstr(P[1][0], 10)
    (3, '-19.99656766')
    """
    ctx, P, Q, _ = as_state_pair(p, q, lam0, mu)
    lam0, mu = prepare_spectral_pair(ctx, lam0, mu, ())
    keep = set(stored_steps(n, every))
    outP, outQ = [to_output(ctx, P, ())], [to_output(ctx, Q, ())]
    name = "mpmath" if ctx is IV else pick_mp_backend(backend, n)
    if mu == 0 or n == 0:
        return outP * len(keep), outQ * len(keep)
    if name == "qd":
        from .qd import qd_orbit_mp

        try:
            return qd_orbit_mp(P, Q, lam0, mu, n, branch=branch, every=every)
        except NumericRangeError:
            if backend == "qd":
                raise
            name = "flint" if flint_available() else "mpmath"
    if name == "mpmath":
        pc, qc = P, Q
        for i in range(1, n + 1):
            pc, qc = _mp_step(ctx, pc, qc, lam0, mu, branch, False)
            if i in keep:
                outP.append(pc)
                outQ.append(qc)
        return outP, outQ
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
