"""Nearly closed gaps (issue 26 item 3): the emitted step within its documented ``16 eps S`` where ``|tr L| ~ 2`` is
an extremum of the trace.

The 12 inputs are the deep fuzz's failures of its third run (docs/fuzz.md, seed 26, kind ``closed``: the chunk is
the key): the emitted closed forms, the transfer-matrix form and C were all 17-74 eps S off, because
``(t - 2)(t + 2)`` carried the trace's rounding at the scale 2 of its terms, which ``S`` does not count (every
first derivative of ``tr`` is small there) and ``sqrt(t^2 - 4)`` amplified.  Fixed by taking ``t^2 - 4`` as
``(A - D)^2 + 4BC`` of the monodromy's entries there (:mod:`symbt.codegen.closed_gap`).  Each route is judged as
the deep fuzz judges it (:func:`test_fuzz_deep._emitted_ok`) and, more strictly, by ``16 eps S`` with ``S`` from the
literal map's differences alone (no float-difference or read-out fallback); the reference is the literal map of
:mod:`symbt.reference` at high precision, which shares no code with the emitted files.  A seeded fuzz inside
the free chain's nearly closed gaps (:func:`closed_gap_inputs`, N = 2, 3, 4, 6) judges every emitted route the same
way beyond these 12.
"""
from __future__ import annotations

import shutil
import subprocess
import types

import mpmath as mp
import numpy as np
import pytest
from test_fuzz_deep import _emitted_ok, _once, literal_scale
from test_fuzz_numeric import EPS, literal, literal_traces

#: chunk -> (p, q, lam0, mu, branch): benchmarks/results/fuzz-deep-2026-11-27.jsonl, the ``emitted`` failures
CLOSED = {
    16: ([-0.0005055540591919833, 0.00043450385781587273, 0.0007416336200574261],
         [-0.0005441565584078684, 0.00041473917314590117, -0.0008994454296036974], 0.9997978787006132,
         0.0008813268126691143, 1),
    17: ([0.0014492827460695272, -0.00047233273492047723, 0.00047417879644331095],
         [-9.220578644192118e-05, 0.00015078741229735624, 0.0011649675140423688], 0.9992234049675441,
         0.0008466568433748711, -1),
    41: ([-0.00027838198094232337, -0.0011860998667408721, -0.004988071223335752],
         [-0.003294585062499522, -0.004320212544129927, -0.006848354068872271], 1.0020211937086012,
         0.0022807224614608823, -1),
    47: ([-0.002275278086509128, -0.004015405269229594, 0.0006405218644127224],
         [-0.0005484006596075499, 0.0010816793850907179, -0.005359462513905358], 1.0008987477547096,
         -0.0022582406727645887, 1),
    49: ([-2.7739138405694163e-05, 0.0006160154241407448, -0.00033162597619973715],
         [-0.00036280446633085966, 0.0006176078452655218, -0.00020871478803464373], -1.000323121131382,
         0.00017473359629782692, -1),
    56: ([0.0001111838040901612, 0.0030847372498286406], [0.0009581026872492311, -0.0008932857269113524],
         -0.0019324167190987237, 0.0006391722120429294, 1),
    88: ([-0.0024476144337046797, 0.0012990430777914618, -0.0011309595430395412],
         [0.0015015767016860195, -0.000577339434125901, -0.0004373273096909774], -0.9992682221004995,
         -0.0008979735364295083, -1),
    113: ([0.0008959338849987738, -0.002378381163840237], [0.0034730536990793554, 0.0004081384841231274],
          0.0007010906025342503, -0.003390449917626534, 1),
    137: ([-6.77185855477553e-05, 0.00188565794969034], [0.0011408269606544307, -0.0006757750915946334],
          -0.00015599567141636784, 0.0012404119229674163, -1),
    142: ([0.004746169868733996, -0.0009044474710965247], [-0.0013375318191297914, -0.006285616976403805],
          0.002288382325538767, -0.001449136679751219, -1),
    143: ([0.002220216204123696, 0.0001118273894655339, -5.844027787922274e-05],
          [0.0014004448638229659, -0.00023762447549307086, -0.0005875178912396879], 0.9992934175827923,
          -0.0005161878816082321, 1),
    163: ([0.0009136256344120925, -0.00014406253818984523, -0.00046283990268805835],
          [0.0002961831316155091, -0.0007776427635819796, 0.00031008032236036725], 0.9999553543040947,
          -0.00024984249463511077, 1),
}
ROUTES = ("closed", "loop", "C closed", "C loop")
#: the transfer-matrix form's own sizes in the seeded fuzz below
LOOP_NS = (4, 6)


def _module(N, form):
    from symbt.codegen import zullo

    mod = types.ModuleType(f"toda{N}_{form}")
    exec(compile(zullo.module_text(N, form), mod.__name__, "exec"), mod.__dict__)
    return mod


def _c_step(tmp, N, form, cc):
    """The C step of ``toda{N}`` in ``form`` (the closed form as ``symbt codegen --target c`` writes it for N <= 3;
    the transfer-matrix C of N >= 4 emitted for this N), compiled with the project's warning flags."""
    from test_codegen_edges import CStep

    from symbt.codegen import emit_c
    from symbt.codegen.c_template import COMMON, HEADER
    from symbt.numeric.core.limits import KAPPA_MAX

    if form == "closed":
        text, header = emit_c.c_files(N)
    else:
        head = emit_c._fill(HEADER.replace("@@KAPPA@@", str(int(KAPPA_MAX))), N, "transfer-matrix")
        text, header = emit_c._loop_c_files(N, head, emit_c._fill(COMMON, N, "transfer-matrix"))
    d = tmp / f"{form}{N}"
    d.mkdir()
    (d / f"toda{N}.h").write_text(header)
    (d / f"toda{N}.c").write_text(text)
    so = d / "step.so"
    r = subprocess.run([cc, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC", "-o",
                        str(so), str(d / f"toda{N}.c"), "-lm"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    step = CStep(so, N)

    def run(p, q, lam0, mu, b):
        rc, got = step(p, q, lam0, mu, b)
        if rc != 0:
            raise CRefusal(rc)
        return np.array(got)
    return run


class CRefusal(Exception):
    """A C step's non-zero status (``args[0]``)."""


@pytest.fixture(scope="module")
def routes(tmp_path_factory):
    """route -> N -> step returning p~ + q~: the committed closed forms (N = 2, 3), the transfer-matrix form
    (numpy; N = 2, 3 and the N >= 4 it is emitted for), and the C steps of both where a C compiler is present."""
    from symbt.generated import toda2, toda3

    def concat(m):
        return lambda *a: np.concatenate(m.bt_step(*a))
    out = {"closed": {2: concat(toda2), 3: concat(toda3)},
           "loop": {N: concat(_module(N, "transfer-matrix")) for N in (2, 3) + LOOP_NS}}
    cc = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if cc is not None:
        tmp = tmp_path_factory.mktemp("closed-gap-c")
        out["C closed"] = {N: _c_step(tmp, N, "closed", cc) for N in (2, 3)}
        out["C loop"] = {N: _c_step(tmp, N, "transfer-matrix", cc) for N in (2, 3) + LOOP_NS}
    return out


@pytest.fixture(scope="module")
def references():
    """chunk -> (the literal map's p~ + q~, its S): high precision, shared by the routes."""
    out = {}
    for chunk, (p, q, lam0, mu, b) in CLOSED.items():
        ref = literal(np.array(p), np.array(q), lam0, mu, b)
        assert isinstance(ref, list)                                     # the premise: a real map
        traces = literal_traces(p, q, lam0, mu)
        with mp.workdps(40):                                             # the premise: a nearly closed gap
            assert all(abs(abs(t) - 2) < 1e-4 for t in traces), traces
        out[chunk] = ref, literal_scale(p, q, lam0, mu, b, traces)
    return out


@pytest.mark.parametrize("route", ROUTES)
@pytest.mark.parametrize("chunk", sorted(CLOSED))
def test_emitted_step_within_16_eps_S_at_a_nearly_closed_gap(chunk, route, routes, references):
    """Every component within 16 eps S of the literal map (S from its differences alone), and the deep fuzz's
    judge passes the state.  Failed before (17-74 eps S on every route; 9.7-12.4 on the loop form at three N = 2
    inputs, which passed there)."""
    if route not in routes:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    p, q, lam0, mu, b = CLOSED[chunk]
    ref, S = references[chunk]
    got = routes[route][len(p)](np.array(p), np.array(q), lam0, mu, b)     # a state (the C status 0), no refusal
    with mp.workdps(40):
        err = [float(abs(mp.mpf(float(g)) - r) / (EPS * s)) for g, r, s in zip(got, ref, S)]
    assert max(err) <= 16, err
    how, why = _emitted_ok(got, ref, p, q, lam0, mu, b, _once(lambda: S))
    assert why is None, why


@pytest.mark.parametrize("chunk", sorted(CLOSED))
def test_mpmath_flavour_at_a_nearly_closed_gap(chunk, references):
    """The ``_mp`` flavour of the committed closed form (the entries' discriminant selected the same way) agrees
    with the literal map to 50 digits relative to S."""
    from symbt.generated import toda2, toda3

    p, q, lam0, mu, b = CLOSED[chunk]
    ref, S = references[chunk]
    with mp.workdps(50):
        pt, qt = {2: toda2, 3: toda3}[len(p)].bt_step_mp(p, q, lam0, mu, b)
        assert max(abs(g - r) / s for g, r, s in zip(pt + qt, ref, S)) < mp.mpf(10) ** -45


def closed_gap_inputs(seed, N, n):
    """``n`` seeded inputs ``(p, q, lam0, mu, b)`` inside nearly closed gaps where the literal map is real: the free
    chain's closed gaps at ``lambda* = 2 cos(k pi / N)`` (``tr L = +-2`` there, an extremum), ``p, q ~ d N(0, 1)``
    with ``d = 10**U(-3.5, -2)`` (the gaps open to ~d), ``lambda_1, lambda_2 = lambda* + d U(-0.3, 0.3)`` (``|t| - 2``
    ~ 1e-7 .. 1e-5, the deep fuzz's failures' regime; on the inputs where the map exists, about 1 in 15 was beyond
    16 eps S before)."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        star = 2 * np.cos(np.pi * rng.integers(1, N) / N)
        d = 10 ** rng.uniform(-3.5, -2)
        p, q = d * rng.normal(size=N), d * rng.normal(size=N)
        l1, l2 = star + d * rng.uniform(-0.3, 0.3, 2)
        x = (p, q, (l1 + l2) / 2, (l1 - l2) / 2, int(rng.choice([1, -1])))
        ref = literal(*x)
        if isinstance(ref, list):
            out.append((x, ref))
    return out


def _refusal(err):
    """The class of a documented refusal of a step (None: not one)."""
    if isinstance(err, CRefusal):
        return {1: "no-map", 2: "no-map", 3: "range", 5: "range"}.get(err.args[0])
    name = type(err).__name__
    return "no-map" if name == "NoRealMapError" else "range" if name in ("NumericRangeError",
                                                                           "IllConditionedError") else None


@pytest.mark.parametrize("N", (2, 3) + LOOP_NS)
def test_fuzz_nearly_closed_gaps(N, routes):
    """A seeded fuzz inside nearly closed gaps (:func:`closed_gap_inputs`), every emitted route of this N: each
    returned state within 16 eps S of the literal map (S from its differences), "no real map" only within 1e-6
    of the boundary of existence (the deep fuzz's judge), ill-conditioned / range refusals counted.  Before the
    entries' discriminant, on these seeds: 22, 12 and 2 route results beyond 16 eps S at N = 2, 3, 4 (none at
    N = 6; up to 61 eps S at N = 4 on other seeds)."""
    from test_fuzz_deep import _near_boundary

    n = 120 if N <= 3 else 60
    counts = {}
    problems = []
    for x, ref in closed_gap_inputs(2600 + N, N, n):
        traces = literal_traces(*x[:4])
        S = None
        for route, steps in routes.items():
            if N not in steps:
                continue
            try:
                got = steps[N](*x)
            except Exception as err:  # noqa: BLE001 -- an untyped error is a failure
                kind = _refusal(err)
                counts[kind] = counts.get(kind, 0) + 1
                if kind is None or (kind == "no-map" and not _near_boundary(*x, traces)):
                    problems.append((route, repr(err), x))
                continue
            counts["state"] = counts.get("state", 0) + 1
            S = S or literal_scale(*x, traces)
            with mp.workdps(40):
                err = max(float(abs(mp.mpf(float(g)) - r) / (EPS * s)) for g, r, s in zip(got, ref, S))
            if not err <= 16:
                problems.append((route, f"{err:.3g} eps S", x))
    assert not problems, (len(problems), problems[:3], counts)
    assert counts.get("state", 0) >= n // 2, counts          # the sampler reaches returned states, not only refusals
