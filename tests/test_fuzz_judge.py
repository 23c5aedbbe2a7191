"""The deep fuzz's own machinery (tests/test_fuzz_deep.py), checked: what makes it cheaper changes no result, and
its judge of the emitted code is not vacuous.

* :func:`test_fuzz_numeric.shared_escalations` hands one route's escalation of an ill-conditioned state to the
  next route that asks for the same one: every route must return, bit for bit, what it returns without it;
* :func:`test_fuzz_deep.literal_scale` (``S`` of docs/codegen.md from the literal map's differences at high
  precision) must agree with ``S`` from float64 differences of ``symbt.numeric``
  (test_codegen_edges.condition_scale) -- two computations that share no code;
* the emitted judge passes a state ``4 eps S`` off and refuses one ``64 eps S`` off.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from test_codegen_edges import condition_scale
from test_fuzz_deep import _emitted_ok, literal_scale
from test_fuzz_numeric import (
    BATCH_ROUTES,
    EPS,
    SINGLE_ROUTES,
    _freeze,
    generate,
    literal,
    literal_traces,
    run_batch,
    shared_escalations,
)

#: a moderate N = 3 state with a real map (branch +1): the judge's planted-error test
STATE = (np.array([-1.0, 0.5, 0.3]), np.array([0.1, -0.2, 0.4]), 4.0, 0.5, 1)


def _every_route(inputs):
    out = []
    for _k, p, q, lam0, mu, b in inputs:
        out += [fn(p, q, lam0, mu, b) for fn in SINGLE_ROUTES.values()]
    for N in sorted({x[1].size for x in inputs}):
        for b in (1, -1):
            sel = [x for x in inputs if x[1].size == N and x[5] == b]
            if sel:
                P, Q, L, M = (np.array([x[k] for x in sel]) for k in (1, 2, 3, 4))
                out += [v for fn in BATCH_ROUTES.values() for v in run_batch(fn, P, Q, L, M, b)]
    return out


def _same(a, b):
    return a == b if isinstance(a, str) or isinstance(b, str) else np.array_equal(a, b)


def test_shared_escalations_change_nothing():
    """Every route returns the same bits with and without the shared escalation, on inputs that escalate."""
    inputs = [x for x in generate(11, 96) if x[1].size <= 6][:32]
    plain = _every_route(inputs)
    with shared_escalations() as memo:
        shared = _every_route(inputs)
        assert memo, "no input escalated: the test proves nothing"
    assert len(plain) == len(shared) and all(_same(a, b) for a, b in zip(plain, shared))
    assert sum(isinstance(v, np.ndarray) for v in plain) >= 20        # states returned, not only refusals


def test_shared_escalation_keys_are_exact():
    """The memo's key tells apart what a dictionary would confuse: -0.0 and 0.0, arrays of other shapes."""
    assert _freeze(0.0) != _freeze(-0.0)
    assert _freeze(np.array([0.0, 1.0])) != _freeze(np.array([-0.0, 1.0]))
    assert _freeze(np.zeros((1, 2))) != _freeze(np.zeros(2))
    assert _freeze((1.0, 2)) != _freeze((1, 2.0))
    assert _freeze(object()) is None


def _ref(state):
    p, q, lam0, mu, b = state
    ref = literal(p, q, lam0, mu, b)
    assert isinstance(ref, list)                                     # the premise: a real map
    return ref, literal_traces(p, q, lam0, mu)


def test_literal_scale_agrees_with_float_differences():
    """``S`` from the literal map at high precision and from float64 forward differences of symbt.numeric agree
    to the differences' own accuracy (step 1e-9: ~1e-7 relative), not more loosely."""
    p, q, lam0, mu, b = STATE
    ref, traces = _ref(STATE)
    S = literal_scale(p, q, lam0, mu, b, traces)
    S_fd = condition_scale(list(p), list(q), lam0, mu, b, ref)
    assert all(abs(a - c) <= 1e-5 * c for a, c in zip(S, S_fd)), (S, S_fd)
    assert all(a > abs(float(r)) for a, r in zip(S, ref))             # S > |f|: the derivatives count


def test_emitted_judge_catches_planted_errors():
    """A state 4 eps S off in q~_2 passes the emitted judge; 64 eps S off is refused (the documented 16)."""
    p, q, lam0, mu, b = STATE
    ref, traces = _ref(STATE)
    S = literal_scale(p, q, lam0, mu, b, traces)
    k = len(p) + 1                                                   # q~_2: the read-out's scale is not involved
    for ulps, wrong in ((4, False), (64, True)):
        with mp.workdps(40):
            v = [float(r) for r in ref]
            v[k] = float(ref[k] + ulps * EPS * S[k])
        how, why = _emitted_ok(np.array(v), ref, p, q, lam0, mu, b, lambda: S)
        assert (why is not None) == wrong, (ulps, how, why)


#: found by the deep run of docs/fuzz.md (seed 26, chunk 104, N = 3, branch -1, |lam| ~ 1e41 >> |p|): the emitted
#: closed form passed its conditioning guard (kappa 1.4e7 < KAPPA_MAX = 2**24) and returned q~_1 1.0e4 eps*S off
#: (S = 213 from the literal map's differences; absolute 4.8e-10): its root w_1, read off the monodromy at lam2,
#: carried the trace's cancellation (1e5); fixed by one turn of the transport in the contracting direction
#: (symbt.codegen.transport.turned)
FOUND_Q1 = (np.array([-5.434139772661011, -4.252599090135255, -1.632277238787376]),
            np.array([-74.50544965467114, -59.14641188582176, 133.6518615404929]),
            -3.730150628765109e+41, 3.608415983017036e+41, -1)


@pytest.fixture(scope="module")
def toda3_routes(tmp_path_factory):
    """The N = 3 emitted steps: the committed closed form, the transfer-matrix form emitted for N = 3 (the loop
    code of N >= 4) and the closed form's C step (where a C compiler is present)."""
    import shutil
    import subprocess
    import types

    from test_codegen_edges import CStep

    import symbt.codegen as cg
    from symbt.codegen import zullo
    from symbt.generated import toda3

    loop = types.ModuleType("toda3_loop")
    exec(compile(zullo.module_text(3, "transfer-matrix"), "toda3_loop", "exec"), loop.__dict__)
    routes = {"closed": lambda *a: np.concatenate(toda3.bt_step(*a)),
              "loop": lambda *a: np.concatenate(loop.bt_step(*a))}
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is not None:
        tmp = tmp_path_factory.mktemp("toda3c")
        assert cg.main(["--target", "c", "--n", "3", "--out", str(tmp), "-q"]) == 0
        subprocess.run([cc, "-std=c99", "-O2", "-shared", "-fPIC", "-o", str(tmp / "t3.so"), str(tmp / "toda3.c"),
                        "-lm"], check=True, capture_output=True, timeout=300)
        step = CStep(tmp / "t3.so", 3)

        def c_route(*a):
            rc, got = step(*a)
            assert rc == 0, rc                                       # a state, not a refusal (the premise)
            return np.array(got)
        routes["C"] = c_route
    return routes


def _errors_in_eps_S(case, got):
    p, q, lam0, mu, b = case
    ref, traces = _ref(case)
    S = literal_scale(p, q, lam0, mu, b, traces)
    with mp.workdps(40):
        return [float(abs(mp.mpf(float(g)) - r) / (EPS * s)) for g, r, s in zip(got, ref, S)]


@pytest.mark.parametrize("route", ["closed", "loop", "C"])
def test_emitted_toda3_within_16_eps_S_at_large_lambda(route, toda3_routes):
    """The emitted forms' documented bound (docs/codegen.md): every returned component within 16 eps S (S from
    the literal map's differences at high precision), in the closed form, the loop form and C alike."""
    if route not in toda3_routes:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    err = _errors_in_eps_S(FOUND_Q1, toda3_routes[route](*FOUND_Q1))
    assert max(err) <= 16, err


#: found by the deep run (seed 26, chunk 105, N = 3, branch -1, |lam| ~ 1e19): the emitted closed form returned
#: p~_1 = -403.957 where the map gives -3.70431495046972 (symbt.numeric: to the last bit): u_2/d_2 as u_2 * (1/d_2)
#: rounded to -1 + eps, and 2 mu (u_1/d_1 - u_2/d_2) cancelled two fractions near -1 times 2 mu = 3.6e18; fixed
#: by symbt.codegen.transport.read_out (2 mu (f_j g_{j+1} - f_{j+1} g_j), no cancelling fractions)
FOUND_P1 = (np.array([-3.7043149504697173, 0.9562990588216604, 3.32967789560084]),
            np.array([13.268371574482979, -50.489573470667146, 37.22120189618416]),
            9.318636959922506e+18, 1.8025784398195384e+18, -1)


@pytest.mark.parametrize("route", ["closed", "loop", "C"])
def test_emitted_toda3_readout_as_accurate_as_numeric(route, toda3_routes):
    """p~ of the emitted forms within 16 eps S (S without the read-out clause), as symbt.numeric's p~ is."""
    from symbt.numeric import bt_step

    if route not in toda3_routes:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    p, q, lam0, mu, b = FOUND_P1
    lib = _errors_in_eps_S(FOUND_P1, np.concatenate(bt_step(p, q, lam0, mu, branch=b)))
    assert max(lib[:3]) <= 16                                        # the premise: float64 can do it
    err = _errors_in_eps_S(FOUND_P1, toda3_routes[route](*FOUND_P1))
    assert max(err) <= 16, err


def test_deep_judge_flags_no_map_where_it_exists(monkeypatch):
    """A symbt.numeric route that says "no real map" where the literal map is real is a failure (existence
    decided alike); a route that refuses with NumericRangeError is not (a documented refusal)."""
    import test_fuzz_deep as deep

    for verdict, flagged in (("NoRealMapError", True), ("NumericRangeError", False)):
        monkeypatch.setitem(SINGLE_ROUTES, "kernel", lambda *a, v=verdict: v)
        stats, failures = deep.deep_chunk(7, 32, {}, {})
        assert stats["states"] > 0                                   # the premise: some maps exist
        whys = {why for route, why, _, _ in failures if route == "kernel"}
        assert whys == ({"no real map reported, but it exists"} if flagged else set()), (verdict, whys)


#: found by the deep run (seed 26, N = 2, q far apart, |lam| >> |p|): every float64 route of symbt.numeric raises
#: NoRealMapError ("|tr L(lam1)| <= 2") where the literal map (60-1300 digits) and symbt.numeric's own mpmath
#: backend (40-400 digits) give a real state.  Chunk 108: tr L(lam_i) = 1.47e155, 1.52e168, min Etilde_j / E_j
#: = +2.06e-13; chunk 114: tr L(lam_i) = 1.62e18, 7.21e27, min Etilde_j / E_j = 2.0 (far from any boundary)
FOUND_NOMAP = {
    108: (np.array([-3.1638448685852483, -2.919129004010822]), np.array([-194.23829279766574, 194.2382927976657]),
          -2.4297043779481497e+84, 1.5660336063884298e+83, -1),
    114: (np.array([-0.42181568736841957, -0.6372169219073047]), np.array([-39.321234636330715, 39.321234636330715]),
          1.1939751255891675e+17, -15101584160.0, 1),
}


def _mp_state(case):
    from symbt.numeric import bt_step

    p, q, lam0, mu, b = case
    ref, _ = _ref(case)
    with mp.workdps(40):                                             # the premise: mpmath agrees with the literal map
        a, c = bt_step(list(map(mp.mpf, p)), list(map(mp.mpf, q)), mp.mpf(lam0), mp.mpf(mu), branch=b)
        assert max(abs(x - r) / max(abs(r), 1) for x, r in zip(a + c, ref)) < mp.mpf(10) ** -30
    return [float(r) for r in ref]


@pytest.mark.parametrize("chunk", sorted(FOUND_NOMAP))
def test_float_step_finds_the_existing_map_far_apart(chunk):
    """The float64 step returns the state the literal map gives (existence decided alike on every route).

    Failed (``NoRealMapError``) before the trace decision compared ``t``'s rounding scale ``eps T`` with
    ``||t| - 2|`` instead of ``|t**2 - 4| / |t|``, which vanishes when ``t`` cancels to noise
    (``symbt.numeric.core.step.trace_kappa``)."""
    from symbt.numeric import bt_step

    p, q, lam0, mu, b = FOUND_NOMAP[chunk]
    ref = _mp_state(FOUND_NOMAP[chunk])
    pt, qt = bt_step(p, q, lam0, mu, branch=b)
    assert np.allclose(np.concatenate([pt, qt]), ref, rtol=1e-12, atol=0)


def test_emitted_toda2_finds_the_existing_map_far_apart():
    """The emitted closed form decides existence as the literal map does (chunk 114's state, far from the
    boundary of existence: min Etilde_j / E_j = 2.0): the literal state, or the documented refusal
    ``IllConditionedError`` (its float64 trace cancelled to noise) -- never ``NoRealMapError``, which it
    raised before its conditioning guard compared ``eps T`` with ``||t| - 2|``."""
    from symbt.generated import toda2

    p, q, lam0, mu, b = FOUND_NOMAP[114]
    ref = _mp_state(FOUND_NOMAP[114])
    try:
        pt, qt = toda2.bt_step(p, q, lam0, mu, b)
    except toda2.IllConditionedError:
        return
    except toda2.NoRealMapError as err:
        raise AssertionError("emitted toda2: %s" % err) from None
    assert np.allclose(np.concatenate([pt, qt]), ref, rtol=1e-12, atol=0)


#: found by the deep run (seed 26; benchmarks/results/fuzz-deep-2026-11-26-nomap.txt): lam1 or lam2 = 0 exactly,
#: positions far apart, min Etilde_j / E_j = 5.5e-113 (chunk 86), 2.4e-144 (chunk 162), 3.9e-150 (chunk 188).
#: The escalation's mpmath runs at 40 and 60 digits agreed on "no real map" (Etilde_j/E_j rounded to <= 0) and
#: that agreement decided it; chunk 86 also raised a bare OverflowError in the sharp condition estimate
#: (math.ldexp past the float64 range) before that.
NOMAP_AT_ZERO = {
    86: (np.array([5.355942124445836, 2.910932584689657, -2.4864351694996882, 6.944217765338692, 5.039453850410704,
                   0.09286660516584463]),
         np.array([19.20856548906663, -403.0850452407689, 109.13024822133666, 106.59342713796002, 102.51045431042081,
                   65.64235008198486]), 8.416039261834152e+110, -8.416039261834152e+110, 1),
    162: (np.array([-0.007466773988405374, -3.305784405301828, -3.785368514464953, -0.011863971454444441,
                    -1.258408165858202, 1.2949799857915714]),
          np.array([334.8722351310196, 336.10749735480226, 212.36872538970877, -154.1489940323986, -374.0716989741516,
                    -355.1277648689804]), -2.434025219099897e+141, 2.434025219099897e+141, 1),
    188: (np.array([4.560722540960275, -0.9540006406810474, -3.909650098293471]),
          np.array([432.54419857438245, -175.0883971487649, -257.45580142561755]), -1.2142295320239114e+149,
          1.2142295320239114e+149, -1),
}


@pytest.mark.parametrize("chunk", sorted(NOMAP_AT_ZERO))
def test_escalation_decides_existence_rigorously_at_lambda_zero(chunk):
    """The float64 step returns the literal map's state where lam1 or lam2 is exactly 0 and the map exists by a
    margin of 1e-150: the escalation's "no real map" is decided by interval arithmetic
    (symbt.numeric.float64.existence), not by two mpmath runs agreeing.  The reference: the literal map of
    symbt.reference with 2000 guard digits (its default guard, ~1000 digits here, is not enough at lam = 0)."""
    from symbt.numeric import bt_step
    from symbt.numeric.core.limits import OK
    from symbt.numeric.float64.existence import decide_existence
    from symbt.reference.literal import reference_step

    p, q, lam0, mu, b = NOMAP_AT_ZERO[chunk]
    assert lam0 + mu == 0 or lam0 - mu == 0                           # the premise
    assert decide_existence(p, q, lam0, mu, b)[0] == OK
    with mp.workdps(30):
        pt, qt = reference_step(list(map(mp.mpf, p)), list(map(mp.mpf, q)), mp.mpf(lam0), mp.mpf(mu), branch=b,
                                guard=2000)
    ref = np.array([float(x) for x in pt + qt])
    for backend in ("auto", "numpy"):
        got = np.concatenate(bt_step(p, q, lam0, mu, branch=b, backend=backend))
        assert np.array_equal(got, ref), (backend, got, ref)


def test_existence_is_decided_only_where_the_intervals_exclude_zero(monkeypatch):
    """decide_existence: no real map inside a band and at an exact band edge (a point interval: |t| = 2 is not
    > 2), the map where it exists -- and None, not a verdict, where the precision budget ends before the
    intervals exclude 0 (chunk 86's min Etilde_j / E_j = 5.5e-113 needs 512 bits); the escalation then refuses
    the state with NumericRangeError (status RANGE) instead of saying "no real map"."""
    import symbt.numeric.float64.existence as ex
    from symbt.numeric.core.limits import OK, RANGE, TRACE1
    from symbt.numeric.float64.rows import escalate_rows

    z = np.zeros(2)
    assert ex.decide_existence(z, z, 0.5, 0.25, 1)[0] == TRACE1                  # tr L(0.75) = -1.44: a band
    assert ex.decide_existence(z, z, 2.5, -0.5, 1)[0] == TRACE1                  # tr L(2) = 2 exactly
    assert ex.decide_existence(np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9]), 10.0, 5.0, 1)[0] == OK
    p, q, lam0, mu, b = NOMAP_AT_ZERO[86]
    assert ex.decide_existence(p, q, lam0, mu, b) == (OK, 512)
    monkeypatch.setattr(ex, "MAX_BITS", 256)
    assert ex.decide_existence(p, q, lam0, mu, b)[0] is None
    assert escalate_rows(p[None], q[None], lam0, mu, b)[2].tolist() == [RANGE]


#: found by the third deep run (seed 26, chunk 133, N = 6, |lam| ~ 3.5e103, branch -1): the transfer-matrix form's
#: rescaled trace at lam1 underflowed to 0 (2**-2410), so t**2 - 4 = 0 and its condition estimate 0/0 = NaN passed
#: the conditioning guard; the trace guard then said "no real map" (numpy: NoRealMapError, C: status 1) where the
#: literal map and symbt.numeric give a state
FOUND_LOOP_NAN = (np.array([-4.338901404876961, -5.724777799228214, 6.418960636318868, 1.3208372969240691,
                            0.2417460741724717, 2.132787392610733]),
                  np.array([-51.04785714923382, 272.30791761423615, 275.46892753823505, -56.394341294473975,
                            87.81651905356236, -528.1511657623258]), 3.527925499006412e+103, 4.684576053793516e+102, -1)


def test_loop_form_refuses_a_trace_it_cannot_represent(tmp_path):
    """The loop form (numpy and C) refuses that state as ill-conditioned -- a documented refusal -- never with
    "no real map" where the map exists (the premise: the literal map is real there)."""
    import shutil
    import subprocess
    import types

    from test_codegen_edges import CStep

    import symbt.codegen as cg
    from symbt.codegen import zullo

    p, q, lam0, mu, b = FOUND_LOOP_NAN
    assert isinstance(literal(p, q, lam0, mu, b), list)
    mod = types.ModuleType("toda6_nan")
    exec(compile(zullo.module_text(6, "transfer-matrix"), "toda6_nan", "exec"), mod.__dict__)
    with pytest.raises(mod.IllConditionedError):
        mod.bt_step(p, q, lam0, mu, b)
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    assert cg.main(["--target", "c", "--n", "6", "--out", str(tmp_path), "-q"]) == 0
    subprocess.run([cc, "-std=c99", "-O2", "-shared", "-fPIC", "-o", str(tmp_path / "t6.so"),
                    str(tmp_path / "toda6.c"), "-lm"], check=True, capture_output=True, timeout=300)
    assert CStep(tmp_path / "t6.so", 6)(p, q, lam0, mu, b)[0] == 5              # SYMBT_TODA_ILL_CONDITIONED


def test_existence_budget_is_shared_by_a_batch(monkeypatch):
    """One escalation call shares one existence budget (``BUDGET_S``) among its states: a batch of states that
    stay undecided costs the budget once plus one first-precision attempt per further state -- not M budgets.
    The intervals are made undecidable and slow (each attempt sleeps), the budget short."""
    import time as _time

    import symbt.numeric.float64.existence as ex
    import symbt.numeric.float64.rows as rows
    from symbt.numeric.core.limits import RANGE

    attempts = []

    def undecided(*args):
        attempts.append(_time.monotonic())
        _time.sleep(0.05)
        return None

    monkeypatch.setattr(ex, "_at", undecided)
    monkeypatch.setattr(ex, "BUDGET_S", 0.3)
    monkeypatch.setattr(rows, "_mp_verdict", lambda *a: (rows.TRACE1, []))    # every run says "no real map"
    M = 6
    z = np.zeros((M, 2))
    start = _time.monotonic()
    st = rows.escalate_rows(z, z, 0.5, 0.25, 1)[2]
    took = _time.monotonic() - start
    assert st.tolist() == [RANGE] * M                                # undecided: refused, never "no real map"
    per_state_budgets = M * 0.3
    assert took < per_state_budgets / 2, took
    assert len(attempts) >= M                                        # every state tried at least once
    assert len(attempts) <= M + 0.3 / 0.05 + 1
