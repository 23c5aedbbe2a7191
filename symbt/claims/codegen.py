r"""Emitted numeric code (``symbt codegen``): the generated modules against their SymPy sources.

One claim per emitted function of ``symbt/generated/toda{N}.py`` and per N emitted by default
(``symbt.codegen.TARGETS``); the claim's ``equation`` names the generated function
(``toda{N}.bt_step``), ``source_equation`` the paper label it is derived from.

For every function ``f`` and sample point ``x`` (float64 values, so that both flavours see
exactly the same input; see :mod:`symbt.codegen.verify`):

* reference: the SymPy source of ``f`` (:func:`symbt.codegen.derive.sources`, the model
  itself, before any rewriting for float64) evaluated with mpmath at 80 digits;
* *condition scale* ``S = |f| + sum_i max(|x_i|, 1) |df/dx_i|`` (central differences of the
  emitted mpmath function at 50 digits);
* numpy flavour: ``|f64 - ref| <= 16 eps S``; mpmath flavour at 50 digits: ``<= 1e-45 S``.

Further: ``phi_grad`` against numerical differentiation of the emitted ``phi``; ``dapp_xy``
against the printed eq. ``xy`` (``literal_step``, 70 digits); ``bt_step`` against the paper's
route (``literal_step``, 70 digits), :func:`symbt.numeric.bt_step` and, normwise, the 50-digit
:func:`symbt.reference.literal.reference_step` (<= 1e-12); ``bt_orbit`` (centre of mass carried)
and :func:`symbt.numeric.bt_orbit`, each against the literal orbit at 50 digits with a bound from
the orbit's measured perturbation growth (two-sided: a worse numeric orbit no longer loosens the
emitted one's bound); the files' provenance hashes.  Sample points: seeded admissible states
(real map, both signs of tr L, both branches) and, for N = 3, the paper's example.
"""
from __future__ import annotations

import importlib
from dataclasses import replace
from functools import cache

import mpmath as mp
import numpy as np

from ..codegen import TARGETS, check, derivation_hash, verify
from ..reference.literal import literal_step
from .base import Outcome, Parts, claim, scene

scene("codegen", "emitted numeric code (symbt codegen): generated numpy/mpmath modules vs their SymPy "
                 "sources, the literal map, the 50-digit step and symbt.numeric (N=2,3)")

STEP_VS_NUMERIC_ULPS = 64
STEP_NORMWISE_TOL = 1e-12
ORBIT_STEPS, ORBIT_STEPS_DEEP = 100, 300


def _scaled(x, s):
    """``x`` (an array, an mpmath number, or nested tuples/lists of them) times ``s``."""
    if isinstance(x, (tuple, list)):
        return type(x)(_scaled(v, s) for v in x)
    if isinstance(x, (int, float, np.ndarray, np.generic)):
        return x * s
    return x * mp.mpf(s)


class _Scaled:
    """The emitted module with every output multiplied by ``scale`` (the statement part "scale")."""

    def __init__(self, mod, scale):
        self._mod, self._scale = mod, scale

    def __getattr__(self, name):
        f = getattr(self._mod, name)
        return (lambda *a, **k: _scaled(f(*a, **k), self._scale)) if callable(f) else f


def _module(N, parts: Parts | None = None):
    """The emitted module ``toda{N}``; the claims read it through their statement part ``scale``
    ("emitted output x scale = source", scale = 1 as emitted), which ``symbt mutate`` perturbs."""
    mod = importlib.import_module(f"symbt.generated.toda{N}")
    scale = 1.0 if parts is None else parts.printed["scale"]
    return mod if scale == 1.0 else _Scaled(mod, scale)


def _parts(N: int | None = None) -> Parts:
    return Parts(printed={"scale": 1.0})


def _compare(N, name, parts: Parts | None = None) -> Outcome:
    from ..codegen import verify

    r = verify.compare(_module(N, parts), N, name)
    worst_m = r["worst_mp"]
    return Outcome("verified" if r["ok"] else "failed", "numeric: emitted vs SymPy source", evidence="sampled",
                   residual=max(r["worst_f64"] * verify.EPS, float(worst_m)),
                   digits=float(-mp.log10(worst_m)) if worst_m > 0 else float(verify.REF_DPS),
                   detail=r["detail"], counterexample=r["bad"])


def _also(out: Outcome, ok: bool, text: str) -> Outcome:
    out = replace(out, detail=out.detail + "; " + text)
    if not ok:
        out = replace(out, status="failed")
    return out


@claim("codegen.invariants", equation="toda{N}.invariants", source_equation="tra", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: invariants, invariants_mp",
       statement="emitted invariants (numpy float64 and mpmath) = its SymPy source: H_0..H_{N-1}, the "
                 "coefficients of tr L(lambda) (N={N})")
def invariants(N: int, parts: Parts) -> Outcome:
    return _compare(N, "invariants", parts)


@claim("codegen.trace", equation="toda{N}.spectral_trace", source_equation="tra", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: spectral_trace, spectral_trace_mp",
       statement="emitted spectral_trace (numpy float64 and mpmath) = its SymPy source: tr L(lambda) (N={N})")
def spectral_trace(N: int, parts: Parts) -> Outcome:
    return _compare(N, "spectral_trace", parts)


@claim("codegen.fields", equation="toda{N}.hamiltonian_fields", source_equation="tra", scene="codegen",
       sizes=TARGETS, parts=_parts, where="symbt/generated/toda{N}.py: hamiltonian_fields, hamiltonian_fields_mp",
       statement="emitted hamiltonian_fields (numpy float64 and mpmath) = its SymPy source: the Hamiltonian "
                 "vector fields of H_0..H_{N-1} (N={N})")
def hamiltonian_fields(N: int, parts: Parts) -> Outcome:
    return _compare(N, "hamiltonian_fields", parts)


@claim("codegen.flow", equation="toda{N}.flow_field", source_equation="eqdisc", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: flow_field, flow_field_mp",
       statement="emitted flow_field (numpy float64 and mpmath) = its SymPy source: the vector field of "
                 "sum_k c_k H_k (N={N})")
def flow_field(N: int, parts: Parts) -> Outcome:
    return _compare(N, "flow_field", parts)


@claim("codegen.phi_tr", equation="todaN.phi_tr", source_equation="newkmu", scene="codegen", parts=_parts,
       where="symbt/generated/toda{2,3}.py: phi_tr, phi_tr_mp",
       statement="emitted phi_tr (numpy float64 and mpmath) = its SymPy source: real Phi = -b(sgn(tr1) "
                 "arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2)) (the same in every toda{N}: checked in each)")
def phi_tr(parts: Parts) -> Outcome:
    outs = [_compare(N, "phi_tr", parts) for N in TARGETS]
    worst = max(outs, key=lambda o: o.residual or 0.0)
    worst = replace(worst, n_scope="all", detail=f"toda{TARGETS}: " + worst.detail
                    + "; phi_tr is a function of the two traces alone, the same for every N")
    if any(o.status != "verified" for o in outs):
        worst = replace(worst, status="failed")
    return worst


@claim("codegen.phi", equation="toda{N}.phi", source_equation="newkmu", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: phi, phi_mp",
       statement="emitted phi (numpy float64 and mpmath) = its SymPy source: real Phi(p, q, lambda0, mu, b) (N={N})")
def phi(N: int, parts: Parts) -> Outcome:
    return _compare(N, "phi", parts)


@claim("codegen.phi_grad", equation="toda{N}.phi_grad", source_equation="newkmu", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: phi_grad, phi_grad_mp",
       statement="emitted phi_grad (numpy float64 and mpmath) = its SymPy source, and = the numerical "
                 "derivative (mp.diff, 50 digits) of the emitted Phi (N={N})")
def phi_grad(N: int, parts: Parts) -> Outcome:
    from ..codegen import verify

    out = _compare(N, "phi_grad", parts)
    r = verify.phi_grad_vs_fd(_module(N, parts), N)
    return _also(out, r <= mp.mpf(10) ** -40, f"vs mp.diff of the emitted Phi: {mp.nstr(r, 3)} (tolerance 1e-40)")


@claim("codegen.integrand", equation="toda{N}.ck_integrand", source_equation="eqdisc", scene="codegen",
       sizes=TARGETS, parts=_parts, where="symbt/generated/toda{N}.py: ck_integrand, ck_integrand_mp",
       statement="emitted ck_integrand (numpy float64 and mpmath) = its SymPy source: the c_k integrand "
                 "lambda^k / sqrt(tr L(lambda)^2 - 4) (N={N})")
def ck_integrand(N: int, parts: Parts) -> Outcome:
    return _compare(N, "ck_integrand", parts)


@claim("codegen.xy", equation="toda{N}.dapp_xy", source_equation="xy", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: dapp_xy, dapp_xy_mp",
       statement="emitted dapp_xy (numpy float64 and mpmath) = its SymPy source, Dapp's x and y, and = eq. xy "
                 "as printed (literal_step, 70 digits), both branches (N={N})")
def dapp_xy(N: int, parts: Parts) -> Outcome:
    from ..codegen import verify

    out = _compare(N, "dapp_xy", parts)
    r = verify.xy_vs_printed(_module(N, parts), N)
    return _also(out, r <= verify.MP_TOL, f"= eq. xy as printed (literal_step, 70 digits): {mp.nstr(r, 3)}")


@claim("codegen.step", equation="toda{N}.bt_step", source_equation="imptransf", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: bt_step, bt_step_mp",
       statement="emitted bt_step (numpy float64 and mpmath) = its SymPy source: one BT step (p, q) -> (p~, q~) "
                 "(N={N})")
def bt_step(N: int, parts: Parts) -> Outcome:
    return _compare(N, "bt_step", parts)


@claim("codegen.step_literal", equation="toda{N}.bt_step", source_equation="imptransf", scene="codegen",
       sizes=TARGETS, parts=_parts, where="symbt/generated/toda{N}.py: bt_step, bt_step_mp",
       statement="the emitted step equals the paper's route (symbt.reference.literal.literal_step, 70 digits) "
                 "and symbt.numeric.bt_step (float64), both branches (N={N})")
def step_literal(N: int, parts: Parts) -> Outcome:
    from ..codegen import verify
    from ..numeric import bt_step as numeric

    mod = _module(N, parts)
    worst_mp, worst_num = mp.mpf(0), 0.0
    for p, q, l0, m in verify.map_states(N):
        for b in (1, -1):
            with mp.workdps(70):
                lp, lq, _ = literal_step(p, q, l0, m, b)
            with mp.workdps(verify.MP_DPS):
                ep, eq = mod.bt_step_mp(p, q, l0, m, b)
            with mp.workdps(70):
                for a, c in zip(ep + eq, lp + lq):
                    worst_mp = max(worst_mp, abs(a - c) / max(1, abs(c)))
            fp, fq = mod.bt_step(p, q, l0, m, b)
            # the plain-Python kernel: bit-identical to numba's (tests/test_numeric_fast.py), no numba load
            np_, nq = numeric(p, q, l0, m, branch=b, backend="python")
            ref = [float(v) for v in lp + lq]
            for a, c, r in zip(list(fp) + list(fq), list(np_) + list(nq), ref):
                worst_num = max(worst_num, abs(a - c) / (verify.EPS * max(1.0, abs(r))))
    ok = worst_mp <= verify.MP_TOL and worst_num <= STEP_VS_NUMERIC_ULPS
    detail = (f"mpmath (50 digits) vs literal_step (70 digits): max rel. diff {mp.nstr(worst_mp, 3)}; "
              f"float64 emitted vs symbt.numeric.bt_step: max diff {worst_num:.1f} eps*max(1,|x|) "
              f"(tolerance {STEP_VS_NUMERIC_ULPS}: two independent float64 routes, each within a few eps*S)")
    return Outcome("verified" if ok else "failed", "numeric: emitted step vs literal and numeric routes",
                   evidence="sampled",
                   residual=float(worst_mp), detail=detail)


@claim("codegen.step_accuracy", equation="toda{N}.bt_step", source_equation="imptransf", scene="codegen",
       sizes=TARGETS, parts=_parts, where="symbt/generated/toda{N}.py: bt_step",
       statement="the emitted float64 bt_step is within 1e-12 normwise (||x - x_ref|| / ||x_ref||, x = (p~, q~)) "
                 "of the 50-digit step symbt.reference.literal.reference_step on admissible states, both "
                 "branches (N={N})")
def step_accuracy(N: int, parts: Parts) -> Outcome:
    from ..codegen import verify

    err = verify.step_accuracy(_module(N, parts), N)
    return Outcome("verified" if err <= STEP_NORMWISE_TOL else "failed", "numeric: float64 step vs 50 digits",
                   evidence="sampled",
                   residual=err, detail=f"max normwise relative error {err:.2e} (tolerance {STEP_NORMWISE_TOL:g}) "
                                        f"over {len(verify.map_states(N))} states x 2 branches")


@cache
def _orbit_reference(N: int, state: tuple, n: int) -> tuple:
    """The literal orbit (50 digits, checked at 75) of ``state``, branch +1, and the growth ``g_k`` (k = 0..n) of
    a perturbation of the initial state after k steps (one seeded direction, 30 digits + guard)."""
    from ._shipped import FD_DPS, guard_digits, literal_orbit

    p, q, l0, m = state
    st = (tuple(p), tuple(q), l0, m)
    g = guard_digits(st)
    ref, chk = literal_orbit(st, 1, n, 50, g), literal_orbit(st, 1, n, 75, g + 25)
    agree = max(float(max(abs(a - c) for a, c in zip(x, y)) / max(1, *(abs(c) for c in y))) for x, y in zip(ref, chk))
    rng = np.random.default_rng(N)
    x0 = np.array(list(p) + list(q))
    growth = np.zeros(n + 1)
    for _ in range(1):
        d = rng.normal(size=2 * N) * np.maximum(np.abs(x0), 1)
        d *= 1e-12 / np.linalg.norm(d)
        xp = x0 + d
        o = literal_orbit((tuple(xp[:N]), tuple(xp[N:]), l0, m), 1, n, FD_DPS, g)
        with mp.workdps(FD_DPS + g):
            dev = [float(mp.sqrt(mp.fsum((a - c) ** 2 for a, c in zip(x, y)))) for x, y in zip(o, ref)]
        growth = np.maximum(growth, np.array(dev) / np.linalg.norm(xp - x0))
    R = np.array([[float(v) for v in x] for x in ref])
    return R, growth, agree


@claim("codegen.orbit", equation="toda{N}.bt_orbit", source_equation="imptransf", scene="codegen", sizes=TARGETS,
       parts=_parts,
       where="symbt/generated/toda{N}.py: bt_orbit",
       statement="the emitted float64 bt_orbit (centre of mass carried separately) and symbt.numeric.bt_orbit are "
                 "each within 16 N eps sqrt(sum_k g_k^2) max|x| of the literal orbit (50 digits, checked at 75) "
                 "over 100 steps (300 under --deep), g_k the orbit's measured perturbation growth after k steps "
                 "(N={N})")
def orbit(N: int, parts: Parts, deep: bool = False) -> Outcome:
    from ..numeric import bt_orbit

    n = ORBIT_STEPS_DEEP if deep else ORBIT_STEPS
    C = 16 * N
    worst = {"emitted": 0.0, "symbt.numeric": 0.0}
    errs = {"emitted": 0.0, "symbt.numeric": 0.0}
    agree_worst, bound_worst = 0.0, 0.0
    for p, q, l0, m in verify.map_states(N, per_sign=1):
        R, growth, agree = _orbit_reference(N, (tuple(p), tuple(q), l0, m), n)
        agree_worst = max(agree_worst, agree)
        scale = np.linalg.norm(np.concatenate([R[:, :N], R[:, N:] - R[:, N:].mean(axis=1, keepdims=True)], axis=1),
                               axis=1)
        # rounding errors of ~C eps |x| per step, carried to step m by the growth of the steps still to come
        # (first order: the map is integrable, its Jacobians depend on the elapsed steps), added as a random walk
        size = np.max(np.linalg.norm(np.maximum(np.abs(R), 1), axis=1))
        bound = C * verify.EPS * np.sqrt(np.cumsum(np.maximum(growth, 1) ** 2)) * size / scale
        bound_worst = max(bound_worst, float(bound[-1]))
        for name, (P, Q) in (("emitted", _module(N, parts).bt_orbit(p, q, l0, m, n)),
                             ("symbt.numeric", bt_orbit(p, q, l0, m, n, backend="python"))):   # = numba's
            e = np.linalg.norm(np.concatenate([P, Q], axis=1) - R, axis=1) / scale
            e = np.where(np.isfinite(e), e, np.inf)
            errs[name] = max(errs[name], float(np.max(e)))
            worst[name] = max(worst[name], float(np.max(e / bound)))
    ok = max(worst.values()) <= 1 and agree_worst <= 1e-45
    return Outcome("verified" if ok else "failed", "numeric: float64 orbits vs the literal orbit (50 digits)",
                   residual=errs["emitted"], evidence="sampled", n_scope=[N],
                   detail=f"max over {len(verify.map_states(N, per_sign=1))} states and {n} steps of "
                          f"||x_m - x_ref|| / ||(p_ref, q_ref - mean q_ref)||: emitted {errs['emitted']:.2e}, "
                          f"symbt.numeric.bt_orbit {errs['symbt.numeric']:.2e}; worst error/bound "
                          f"{worst['emitted']:.3g} and {worst['symbt.numeric']:.3g} (bound at step n up to "
                          f"{bound_worst:.2e}); reference self-agreement 50/75 digits {agree_worst:.1e}")


def _files_parts(N: int) -> Parts:
    return Parts(printed={"derivation": derivation_hash()})


@claim("codegen.files", equation="toda{N}.provenance", source_equation="provenance", scene="codegen", sizes=TARGETS,
       parts=_files_parts,
       where="symbt/generated/toda{N}.py header",
       statement="the generated module is present, not edited by hand and not stale (provenance hashes match "
                 "the derivation sources) (N={N})")
def files(N: int, parts: Parts) -> Outcome:
    from ..codegen import DEFAULT_OUT, read_header

    problems = check(ns=(N,))
    for name in (f"toda{N}.py", "__init__.py"):
        path = DEFAULT_OUT / name
        recorded = read_header(path.read_text(encoding="utf-8")).get("derivation-sha256") if path.is_file() else None
        if recorded != parts.printed["derivation"]:
            problems.append(f"{path}: records derivation {str(recorded)[:12]}..., the statement names "
                            f"{parts.printed['derivation'][:12]}...")
    if problems:
        return Outcome("failed", "provenance hashes", evidence="proof", detail="; ".join(problems))
    return Outcome("verified", "provenance hashes", evidence="proof",
                   detail=f"derivation-sha256 {derivation_hash()[:16]}... and content hash match")
