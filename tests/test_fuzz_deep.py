"""The deep fuzz (issues 21, 26): >= 1e5 seeded inputs through every step route, judged once per input.

The inputs are those of :func:`test_fuzz_numeric.generate` (near band edges, across gaps, nearly closed
gaps, large ``|q_i - q_j|``; N = 2, 3, 6, 16).  Each input is judged against one reference, the literal map
of :mod:`symbt.reference` at 40 + guard digits (60 digits where ``kappa > 1e10``, on 1 in 50, and where
it says no real map), never against the code under test; where every route refused and the 40-digit
literal traces alone decide (``|t| <= 2`` or opposite signs), no step is computed.  Routes:

* every input: the single-state fused kernel (``bt_step``, numba), the block kernel (``bt_step`` on a
  batch), the emitted numpy module (closed forms ``toda2``/``toda3`` as committed, loop forms ``toda6``,
  ``toda16`` emitted at the start) and its C step (compiled where a C compiler is present);
* 1 in :data:`ENSEMBLE_SUB`: the ensemble orbit (``bt_orbit`` on a batch, one step);
* 1 in :data:`SUB`: the plain-Python kernel, the numpy route (single and batch), the single-state orbit;
  for the emitted states ``S`` by forward differences (their documented ``16 eps S``);
* 1 in :data:`MP_SUB`: the multiprecision backends at 30 digits (mpmath, Arb, quad-double where
  installed), bound ``32 N 2**-103 kappa rho s``.

float64 routes of symbt.numeric: the documented bound of test_fuzz_numeric (``32 N eps kappa rho s``).
Emitted states off the 1-in-SUB subsample: within ``16 eps |f|`` per component, else within the
conditioning bound ``32 N eps kappa rho s``, else ``S`` decides (so a state can pass that ``16 eps S``
would refuse: docs/fuzz.md says how often ``S`` was the judge).  Within 1e-6 of the boundary of
existence an emitted state where no real map exists is accepted (docs/codegen.md).

``SYMBT_FUZZ_DEEP=1`` runs ``SYMBT_FUZZ_COUNT`` inputs (default 1e5) or until ``SYMBT_FUZZ_BUDGET``
seconds (default 36000; checked between chunks of 500); docs/fuzz.md records a run.
"""
from __future__ import annotations

import contextlib
import importlib.util
import os
import time

import mpmath as mp
import numpy as np
import pytest
from test_fuzz_numeric import (
    BATCH_ROUTES,
    EPS,
    NS,
    SINGLE_ROUTES,
    TYPED,
    _bound,
    _error,
    _mpv,
    generate,
    kappa_hp,
    literal,
    literal_guard,
    literal_traces,
    run_batch,
    trace_kappa_hp,
)

from symbt.numeric import bt_step
from symbt.numeric.backends import qd_available
from symbt.reference.literal import literal_step

#: the deep run: every input through the fast routes; 1 in SUB also through the slow float64 routes, 1 in
#: MP_SUB through the multiprecision backends at 30 digits (mpmath, Arb, quad-double where installed)
SUB, MP_SUB = 20, 200
#: the C step's documented refusals (c_template): no real map (trace 1, positivity 2), range 3, ill-conditioned 5;
#: 4 (invalid input) cannot occur for the fuzz's finite inputs
C_REFUSALS = (1, 2, 3, 5)
DEEP_SINGLE = ("kernel",)
DEEP_BATCH = ("block",)
ENSEMBLE_SUB = 4             # the ensemble orbit (bt_orbit on a batch) on 1 in 4
MP_BACKENDS = tuple(n for n, ok in (("mpmath", True), ("flint", importlib.util.find_spec("flint") is not None),
                                     ("qd", qd_available())) if ok)


def _mp_route(backend):
    def run(p, q, lam0, mu, branch):
        with mp.workdps(30):
            try:
                a, b = bt_step(_mpv(p), _mpv(q), mp.mpf(lam0), mp.mpf(mu), branch=branch, backend=backend)
            except TYPED as err:
                return type(err).__name__
            return [mp.mpf(x) for x in list(a) + list(b)]
    return run


def _emitted_routes(tmp):
    """The emitted modules by N (``None`` where absent): closed forms ``toda2``/``toda3`` (committed), loop
    forms ``toda6``/``toda16`` and the C steps of all four (compiled where a C compiler is present)."""
    import shutil
    import subprocess

    import symbt.codegen as cg
    from symbt.generated import toda2, toda3

    sys_mods = {2: toda2, 3: toda3}
    assert cg.main(["--n", "6", "16", "--out", str(tmp), "-q"]) == 0
    for N in (6, 16):
        spec = importlib.util.spec_from_file_location(f"toda{N}_deep", tmp / f"toda{N}.py")
        sys_mods[N] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys_mods[N])
    cstep = {}
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is not None:
        from test_codegen_edges import CStep

        assert cg.main(["--target", "c", "--n", *map(str, NS), "--out", str(tmp), "-q"]) == 0
        for N in NS:
            so = tmp / f"libtoda{N}.so"
            subprocess.run([cc, "-std=c99", "-O2", "-shared", "-fPIC", "-o", str(so), str(tmp / f"toda{N}.c"),
                            "-lm"], check=True, capture_output=True, timeout=300)
            cstep[N] = CStep(so, N)
    return sys_mods, cstep


def _emitted_results(inputs, mods, csteps):
    """``{route: {i: outcome}}``: the emitted numpy module (masked batch) and the C step for every input."""
    out = {"emitted": {}, "C": {}}
    for N in NS:
        idx = [i for i, x in enumerate(inputs) if x[1].size == N]
        if not idx:
            continue
        P, Q = (np.array([inputs[i][k] for i in idx]) for k in (1, 2))
        L, M, B = (np.array([inputs[i][k] for i in idx]) for k in (3, 4, 5))
        try:
            with np.errstate(all="ignore"):
                MP, MQ = mods[N].bt_step(P, Q, L, M, B, errors="mask")
            bad = np.ma.getmaskarray(MP).any(-1)
            for k, i in enumerate(idx):
                out["emitted"][i] = "masked" if bad[k] else np.concatenate([MP[k].data, MQ[k].data])
        except Exception as err:  # noqa: BLE001 -- an untyped error is what the fuzz looks for
            for i in idx:
                out["emitted"][i] = "UNTYPED %s: %s" % (type(err).__name__, err)
        for i in idx if N in csteps else ():
            _, p, q, lam0, mu, b = inputs[i]
            rc, got = csteps[N](p, q, lam0, mu, b)
            out["C"][i] = np.array(got) if rc == 0 else ("status %d" % rc if rc in C_REFUSALS else "UNTYPED %d" % rc)
    return out


def _emitted_ok(v, ref, p, q, lam0, mu, b, kappa, full):
    """``(how, why)``: the emitted code's documented bound ``16 eps S`` (docs/codegen.md).  Within ``16 eps |f|``
    per component it holds at once (``S >= |f|``, how = "f"); ``full``: ``S`` by forward differences
    (test_codegen_edges.judge_state, ~0.4 s a state, how = "S"); else within the conditioning bound of
    :func:`_bound` (how = "kappa"), and beyond it ``S`` decides."""
    from test_codegen_edges import judge_state

    with mp.workdps(40):
        if all(abs(mp.mpf(float(g)) - r) <= 16 * EPS * abs(r) for g, r in zip(v, ref)):
            return "f", None
    if not full and _error(v, ref, p, q, lam0, mu) <= _bound(p, q, kappa):
        return "kappa", None
    return "S", judge_state([float(x) for x in v], list(p), list(q), lam0, mu, b, True, ref)


def _near_boundary(p, q, lam0, mu, b, traces, info=None, within=1e-6):
    """True within ``within`` of the boundary of existence: ``(|t_i| - 2) / |t_i|`` or ``Etilde_j / E_j`` (the
    literal map at 40 + guard digits, ``info`` of its step where already computed; real parts) in
    ``(-within, within)``; ``traces``: the 40-digit literal traces."""
    with mp.workdps(40):
        if min(abs((abs(x) - 2) / x) for x in traces) < within:
            return True
    with mp.workdps(40 + literal_guard(p, traces)):
        if info is None:
            info = literal_step(_mpv(p), _mpv(q), mp.mpf(lam0), mp.mpf(mu), b)[2]
        return min(abs(mp.re(et / e)) for et, e in zip(info["E_new"], info["E"])) < within


def _no_map_by_traces(traces):
    """True where the literal traces at 40 digits decide that no real map exists (``|t| <= 2`` or opposite
    signs); False where ``Etilde_j`` must decide."""
    return min(abs(x) for x in traces) <= 2 or traces[0] * traces[1] < 0


def _freeze(x):
    """A dictionary key for an argument of the escalation, exact to the bit; ``None`` if there is none."""
    if isinstance(x, np.ndarray):
        return ("a", x.dtype.str, x.shape, x.tobytes())
    if isinstance(x, float):
        return ("f", x.hex())
    if isinstance(x, (tuple, list)):
        items = tuple(_freeze(v) for v in x)
        return None if None in items else ("t", items)
    if isinstance(x, (int, str, np.integer, np.floating)):
        return (type(x).__name__, repr(x))
    return None


@contextlib.contextmanager
def shared_escalations():
    """Within the block, ``symbt.numeric``'s escalation of one ill-conditioned state (``rows._mp_verdict``: the
    mpmath step at a given precision of the exact binary input) is computed once per distinct argument list
    and its result handed to every route that asks again -- the fused kernel, the block kernel, the numpy
    route, the orbits and ``run_batch``'s reruns each escalate the same states.  The escalation is a pure
    function of its arguments (the key holds every one of them, bit for bit: a route that passes a different
    shift, precision or state gets its own computation), so every route returns what it would without the
    memo; it only saves the repeats.  Yields the memo (for counting); a no-op if the function is gone."""
    try:
        from symbt.numeric.float64 import rows
        orig = rows._mp_verdict
    except (ImportError, AttributeError):
        yield None
        return
    memo = {}

    def verdict(*args, **kw):
        key = _freeze((args, sorted(kw.items())))
        if key is None:
            return orig(*args, **kw)
        if key not in memo:
            memo[key] = orig(*args, **kw)
        st, vals = memo[key]
        return st, list(vals)

    rows._mp_verdict = verdict
    try:
        yield memo
    finally:
        rows._mp_verdict = orig


def deep_chunk(seed, count, mods, csteps):
    """One chunk of the deep run: ``(stats, failures)``, every route of the module docstring sampled as said
    at :data:`SUB`, :data:`MP_SUB`; the reference (literal map, 40 + guard digits; 60 where ``kappa > 1e10``)
    is computed once per input and judges every route."""
    with shared_escalations():
        return _deep_chunk(generate(seed, count), mods, csteps)


def _deep_chunk(inputs, mods, csteps):
    res = {n: {} for n in (*SINGLE_ROUTES, *BATCH_ROUTES, *MP_BACKENDS)}
    for i, (_k, p, q, lam0, mu, b) in enumerate(inputs):
        names = list(SINGLE_ROUTES) if i % SUB == 0 else list(DEEP_SINGLE)
        fns = [(n, SINGLE_ROUTES[n]) for n in names]
        fns += [(n, _mp_route(n)) for n in (MP_BACKENDS if i % MP_SUB == 0 else ())]
        for name, fn in fns:
            try:
                res[name][i] = fn(p, q, lam0, mu, b)
            except Exception as err:  # noqa: BLE001
                res[name][i] = "UNTYPED %s: %s" % (type(err).__name__, err)
    for N in NS:
        for b in (1, -1):
            idx = [i for i, x in enumerate(inputs) if x[1].size == N and x[5] == b]
            for name, fn in BATCH_ROUTES.items():
                sub = 1 if name in DEEP_BATCH else ENSEMBLE_SUB if name == "ensemble" else SUB
                sel = [i for i in idx if i % sub == 0]
                if not sel:
                    continue
                P, Q, L, M = (np.array([inputs[i][k] for i in sel]) for k in (1, 2, 3, 4))
                try:
                    vals = run_batch(fn, P, Q, L, M, b)
                except Exception as err:  # noqa: BLE001
                    vals = ["UNTYPED %s: %s" % (type(err).__name__, err)] * len(sel)
                res[name].update(zip(sel, vals))
    if mods:
        res.update(_emitted_results(inputs, mods, csteps))
    stats = {"inputs": len(inputs), "states": 0, "no_map": 0, "undecided": 0, "refused_existing": 0,
             "route_states": 0, "route_typed": 0, "emitted_f": 0, "emitted_kappa": 0, "emitted_S": 0,
             "emitted_boundary": 0}
    failures = []
    for i, (kind, p, q, lam0, mu, b) in enumerate(inputs):
        got = {n: r[i] for n, r in res.items() if i in r}
        case = (kind, list(p), list(q), lam0, mu, b)
        for n, v in got.items():
            if isinstance(v, str) and v.startswith("UNTYPED"):
                failures.append((n, "untyped error", v, case))
        states = {n: v for n, v in got.items() if not isinstance(v, str)}
        stats["route_states"] += len(states)
        stats["route_typed"] += len(got) - len(states)
        traces = literal_traces(p, q, lam0, mu)       # 40 digits, shared by every judge below
        if not states and _no_map_by_traces(traces):
            stats["no_map"] += 1              # every route refused, and the traces alone say no map exists
            continue
        kt = trace_kappa_hp(p, q, lam0, mu, traces)
        kappa = kappa_hp(p, q, lam0, mu, b, kt, values=True, traces=traces) if states else None
        ref = kappa[1] if kappa and kappa[0] <= 1e10 and i % 50 else literal(p, q, lam0, mu, b, traces)
        if ref == "undecided":
            stats["undecided"] += 1
            continue
        exists = isinstance(ref, list)
        stats["states" if exists else "no_map"] += 1
        stats["refused_existing"] += exists and len(states) < len(got)
        for n, v in got.items() if exists else ():
            if isinstance(v, str):        # a typed refusal where the map exists, by route and error
                key = "refused %s %s" % (n, v.split(":")[0])
                stats[key] = stats.get(key, 0) + 1
        k = kt if kappa is None else kappa[0]
        near = None                           # _near_boundary, computed once per input where asked
        for n, v in states.items():
            if not exists and n in ("emitted", "C") and near is None:
                near = _near_boundary(p, q, lam0, mu, b, traces, kappa[2] if kappa else None)
            if not exists and n in ("emitted", "C") and near:
                stats["emitted_boundary"] += 1   # docs/codegen.md: within 1e-6 of the boundary either answer
            elif not exists:
                failures.append((n, "finite state without a real map", None, case))
            elif n in ("emitted", "C"):
                how, why = _emitted_ok(v, ref, p, q, lam0, mu, b, k, full=i % SUB == 0)
                stats["emitted_" + how] += 1
                if why:
                    failures.append((n, "beyond 16 eps S", why, case))
            else:
                eps = 2.0 ** -mp.mpf(103) if n in MP_BACKENDS else EPS
                err, bound = _error(v, ref, p, q, lam0, mu), _bound(p, q, k) * float(eps / EPS)
                if not err <= bound:
                    failures.append((n, "beyond bound", "error %.3g > bound %.3g (kappa %.3g)" % (err, bound, k),
                                     case))
    return stats, failures


def deep_run(count, budget, seed, chunk=500, emitted=True, tmp=None, log=print):
    """Seeded chunks until ``count`` inputs or ``budget`` seconds (checked between chunks; a chunk of 500
    takes ~1-4 min on one core): ``(totals, failures, seconds)``."""
    import pathlib
    import tempfile

    mods, csteps = _emitted_routes(pathlib.Path(tmp or tempfile.mkdtemp())) if emitted else ({}, {})
    t0 = time.perf_counter()
    total, failures, k = {}, [], 0
    while total.get("inputs", 0) < count and time.perf_counter() - t0 < budget:
        stats, fails = deep_chunk(seed * 100003 + k, min(chunk, count - total.get("inputs", 0)), mods, csteps)
        for key, v in stats.items():
            total[key] = total.get(key, 0) + v
        failures += fails
        k += 1
        for fail in fails:
            log("FAIL %d %r" % (k, fail))
        log("fuzz deep run: chunk %d, %s, failures %d, %.0f s" % (k, total, len(failures),
                                                                  time.perf_counter() - t0))
    return total, failures, time.perf_counter() - t0


@pytest.mark.deep
@pytest.mark.skipif(not os.environ.get("SYMBT_FUZZ_DEEP"), reason="1e5 inputs: set SYMBT_FUZZ_DEEP=1")
def test_fuzz_deep_run(tmp_path):
    """``SYMBT_FUZZ_COUNT`` inputs (default 1e5) in seeded chunks, or until ``SYMBT_FUZZ_BUDGET`` seconds.
    symbt.numeric's routes: 0 failures.  The emitted forms' failures (no ill-conditioning guard, see
    test_codegen_edges.ILLCOND3 and docs/fuzz.md) make the test an xfail until that guard exists."""
    total, failures, _ = deep_run(int(os.environ.get("SYMBT_FUZZ_COUNT", "100000")),
                                  float(os.environ.get("SYMBT_FUZZ_BUDGET", "36000")),
                                  int(os.environ.get("SYMBT_FUZZ_SEED", "26")), tmp=tmp_path,
                                  log=lambda m: print(m, flush=True))
    numeric = [f for f in failures if f[0] not in ("emitted", "C")]
    assert not numeric, numeric[:5]
    if failures:
        pytest.xfail("%d emitted wrong results (the deep run of docs/fuzz.md predates the emitted forms' "
                     "ill-conditioning guard and has not been repeated)" % len(failures))


@pytest.mark.slow
def test_deep_chunk_small(tmp_path):
    """The deep run's machinery on 64 inputs (every route, the emitted modules and C): 0 failures."""
    total, failures, _ = deep_run(64, 600, seed=5, chunk=64, tmp=tmp_path, log=lambda m: None)
    assert not failures, failures[:3]
    # a reach floor, not an accuracy bound: the 64 near-edge inputs give ~100 returned states over the routes
    # (fewer since the emitted forms refuse ill-conditioned states, as symbt.numeric's float64 kernels do)
    assert total["inputs"] == 64 and total["route_states"] >= 90 and total["states"] + total["no_map"] >= 60




@pytest.mark.slow
def test_deep_judge_catches_planted_errors(monkeypatch):
    """The judge is not vacuous: a route that returns the real part of the complex continuation (a finite state
    where no real map exists) and p~ off by 1e-6 relative is flagged for both (symbt.numeric routes only; 1e-9
    is not flagged on these 32 inputs: near band edges and far apart kappa * rho exceeds 1e5)."""
    def planted(p, q, lam0, mu, b):
        try:
            a, c = bt_step(p, q, lam0, mu, branch=b, allow_complex=True)
        except TYPED as err:
            return type(err).__name__
        return np.concatenate([np.real(a) * (1 + 1e-6), np.real(c)])

    monkeypatch.setitem(SINGLE_ROUTES, "kernel", planted)
    stats, failures = deep_chunk(7, 32, {}, {})
    whys = {why for route, why, _, _ in failures if route == "kernel"}
    assert whys == {"finite state without a real map", "beyond bound"}, (whys, stats)
    assert all(route == "kernel" for route, _, _, _ in failures)
