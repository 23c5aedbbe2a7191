r"""The checks of the emitted code, checked: their metrics and the printer's powers (issue 21, seeds 4 and 5).

* ``checker.codegen_metrics`` -- the two measures :mod:`symbt.codegen.verify` reports besides the numpy flavour's
  error (``checker.codegen`` covers that one):

  1. :func:`~symbt.codegen.verify.compare` fails a module whose *mpmath* flavour is off by a relative ``1e-40`` in
     output 1 (the tolerance is ``MP_TOL = 1e-45`` relative to the condition scale), names output 1 and the mpmath
     value, and reports ``worst_mp`` within a relative ``1e-6`` of ``1e-40 |f_1| / S_1`` (over three points and at
     each alone: the worst point may have every ``|x_i| >= 1``) -- the largest relative error
     seen, not a stale one -- with ``f_1 = H_1`` and its condition scale ``S_1 = |H_1| + sum_i max(|x_i|, 1)
     |dH_1/dx_i|`` computed here from the literal trace (``mpmath.diff``), not by ``verify``'s own scale;
  2. :func:`~symbt.codegen.verify.xy_vs_printed` reports the relative error ``1e-40`` of a probe whose ``y`` is
     off by that where ``y`` is negative; :func:`~symbt.codegen.verify.interpret` divides ``Quotient(a, b)``
     IEEE-style: ``a/b``, and ``sgn(a) inf`` at ``b = 0`` only (``b = 1`` and ``2`` divide), and evaluates the six
     relations as Python compares (``(-3, 2)`` and ``(2, 2)``; seed 22: ``!=`` read as ``==``);
  3. :func:`~symbt.codegen.verify.phi_grad_vs_fd` measures ``|mp.diff(Phi) - g| / max(1, |g|)`` (its docstring):
     on a probe module whose ``Phi`` is linear with every slope ``1/4`` and whose gradient is off by ``1e-30`` in
     one entry, it returns ``1e-30`` to within ``1e-40`` (numerical differentiation of a linear function at 50
     digits is exact to ~1e-48), where the relative measure ``1e-30 / 1/4`` would be four times larger.

* ``library.printer_powers`` -- :class:`~symbt.codegen.printer.ExprPrinter` prints a power ``x**k`` with an
  integer or half-integer exponent, negative ones included, in every flavour (numpy ``**``, mpmath, the ops
  namespace, C as repeated products of ``x`` or ``sqrt(x)``), and refuses any other rational exponent with
  ``ValueError`` (its module docstring).  The printed text, evaluated by Python at ``x = 9/4`` and ``x = 4``
  (perfect squares: every power is an exact dyadic or a quotient rounded once), equals ``x**k`` computed with
  exact rationals to within one rounding per operation, for ``k`` in ``2, 3, -1, -2, 1/2, 3/2, 5/2, -1/2,
  -3/2``, and so does ``c x (x + 1)/(x + 3)`` for the coefficients ``c = 3/2, 1/2, -5/4, 7/3`` (a numerator other
  than 1 is printed in the numerator, the denominator in the denominator) within 6 roundings; ``x**(1/3)``,
  ``x**(2/3)`` and ``x**(-5/3)`` are refused; a rational constant alone is printed by the ``ops`` flavour only when
  dyadic (``x + 3/4``, ``x - 5/8`` exactly; ``x + 1/3``, ``x + 7/12`` refused).

Shown to fail on planted bugs in ``tests/test_killers_controls.py``.
"""
from __future__ import annotations

import math
from fractions import Fraction
from types import ModuleType, SimpleNamespace
from typing import Any, cast

import mpmath as mp
import numpy as np
import sympy as sp

from .base import Outcome, claim, failed

#: checker.codegen_metrics: the mpmath flavour's planted error (relative), the gradient's (absolute)
MP_OFF, GRAD_OFF, GRAD_SLOPE = mp.mpf(10) ** -40, mp.mpf(10) ** -30, mp.mpf(1) / 4


def _probe_phi(N: int) -> SimpleNamespace:
    """A module with ``phi_mp = (sum p + sum q) / 4`` and ``phi_grad_mp`` its gradient, off by ``GRAD_OFF`` in
    ``d/dp_0``."""
    def phi_mp(p: Any, q: Any, l0: Any, m: Any, b: int) -> Any:
        return GRAD_SLOPE * (mp.fsum(p) + mp.fsum(q))

    def phi_grad_mp(p: Any, q: Any, l0: Any, m: Any, b: int) -> tuple[list[Any], list[Any]]:
        gp = [GRAD_SLOPE] * N
        gp[0] = GRAD_SLOPE + GRAD_OFF
        return gp, [GRAD_SLOPE] * N
    return SimpleNamespace(phi_mp=phi_mp, phi_grad_mp=phi_grad_mp)


def _probe_xy(off: Any) -> SimpleNamespace:
    """A module whose ``dapp_xy_mp`` is the printed x, y of eq. xy (``literal_step`` at 70 digits) with y off by a
    relative ``off`` where y is negative (a measure that lost the modulus of its denominator would not see it)."""
    from ..reference.literal import literal_step

    def dapp_xy_mp(p: Any, q: Any, l0: Any, m: Any, b: int) -> tuple[Any, Any]:
        with mp.workdps(70):
            info = literal_step(p, q, l0, m, b)[2]
            y = info["y"][0]
            return +info["x_formula"], y * (1 + off) if y < 0 else +y
    return SimpleNamespace(dapp_xy_mp=dapp_xy_mp)


def _planted_measure(pt: dict[str, Any]) -> Any:
    """``|H_1| MP_OFF / S_1`` at ``pt`` with ``H_1`` and its gradient from the literal trace (the second coefficient
    of ``tr L(lambda)``, :func:`~symbt.claims.library_derive_file.trace_invariants`, differentiated by
    ``mpmath.diff``)."""
    from .library_derive_file import trace_invariants

    xs = [mp.mpf(x) for x in (*pt["p"], *pt["q"])]
    n = len(pt["p"])

    def h1(*x: Any) -> Any:
        return trace_invariants(list(x[:n]), list(x[n:]))[1]

    grad = [mp.diff(h1, xs, tuple(int(j == i) for j in range(len(xs)))) for i in range(len(xs))]
    scale = abs(h1(*xs)) + mp.fsum(max(abs(x), 1) * abs(g) for x, g in zip(xs, grad))
    return abs(h1(*xs)) * MP_OFF / scale


@claim("checker.codegen_metrics", equation="tra", scene="checker", N=2,
       where="symbt.codegen.verify.compare (the mpmath flavour's measure), verify.xy_vs_printed, verify.interpret, "
             "verify.phi_grad_vs_fd",
       statement="codegen.verify.compare fails toda2.invariants with the mpmath flavour's output 1 off by a relative "
                 "1e-40, names output 1 and its mpmath value at the point, and reports worst_mp "
                 "within a relative 1e-6 of 1e-40 |f_1|/S_1 (at the worst "
                 "of three points and at each alone); xy_vs_printed reports 1e-40 for y off by that where y < 0; "
                 "interpret's Quotient(-3, b) is -3, -3/2, -inf at b = 1, 2, 0, its Max(-3, 2) 2 and Min(-3, 2) "
                 "-3, its six relations Python's comparisons at (-3, 2) and (2, 2); phi_grad_vs_fd on "
                 "a linear Phi of slope 1/4 whose gradient is off by 1e-30 returns 1e-30 to within 1e-40; the points "
                 "of every N = 2, 3 function without a map take both signs in each coordinate of p, q and c")
def codegen_metrics() -> Outcome:
    from ..codegen import verify
    from ..codegen.derive import interface
    from ..generated import toda2

    spec = interface(2)["invariants"]
    pts = verify.points(spec, 2)[:3]

    def off_mp(**pt: Any) -> Any:
        v = list(toda2.invariants_mp(**pt))
        v[1] = v[1] * (1 + MP_OFF)
        return v

    wrong = SimpleNamespace(invariants=toda2.invariants, invariants_mp=off_mp)
    res = verify.compare(cast(ModuleType, wrong), 2, "invariants", pts=pts)
    bad = res["bad"] or {}
    # the measure the planted error should give: |f_1| MP_OFF / S_1 at the worst of the points, with f_1 = H_1
    # and S_1 = |H_1| + sum_i max(|x_i|, 1) |dH_1/dx_i| from the literal trace (mpmath's own differentiation):
    # not verify's condition scale, which is what is checked
    with mp.workdps(verify.MP_DPS):
        want = max(_planted_measure(pt) for pt in pts)
    problems = []
    # the value reported is the mpmath flavour's output 1 at the point reported
    named = next((pt for pt in pts if repr(pt) == bad.get("point")), None)
    with mp.workdps(verify.MP_DPS):      # compare's precision (at 15 digits the 30 printed would differ)
        named_mp = mp.nstr(off_mp(**named)[1], 30) if named is not None else None
    if named is None or bad.get("mp") != named_mp:
        problems.append(f"the reported mpmath value {bad.get('mp')} is not output 1 at the reported point")
    if res["ok"] or bad.get("output") != 1 or "mp" not in bad:
        problems.append(f"compare with the mpmath flavour off by 1e-40 in output 1: ok={res['ok']}, reported {bad}")
    # the two scales differ only by verify's forward differences (h = 1e-18 max(|x|, 1) at 50 digits: ~18 digits),
    # so the measures agree to far better than the 1e-6 asked (a scale that weighed a coordinate below 1 by |x|
    # instead of 1 moves it by a fraction of the sum)
    if not abs(res["worst_mp"] / want - 1) <= 1e-6:
        problems.append(f"worst_mp {mp.nstr(res['worst_mp'], 3)}, the planted error gives {mp.nstr(want, 3)}")
    # point by point as well: the worst point alone could be one where every |x_i| >= 1, which leaves the weights
    # max(|x_i|, 1) untested
    for i, pt in enumerate(pts):
        one = verify.compare(cast(ModuleType, wrong), 2, "invariants", pts=[pt])
        with mp.workdps(verify.MP_DPS):
            here = _planted_measure(pt)
        if not abs(one["worst_mp"] / here - 1) <= 1e-6:
            problems.append(f"point {i}: worst_mp {mp.nstr(one['worst_mp'], 8)}, the planted error gives "
                            f"{mp.nstr(here, 8)}")
    xy = verify.xy_vs_printed(cast(ModuleType, _probe_xy(MP_OFF)), 2)
    if not abs(xy / MP_OFF - 1) <= 1e-6:
        problems.append(f"xy_vs_printed with y off by a relative 1e-40 where y < 0: {mp.nstr(xy, 5)}")
    # the interpreter's IEEE-style quotient: a / b, and sgn(a) inf at b = 0 only
    from ..codegen.printer import Quotient
    a_, b_ = sp.symbols("a b")
    quot = [verify.interpret(Quotient(a_, b_), {a_: mp.mpf(-3), b_: mp.mpf(v)}, {}) for v in (1, 2, 0)]
    if quot != [-3, mp.mpf(-3) / 2, -mp.inf]:
        problems.append(f"interpret(Quotient(-3, b)) at b = 1, 2, 0: {quot}")
    # Max and Min (the guards' kt is a Max; a user's expression may hold either)
    env = {a_: mp.mpf(-3), b_: mp.mpf(2)}
    mm = [verify.interpret(f(a_, b_, evaluate=False), env, {}) for f in (sp.Max, sp.Min)]
    if mm != [2, -3]:
        problems.append(f"interpret(Max(-3, 2)), interpret(Min(-3, 2)): {mm}")
    # the six relations (a guard's or a Piecewise's condition) at a < b and a = a, against Python's own comparisons
    for u, v in ((-3, 2), (2, 2)):
        pair = {a_: mp.mpf(u), b_: mp.mpf(v)}
        got = [bool(verify.interpret(rel(a_, b_, evaluate=False), pair, {}))
               for rel in (sp.Ge, sp.Gt, sp.Le, sp.Lt, sp.Eq, sp.Ne)]
        if got != [u >= v, u > v, u <= v, u < v, u == v, u != v]:
            problems.append(f"interpret of >=, >, <=, <, ==, != at ({u}, {v}): {got}")
    r = verify.phi_grad_vs_fd(cast(ModuleType, _probe_phi(2)), 2)
    if not abs(r - GRAD_OFF) <= mp.mpf(10) ** -40:
        problems.append(f"phi_grad_vs_fd on a gradient off by 1e-30 (slopes 1/4): {mp.nstr(r, 5)}, want 1e-30 "
                        "(|mp.diff - g| / max(1, |g|))")
    # the points of a function without a map (no lam0) span both signs of every coordinate of p, q and c: a
    # form wrong in one sign cell of its arguments is sampled there
    for N in (2, 3):
        for name, fs in interface(N).items():
            kinds = {a.name for a in fs.args}
            if kinds & {"lam0", "lam", "tr1"}:
                continue
            fpts = verify.points(fs, N)
            for kind in sorted(kinds & {"p", "q", "c"}):
                for i in range(N):
                    signs = {v[kind][i] > 0 for v in fpts}
                    if signs != {True, False}:
                        problems.append(f"verify.points of toda{N}.{name}: {kind}[{i}] takes one sign only")
    detail = (f"mpmath flavour off by 1e-40: ok={res['ok']}, worst_mp {mp.nstr(res['worst_mp'], 3)} (planted "
              f"{mp.nstr(want, 3)}), reported output {bad.get('output')}; phi_grad_vs_fd: {mp.nstr(r, 5)}")
    if problems:
        return failed("numeric: codegen.verify's measures on planted errors", detail="; ".join(problems))
    return Outcome("verified", "numeric: codegen.verify's measures on planted errors of known size",
                   evidence="sampled", n_scope=[2], detail=detail)


#: library.printer_powers: exponents printed, exponents refused, the points (perfect squares)
POWERS = (sp.Integer(2), sp.Integer(3), sp.Integer(-1), sp.Integer(-2), sp.Rational(1, 2), sp.Rational(3, 2),
          sp.Rational(5, 2), sp.Rational(-1, 2), sp.Rational(-3, 2))
REFUSED = (sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(-5, 3))
POWER_POINTS = (Fraction(9, 4), Fraction(4))
#: library.printer_powers: rational coefficients (a numerator other than 1, negative, non-dyadic)
COEFFS = (sp.Rational(3, 2), sp.Rational(1, 2), sp.Rational(-5, 4), sp.Rational(7, 3))


def _namespace(flavour: str) -> dict[str, Any]:
    if flavour == "numpy":
        return {"np": np}
    if flavour == "mpmath":
        return {"mpmath": mp, "_Q": lambda p, q: mp.mpf(p) / q}
    if flavour == "ops":
        return {"_X": np}
    return {"sqrt": math.sqrt}


def _printed_at(text: str, flavour: str, exact: sp.Rational, v: Fraction) -> tuple[sp.Rational, Any, Any]:
    """``(exact, got, relative error)``: the printed ``text`` evaluated by Python at ``x = v`` (an mpf for the
    mpmath flavour, a double otherwise) against the exact rational value (``v`` a perfect square)."""
    want = mp.mpf(int(sp.numer(exact))) / int(sp.denom(exact))
    with mp.workdps(30):
        arg = mp.mpf(v.numerator) / v.denominator if flavour == "mpmath" else float(v)
        got = mp.mpf(eval(text, _namespace(flavour), {"x": arg}))  # noqa: S307 -- the printer's own text
        return exact, got, abs(got - want) / abs(want)


@claim("library.printer_powers", equation="checker", scene="library",
       where="symbt.codegen.printer.ExprPrinter._pow (integer and half-integer exponents, every flavour)",
       statement="x**k printed in the numpy, mpmath, ops and C flavours, k in 2, 3, -1, -2, 1/2, 3/2, 5/2, -1/2, "
                 "-3/2, and c x (x + 1)/(x + 3) for c = 3/2, 1/2, -5/4, 7/3 evaluate (Python, x = 9/4 and 4) to "
                 "the exact value within 4 (6) roundings; x**(1/3), "
                 "x**(2/3), x**(-5/3) are refused with ValueError in every flavour; the ops flavour prints x + 3/4 "
                 "and x - 5/8 exactly and refuses x + 1/3 and x + 7/12 (non-dyadic)")
def printer_powers() -> Outcome:
    from ..codegen.printer import ExprPrinter

    x = sp.Symbol("x", positive=True)
    bad, n = [], 0
    for flavour in ("numpy", "mpmath", "ops", "c"):
        pr = ExprPrinter(flavour, {x: "x"})
        for e, ulps in [(sp.Pow(x, k, evaluate=False), 4) for k in POWERS] + [
                (sp.Mul(c, x, x + 1, evaluate=False) / (x + 3), 6) for c in COEFFS]:   # coefficient: num., den.
            text = pr.text(e)
            for v in POWER_POINTS:
                exact, got, err = _printed_at(text, flavour, e.subs(x, sp.Rational(v.numerator, v.denominator)), v)
                n += 1
                if not err <= ulps * 2.0 ** -53:
                    bad.append(f"{flavour}: {e} printed {text!r} = {mp.nstr(got, 17)} at x = {v}, exactly {exact} "
                               f"(relative {mp.nstr(err, 3)})")
        for k in REFUSED:
            try:
                text = pr.text(sp.Pow(x, k, evaluate=False))
            except ValueError:
                continue
            bad.append(f"{flavour}: x**{k} printed {text!r}, not refused")
    # a rational constant standing alone: the ops flavour (transfer-matrix kernels) prints dyadic ones, exact as
    # doubles, and refuses any other (its printer's rule)
    ops = ExprPrinter("ops", {x: "x"})
    for c, dyadic in ((sp.Rational(3, 4), True), (sp.Rational(-5, 8), True), (sp.Rational(1, 3), False),
                      (sp.Rational(7, 12), False)):
        try:
            text = ops.text(x + c)
        except ValueError:
            if dyadic:
                bad.append(f"ops: x + {c} refused")
            continue
        exact, got, err = _printed_at(text, "ops", sp.Rational(9, 4) + c, Fraction(9, 4))
        if not dyadic or err != 0:
            bad.append(f"ops: x + {c} printed {text!r} = {mp.nstr(got, 17)} at x = 9/4 (exactly {exact})")
    detail = (f"{len(POWERS)} exponents and {len(COEFFS)} coefficients x 4 flavours x {len(POWER_POINTS)} points = "
              f"{n} evaluations, "
              f"{len(REFUSED)} exponents refused in each flavour")
    if bad:
        return failed("numeric: printed powers evaluated by Python vs exact rationals", detail="; ".join(bad[:6]))
    return Outcome("verified", "numeric: printed powers evaluated by Python at perfect squares vs exact rationals "
                   "(4 roundings)", evidence="sampled", n_scope="all", detail=detail)
