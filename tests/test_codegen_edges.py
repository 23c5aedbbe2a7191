"""Emitted code at the edges (issue 21): the committed closed forms ``symbt.generated.toda2``/``toda3``, the
loop (transfer-matrix) form that ``symbt codegen`` emits for N >= 4, and their C targets never return a wrong
state.

Every case is judged against ``symbt.reference.literal.reference_step`` (the paper's literal map at 50
digits plus guard digits; complex where no real map exists), never against the code under test:

* a returned state must exist (the reference is real) and be accurate to the documented bound
  ``|f64 - ref| <= 16 eps S`` per component, ``S = |f| + sum_i max(|x_i|, 1) |df/dx_i|`` (docs/codegen.md),
  the derivatives by forward differences (relative step 1e-9) of ``symbt.numeric``'s float64 step -- an
  implementation that shares nothing with the emitted file -- or of the reference where that step
  raises at a perturbed point.  At the few states where ``S`` misses the conditioning of the read-out
  ``p~_j = p_j + eta_j - eta_{j+1}`` (eq. ``imptransf``: its terms round at their own scale even where
  they cancel), ``S`` of ``p~_j`` is raised to ``|p_j| + |eta_j| + |eta_{j+1}|`` from the paper's literal
  step (counted in ``BEYOND_S``);
* ``NoRealMapError`` / a non-zero C status ``1``, ``2`` (no real map) must agree with the reference, except
  within float64's resolution of the boundary of existence (the reference's ``min_j Etilde_j / E_j`` or
  ``(|tr L(lam_i)| - 2) / |tr L(lam_i)|`` below ``BOUNDARY``, where the float64 guards themselves carry
  errors of ``eps`` times the trace's condition);
* ``NumericRangeError`` / status ``3`` is a documented result (counted, never a wrong state);
* anything else (another exception, a finite wrong state, a masked batch element that disagrees with
  the single-state call) fails.

The fuzz samples seeded states near band edges, across spectral gaps and at large ``|q_i - q_j|``; the
``slow`` variant runs 1e5 inputs.
"""
from __future__ import annotations

import ctypes
import importlib.util
import math
import shutil
import subprocess

import mpmath as mp
import numpy as np
import pytest

import symbt.codegen as cg
from symbt.generated import toda2, toda3
from symbt.numeric import bt_step as numeric_step
from symbt.reference.literal import literal_step, literal_trace, reference_step

EPS = 2.0 ** -52
TOL_ULPS = 16
BOUNDARY = 1e-6
#: errors beyond 16 eps S accepted because symbt.numeric's float64 step is as far off (see judge_state)
BEYOND_S: list[float] = []
MODULES = {2: toda2, 3: toda3}
CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
OK, TRACE, POSITIVITY, RANGE, INVALID, ILL_CONDITIONED = 0, 1, 2, 3, 4, 5

#: issue 21: the emitted closed form lost p~_2, p~_3 (relative error 0.31) at large |q_i - q_j|
FAR = ([-6.670844734995089, 6.749416383837502, 9.945390979638757],
       [999.5531082492741, 351.51762457052644, 699.0759141727409], -179.0, 155.0, -1)
#: issue 21: tr L(lam1) ~ +1.2e8, tr L(lam2) ~ -9.1e7 (different gaps): no real map, for either branch
GAPS = [([0.0, 0.0], [0.0, 19.0], math.exp(9.5), 0.3 * math.exp(9.5)),
        ([0.0, 0.0], [0.0, 200.0], 2.5e43, 0.5e43)]
#: issue 21 (claim shipped.c.n5): the loop form's C returned q~_1 = q_1 with status OK (the monodromy at
#: lambda_1 ~ 1e274 overflowed tr^2 - 4: an infinite slope read out as 2 mu/d = 0); its Python refused
FAR5 = ([-7.671527, 4.302277, 6.876684, 7.203808, -0.57681],
        [374.986031, 363.444323, 978.299961, 897.010457, 888.548403], 110.258, 101.361, 1)
LOOP_NS = (4, 5, 8)
#: the N = 8 loop-form outlier (deep fuzz, seed 4008): q~_1 was 240 eps*S off (S = 1.7).  The root u_1 read
#: off the monodromy carried ~2e-11 relative error: at lambda_1 the entries of |m_8| ... |m_1| exceed those of
#: M by ~2e8 (kappa of the trace), and d_1 = w_1 - u_1 passed it to log1p(-2 mu/d_1).  One turn of the
#: transport refines the root (loop_template._turn_forward/_turn_backward, the C template's pass 0)
OUTLIER8 = ([91.12139006057448, 59.37312396266917, 0.020563195771502483, 82.94418461018756, -22.432634756401722,
             27.498263964984055, -93.60599615177755, -51.82715841931297],
            [0.03793090836411436, 0.15022687466823118, 0.8190370606420057, 0.08917174918052212,
             0.9034666164359402, 0.6173843857447018, 0.733373705394074, 0.47444817791041294],
            22.72876567344855, -0.25968054990185685, 1)


# --------------------------------------------------------------------------- the reference and the bound

def reference(p, q, lam0, mu, b, dps=50):
    """``(exists, values, margin)``: the 50-digit step (p~ + q~), and how far the state is from the boundary
    of existence (min of ``Etilde_j/E_j`` and ``(|tr_i| - 2)/|tr_i|``; negative where no real map)."""
    with mp.workdps(dps):
        try:
            rp, rq = reference_step(p, q, lam0, mu, branch=b)
        except ZeroDivisionError:   # an exact zero in the literal transport: far more guard digits
            rp, rq = reference_step(p, q, lam0, mu, branch=b, guard=2000)
        vals = rp + rq
        tr = [literal_trace(mp.mpf(lam0) + s * mp.mpf(mu), p, q) for s in (1, -1)]
        margin = min((abs(t) - 2) / abs(t) for t in tr)
        exists = all(isinstance(v, mp.mpf) for v in vals) and margin > 0
        if exists:
            margin = min([margin] + [mp.exp(a - mp.mpf(x)) for a, x in zip(rq, q)])
        return exists, vals, float(margin) if exists else -1.0


def _numeric(x, N):
    p, q, lam0, mu, b = x[:N], x[N:2 * N], x[2 * N], x[2 * N + 1], x[2 * N + 2]
    pt, qt = numeric_step(np.array(p), np.array(q), lam0, mu, branch=int(b))
    return [float(v) for v in list(pt) + list(qt)]


def _ref_values(x, N):
    ok, vals, _ = reference(x[:N], x[N:2 * N], x[2 * N], x[2 * N + 1], int(x[2 * N + 2]), dps=30)
    if not ok:
        raise ArithmeticError("no real map at a perturbed point")
    return [float(v) for v in vals]


def condition_scale(p, q, lam0, mu, b, ref):
    """``S_k = |f_k| + sum_i max(|x_i|, 1) |df_k/dx_i|`` by forward differences (step 1e-9 max(|x_i|, 1))."""
    N = len(p)
    x = list(p) + list(q) + [lam0, mu, b]
    S = [abs(float(v)) for v in ref]
    for f in (_numeric, _ref_values):
        try:
            f0 = f(x, N)
            grads = []
            for i in range(2 * N + 2):
                h = 1e-9 * max(abs(x[i]), 1.0)
                xh = list(x)
                xh[i] = x[i] + h
                grads.append((max(abs(x[i]), 1.0), [(a - c) / h for a, c in zip(f(xh, N), f0)]))
        except (ValueError, OverflowError, ArithmeticError):
            continue      # symbt.numeric raises at a perturbed point: take the reference's differences
        return [s + sum(w * abs(g[k]) for w, g in grads) for k, s in enumerate(S)]
    return [math.inf] * len(S)


def judge_state(got, p, q, lam0, mu, b, exists, ref):
    """None if the returned state ``got`` (p~ + q~) is right, else why not."""
    if not exists:
        return "a finite state where no real map exists"
    with mp.workdps(50):   # S >= |f|: within 16 eps |f| the bound holds without the differences
        if all(abs(mp.mpf(g) - r) <= TOL_ULPS * EPS * abs(r) for g, r in zip(got, ref)):
            return None
    S = condition_scale(p, q, lam0, mu, b, ref)

    def error(vals):
        with mp.workdps(50):
            return max(float(abs(mp.mpf(g) - r) / (EPS * max(s, 1e-300))) for g, r, s in zip(vals, ref, S))
    err = error(got)
    if err <= TOL_ULPS:
        return None
    # S misses the conditioning of the read-out at a few states: p~_j = p_j + eta_j - eta_{j+1} (eq. imptransf)
    # rounds at the scale of its terms even where they cancel; that scale, from the paper's literal step
    N = len(p)
    with mp.workdps(30):    # the literal transport loses ~2 log10|tr| digits
        big = max([mp.mpf(10)] + [abs(literal_trace(mp.mpf(lam0) + s * mp.mpf(mu), p, q)) for s in (1, -1)])
    with mp.workdps(60 + 2 * int(mp.log10(big))):
        eta = literal_step(p, q, lam0, mu, b)[2]["eta"]
        terms = [abs(mp.mpf(p[j])) + abs(eta[j]) + abs(eta[(j + 1) % N]) for j in range(N)]
    S[:N] = [max(s, float(t)) for s, t in zip(S[:N], terms)]
    if error(got) <= TOL_ULPS:
        BEYOND_S.append(err)
        return None
    lib = error(_numeric(list(p) + list(q) + [lam0, mu, b], N))
    return (f"error {err:.3g} eps*S > {TOL_ULPS} (symbt.numeric: {lib:.3g} with the read-out's scale; got {got}, "
            f"reference {[mp.nstr(r, 17) for r in ref]})")


def judge_error(kind, exists, margin):
    """None if raising ``kind`` ('no-map', 'range', or anything else) is right for the state."""
    if kind == "range":
        return None
    if kind == "no-map":
        ok = not exists or margin < BOUNDARY
        return None if ok else f"no real map reported, but it exists (margin {margin:.3g})"
    return f"untyped error {kind}"


# --------------------------------------------------------------------------- the two cases of issue 21

def test_far_apart_positions_give_the_50_digit_step_in_numpy_and_mpmath():
    p, q, lam0, mu, b = FAR
    exists, ref, margin = reference(p, q, lam0, mu, b)
    assert exists and abs(float(ref[1]) - 316.7494163838375) < 1e-9        # the premise (p~_2 = 316.75)
    pt, qt = toda3.bt_step(p, q, lam0, mu, b)
    assert judge_state(list(pt) + list(qt), p, q, lam0, mu, b, exists, ref) is None
    with mp.workdps(50):
        mpt, mqt = toda3.bt_step_mp(p, q, lam0, mu, b)
        S = condition_scale(p, q, lam0, mu, b, ref)
        assert max(abs(a - r) / s for a, r, s in zip(mpt + mqt, ref, S)) <= mp.mpf(10) ** -45
    # the batch (errors='mask') gives the same numbers, unmasked
    P, Q = toda3.bt_step(np.array([p, p]), np.array([q, q]), lam0, mu, b, errors="mask")
    assert not np.ma.is_masked(P) and np.array_equal(np.asarray(P[1]), pt) and np.array_equal(np.asarray(Q[0]), qt)


@pytest.mark.parametrize("case", range(len(GAPS)))
@pytest.mark.parametrize("b", (1, -1))
def test_traces_of_opposite_signs_raise_no_real_map(case, b):
    p, q, lam0, mu = GAPS[case]
    exists, _, _ = reference(p, q, lam0, mu, b)
    with mp.workdps(30):
        t1, t2 = (literal_trace(mp.mpf(lam0) + s * mp.mpf(mu), p, q) for s in (1, -1))
    assert not exists and t1 * t2 < 0                                       # the premise
    with pytest.raises(toda2.NoRealMapError) as exc:
        toda2.bt_step(p, q, lam0, mu, b)
    assert exc.value.condition == "positivity"
    with pytest.raises(toda2.NoRealMapError):
        toda2.bt_step_mp(p, q, lam0, mu, b)
    P, Q = toda2.bt_step(np.array([p, [0.0, 0.5]]), np.array([q, [0.0, 0.1]]), lam0, mu, b, errors="mask")
    assert P.mask[0].all() and Q.mask[0].all()


# --------------------------------------------------------------------------- the C target

class CStep:
    """``toda{N}_bt_step`` of a compiled ``toda{N}.c``, through ctypes."""

    def __init__(self, so, N):
        self.N = N
        D, P = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
        self.fn = getattr(ctypes.CDLL(str(so)), f"toda{N}_bt_step")
        self.fn.argtypes = [P, P, D, D, ctypes.c_int, P, P]
        self.fn.restype = ctypes.c_int

    def __call__(self, p, q, lam0, mu, b):
        arr = ctypes.c_double * self.N
        pt, qt = arr(*[7.0] * self.N), arr(*[7.0] * self.N)
        rc = self.fn(arr(*p), arr(*q), float(lam0), float(mu), int(b), pt, qt)
        return rc, list(pt) + list(qt)


@pytest.fixture(scope="module")
def c_steps(tmp_path_factory):
    if CC is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    out = tmp_path_factory.mktemp("c-edges")
    assert cg.main(["--target", "c", "--n", "2", "3", "--out", str(out), "-q"]) == 0
    steps = {}
    for N in (2, 3):
        so = out / f"libtoda{N}.so"
        r = subprocess.run([CC, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC",
                            "-o", str(so), str(out / f"toda{N}.c"), "-lm"], capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        steps[N] = CStep(so, N)
    return steps


#: found by the deep fuzz (tests/test_fuzz_numeric.py, docs/fuzz.md): at lambda ~ 1.2e9 the N = 3 traces
#: (~ -5.6e12 and +2.4e24; 1.2e13 and 2.1e13) are the cancelled remainders of terms ~ lambda**3 ~ 1.8e27, so the
#: trace's condition T |t| / |t**2 - 4| ~ 1e14 > 1/eps: float64 cannot decide the signs or the slopes.
#: symbt.numeric refuses its float64 result there (status ILLCOND) and recomputes at higher precision; the
#: emitted forms have no such guard and return a finite state (a wrong one; the first has no real map)
ILLCOND3 = [([0.4385582671715961, 1.88679362543912, -4.372305086454735],
             [5.429660216961235, 30.9895385043942, -36.419198721355436], 1223226771.5601768, -401869.06804025173, -1),
            ([0.4385582671715961, 1.88679362543912, -4.372305086454735],
             [5.429660216961235, 30.9895385043942, -36.419198721355436], 1222824902.492144, -1.5497207641601562e-06, 1)]


@pytest.mark.parametrize("case", range(len(ILLCOND3)))
def test_emitted_refuses_or_is_right_at_ill_conditioned_traces(case):
    p, q, lam0, mu, b = ILLCOND3[case]
    exists, ref, margin = reference(p, q, lam0, mu, b)
    kind, got = _python_outcome(toda3, p, q, lam0, mu, b)
    why = judge_state(got, p, q, lam0, mu, b, exists, ref) if kind == "state" else judge_error(kind, exists, margin)
    assert why is None, why


def test_c_far_apart_positions_and_opposite_traces(c_steps):
    p, q, lam0, mu, b = FAR
    exists, ref, _ = reference(p, q, lam0, mu, b)
    rc, got = c_steps[3](p, q, lam0, mu, b)
    assert rc == OK and judge_state(got, p, q, lam0, mu, b, exists, ref) is None
    for p, q, lam0, mu in GAPS:
        for b in (1, -1):
            rc, got = c_steps[2](p, q, lam0, mu, b)
            assert rc == POSITIVITY and got == [7.0] * 4                   # outputs untouched on failure


# --------------------------------------------------------------------------- the fuzz

def _band_edges(p, q):
    """Real roots of tr L(lambda) = +-2 (float64, from the 30-digit invariants), sorted; [] if out of range."""
    from symbt.numeric import invariants

    with mp.workdps(30):
        H = invariants([mp.mpf(v) for v in p], [mp.mpf(v) for v in q])
    coef = [1.0] + [float(h) for h in reversed(H)]
    if not all(math.isfinite(c) for c in coef):
        return []
    edges = []
    for s in (2.0, -2.0):
        c = list(coef)
        c[-1] -= s
        edges += [float(r.real) for r in np.roots(c) if abs(r.imag) <= 1e-9 * max(1.0, abs(r))]
    return sorted(edges)


def sample(N, n, seed):
    """``n`` seeded inputs ``(p, q, lam0, mu, branch)``: a quarter each generic, near a band edge, across (or
    within) spectral gaps, and at large |q_i - q_j| (up to ~1000: past 700 the float64 range ends)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        kind = len(out) % 4
        p = list(rng.uniform(-10, 10, N) * 10 ** rng.uniform(-1, 1))
        spread = 10 ** rng.uniform(2, 3) if kind == 3 else rng.uniform(0, 6)
        q = list(rng.uniform(0, spread, N))
        b = int(rng.choice((1, -1)))
        edges = _band_edges(p, q) if kind in (1, 2) else []
        if kind == 1 and edges:
            e = float(rng.choice(edges))
            l1 = e + rng.choice((-1, 1)) * 10 ** rng.uniform(-12, -1) * max(1.0, abs(e))
            l2 = float(rng.uniform(min(edges) - 10, max(edges) + 10))
        elif kind == 2 and len(edges) >= 2:
            gaps = [(edges[0] - 20, edges[0])] + [(edges[k], edges[k + 1]) for k in range(1, len(edges) - 1, 2)]
            gaps.append((edges[-1], edges[-1] + 20))
            l1, l2 = (float(rng.uniform(*gaps[rng.integers(len(gaps))])) for _ in range(2))
        else:
            scale = 10 ** rng.uniform(0, 2)
            l1, l2 = rng.uniform(-scale, scale, 2)
        out.append((p, q, (l1 + l2) / 2, (l1 - l2) / 2, b))
    return out


def _python_outcome(mod, p, q, lam0, mu, b):
    try:
        pt, qt = mod.bt_step(p, q, lam0, mu, b)
    except mod.NoRealMapError:
        return "no-map", None
    except mod.NumericRangeError:
        return "range", None
    except Exception as exc:  # noqa: BLE001 -- an untyped error is what the fuzz looks for
        return f"{type(exc).__name__}: {exc}", None
    return "state", [float(v) for v in list(pt) + list(qt)]


def fuzz(N, n, seed, c_step=None, mod=None):
    """Run ``n`` sampled inputs through the emitted module (``mod``, default the committed ``toda{N}``; single,
    and masked batch) and the C step; returns ``(problems, counts)``."""
    mod, xs = mod or MODULES[N], sample(N, n, seed)
    problems, counts = [], {}
    P, Q = (np.array([x[i] for x in xs]) for i in (0, 1))
    L0, MU, B = (np.array([x[i] for x in xs]) for i in (2, 3, 4))
    with np.errstate(all="ignore"):
        MP, MQ = mod.bt_step(P, Q, L0, MU, B, errors="mask")
    for i, (p, q, lam0, mu, b) in enumerate(xs):
        exists, ref, margin = reference(p, q, lam0, mu, b)
        kind, got = _python_outcome(mod, p, q, lam0, mu, b)
        counts[kind] = counts.get(kind, 0) + 1
        why = judge_state(got, p, q, lam0, mu, b, exists, ref) if kind == "state" else judge_error(kind, exists, margin)
        masked = bool(np.ma.getmaskarray(MP)[i].any())
        if masked != (kind != "state"):
            why = why or f"the masked batch disagrees with the single call ({kind})"
        elif not masked:     # the batch may differ from the single call in the last bits (numpy's SIMD loops)
            bwhy = judge_state([float(v) for v in list(MP[i]) + list(MQ[i])], p, q, lam0, mu, b, exists, ref)
            why = why or (f"batch: {bwhy}" if bwhy else None)
        if c_step is not None:
            rc, cgot = c_step(p, q, lam0, mu, b)
            ckind = {OK: "state", TRACE: "no-map", POSITIVITY: "no-map", RANGE: "range", ILL_CONDITIONED: "range"}.get(
                rc, f"status {rc}")
            cwhy = (judge_state(cgot, p, q, lam0, mu, b, exists, ref) if ckind == "state"
                    else judge_error(ckind, exists, margin))
            why = why or (f"C: {cwhy}" if cwhy else None)
        if why:
            problems.append((why, (p, q, lam0, mu, b)))
    return problems, counts


@pytest.mark.parametrize("N", (2, 3))
def test_fuzz_emitted_step_never_wrong(N, c_steps):
    problems, counts = fuzz(N, 1500, seed=21 + N, c_step=c_steps[N])
    assert not problems, (len(problems), problems[:3], counts)
    assert counts.get("state", 0) > 300 and counts.get("no-map", 0) > 100, counts   # the sampler reaches both


@pytest.mark.slow
@pytest.mark.parametrize("N", (2, 3))
def test_fuzz_emitted_step_never_wrong_deep(N, c_steps):
    problems, counts = fuzz(N, 50_000, seed=2100 + N, c_step=c_steps[N])
    assert not problems, (len(problems), problems[:3], counts)


# --------------------------------------------------------------------------- the loop form (N >= 4)

@pytest.fixture(scope="module")
def loop_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("loop-edges")
    assert cg.main(["--n", *map(str, LOOP_NS), "--out", str(out), "-q"]) == 0
    assert cg.main(["--target", "c", "--n", *map(str, LOOP_NS), "--out", str(out), "-q"]) == 0
    return out


@pytest.fixture(scope="module")
def loop_modules(loop_dir):
    mods = {}
    for N in LOOP_NS:
        spec = importlib.util.spec_from_file_location(f"toda{N}_edges", loop_dir / f"toda{N}.py")
        mods[N] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mods[N])
        assert mods[N].FORM == "transfer-matrix"
    return mods


def _compile(CCpath, src, so):
    r = subprocess.run([CCpath, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC",
                        "-o", str(so), str(src), "-lm"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr


@pytest.fixture(scope="module")
def c_loop_steps(loop_dir):
    """The compiled loop-form C steps; empty without a C compiler (the tests that need one skip)."""
    steps = {}
    if CC is not None:
        for N in LOOP_NS:
            _compile(CC, loop_dir / f"toda{N}.c", loop_dir / f"libtoda{N}.so")
            steps[N] = CStep(loop_dir / f"libtoda{N}.so", N)
    return steps


def test_loop_form_far_apart_positions_give_the_50_digit_step(loop_modules):
    p, q, lam0, mu, b = FAR5
    exists, ref, _ = reference(p, q, lam0, mu, b)
    assert exists and abs(float(ref[5]) - 380.10056658347552) < 1e-9      # the premise (q~_1 - q_1 = 5.11)
    mod = loop_modules[5]
    pt, qt = mod.bt_step(p, q, lam0, mu, b)
    assert judge_state(list(pt) + list(qt), p, q, lam0, mu, b, exists, ref) is None
    with mp.workdps(50):
        mpt, mqt = mod.bt_step_mp(p, q, lam0, mu, b)
        S = condition_scale(p, q, lam0, mu, b, ref)
        assert max(abs(a - r) / s for a, r, s in zip(mpt + mqt, ref, S)) <= mp.mpf(10) ** -45
    P, Q = mod.bt_step(np.array([p, p]), np.array([q, q]), lam0, mu, b, errors="mask")
    assert not np.ma.is_masked(P) and np.array_equal(np.asarray(P[1]), pt) and np.array_equal(np.asarray(Q[0]), qt)


def test_c_loop_form_far_apart_positions(c_loop_steps):
    if not c_loop_steps:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    p, q, lam0, mu, b = FAR5
    exists, ref, _ = reference(p, q, lam0, mu, b)
    rc, got = c_loop_steps[5](p, q, lam0, mu, b)
    assert rc == OK and judge_state(got, p, q, lam0, mu, b, exists, ref) is None


def test_loop_form_refuses_the_ill_conditioned_outlier(loop_modules, c_loop_steps):
    """The N = 8 outlier: a well-conditioned output (S of q~_1 = 1.7) behind an ill-conditioned monodromy.
    The one-turn refinement made it right (9e-14 off before); since the conditioning guard the emitted step
    refuses it, as symbt.numeric's float64 kernel does (it recomputes at higher precision)."""
    p, q, lam0, mu, b = OUTLIER8
    exists, ref, _ = reference(p, q, lam0, mu, b)
    assert exists
    with mp.workdps(40):          # the premise: the trace is ill-conditioned (T |t| / |t^2 - 4| ~ 2e8)
        t1 = literal_trace(mp.mpf(lam0) + mp.mpf(mu), p, q)
        assert 9e5 < t1 < 1e6
    with pytest.raises(loop_modules[8].IllConditionedError):
        loop_modules[8].bt_step(p, q, lam0, mu, b)
    pt, qt = numeric_step(p, q, lam0, mu, branch=b)          # symbt.numeric: recomputed, right
    assert judge_state(list(pt) + list(qt), p, q, lam0, mu, b, exists, ref) is None
    if c_loop_steps:
        assert c_loop_steps[8](p, q, lam0, mu, b)[0] == ILL_CONDITIONED


@pytest.mark.parametrize("N", LOOP_NS)
def test_fuzz_loop_form_never_wrong(N, loop_modules, c_loop_steps):
    """The loop form (numpy single and masked batch; C where a compiler is present) on 300 seeded inputs."""
    problems, counts = fuzz(N, 300, seed=40 + N, c_step=c_loop_steps.get(N), mod=loop_modules[N])
    assert not problems, (len(problems), problems[:3], counts)
    assert counts.get("state", 0) > 60 and counts.get("no-map", 0) > 20, counts   # the sampler reaches both


@pytest.mark.slow
@pytest.mark.parametrize("N", LOOP_NS)
def test_fuzz_loop_form_never_wrong_deep(N, loop_modules, c_loop_steps):
    problems, counts = fuzz(N, 10_000, seed=4000 + N, c_step=c_loop_steps.get(N), mod=loop_modules[N])
    assert not problems, (len(problems), problems[:3], counts)
