r"""Emitted numeric code (``symbt codegen``): the generated modules against their sources.

For every emitted function ``f`` of ``symbt/generated/toda{2,3}.py`` (see
:mod:`symbt.codegen.derive`) and every sample point ``x`` (float64 values, so
that both flavours see exactly the same input):

* reference: the SymPy source expression of ``f`` evaluated with 60-digit
  Floats (independent of the printer and of CSE);
* *condition scale* ``S = |f| + sum_i max(|x_i|, 1) |df/dx_i|`` (central
  differences of the emitted mpmath function at 50 digits): the size of the
  change of ``f`` under relative-or-absolute input perturbations of one unit.
  A float64 evaluation that is backward stable up to a few roundings per input
  is within a few ``eps * S`` of the truth; for well-conditioned points ``S`` is
  a small multiple of ``|f|``, near zeros of ``f`` it keeps the test meaningful;
* numpy flavour: ``|f64 - ref| <= F64_TOL_ULPS * eps * S`` (``F64_TOL_ULPS = 16``:
  a handful of roundings of the inputs and of every ``exp``/``sqrt``/``acosh``
  along a CSE chain, each contributing at most ``~eps * S``);
* mpmath flavour at 50 digits: ``|mp - ref| <= 1e-45 * S``.

The emitted step is also compared with :func:`symbt.reference.literal.literal_step`
(the paper's route at 70 digits) and, when importable, with
:func:`symbt.numeric.bt_step` (float64).  Sample points: seeded random states
(``admissible_states``: real map, both signs of tr L, both branches) and, for
N = 3, the paper's example.
"""
from __future__ import annotations

import importlib
import random
from functools import cache

import mpmath as mp
import numpy as np
import sympy as sp

from ..reference.literal import literal_step
from ..reference.samples import admissible_states, paper_state
from .base import Outcome, claim, failed, scene

scene("codegen", "emitted numeric code (symbt codegen): generated numpy/mpmath modules vs their SymPy "
                 "sources, the literal map and symbt.numeric (N=2,3)")

F64_TOL_ULPS = 16
STEP_VS_NUMERIC_ULPS = 64
MP_TOL = mp.mpf(10) ** -45
REF_DPS, MP_DPS = 60, 50
EPS = float(np.finfo(np.float64).eps)

# claim id stem, emitted function name, paper label, what it computes (static: no derivation at import)
_FUNCS = (
    ("invariants", "invariants", "tra", "H_0..H_{N-1}, the coefficients of tr L(lambda)"),
    ("trace", "spectral_trace", "tra", "tr L(lambda)"),
    ("fields", "hamiltonian_fields", "tra", "the Hamiltonian vector fields of H_0..H_{N-1}"),
    ("flow", "flow_field", "eqdisc", "the vector field of sum_k c_k H_k"),
    ("phi_tr", "phi_tr", "newkmu", "real Phi = -b(sgn(tr1) arccosh(|tr1|/2) + sgn(tr2) arccosh(|tr2|/2))"),
    ("phi", "phi", "newkmu", "real Phi(p, q, lambda0, mu, b)"),
    ("phi_grad", "phi_grad", "newkmu", "grad_(p,q) Phi (also = numerical derivative of the emitted Phi)"),
    ("integrand", "ck_integrand", "eqdisc", "the c_k integrand lambda^k / sqrt(tr L(lambda)^2 - 4)"),
    ("xy", "dapp_xy", "xy", "Dapp's x and y (eq. xy as printed, both branches)"),
    ("step", "bt_step", "imptransf", "the closed-form BT step (p, q) -> (p~, q~)"),
)


def _module(N):
    return importlib.import_module(f"symbt.generated.toda{N}")


def _spec(N, name):
    from ..codegen.derive import specs

    return next(s for s in specs(N) if s.name == name)


@cache
def _map_states(N):
    """(p, q, lam0, mu) as float lists: 2 per sign of tr L (+ the paper's example for N = 3)."""
    with mp.workdps(30):
        st = admissible_states(N, 1, 2) + admissible_states(N, -1, 2)
        if N == 3:
            st.append(paper_state("5"))
    return [([float(v) for v in p], [float(v) for v in q], float(l0), float(m)) for p, q, l0, m in st]


def _points(spec, N):
    """List of argument dicts (python floats / lists of floats / branch ints)."""
    rng = random.Random(7919 * N + len(spec.name))
    kinds = {a.name for a in spec.args}
    pts = []
    if "lam0" in kinds:
        for p, q, l0, m in _map_states(N):
            for b in (1, -1):
                pts.append(dict(p=p, q=q, lam0=l0, mu=m, branch=b))
    elif "lam" in kinds:
        for p, q, l0, m in _map_states(N):
            for lv in (l0 + m, l0 - m):
                pts.append(dict(lam=lv, p=p, q=q))
    elif "tr1" in kinds:
        for _ in range(6):
            t1, t2 = (rng.choice((1, -1)) * rng.uniform(2.2, 40) for _ in range(2))
            pts.append(dict(tr1=t1, tr2=t2, branch=rng.choice((1, -1))))
    else:
        for _ in range(6):
            pt = dict(p=[rng.uniform(-3, 3) for _ in range(N)], q=[rng.uniform(-1.5, 1.5) for _ in range(N)])
            if "c" in kinds:
                pt["c"] = [rng.uniform(-1, 1) for _ in range(N)]
            pts.append(pt)
    return pts


def _flat(out):
    """Flatten the (tuple of) outputs of an emitted function into a list of scalars."""
    outs = out if isinstance(out, tuple) else (out,)
    res = []
    for o in outs:
        if isinstance(o, np.ndarray):
            res += [float(v) for v in o.reshape(-1)]
        elif isinstance(o, list):
            for v in o:
                res += v if isinstance(v, list) else [v]
        else:
            res.append(o)
    return res


def _reference(spec, pt):
    """The SymPy source of every output at 60 digits (inputs are the exact float64 values)."""
    subs = {}
    for a in spec.args:
        vals = pt[a.name] if a.kind == "state" else [pt[a.name]]
        for s, v in zip(a.symbols, vals):
            subs[s] = sp.Integer(v) if a.kind == "branch" else sp.Float(mp.mpf(v), REF_DPS)
    out = []
    with mp.workdps(REF_DPS):
        for o in spec.outputs:
            for e in o.exprs:
                v = sp.sympify(e).xreplace(subs).evalf(REF_DPS)
                out.append(mp.mpmathify(complex(v)) if not v.is_real else mp.mpf(v))
    return out


def _scale(spec, fn_mp, pt, ref):
    """S_k = |f_k| + sum_i max(|x_i|, 1) |df_k/dx_i| (central differences of the mpmath flavour)."""
    S = [abs(r) for r in ref]
    with mp.workdps(MP_DPS):
        for a in spec.args:
            if a.kind == "branch":
                continue
            n = len(pt[a.name]) if a.kind == "state" else 1
            for i in range(n):
                x0 = mp.mpf(pt[a.name][i] if a.kind == "state" else pt[a.name])
                h = mp.mpf(10) ** -18 * max(abs(x0), 1)
                vals = []
                for sgn in (1, -1):
                    args = {k: (list(v) if isinstance(v, list) else v) for k, v in pt.items()}
                    if a.kind == "state":
                        args[a.name][i] = x0 + sgn * h
                    else:
                        args[a.name] = x0 + sgn * h
                    vals.append(_flat(fn_mp(**args)))
                for k in range(len(S)):
                    S[k] += max(abs(x0), 1) * abs(vals[0][k] - vals[1][k]) / (2 * h)
    return S


def _compare(N, name):
    spec = _spec(N, name)
    mod = _module(N)
    fn, fn_mp = getattr(mod, name), getattr(mod, name + "_mp")
    worst_f, worst_m, bad_f, bad_m = 0.0, mp.mpf(0), None, None
    npts = 0
    for pt in _points(spec, N):
        ref = _reference(spec, pt)
        S = _scale(spec, fn_mp, pt, ref)
        with np.errstate(all="ignore"):
            f64 = _flat(fn(**pt))
        with mp.workdps(MP_DPS):
            fm = _flat(fn_mp(**pt))
        with mp.workdps(REF_DPS):
            for k, (r, s) in enumerate(zip(ref, S)):
                s = max(s, mp.mpf(10) ** -300)
                ef = float(abs(mp.mpf(f64[k]) - r) / (EPS * s))
                em = abs(mp.mpmathify(fm[k]) - r) / s
                if not ef <= worst_f:
                    worst_f, bad_f = ef, dict(point=repr(pt), output=k, ref=mp.nstr(r, 17), f64=repr(f64[k]))
                if em > worst_m:
                    worst_m, bad_m = em, dict(point=repr(pt), output=k, ref=mp.nstr(r, 30), mp=mp.nstr(fm[k], 30))
        npts += 1
    ok = worst_f <= F64_TOL_ULPS and worst_m <= MP_TOL
    detail = (f"{npts} points x {len(ref)} outputs; numpy: max |f64 - ref| = {worst_f:.2f} eps*S "
              f"(tolerance {F64_TOL_ULPS}); mpmath at {MP_DPS} digits: max |mp - ref|/S = {mp.nstr(worst_m, 3)} "
              f"(tolerance 1e-45); ref = SymPy source at {REF_DPS} digits, "
              "S = |f| + sum_i max(|x_i|,1)|df/dx_i|")
    return Outcome("verified" if ok else "failed", "numeric: emitted vs SymPy source",
                   residual=max(worst_f * EPS, float(worst_m)),
                   digits=float(-mp.log10(worst_m)) if worst_m > 0 else float(REF_DPS),
                   detail=detail, counterexample=None if ok else (bad_f if worst_f > F64_TOL_ULPS else bad_m))


def _phi_grad_fd(N):
    """dPhi/dx of the emitted gradient vs numerical differentiation of the emitted Phi (both signs of tr)."""
    mod = _module(N)
    worst = mp.mpf(0)
    with mp.workdps(MP_DPS):
        for p, q, l0, m in _map_states(N):
            for b in (1, -1):
                gp, gq = mod.phi_grad_mp(p, q, l0, m, b)
                for i in range(N):
                    for which, g in (("p", gp[i]), ("q", gq[i])):
                        def f(t, which=which, i=i):
                            pp, qq = list(map(mp.mpf, p)), list(map(mp.mpf, q))
                            (pp if which == "p" else qq)[i] = t
                            return mod.phi_mp(pp, qq, l0, m, b)
                        x0 = mp.mpf((p if which == "p" else q)[i])
                        d = mp.diff(f, x0)
                        worst = max(worst, abs(d - g) / max(1, abs(g)))
    return worst


def _xy_printed(N):
    """The emitted (rewritten) x, y vs the printed quotients of eq. xy (symbt.reference.literal, 70 digits)."""
    mod = _module(N)
    worst = mp.mpf(0)
    for p, q, l0, m in _map_states(N):
        for b in (1, -1):
            with mp.workdps(70):
                info = literal_step(p, q, l0, m, b)[2]
            with mp.workdps(MP_DPS):
                x, y = mod.dapp_xy_mp(p, q, l0, m, b)
            with mp.workdps(70):
                worst = max(worst, abs(x - info["x_formula"]) / abs(info["x_formula"]),
                            abs(y - info["y"][0]) / abs(info["y"][0]))
    return worst


for _N in (2, 3):
    def _make(N):
        for stem, fname, label, what in _FUNCS:
            if stem == "phi_tr" and N == 3:
                continue  # phi_tr does not depend on N: checked once
            cid = f"codegen.{stem}" + ("" if stem == "phi_tr" else f".n{N}")

            def check(N=N, fname=fname):
                out = _compare(N, fname)
                if fname == "dapp_xy" and out.status == "verified":
                    r = _xy_printed(N)
                    out.detail += f"; = eq. xy as printed (literal_step, 70 digits): {mp.nstr(r, 3)}"
                    if r > MP_TOL:
                        out.status = "failed"
                if fname == "phi_grad" and out.status == "verified":
                    r = _phi_grad_fd(N)
                    out.detail += f"; vs mp.diff of the emitted Phi: {mp.nstr(r, 3)}"
                    if r > mp.mpf(10) ** -40:
                        out.status = "failed"
                return out

            claim(cid, equation=label, scene="codegen", N=None if stem == "phi_tr" else N,
                  where="symbt/generated/" + f"toda{N}.py: {fname}, {fname}_mp",
                  statement=f"emitted {fname} (numpy float64 and mpmath) = its SymPy source: {what}"
                            + ("" if stem == "phi_tr" else f" (N={N})"))(check)

        @claim(f"codegen.step_literal.n{N}", equation="imptransf", scene="codegen", N=N,
               where=f"symbt/generated/toda{N}.py: bt_step, bt_step_mp",
               statement="the emitted closed-form step equals the paper's route (symbt.reference.literal.literal_step, "
                         f"70 digits) and symbt.numeric.bt_step (float64), both branches (N={N})")
        def step_literal(N=N):
            mod = _module(N)
            worst_mp, worst_num = mp.mpf(0), 0.0
            from ..numeric import bt_step as numeric
            for p, q, l0, m in _map_states(N):
                for b in (1, -1):
                    with mp.workdps(70):
                        lp, lq, _ = literal_step(p, q, l0, m, b)
                    with mp.workdps(MP_DPS):
                        ep, eq = mod.bt_step_mp(p, q, l0, m, b)
                    with mp.workdps(70):
                        for a, c in zip(ep + eq, lp + lq):
                            worst_mp = max(worst_mp, abs(a - c) / max(1, abs(c)))
                    fp, fq = mod.bt_step(p, q, l0, m, b)
                    np_, nq = numeric(p, q, l0, m, branch=b)
                    ref = [float(v) for v in lp + lq]
                    for a, c, r in zip(list(fp) + list(fq), list(np_) + list(nq), ref):
                        worst_num = max(worst_num, abs(a - c) / (EPS * max(1.0, abs(r))))
            ok = worst_mp <= MP_TOL and worst_num <= STEP_VS_NUMERIC_ULPS
            detail = (f"mpmath (50 digits) vs literal_step (70 digits): max rel. diff {mp.nstr(worst_mp, 3)}; "
                      + f"float64 emitted vs symbt.numeric.bt_step: max diff {worst_num:.1f} eps*max(1,|x|) "
                        f"(tolerance {STEP_VS_NUMERIC_ULPS}: two independent float64 routes, each within a few eps*S)")
            return Outcome("verified" if ok else "failed", "numeric: emitted step vs literal and numeric routes",
                           residual=float(worst_mp), detail=detail)

        @claim(f"codegen.files.n{N}", equation="provenance", scene="codegen", N=N,
               where=f"symbt/generated/toda{N}.py header",
               statement="the generated module is present, not edited by hand and not stale "
                         f"(provenance hashes match the derivation sources) (N={N})")
        def files_check(N=N):
            from .. import codegen

            problems = [msg for msg in codegen.check() if f"toda{N}.py" in msg or "__init__.py" in msg]
            if problems:
                return failed("provenance hashes", detail="; ".join(problems))
            return Outcome("verified", "provenance hashes",
                           detail=f"derivation-sha256 {codegen.derivation_hash()[:16]}... and content hash match")

    _make(_N)
