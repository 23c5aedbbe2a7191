r"""The arithmetic contexts against their interface table (scene ``numeric-paths``, issue 21).

:func:`~symbt.numeric.core.step.step_core` is written once against a *context* (:mod:`symbt.numeric.core.context`,
the mpmath style: backends bind primitives); the float64, complex float64, mpmath, interval and Arb contexts each
bind ``div``, ``ldexp``, ``acosh_half_abs``, ``re_dot``, ``positive``, ``align`` and ``half_plane``.  Most claims
reach a primitive only through a whole step, where a slip in a rarely taken case (a division by an exact zero, a
tie ``Re(ref conj g) = 0``, a ball that straddles 0) changes nothing they look at.

* ``paths.contexts`` -- every context's primitives on exact dyadic samples (zeros included) against the table
  of :mod:`symbt.numeric.core.context`'s docstring, evaluated in Python's complex arithmetic (exact on these
  samples): ``div(a, b) = a/b`` and an infinity (``nan`` for ``0/0``; an interval: the whole line) at an exact
  zero; ``ldexp(x, e) = x 2^e`` (complex values too); ``re_dot(a, b) = Re(a conj b)``; ``positive(x)``
  "certainly ``x > 0``" (real and positive -- for the complex contexts too --; an interval or a certain ball
  wholly above 0, a certain ball straddling 0 raises ``Uncertain``, a midpoint ball by its midpoint);
  ``align(g, ref) = (+-g, plus)`` with ``plus`` iff ``Re(ref conj g) >= 0`` and ``half_plane(a, g)`` iff
  ``Re(a conj g) >= 0``, at ``g != 0`` (real contexts: ``g > 0``, the principal root they are given) and at
  ``ref``, ``a`` = 0 (the tie is ``>= 0``); ``out_of_range`` false on moderate values; ``select`` on one bool and
  (float) on a mixed mask; ``all_positive``
  over rows (NaN fails); ``acosh_half_abs(t, g, e) = arccosh(|t| 2^e / 2)`` and the elementary functions
  ``exp``, ``log``, ``log1p``, ``sqrt`` (principal branches; ``log1p`` near 0 and near -1) against mpmath at 40
  digits (float64 within 4 ulps, the others within ``1e-25`` at 140 bits); the Jacobian's dual numbers
  (:class:`~symbt.numeric.multiprec.lohner_checks.Dual`, the context ``DUAL``) through ``+ - * /`` with constants
  on either side and ``exp``, ``log``, ``log1p``, ``sqrt``: value and gradient against ``mpmath.diff`` of the
  same expressions.  The Arb contexts are skipped without python-flint (said in the detail).

  Written against the table, the claim found five primitives that did not meet it: the complex float64
  context's ``log1p`` (numpy's complex ``log1p`` is ``log(1 + x)``: 6e-9 relative at ``|x| = 1e-8``; the complex
  continuation's positions take it), and, in branches no step takes, its ``ldexp`` (numpy's takes no complex
  values) and ``positive`` (``Re x > 0``, where the mpmath and Arb contexts decide "real and positive"), the
  mpmath context's ``ldexp`` of an mpc, and the interval context's ``acosh_half_abs``, which ignored the scale.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import mpmath as mp
import numpy as np

from .base import Outcome, claim, failed

#: exact dyadic samples: real, and complex (with a purely imaginary one and the zero)
REALS = (-2.5, 0.0, 0.75, 3.0)
#: (t, e) of acosh_half_abs: |t| 2^e / 2 from 1 (the band edge) up, e = 0 on both of its forms' sides
ACOSH_CASES = ((3.0, 0), (-2.5, 0), (2.0, 0), (3.0, 1), (3.0, 2), (-0.75, 3))
COMPLEXES = (1 + 2j, -1 + 0.5j, 0.5 - 3j, 2j, 0j, -4 + 0j, 0.5 + 0j, 3 + 0j)


@dataclass(frozen=True)
class _Ctx:
    """A context with its value maker ``mk`` (Python number -> value), reader ``back`` (value -> complex) and
    whether it takes complex values."""

    name: str
    ctx: Any
    mk: Callable[[complex], Any]
    back: Callable[[Any], complex]
    complex_: bool
    tol: float              # acosh_half_abs's relative tolerance
    exact: Callable[[Any], Any] = lambda v: mp.mpf(complex(np.asarray(v).ravel()[0]).real)  # a real value, in full
    #: a complex value, in full
    exact_c: Callable[[Any], Any] = lambda v: mp.mpc(complex(np.asarray(v).ravel()[0]))
    #: the outcome of a division by an exact zero, as the context documents it (an interval: the whole line)
    by_zero: Callable[[Any, complex], bool] = lambda v, a: bool(v != v) if a == 0 else bool(np.isinf(abs(v)))


def _contexts() -> tuple[list[_Ctx], str]:
    from ..numeric.core.context import COMPLEX, FLOAT, IV, MP

    def mpv(x: complex) -> Any:
        return mp.mpf(x.real) if x.imag == 0 and not isinstance(x, complex) else mp.mpc(x.real, x.imag)

    out = [_Ctx("FLOAT", FLOAT, lambda x: np.array([float(x.real)]), lambda v: complex(np.asarray(v).ravel()[0]),
                False, 4 * 2.0 ** -53),
           _Ctx("COMPLEX", COMPLEX, lambda x: np.array([complex(x)]), lambda v: complex(np.asarray(v).ravel()[0]),
                True, 4 * 2.0 ** -53),
           _Ctx("MP (mpf)", MP, lambda x: mp.mpf(x.real), lambda v: complex(v), False, 1e-25, lambda v: v,
                lambda v: v),
           _Ctx("MP (mpc)", MP, lambda x: mp.mpc(x.real, x.imag), lambda v: complex(v), True, 1e-25, lambda v: v,
                lambda v: v),
           _Ctx("IV", IV, lambda x: mp.iv.mpf(x.real), lambda v: complex(float(v.mid)), False, 1e-25,
                lambda v: mp.mpf(v.mid), lambda v: mp.mpf(v.mid), lambda v, a: bool(mp.isinf(v.a) and mp.isinf(v.b)))]
    try:
        from flint import acb, arb

        from ..numeric.multiprec.arb import ACB, ARB_CERTAIN, ARB_MID
    except ImportError:
        return out, "python-flint absent: the Arb contexts not checked"

    def arb_back(v: Any) -> complex:
        return complex(float(v.mid()))

    def acb_back(v: Any) -> complex:
        return complex(float(v.real.mid()), float(v.imag.mid()))

    def arb_exact(v: Any) -> Any:
        ball = v.real if isinstance(v, acb) else v
        return mp.mpf(ball.mid().str(40, radius=False))

    def arb_exact_c(v: Any) -> Any:
        if isinstance(v, acb):
            return mp.mpc(arb_exact(v.real), arb_exact(v.imag))
        return arb_exact(v)

    out += [_Ctx("ARB_MID", ARB_MID, lambda x: arb(x.real), arb_back, False, 1e-25, arb_exact, arb_exact_c),
            _Ctx("ARB_CERTAIN", ARB_CERTAIN, lambda x: arb(x.real), arb_back, False, 1e-25, arb_exact, arb_exact_c),
            _Ctx("ACB", ACB, lambda x: acb(x.real, x.imag), acb_back, True, 1e-25, arb_exact, arb_exact_c)]
    return out, "Arb contexts included"


def _ball_prec(bits: int) -> Any:
    """python-flint's working precision ``bits`` inside (a no-op without python-flint)."""
    try:
        from ..numeric.multiprec.arb import flint_prec
    except ImportError:
        import contextlib

        return contextlib.nullcontext()
    return flint_prec(bits)


def _cond(c: Any) -> bool:
    return bool(np.asarray(c).ravel()[0]) if isinstance(c, np.ndarray) else bool(c)


def _check_context(c: _Ctx) -> list[str]:
    from ..numeric.core.context import iv_prec

    bad: list[str] = []
    samples = [complex(v) for v in (COMPLEXES if c.complex_ else REALS)]
    ctx, mk, back = c.ctx, c.mk, c.back
    with np.errstate(all="ignore"), mp.workdps(40), iv_prec(140), _ball_prec(140):
        for a in samples:
            for b in samples:
                r = back(ctx.re_dot(mk(a), mk(b)))
                if r != (a * b.conjugate()).real:
                    bad.append(f"re_dot({a}, {b}) = {r}")
                if b != 0:
                    q = back(ctx.div(mk(a), mk(b)))
                    if abs(q - a / b) > 1e-15 * abs(a / b):
                        bad.append(f"div({a}, {b}) = {q}")
                # the decisions: g != 0 (real contexts: g > 0), the tie at a = 0 / ref = 0 included
                if b != 0 and (c.complex_ or b.real > 0):
                    want = (a * b.conjugate()).real >= 0
                    if _cond(ctx.half_plane(mk(a), mk(b))) != want:
                        bad.append(f"half_plane({a}, {b}) is {not want}")
                    val, plus = ctx.align(mk(b), mk(a))
                    if _cond(plus) != want or back(val) != (b if want else -b):
                        bad.append(f"align(g={b}, ref={a}) = ({back(val)}, {_cond(plus)})")
            zero = ctx.div(mk(a), mk(0j))
            if not c.by_zero(back(zero) if c.name != "IV" else zero, a):
                bad.append(f"div({a}, 0) = {zero} (want {'nan' if a == 0 else 'an infinity'})")
            for e in (0, 1, 3, -2):
                if back(ctx.ldexp(mk(a), e)) != a * 2.0 ** e:
                    bad.append(f"ldexp({a}, {e}) = {back(ctx.ldexp(mk(a), e))}")
            want_pos = a.imag == 0 and a.real > 0
            if _cond(ctx.positive(mk(a))) != want_pos:
                bad.append(f"positive({a}) is {not want_pos}")
            if _cond(ctx.out_of_range(mk(a), mk(a))):      # a moderate value is in every context's range
                bad.append(f"out_of_range({a}) is true")
            for c_ in (True, False):        # select: lazy where the condition is one bool
                if back(ctx.select(c_, lambda: mk(a), lambda: mk(a + 1))) != (a if c_ else a + 1):
                    bad.append(f"select({c_}) does not pick {'f' if c_ else 'g'}")
        for t, e in ACOSH_CASES:
            T = mk(complex(t))
            g = ctx.sqrt(T * T - mk(complex(4.0 ** (1 - e))))
            got = c.exact(ctx.acosh_half_abs(T, g, e))
            want = mp.acosh(abs(mp.mpf(t)) * mp.mpf(2) ** e / 2)
            if not abs(got - want) <= c.tol * abs(want):
                bad.append(f"acosh_half_abs({t}, e={e}) = {got} (want {mp.nstr(want, 17)})")
    return bad


def _float_rows() -> list[str]:
    """The float contexts over batch rows: all_positive (NaN fails) and select with a mixed mask."""
    from ..numeric.core.context import COMPLEX, FLOAT

    bad = []
    for rows, want in (([0.75, 3.0], True), ([0.75, 0.0], False), ([0.5, math.nan], False), ([-1.0, 2.0], False)):
        if FLOAT.all_positive(np.array(rows)) != want:
            bad.append(f"FLOAT.all_positive({rows}) is {not want}")
    for crow, want in (([0.75 + 0j, 3 + 0j], True), ([0.75 + 0j, 1 + 1e-300j], False), ([0.5 + 0j, -2 + 0j], False)):
        if COMPLEX.all_positive(np.array(crow)) != want:
            bad.append(f"COMPLEX.all_positive({crow}) is {not want}")
    mask = np.array([True, False, True])
    f, g = np.array([1.0, 2.0, 3.0]), np.array([-1.0, -2.0, -3.0])
    for m, picked in ((mask, [1.0, -2.0, 3.0]), (np.ones(3, bool), f.tolist()), (np.zeros(3, bool), g.tolist())):
        if FLOAT.select(m, lambda: f, lambda: g).tolist() != picked:
            bad.append(f"FLOAT.select({m.tolist()}) is not {picked}")
    return bad


def _elementary(c: _Ctx) -> list[str]:
    """exp, log, log1p, sqrt (principal branches) against mpmath at 40 digits: float64 within 4 ulps of the value's
    size, the others within 1e-25 (at 140 bits)."""
    from ..numeric.core.context import iv_prec

    bad = []
    real = (0.75, 3.0, 1e-3, 25.0)
    # complex: the principal branches, and log1p near 0 (where log(1 + x) loses digits) and near -1
    points = [complex(v) for v in real] + ([1 + 2j, -1 + 0.5j, -4 + 0j, 0.5 - 3j, 1e-8 + 1e-9j, -1e-10 + 1e-6j,
                                            -0.999 + 0.001j] if c.complex_ else [])
    fns = (("exp", mp.exp), ("log", mp.log), ("log1p", mp.log1p), ("sqrt", mp.sqrt))
    with np.errstate(all="ignore"), mp.workdps(40), iv_prec(140), _ball_prec(140):
        for name, ref in fns:
            for x in points:
                got = c.exact_c(getattr(c.ctx, name)(c.mk(x)))
                want = ref(mp.mpc(x.real, x.imag) if c.complex_ else mp.mpf(x.real))
                if not abs(got - want) <= c.tol * abs(want):
                    bad.append(f"{name}({x}) = {mp.nstr(got, 17)} (want {mp.nstr(want, 17)})")
    return bad


def _dual_rules() -> list[str]:
    """The Jacobian's dual numbers (value, gradient) through the arithmetic and the elementary functions the
    step uses, against mpmath.diff of the same expressions (40 digits): f(x, y) at (3/4, 5/2)."""
    from flint import arb, arb_mat

    from ..numeric.multiprec.lohner_checks import DUAL, Dual

    exprs = (("x + y * 2 - 1", lambda x, y, L: x + y * 2 - 1), ("3 - x", lambda x, y, L: 3 - x),
             ("-x * y", lambda x, y, L: -x * y), ("x / y", lambda x, y, L: x / y), ("x / 4", lambda x, y, L: x / 4),
             ("2 / x", lambda x, y, L: 2 / x), ("exp(x y)", lambda x, y, L: L.exp(x * y)),
             ("log(x + y)", lambda x, y, L: L.log(x + y)), ("log1p(x / y)", lambda x, y, L: L.log1p(x / y)),
             ("sqrt(x + y)", lambda x, y, L: L.sqrt(x + y)))

    class _MP:
        exp, log, log1p, sqrt = mp.exp, mp.log, mp.log1p, mp.sqrt

    bad = []
    with mp.workdps(40), _ball_prec(140):
        X = Dual(arb(0.75), arb_mat([[1, 0]]))
        Y = Dual(arb(2.5), arb_mat([[0, 1]]))
        for text, f in exprs:
            d = f(X, Y, DUAL)
            want_v = f(mp.mpf(0.75), mp.mpf(2.5), _MP)
            want_d = [mp.diff(lambda a, b: f(a, b, _MP), (mp.mpf(0.75), mp.mpf(2.5)), (1, 0)),
                      mp.diff(lambda a, b: f(a, b, _MP), (mp.mpf(0.75), mp.mpf(2.5)), (0, 1))]
            got = [d.v] + [d.d[0, k] for k in range(2)]
            for g, w in zip(got, [want_v] + want_d):
                if not abs(mp.mpf(g.mid().str(40, radius=False)) - w) <= mp.mpf(10) ** -25 * max(1, abs(w)):
                    bad.append(f"the dual {text}: {g.str(12, radius=False)} (want {mp.nstr(w, 12)})")
                    break
    return bad


def _ball_decisions() -> list[str]:
    """Where a ball or an interval straddles 0: a midpoint decision, a refusal to decide, or 'not certain'."""
    from flint import arb

    from ..numeric.core.context import IV
    from ..numeric.multiprec.arb import ARB_CERTAIN, ARB_MID, Uncertain

    bad = []
    if not ARB_MID.positive(arb(0.25, 0.5)) or ARB_MID.positive(arb(-0.25, 0.5)):
        bad.append("ARB_MID.positive does not decide a straddling ball by its midpoint")
    for ball in (arb(0.25, 0.5), arb(-0.25, 0.5), arb(0, 1)):      # [-1/4, 3/4], [-3/4, 1/4], [-1, 1]
        try:
            ARB_CERTAIN.positive(ball)
            bad.append(f"ARB_CERTAIN.positive decided the ball {ball} straddling 0")
        except Uncertain:
            pass
    if not ARB_CERTAIN.positive(arb(0.5, 0.25)) or ARB_CERTAIN.positive(arb(-0.5, 0.25)):
        bad.append("ARB_CERTAIN.positive on balls wholly above / below 0")
    if IV.positive(mp.iv.mpf([-1, 2])) or not IV.positive(mp.iv.mpf([0.5, 2])):
        bad.append("IV.positive is not 'the whole interval above 0'")
    return bad


@claim("paths.contexts", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/context.py (FLOAT, COMPLEX, MP, IV), symbt/numeric/multiprec/arb.py (ARB_MID, "
             "ARB_CERTAIN, ACB): the primitives step_core is written against",
       statement="every arithmetic context's div, ldexp, re_dot, positive, align, half_plane and acosh_half_abs on "
                 "exact dyadic samples (zeros and the tie Re(ref conj g) = 0 included; complex samples for the "
                 "complex contexts) equal the interface table's definitions evaluated in Python's complex "
                 "arithmetic (acosh: mpmath at 40 digits); straddling balls and intervals are decided as documented; "
                 "out_of_range is false on every moderate sample")
def contexts() -> Outcome:
    ctxs, note = _contexts()
    bad: list[str] = []
    for c in ctxs:
        bad += [f"{c.name}: {b}" for b in _check_context(c) + _elementary(c)]
    bad += _float_rows()
    if "absent" not in note:
        bad += _ball_decisions() + _dual_rules()
    detail = f"{len(ctxs)} contexts ({', '.join(c.name for c in ctxs)}); {note}."
    if bad:
        return failed("the contexts' primitives vs the interface table", detail="; ".join(bad[:6]) + ". " + detail)
    return Outcome("verified", "numeric: the contexts' primitives vs the interface table's definitions",
                   evidence="sampled", n_scope="all", detail=detail, printed="every primitive as documented")
