"""The claims on :mod:`symbt.reference`'s sampler and Carlson integral kill the bugs they were written for (issue 21).

Each test plants one single-point bug of ``symbt mutate --source``'s kind (the survivors of its run on
``reference.samples`` and ``reference.elliptic``, docs/mutation.md) with ``monkeypatch`` and requires the claim to
fail; unpatched, the claims verify.
"""
from __future__ import annotations

import mpmath as mp
from planting import planted as _planted

from symbt.claims import library_samples
from symbt.reference import elliptic, samples


def status(claim) -> str:
    return claim.run().status


def test_unpatched_verified():
    assert status(library_samples.sampler_contract) == "verified"
    assert status(library_samples.carlson_against_mpmath) == "verified"
    assert status(library_samples.regime_by_trace) == "verified"


def test_sampler_one_state_too_many(monkeypatch):
    # `while len(out) <= count` (mutant samples:46): one state more than asked for
    real = samples.admissible_states
    monkeypatch.setattr(library_samples, "admissible_states", lambda N, s, count, seed=0: real(N, s, count + 1, seed))
    assert status(library_samples.sampler_contract) == "failed"


def test_sampler_values_depend_on_precision(monkeypatch):
    # lam0 computed at the working precision (off by 10^(5 - dps)) instead of read from an exact decimal string
    real = samples.admissible_states

    def rounded(N, s, count, seed=0):
        return [(p, q, l0 + mp.mpf(10) ** (5 - mp.mp.dps), m) for p, q, l0, m in real(N, s, count, seed)]
    monkeypatch.setattr(library_samples, "admissible_states", rounded)
    assert status(library_samples.sampler_contract) == "failed"


def test_sampler_stream_reseeded(monkeypatch):
    # a count-dependent seed (a slip in the seed formula): count 3 is no longer the start of count 5
    real = samples.admissible_states
    monkeypatch.setattr(library_samples, "admissible_states",
                        lambda N, s, count, seed=0: real(N, s, count, seed + count))
    assert status(library_samples.sampler_contract) == "failed"


def _rf_loop_wrong_series(x, y, z, sqrt, scale):
    # elliptic._rf_loop with the order-5 coefficient 3/44 of E2 E3 dropped to 1/44 (mutant elliptic:109)
    A0 = (x + y + z) / 3
    Q = max(abs(A0 - x), abs(A0 - y), abs(A0 - z)) * scale
    xm, ym, zm, A, p4 = x, y, z, A0, 1
    while p4 * abs(A) <= Q:
        sx, sy, sz = sqrt(xm), sqrt(ym), sqrt(zm)
        lam = sx * sy + sx * sz + sy * sz
        xm, ym, zm, A, p4 = (xm + lam) / 4, (ym + lam) / 4, (zm + lam) / 4, (A + lam) / 4, 4 * p4
    X, Y = (A0 - x) / (p4 * A), (A0 - y) / (p4 * A)
    Z = -X - Y
    E2, E3 = X * Y - Z * Z, X * Y * Z
    return (1 - E2 / 10 + E3 / 14 + E2 * E2 / 24 - E2 * E3 / 44) / sqrt(A)


def test_carlson_series_term(monkeypatch):
    monkeypatch.setattr(elliptic, "_rf_loop", _rf_loop_wrong_series)
    assert status(library_samples.carlson_against_mpmath) == "failed"


def test_carlson_no_guard_bits(monkeypatch):
    # the duplication stopped two iterations early (the scale of the stopping rule divided by 16): the series'
    # truncation error shows at 50 digits
    real = elliptic._rf_loop
    monkeypatch.setattr(elliptic, "_rf_loop", lambda x, y, z, sqrt, scale: real(x, y, z, sqrt, scale / 16 ** 2))
    assert status(library_samples.carlson_against_mpmath) == "failed"


def _read_the_streams(monkeypatch, record) -> None:
    """Draw the states of the streams the claims read (N = 2..8, both signs, seeds 0-2 and 11, up to 8 states: a
    stream is read in order, so fewer states read a prefix), calling ``record(args, ok, info)`` at every
    ``_real_map`` the sampler calls."""
    real = samples._real_map

    def recording(*args):
        ok, info = real(*args)
        record(args, ok, info)
        return ok, info
    monkeypatch.setattr(samples, "_real_map", recording)
    for N in range(2, 9):
        for s in (1, -1):
            for seed in (0, 1, 2, 11):
                with mp.workdps(30):
                    samples.admissible_states(N, s, 8, seed=seed)


def test_no_trace_at_the_sampler_margin(monkeypatch):
    # the fact behind the equivalence marks samples:62 (`> 2.2` vs `>= 2.2`, mutants-equivalent.toml): the two
    # comparisons differ only at a trace equal to the double 2.2; no trace the comparison reads, on the streams
    # the claims draw from (N = 2..8, both signs, seeds 0-2 and 11, up to 8 states: a stream is read in order, so
    # fewer states read a prefix), equals it
    read: list = []

    def record(args, ok, info):
        if ok and args[-1] == 1:
            read.extend((info["tr1"], info["tr2"]))
    _read_the_streams(monkeypatch, record)
    assert len(read) > 1000
    assert not [t for t in read if isinstance(t, mp.mpf) and abs(t) == 2.2]


def test_branch_minus_never_fails_positivity_on_the_streams(monkeypatch):
    # the fact behind the equivalence mark samples:74 (`_real_map(*state, -1)[0]` -> `[1]`: the info dict, truthy
    # where [0] is False only when the -1 step ran but some E~_j <= 0): on the streams the claims draw from (as
    # above), every state the -1 test reads with a real +1 map and traces beyond 2.2 has no such -1 step -- the
    # -1 map is real or it raised (info None) -- so both read the same truth value and keep the same states
    minus: list = []

    def record(args, ok, info):
        if args[-1] == -1:
            minus.append((ok, info is not None))
    _read_the_streams(monkeypatch, record)
    assert len(minus) > 400
    assert all(ok == has_info for ok, has_info in minus)


def test_regime_of_the_lower_parameter(monkeypatch):
    # regime() classifies lambda_- = lam0 - mu by (lam0 - mu - I1)/r instead of + I1 (mutant elliptic:298)
    monkeypatch.setattr(elliptic, "regime", _regime_wrong_minus)
    assert status(library_samples.regime_by_trace) == "failed"


def _regime_wrong_minus(I1, I2, lam0, mu):
    k, _ = elliptic.modulus(I2)
    r = mp.sqrt(I2 - 2)

    def zone(s):
        if abs(s) < 1:
            return "in"
        if k * abs(s) > 1:
            return "out+" if s > 0 else "out-"
        return "gap"
    zp, zm = zone((lam0 + mu + I1) / r), zone((lam0 - mu - I1) / r)
    if "gap" in (zp, zm):
        return "gap"
    if zp == zm == "in":
        return "inner"
    if zp == zm:
        return "outer-same"
    return "mixed" if "in" in (zp, zm) else "outer-opposite"


def test_regime_outer_zones_swapped_sign(monkeypatch):
    # the band test `abs(s) < 1` taken as `s < 1` (an abs lost): large negative s is called inner
    real_modulus = elliptic.modulus
    monkeypatch.setattr(elliptic, "regime", lambda I1, I2, lam0, mu: _regime_lost_abs(I1, I2, lam0, mu, real_modulus))
    assert status(library_samples.regime_by_trace) == "failed"


def _regime_lost_abs(I1, I2, lam0, mu, modulus):
    k, _ = modulus(I2)
    r = mp.sqrt(I2 - 2)

    def zone(s):
        if s < 1:
            return "in"
        if k * abs(s) > 1:
            return "out+" if s > 0 else "out-"
        return "gap"
    zp, zm = zone((lam0 + mu + I1) / r), zone((lam0 - mu + I1) / r)
    if "gap" in (zp, zm):
        return "gap"
    if zp == zm == "in":
        return "inner"
    if zp == zm:
        return "outer-same"
    return "mixed" if "in" in (zp, zm) else "outer-opposite"


def test_moments_boundary_not_refused(monkeypatch):
    # the refusal of c_0 c_2 <= c_1^2 made strict (as mutant inverse:155 `<`): here the target is nudged off the
    # boundary by 1e-12 before the test, and the direction mode "solves" (1, 2, 4) with a vanishing mu
    from symbt.claims import library_moments

    real = library_moments.solve_parameters

    def nudged(p, q, c, **kw):
        c = list(c)
        return real(p, q, [c[0], c[1], c[2] * (1 + mp.mpf(10) ** -12)] + c[3:], **kw)
    assert status(library_moments.moment_condition) == "verified"
    monkeypatch.setattr(library_moments, "solve_parameters", nudged)
    assert status(library_moments.moment_condition) == "failed"


# --------------------------------------------------------------------------- library.proposal

def test_proposal_unpatched_verified():
    from symbt.claims import library_sampler

    assert status(library_sampler.proposal_margins) == "verified"


def test_proposal_gap_zone_past_its_edge(monkeypatch):
    # _s_in's gap zone 1 + (1/k + 1) u (mutant elliptic:410): drawn past the band edge s = 1/k, cases kept by their
    # regime lie arbitrarily near it
    from symbt.claims import library_sampler

    monkeypatch.setattr(elliptic, "_s_in", _planted(elliptic._s_in, "(1 / k - 1)", "(1 / k + 1)"))
    assert status(library_sampler.proposal_margins) == "failed"


def test_proposal_x_past_the_turning_point(monkeypatch):
    # sample_case's x range acosh(I2) for acosh(I2 / 2) (mutant elliptic:435): p1 = p2 where the root is clamped
    from symbt.claims import library_sampler

    monkeypatch.setattr(elliptic, "sample_case", _planted(elliptic.sample_case, "math.acosh(I2 / 2) * (x_sign",
                                                          "math.acosh(I2) * (x_sign"))
    assert status(library_sampler.proposal_margins) == "failed"


def test_proposal_level_set_sign(monkeypatch):
    # Pr = sqrt(I2 + 2 cosh x) (mutant elliptic:436 sign): the state is not on the proposal's level set
    from symbt.claims import library_sampler

    monkeypatch.setattr(elliptic, "sample_case", _planted(elliptic.sample_case, "max(I2 - 2 * math.cosh(x)",
                                                          "max(I2 + 2 * math.cosh(x)"))
    assert status(library_sampler.proposal_margins) == "failed"


def test_proposal_level_set_factor(monkeypatch):
    # Pr = sqrt(I2 - cosh x) (mutant elliptic:436 drop-factor, marked equivalent before this claim)
    from symbt.claims import library_sampler

    monkeypatch.setattr(elliptic, "sample_case", _planted(elliptic.sample_case, "max(I2 - 2 * math.cosh(x)",
                                                          "max(I2 - math.cosh(x)"))
    assert status(library_sampler.proposal_margins) == "failed"


def test_proposal_separation_filter(monkeypatch):
    # the filter |sa - sb| < 0.05 taken as |sa + sb| (mutant elliptic:431, marked equivalent before this claim)
    from symbt.claims import library_sampler

    monkeypatch.setattr(elliptic, "sample_case", _planted(elliptic.sample_case, "abs(sa - sb) < 0.05",
                                                          "abs(sa + sb) < 0.05"))
    assert status(library_sampler.proposal_margins) == "failed"


# --------------------------------------------------------------------------- library.shift_real

def test_shift_real_part_condition_flipped(monkeypatch):
    # shift's real dtheta1 computed only when |T1| <= 2 (mutant elliptic:270): None off the bands
    from symbt.claims import library_sampler

    assert status(library_sampler.shift_real_part) == "verified"
    monkeypatch.setattr(elliptic, "shift", _planted(elliptic.shift, "and abs(T1) >= 2 and abs(T2) >= 2:",
                                                    "and abs(T1) <= 2 and abs(T2) >= 2:"))
    assert status(library_sampler.shift_real_part) == "failed"
