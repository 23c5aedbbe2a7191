r"""What ships, 4k: six documented rules of the numeric routes that seed 3's mutation sample showed unchecked
(scene ``numeric-paths``; issue 21 item 4, docs/mutation.md "seed 3").

* ``paths.qd_tables`` -- the quad-double exponential's tables (:mod:`symbt.numeric.multiprec.qd_arith`: row
  ``j + 89`` of ``EXP_TAB`` / ``EXPM1_TAB`` is ``exp(j/256)`` / ``expm1(j/256)`` rounded to a quad-double, ``j`` in
  ``[-89, 89]``, so that every reduced argument ``|a - m ln 2| <= ln2 / 2`` has its row) against mpmath at 400 bits
  (the four rows at either end, rows -1..1 and every 8th: 31 per table),
  and ``expm1``, ``log1p`` at arguments whose reduction lands on the tables' end rows (``j = +-89``, ``m = 0``) and
  just past them (``m = +-1``) within ``2**-200`` relative (a few quad-double roundings, ``2**-209`` each, of a
  well-conditioned function) of mpmath; the references of the end rows, row 0 and the calls checked at 500 bits.
  The tables are built once, when the module is imported (``symbt mutate --source`` counts the builder's lines as
  import lines: a mutant there runs every claim, this one included).
* ``paths.inline_lines`` -- :func:`~symbt.numeric.core.inline.inlined` keeps the source's line numbers (the code it
  compiles starts at the source function's first line, and a traceback through it names the line of the source
  that raised: ``inline.py``'s rule, ``tracebacks name the source's lines``), read against
  :func:`inspect.getsourcelines` of the source function.
* ``paths.compress.n3`` -- :func:`~symbt.numeric.flow.coefficients.flow_quadrature` with ``compress`` (its
  docstring: the composite rule is replaced by the *smallest* single Gauss--Legendre rule on the whole interval,
  8 to 128 nodes, whose integrals agree with the composite ones to ``compress``): at the paper's state, both
  branches, ``compress = 1e-9`` and ``2e-15``, the returned rule is a single ``n``-point Gauss--Legendre rule on
  ``[lam0 - mu, lam0 + mu]`` (nodes against :func:`numpy.polynomial.legendre.leggauss`), ``n`` is one of the
  documented candidates and at most the smallest candidate whose ``c_k`` (``k = 0..N``, the integrand
  ``-b lam^k / sqrt(tr L(lam)^2 - 4)`` with the literal trace at 30 digits, an independent route) agree with the
  composite rule's to ``compress`` relative, and its ``c_k`` agree with the composite rule's to ``compress``
  relative (the scale the rule judges by is at least ``|c_k|``, so a larger difference is refused by it).
* ``paths.python_kernel.n3`` -- ``bt_orbit(..., backend="python")`` on a batch runs the plain-Python kernel
  (its docstring: ``"python"`` is the plain-Python kernel): it runs with numba switched off (``SYMBT_NO_NUMBA=1``,
  where asking for numba raises ``MissingDependencyError``), and every member equals its single-state orbit bit for
  bit (a consistency check: only the route is in question).
* ``paths.decimal_input.n3`` -- :func:`~symbt.numeric.certified_orbit` takes decimal strings as balls that contain
  the decimal value (its module docstring): the state ``("-20.1", "10.3", "1.7")``, ``("1.1", "0", "0.9")``,
  ``lam0 = "10.5"``, ``mu = "5.25"``, one step, encloses the literal map of the decimal state at 60 digits
  (checked at 80), radii below ``1e-25``; the same digits as floats (other numbers) are outside the enclosure.
* ``paths.error_bounds.n3`` -- :func:`~symbt.numeric.multiprec.lohner_checks.float64_error_bounds` (``max_i |x64_i -
  x_i| + r_i`` per stored state, rounded up) bounds the float64 orbit's error against the literal map iterated at
  50 digits (the true error must not exceed it) and is within ``2 max r_i`` plus one float rounding of that error
  (two-sided), on the paper's state and its mirror, 3 steps.

Shown to fail on planted bugs in ``tests/test_killers_numeric4.py``.
"""
from __future__ import annotations

import importlib.util
import inspect
import math

import mpmath as mp
import numpy as np

from ._shipped import without_numba
from .base import Outcome, claim, failed, skipped

#: paths.qd_tables: arguments whose reduction lands on the tables' end rows (j = +-89, m = 0) and just past them
QD_EXPM1_ARGS = (0.3459, 0.34655, -0.3459, -0.34655, 0.3467, -0.3467, 0.2, 1e-3)
#: the relative accuracy asked of expm1 / log1p / a table row (a few quad-double roundings of 2**-209 each)
QD_REL = 2.0 ** -200
QD_TAB, QD_TAB_HALF = 256, 89
#: the rows compared with mpmath (every row is compared with the rebuilt table): the ends, the middle, every 8th
QD_ROWS = sorted({j for j in range(-QD_TAB_HALF, QD_TAB_HALF + 1) if abs(j) >= QD_TAB_HALF - 3 or abs(j) <= 1
                  or j % 8 == 0})


def _qd_value(t: object) -> mp.mpf:
    """The exact sum of a quad-double's four doubles (at the caller's precision, >= 300 bits)."""
    return mp.fsum(mp.mpf(float(x)) for x in t)  # type: ignore[attr-defined]


def _qd_rel(got: mp.mpf, ref: mp.mpf) -> float:
    return float(abs(got - ref) / abs(ref)) if ref != 0 else float(abs(got))


@claim("paths.qd_tables", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/multiprec/qd_arith.py: the exp / expm1 tables and their end rows",
       statement="the quad-double tables EXP_TAB, EXPM1_TAB: 179 rows, row j + 89 = exp(j/256), expm1(j/256) "
                 "within 2**-200 relative (mpmath at 400 bits, the end rows checked at 500; the ends, the middle and "
                 "every 8th row), j in [-89, 89]; "
                 "expm1 and log1p where the reduction lands on the end rows (j = +-89, m = 0) and past them "
                 "(m = +-1) within 2**-200 relative of mpmath")
def qd_tables() -> Outcome:
    from ..numeric.multiprec import qd_arith

    bad, worst = [], 0.0
    for name, table, fn in (("EXP_TAB", qd_arith.EXP_TAB, mp.exp), ("EXPM1_TAB", qd_arith.EXPM1_TAB, mp.expm1)):
        want = (2 * QD_TAB_HALF + 1, 4)
        if np.shape(table) != want:
            bad.append(f"{name}: shape {np.shape(table)}, want {want}")
            continue
        for j in QD_ROWS:
            with mp.workprec(400):
                ref = fn(mp.mpf(j) / QD_TAB)
                got = _qd_value(table[j + QD_TAB_HALF])
            agree = 0.0
            if abs(j) in (0, 1, QD_TAB_HALF):   # the reference checked where the claim's cases are
                with mp.workprec(500):
                    agree = _qd_rel(fn(mp.mpf(j) / QD_TAB), ref) if j != 0 else 0.0
            rel = _qd_rel(got, ref)
            worst = max(worst, rel)
            if not (rel <= QD_REL and agree <= 2.0 ** -390):
                bad.append(f"{name} row j = {j}: relative error {rel:.3g} (reference agreement {agree:.3g})")
    for a in QD_EXPM1_ARGS:
        x = (a, 0.0, 0.0, 0.0)
        try:
            got_e = qd_arith.expm1(x)
            got_l = qd_arith.log1p((math.expm1(a), 0.0, 0.0, 0.0))
        except (IndexError, ArithmeticError, ValueError) as exc:
            bad.append(f"expm1 / log1p at {a}: {type(exc).__name__}: {exc}")
            continue
        for name, got, f, arg in (("expm1", got_e, mp.expm1, a), ("log1p", got_l, mp.log1p, math.expm1(a))):
            with mp.workprec(400):
                ref, val = f(mp.mpf(arg)), _qd_value(got)
            with mp.workprec(500):
                agree = _qd_rel(f(mp.mpf(arg)), ref)
            rel = _qd_rel(val, ref)
            worst = max(worst, rel)
            if not (rel <= QD_REL and agree <= 2.0 ** -390):
                bad.append(f"{name}({arg!r}): relative error {rel:.3g}")
    m, i, _ = qd_arith.exp_parts((QD_EXPM1_ARGS[0], 0.0, 0.0, 0.0))
    if (m, i - QD_TAB_HALF) != (0, QD_TAB_HALF):
        bad.append(f"the first argument reduces to m = {m}, j = {i - QD_TAB_HALF}, not the end row: premise fails")
    detail = (f"worst relative error {worst:.3g} (bound {QD_REL:.3g}) over 2 x {len(QD_ROWS)} rows and "
              f"{len(QD_EXPM1_ARGS)} x 2 calls.")
    if bad:
        return failed("numeric: the quad-double tables and expm1/log1p vs mpmath", detail="; ".join(bad[:6]) + ". "
                      + detail)
    return Outcome("verified", "numeric: the quad-double tables and expm1/log1p vs mpmath (400 bits, checked at "
                   "500)", evidence="sampled", n_scope="all", detail=detail,
                   printed="every row and call within 2**-200 relative")


def _inline_probe(x: float) -> float:
    """A function for ``paths.inline_lines``: raises on a known line of this file."""
    y = x + 1.0
    if y > 2.0:
        raise ValueError("the probe's raise")
    return y


@claim("paths.inline_lines", equation="bt_step", source_equation="imptransf", scene="numeric-paths",
       where="symbt/numeric/core/inline.py: inlined (the rewritten code keeps the source's line numbers)",
       statement="inlined(f, ...) compiles code that starts at f's first source line, and a traceback through it "
                 "names the source line that raised (inspect.getsourcelines of f); the value is f's")
def inline_lines() -> Outcome:
    from ..numeric.core.inline import inlined

    g = inlined(_inline_probe, "inline_probe_copy", {}, {})
    lines, start = inspect.getsourcelines(_inline_probe)
    raise_line = start + next(i for i, text in enumerate(lines) if "raise ValueError" in text)
    bad = []
    if g.__code__.co_firstlineno != start:
        bad.append(f"the inlined code starts at line {g.__code__.co_firstlineno}, the source at {start}")
    if g(0.5) != _inline_probe(0.5):
        bad.append("the inlined function's value differs")
    try:
        g(5.0)
        bad.append("the inlined function did not raise")
    except ValueError as exc:
        tb = exc.__traceback__
        while tb is not None and tb.tb_next is not None:
            tb = tb.tb_next
        if tb is None or tb.tb_lineno != raise_line or tb.tb_frame.f_code.co_filename != inspect.getsourcefile(
                _inline_probe):
            bad.append(f"the traceback names line {tb.tb_lineno if tb else None}, the source raises at {raise_line}")
    detail = f"source lines {start}..{start + len(lines) - 1}, raise at {raise_line}."
    if bad:
        return failed("numeric: inlined code's line numbers vs the source's", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: inlined code's line numbers vs the source's (inspect)", evidence="sampled",
                   n_scope="all", detail=detail, printed="the same first line and the raising line")


#: paths.compress: the documented candidate sizes (flow_quadrature's docstring: 8 to 128 nodes), the tolerances
COMPRESS_SIZES = (8, 12, 16, 20, 24, 32, 40, 48, 56, 64, 80, 96, 112, 128)
COMPRESS_TOLS = (1e-9, 2e-15)
PAPER = ((-20.0, 10.0, 1.0), (1.0, 0.0, 0.9), 10.0, 5.0)


def _gl_moments(p: list, q: list, a: float, b: float, branch: int, n: int, N: int) -> list[float]:
    """``c_k`` (k = 0..N) by the n-point Gauss--Legendre rule of numpy on [a, b], the literal trace at 30 digits."""
    x, w = np.polynomial.legendre.leggauss(n)
    nd, wt = 0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w
    from ..reference.literal import literal_trace

    with mp.workdps(30):
        inv = [1 / mp.sqrt(literal_trace(mp.mpf(float(v)), p, q) ** 2 - 4) for v in nd]
        return [-branch * float(mp.fsum(mp.mpf(float(wi)) * mp.mpf(float(v)) ** k * iv
                                        for wi, v, iv in zip(wt, nd, inv))) for k in range(N + 1)]


@claim("paths.compress", equation="flow", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/flow/coefficients.py: flow_quadrature(compress=...) (the compressed rule)",
       statement="flow_quadrature at the paper's state (N={N}), both branches, compress = 1e-9 and 2e-15: a single "
                 "n-point Gauss-Legendre rule on [lam0 - mu, lam0 + mu] (numpy's leggauss), n a documented "
                 "candidate, at most the smallest candidate whose c_k (literal trace, 30 digits) agree with the "
                 "composite rule's to compress relative, fewer nodes than the composite rule, its c_k within "
                 "compress relative of the composite rule's")
def compress(N: int) -> Outcome:
    from ..numeric.flow.coefficients import flow_quadrature

    p, q, l0, m = PAPER
    a, b = l0 - m, l0 + m
    bad, seen = [], []
    for branch in (1, -1):
        with without_numba():       # the rule's existence check: the plain-Python kernel (bit-identical)
            comp = flow_quadrature(list(p), list(q), l0, m, branch=branch)
        ref = comp.moments(range(N + 1))
        cand = {}
        for tol in COMPRESS_TOLS:
            with without_numba():
                rule = flow_quadrature(list(p), list(q), l0, m, branch=branch, compress=tol)
            n = rule.nodes.size
            # the smallest candidate that agrees to tol relative by the independent route (computed as needed)
            strict = None
            for k in COMPRESS_SIZES:
                if k >= comp.nodes.size:
                    break
                if k not in cand:
                    cand[k] = _gl_moments(list(p), list(q), a, b, branch, k, N)
                if all(abs(c - r) <= tol * abs(r) for c, r in zip(cand[k], ref)):
                    strict = k
                    break
            seen.append(f"branch {branch}, compress {tol:g}: {n} nodes (composite {comp.nodes.size}, smallest "
                        f"agreeing candidate {strict})")
            if n not in COMPRESS_SIZES or rule.panels != 1:
                bad.append(f"branch {branch}, compress {tol:g}: {n} nodes in {rule.panels} panels, not one "
                           "documented candidate rule")
                continue
            x, w = np.polynomial.legendre.leggauss(n)
            nd, wt = 0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w
            span = 8 * np.finfo(float).eps * max(abs(a), abs(b))
            if not (np.max(np.abs(np.sort(rule.nodes) - np.sort(nd))) <= span
                    and np.max(np.abs(np.sort(rule.weights) - np.sort(wt))) <= 8 * np.finfo(float).eps * (b - a)):
                bad.append(f"branch {branch}, compress {tol:g}: the nodes or weights are not numpy's "
                           f"{n}-point Gauss-Legendre rule on [{a}, {b}]")
            if strict is None or not n <= strict or not n < comp.nodes.size:
                bad.append(f"branch {branch}, compress {tol:g}: {n} nodes, the smallest agreeing candidate is "
                           f"{strict}, the composite rule has {comp.nodes.size}")
            got = rule.moments(range(N + 1))
            if not all(abs(c - r) <= tol * abs(r) for c, r in zip(got, ref)):
                bad.append(f"branch {branch}, compress {tol:g}: c_k differ from the composite rule's by more "
                           "than compress")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: the compressed rule vs its documented choice", detail="; ".join(bad) + ". " + detail)
    return Outcome("verified", "numeric: the compressed rule vs its documented choice (numpy's Gauss-Legendre, the "
                   "literal trace)", evidence="sampled", detail=detail,
                   printed="the smallest agreeing single rule")


@claim("paths.python_kernel", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       where="symbt/numeric/float64/orbit.py: the ensemble's kernel for backend='python'",
       statement="bt_orbit(backend='python') on a batch of the paper's state and its mirror (N={N}, 3 steps, both "
                 "branches) with numba switched off (SYMBT_NO_NUMBA=1): it runs (the plain-Python kernel needs no "
                 "numba), and every member equals its single-state orbit bit for bit")
def python_kernel(N: int) -> Outcome:
    from ..numeric import bt_orbit
    from ..numeric.core.errors import MissingDependencyError

    p, q, l0, m = PAPER
    P0 = np.array([p, [-v for v in p]])
    Q0 = np.array([q, q])
    L0, M = np.array([l0, -l0]), np.array([m, -m])
    bad = []
    with without_numba():
        for b in (1, -1):
            try:
                P, Q = bt_orbit(P0, Q0, L0, M, 3, branch=b, backend="python")
            except MissingDependencyError as exc:
                bad.append(f"branch {b}: MissingDependencyError: {exc}")
                continue
            for k in range(2):
                Pk, Qk = bt_orbit(P0[k], Q0[k], float(L0[k]), float(M[k]), 3, branch=b, backend="python")
                if not (np.array_equal(P[:, k], Pk) and np.array_equal(Q[:, k], Qk)):
                    bad.append(f"branch {b}, member {k}: differs from its single-state orbit")
    detail = "2 members x 2 branches, 3 steps, numba switched off."
    if bad:
        return failed("numeric: bt_orbit(backend='python') vs the plain-Python kernel", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: bt_orbit(backend='python') without numba vs single-state orbits "
                   "(consistency)", evidence="sampled", detail=detail,
                   printed="runs without numba, member = single state")


#: paths.decimal_input: a state given as decimal strings (not binary numbers), one step
DECIMAL_STATE = (("-20.1", "10.3", "1.7"), ("1.1", "0", "0.9"), "10.5", "5.25")


@claim("paths.decimal_input", equation="bt_step", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/certified.py: decimal strings as input balls (_ball)",
       statement="certified_orbit on the decimal strings p = (-20.1, 10.3, 1.7), q = (1.1, 0, 0.9), lam0 = 10.5, "
                 "mu = 5.25 (N={N}), one step, both branches, at 30 digits: the enclosure contains the literal map "
                 "of the decimal state (60 digits, checked at 80), radii below 1e-25, and excludes the literal "
                 "map of the nearest doubles")
def decimal_input(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import certified_orbit
    from ..reference.literal import literal_step

    p, q, l0, m = DECIMAL_STATE
    bad, worst = [], 0.0
    for b in (1, -1):
        with mp.workdps(30):
            P, Q, Pr, Qr = certified_orbit(list(p), list(q), l0, m, 1, branch=b)
            got = [(x, r) for x, r in zip(list(P[1]) + list(Q[1]), list(Pr[1]) + list(Qr[1]))]
        refs = {}
        for name, conv in (("decimal", mp.mpf), ("double", lambda s: mp.mpf(float(s)))):
            for dps in (60, 80):
                with mp.workdps(dps):
                    pt, qt, _ = literal_step([conv(v) for v in p], [conv(v) for v in q], conv(l0), conv(m), b)
                    refs[(name, dps)] = [+v for v in list(pt) + list(qt)]
        with mp.workdps(60):
            agree = max(abs(x - y) for x, y in zip(refs[("decimal", 60)], refs[("decimal", 80)]))
            inside = all(abs(x - r) <= rad + agree for (x, rad), r in zip(got, refs[("decimal", 60)]))
            outside = any(abs(x - r) > rad + agree for (x, rad), r in zip(got, refs[("double", 60)]))
            worst = max(worst, float(max(rad for _, rad in got)))
        if not (inside and outside and worst < 1e-25 and agree < mp.mpf(10) ** -50):
            bad.append(f"branch {b}: decimal inside {inside}, doubles outside {outside}, radius {worst:.3g}")
    detail = f"worst radius {worst:.3g}."
    if bad:
        return failed("numeric: certified_orbit on decimal strings vs the literal map", detail="; ".join(bad) + ". "
                      + detail)
    return Outcome("verified", "numeric: certified_orbit on decimal strings vs the literal map (60 digits)",
                   evidence="sampled", detail=detail, printed="the decimal state's map enclosed")


@claim("paths.error_bounds", equation="bt_orbit", source_equation="imptransf", scene="numeric-paths", sizes=(3,),
       requires=("flint",),
       where="symbt/numeric/multiprec/lohner_checks.py: float64_error_bounds",
       statement="float64_error_bounds(certified_orbit, bt_orbit) on the paper's state and its mirror (N={N}, 3 "
                 "steps, both branches): per stored state at least the float64 orbit's largest error against the "
                 "literal map iterated at 50 digits, and at most that error + 2 max radius + one float rounding")
def error_bounds(N: int) -> Outcome:
    if importlib.util.find_spec("flint") is None:
        return skipped("python-flint is not installed (.[certified])")
    from ..numeric import bt_orbit, certified_orbit
    from ..numeric.multiprec.lohner_checks import float64_error_bounds
    from ..reference.literal import literal_step

    p, q, l0, m = PAPER
    bad, seen = [], []
    for name, (pp, ll, mm) in (("paper", (list(p), l0, m)), ("mirror", ([-v for v in p], -l0, -m))):
        for b in (1, -1):
            with mp.workdps(30):
                orbit = certified_orbit(pp, list(q), ll, mm, 3, branch=b)
            with without_numba():       # the plain-Python kernel (bit-identical): no numba compile in verify
                P64, Q64 = bt_orbit(pp, list(q), ll, mm, 3, branch=b)
            bounds = float64_error_bounds(*orbit, P64, Q64)
            with mp.workdps(50):
                x = [mp.mpf(v) for v in pp + list(q)]
                for i in range(len(bounds)):
                    f64 = [mp.mpf(float(v)) for v in list(P64[i]) + list(Q64[i])]
                    err = max(abs(u - v) for u, v in zip(f64, x))
                    rad = max(list(orbit[2][i]) + list(orbit[3][i]))
                    # the literal map at 50 digits stands in for the exact orbit: 1e-45 of slack either side
                    lo_ok = mp.mpf(bounds[i]) >= err - mp.mpf(10) ** -45
                    hi_ok = mp.mpf(bounds[i]) <= (err + 2 * rad) * (1 + mp.mpf(2) ** -50) + mp.mpf(10) ** -45
                    if not (lo_ok and hi_ok and (err > 0 or i == 0)):
                        bad.append(f"{name}, branch {b}, state {i}: bound {bounds[i]:.6g}, float64 error "
                                   f"{mp.nstr(err, 6)}, radius {mp.nstr(rad, 3)}")
                    if i + 1 < len(bounds):
                        pt, qt, _ = literal_step(x[:N], x[N:], ll, mm, b)
                        x = list(pt) + list(qt)
            seen.append(f"{name}, branch {b}: bounds {', '.join('%.3g' % v for v in bounds[1:])}")
    detail = "; ".join(seen) + "."
    if bad:
        return failed("numeric: float64_error_bounds vs the float64 orbit's error", detail="; ".join(bad[:6]) + ". "
                      + detail)
    return Outcome("verified", "numeric: float64_error_bounds vs the float64 orbit's error against the literal map "
                   "(50 digits)", evidence="sampled", detail=detail, printed="error <= bound <= error + 2 radius")
