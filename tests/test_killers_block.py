"""The claims of ``symbt/claims/shipped_block_file.py`` kill the bugs they were written for, and the proofs of the
equivalence marks of the float64 kernels' fresh samples (issue 21, item 4; docs/mutation.md, "Fresh samples of
symbt/numeric/float64/kernels_block.py and kernels.py").

Each killer test plants one single-point bug of ``symbt mutate --source``'s kind -- the mutant's own text, with
:func:`planting.planted` -- and requires the claim to fail; unpatched, every claim verifies.  Most are mutants of
the seed-41 sample (``--sample 25 --seed 41``), the others their neighbours.
"""
from __future__ import annotations

import inspect
import itertools
import math

import numpy as np
import pytest
from planting import planted

from symbt.claims import REGISTRY, load_all
from symbt.numeric.float64 import kernels, kernels_block

load_all()

CLAIMS = ["paths.hook_rules", "paths.block_slopes.n3", "paths.block_driver.n3"]


def status(cid: str) -> str:
    return REGISTRY[cid].run().status


@pytest.mark.parametrize("cid", CLAIMS)
def test_unpatched_verified(cid):
    assert status(cid) == "verified"


# --------------------------------------------------------------------------- paths.hook_rules

HOOK_MUTANTS = [  # (hook, function, old, new): the seed-41 sample's mutants of kernels.py's hooks, and neighbours
    ("track", "_track", "aa * Ba + Da", "aa * Ba - Da"),                        # kernels:190
    ("track", "_track", "cn = abs(lam) + abs(pj)", "cn = lam + abs(pj)"),       # kernels:185
    ("track", "_track", "if cn * kd > kn * abs(a):", "if not (cn * kd > kn * abs(a)):"),   # kernels:186
    ("track", "_track", "rj * Aa, rj * Ba", "rj * Aa, rj * Aa"),
    ("in_range", "_in_range", "return (abs(A) < 1e290", "return (abs(A) <= 1e290"),         # kernels:212
    ("in_range", "_in_range", "or abs(B) > 1e-290", "or abs(B) > 1e-145"),                  # kernels:213
    ("in_range", "_in_range", "abs(D) < 1e290", "D < 1e290"),
    ("rescale_last", "_rescale_last", "if aux[2] > _BIG or aux[3] > _BIG:", "if aux[2] > _BIG:"),
    ("two_of", "_two_of", "return 2.0 * aux[6]", "return aux[6]"),
    ("decided", "_decided", "tt[i + 2] = k", "tt[i + 1] = k"),
    ("decided", "_decided", "ta = abs(t) + 2.0 * aux[6]", "ta = abs(t) + 2.0"),
    ("disc_fits", "_disc_fits", "return disc < 1e300", "return disc <= 1e300"),
    ("sharpen", "_sharpen", "if ks < tt[i]:", "if ks < tt[i + 1]:"),           # kernels:253
    ("step_kappa", "_step_kappa", "max(tt[2], tt[3])", "max(tt[2], tt[2])"),
    ("trusted", "_trusted", "kt * (abs(u) + abs(w))", "kt * (u + abs(w))"),   # kernels:266
    ("trusted", "_trusted", "(abs(x + 1.0) + abs(x))", "(x + 1.0 + abs(x))"),
    ("trusted", "_trusted", "KAPPA_MAX * abs(dn)", "KAPPA_MAX * dn"),
    ("advance", "_advance", "r[j] = r[j] + r[j] * d", "r[j] = r[j] - r[j] * d"),      # kernels:273
    ("advance", "_advance", "r[j] = r[j] + r[j] * d", "r[j] = r[j] + r[j - 1] * d"),  # kernels:273
    ("advance", "_advance", "fl[j] = fl[j] + fl[j] * x", "fl[j - 1] = fl[j] + fl[j] * x"),  # kernels:278
    ("advance", "_advance", "fh[j] = s", "fh[j - 1] = s"),                    # kernels:279
    ("advance", "_advance", "fl[j] = fl[j] + fl[j] * x", "fl[j] = fl[j] * x"),
    ("advance", "_advance", "fl[j] = fl[j] + fl[j] * x", "fl[j] = fl[j] + fl[j - 1] * x"),   # seed 42's :278
]


@pytest.mark.parametrize("hook,func,old,new", HOOK_MUTANTS)
def test_hook_rules_see_a_hook_mutant(monkeypatch, hook, func, old, new):
    monkeypatch.setitem(kernels.HOOKS, hook, planted(getattr(kernels, func), old, new))
    assert status("paths.hook_rules") == "failed"


@pytest.mark.parametrize("func,old,new", [
    ("_logf", "fh > 1e-300", "fh > 1e-150"),                                      # kernels:128
    ("_logf", "fh < 1e300", "fh <= 1e300"),
    ("_logf", "math.log1p(fl / fh)", "math.log1p(fl)"),
    ("_dd_add", "lo = lo + ((hi - (t - bp)) + (s - bp))", "lo = lo + ((hi - (t - bp)) - (s - bp))"),
    ("_dd_add", "return h2, lo - (h2 - t)", "return h2, lo + (h2 - t)"),
    ("_dd_low", "return (h - y) + lo", "return (h - y) - lo"),
])
def test_hook_rules_see_a_double_double_mutant(monkeypatch, func, old, new):
    monkeypatch.setattr(kernels, func, planted(getattr(kernels, func), old, new))
    assert status("paths.hook_rules") == "failed"


# --------------------------------------------------------------------------- paths.block_slopes

SLOPES_MUTANTS = [  # the seed-41 sample's mutants of _slopes, and neighbours
    ("Ab[0, k] = abs(A[k])", "Ab[1, k] = abs(A[k])"),                             # kernels_block:70
    ("D[k] = r[j, k] * b0", "D[k - 1] = r[j, k] * b0"),                           # kernels_block:90
    ("disc = (t - two) * (t + two)", "disc = (t - two) * (t - two)"),             # kernels_block:116
    ("kap = T * ta / abs(disc) * (Kn[k] / Kd[k])", "kap = T * ta / abs(disc) * (Kn[k] / Kd[k - 1])"),  # :121
    ("r[:, k], lam[k], lo[k])", "r[:, k], lam[k], lo[k + 1])"),                   # kernels_block:124
    ("u1[k] = root_slope(", "u1[k + 1] = root_slope("),                           # kernels_block:136
    ("if nf < B:", "if nf > B:"),                                                 # kernels_block:146
    ("for j in range(N - 1, 0, -1):", "for j in range(N - 1, 0, -0):"),           # kernels_block:150
    ("Kn[k] = abs(lam[k]) + abs(p[0, k])", "Kn[k] = lam[k] + abs(p[0, k])"),
    ("cn = abs(lam[k]) + abs(p[j, k])", "cn = abs(lam[k]) + abs(p[j - 1, k])"),
    ("if Ab[0, k] > _BIG or Ab[1, k] > _BIG:", "if not (Ab[0, k] > _BIG or Ab[1, k] > _BIG):"),
    ("if big > 0:", "if big > 1:"),
    ("dst = tmp if nf > 0 else u", "dst = tmp if nf > 1 else u"),
    ("if nf > 0:\n            for j in range(1, N):", "if nf > 1:\n            for j in range(1, N):"),
    ("if nf > 0:\n        for j in range(N - 1):", "if nf > 1:\n        for j in range(N - 1):"),
    ("u[j + 1, k] = -r[j, k] / (lam_add(lam[k], lo[k], p[j, k])",
     "u[j + 1, k] = -r[j, k] / (lam_add(lam[k], lo[k - 1], p[j, k])"),
    ("dst[j, k] = -lam_add(lam[k], lo[k], p[j, k])", "dst[j, k] = -lam_add(lam[k], lo[k - 1], p[j, k])"),
    ("status[k] = st if st != OK else bad", "status[k] = st if st == OK else bad"),
    ("ks = sharp_trace_kappa(p[:, k], r[:, k], lam[k], lo[k])\n            kap = ks if ks < kap else kap",
     "ks = sharp_trace_kappa(p[:, k], r[:, k], lam[k], lo[k])\n            kap = ks if ks > kap else kap"),
]


@pytest.mark.parametrize("old,new", SLOPES_MUTANTS)
def test_block_slopes_see_a_mutant(monkeypatch, old, new):
    monkeypatch.setattr(kernels_block, "_slopes", planted(kernels_block._slopes, old, new))
    assert status("paths.block_slopes.n3") == "failed"


# --------------------------------------------------------------------------- paths.block_driver

DRIVER_MUTANTS = [  # (function, old, new): the seed-41 sample's mutants of the block driver, and neighbours
    ("run_block", "o1[k], o2[k] = lam_split(l1[k], l2[k], tm[k])",
     "o1[k], o2[k] = lam_split(l1[k], l2[k - 1], tm[k])"),                        # kernels_block:237
    ("run_block", "outQ[0, i0 + k, N + j] = 0.0", "outQ[0, i0 + k, N - j] = 0.0"),   # kernels_block:247
    ("run_block", "_slopes(p, r, l2, o2, -branch,", "_slopes(p, r, l2, o2, branch,"),  # kernels_block:252
    ("run_block", "(t1[k] < 0.0) != (t2[k] < 0.0)", "(t1[k] < 0.0) == (t2[k] < 0.0)"),   # kernels_block:255
    ("run_block", "x = tm[k] / dn\n                xr[j, k] = x", "x = tm[k - 1] / dn\n                xr[j, k] = x"),
    ("run_block", "s0 = st[k]", "s0 = st[k + 1]"),                                # kernels_block:268
    ("run_block", "outP[row, i0 + k, j] = p[j, k]", "outP[row, i0 - k, j] = p[j, k]"),   # kernels_block:311
    ("run_block", "nbad += 1 if st[k] != OK else 0", "nbad += 1 if st[k] != OK else 1"),  # kernels_block:318
    ("run_block", "nbad += 1 if st[k] != OK else 0", "nbad += 1 if st[k] == OK else 0"),
    ("run_block", "p[j, k] = p[j, k] + tm[k] * (gq[jn, k]", "p[j, k] = p[j, k] + tm[k - 1] * (gq[jn, k]"),
    ("run_block", "status[i0 + k] = st[k]", "status[i0 + k] = st[k - 1]"),
    ("run_block", "wide = outQ.shape[2] > N", "wide = outQ.shape[2] >= N"),
    ("run_block", "if i % anchor == 0:", "if i % anchor != 0:"),
    ("ensemble", "i1 = min(M, i0 + block)", "i1 = min(M, i0 - block)"),           # kernels_block:341
    ("ensemble", "i1 = min(M, i0 + block)", "i1 = max(M, i0 + block)"),
    ("_anchor", "status[k] = status[k] if status[k] != OK else RANGE\n                s = 0.0",
     "status[k] = status[k] if status[k] == OK else RANGE\n                s = 0.0"),
    ("_anchor", "jn = j + 1 if j + 1 < N else 0", "jn = j + 1 if j + 1 < N else 1"),
]


@pytest.mark.parametrize("func,old,new", DRIVER_MUTANTS)
def test_block_driver_sees_a_mutant(monkeypatch, func, old, new):
    # kernel("ensemble", "python") runs kernels_block's own functions once a global of the module was replaced
    monkeypatch.setattr(kernels_block, func, planted(getattr(kernels_block, func), old, new))
    assert status("paths.block_driver.n3") == "failed"


# --------------------------------------------------------------------------- equivalence marks

MIN_CONDITIONALS = [  # (module, line text, original expression, mutant expression) over (ks, x)
    (kernels_block.__file__, "kap = ks if ks < kap else kap", "ks if ks < x else x", "ks if ks <= x else x"),
    (kernels_block.__file__, "k1[k] = ks if ks < k1[k] else k1[k]", "ks if ks < x else x", "ks if ks <= x else x"),
    (kernels_block.__file__, "k2[k] = ks if ks < k2[k] else k2[k]", "ks if ks < x else x", "ks if ks <= x else x"),
    (kernels.__file__, "k = ks if ks < k else k", "ks if ks < x else x", "ks if ks <= x else x"),
]


def test_min_written_as_a_conditional_is_equivalent():
    # mutants-equivalent.toml, kernels_block:125/275/277 and kernels:232 (`ks if ks < x else x` -> `ks <= x`) and
    # kernels:253 (`if ks < tt[i]: tt[i] = ks` -> `<=`): the two forms differ only where ks == x, and there the
    # mutant takes ks, the original x -- the same double, unless they are zeros of opposite sign.  The values are
    # condition estimates, >= 1 or +inf or NaN (never a zero), and a NaN fails both comparisons.  Checked: each line
    # is in its source once, and both forms are the same bits over ties, infinities, NaN and neighbouring doubles.
    values = [1.0, 1.5, math.nextafter(1.5, 2.0), 2.0 ** 24, 1e300, math.inf, math.nan]
    for path, line, orig, mut in MIN_CONDITIONALS:
        assert open(path).read().count(line) == 1, line
        f, g = eval("lambda ks, x: " + orig), eval("lambda ks, x: " + mut)    # noqa: S307 -- our own text
        for ks, x in itertools.product(values, repeat=2):
            a, b = f(ks, x), g(ks, x)
            assert (math.isnan(a) and math.isnan(b)) or a.hex() == b.hex()
    src = inspect.getsource(kernels._sharpen)
    assert src.count("if ks < tt[i]:\n            tt[i] = ks") == 1
    sharp_le = planted(kernels._sharpen, "if ks < tt[i]:", "if ks <= tt[i]:")
    p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    k1 = kernels.sharp_trace_kappa(p, r, 15.0, 0.0)
    k2 = kernels.sharp_trace_kappa(p, r, 5.0, 0.0)
    for t2, t3 in itertools.product((k1, 2 * k1, 0.5 * k1), (k2, 3 * k2, 0.25 * k2)):   # ties included
        a, b = np.array([0.0, 0.0, t2, t3]), np.array([0.0, 0.0, t2, t3])
        assert kernels._sharpen(a, p, r, 15.0, 0.0, 5.0, 0.0) == sharp_le(b, p, r, 15.0, 0.0, 5.0, 0.0)
        assert a.tobytes() == b.tobytes()


def _zero_trace_block():
    """A block of three N = 2 members whose middle one has the scaled trace exactly 0: p = 0, lam = 1 (a_j = 1),
    r = (1/2, 1/2): t = a_1 a_0 - r_0 - r_1 = 0; the others moderate, of both trace signs."""
    p = np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 2.0]])
    r = np.array([[0.5, 0.5, 0.25], [2.0, 0.5, 3.0]])
    lam = np.array([5.0, 1.0, -6.0])
    return p, r, lam


def _run_slopes(fn, s, p, r, lam):
    N, B = p.shape
    out = {"u": np.zeros((N, B)), "tmp": np.zeros((N, B)), "Ab": np.zeros((4, B))}
    for name in ("A", "Bm", "C", "D", "u1", "tt", "kt", "Kn", "Kd", "sc"):
        out[name] = np.zeros(B)
    out["fw"], out["status"] = np.zeros(B, np.int64), np.zeros(B, np.int64)
    with np.errstate(all="ignore"):
        fn(p, r, lam, np.zeros(B), s, out["u"], out["tmp"], out["A"], out["Bm"], out["C"], out["D"], out["u1"],
           out["fw"], out["status"], 1, out["Ab"], out["tt"], out["kt"], out["Kn"], out["Kd"], out["sc"])
    return out


def test_transport_direction_at_a_zero_trace_is_equivalent():
    # mutants-equivalent.toml, kernels_block:137 (`t < 0.0` -> `t <= 0.0`; `t >= 0.0` -> `t > 0.0`) and :255
    # (`t1[k] < 0.0` -> `<= 0.0`, likewise t2): they differ only at a scaled trace exactly 0 (+-0.0).  There
    # disc = (t - two)(t + two) = -two**2 < 0 (two = 2 sc > 0), so every branch of _slopes' `bad` but OK is taken
    # before it (RANGE, ILLCOND, or the code where `not disc > 0`): the member's status is not OK ("first failure
    # wins" keeps it so).  At :137 the direction fw[k] then only chooses which transport fills that member's own
    # slopes (nf only decides whether each loop runs; a member's slopes are those of its own direction either way)
    # -- values of a failed member, never read; at :255 the test `st[k] == OK and ...` is false either way.
    # Checked: the block with a zero trace through the original and both planted _slopes, for s = +-1: its status
    # is the code in all three, every other output bit for bit the same except that member's slopes (tmp: scratch).
    p, r, lam = _zero_trace_block()
    plants = [planted(kernels_block._slopes, "f = (t < 0.0) if spos", "f = (t <= 0.0) if spos"),
              planted(kernels_block._slopes, "else (t >= 0.0)  #", "else (t > 0.0)  #")]
    for s in (1, -1):
        ref = _run_slopes(kernels_block._slopes, s, p, r, lam)
        assert ref["tt"][1] == 0.0 and ref["status"].tolist() == [0, 1, 0]
        for fn in plants:
            got = _run_slopes(fn, s, p, r, lam)
            for name, arr in ref.items():
                if name == "tmp":               # scratch
                    continue
                if name in ("u", "u1", "fw"):
                    assert np.array_equal(got[name][..., [0, 2]], arr[..., [0, 2]]), name
                else:
                    assert got[name].tobytes() == arr.tobytes(), name
    src = inspect.getsource(kernels_block.run_block)
    assert src.count("if st[k] == OK and (t1[k] < 0.0) != (t2[k] < 0.0):") == 1


def test_block_read_out_positivity_at_minus_one_is_equivalent():
    # mutants-equivalent.toml, kernels_block:267 (`not x + 1.0 > 0.0` -> `>= 0.0` in run_block's first read-out
    # test): the argument of the mark kernels_block:286 (the sharp tier's copy of the same chain): they differ only
    # at x == -1.0, where the read-out test just before has right side 0 and left side >= |dn| > 0 (kt >= 1) or
    # NaN, so the chain gives ILLCOND first.  Checked: the chain in the source, and both forms at x = -1.
    from symbt.numeric.core.limits import ILLCOND, KAPPA_MAX, OK, POSITIVITY, RANGE

    src = inspect.getsource(kernels_block.run_block)
    chain = ("ok = (kt[k] * (abs(u[j, k]) + abs(w[j, k])) * (abs(x + 1.0) + abs(x))\n"
             "                      <= KAPPA_MAX * abs(dn) * abs(x + 1.0))          # kernels.orbit\n"
             "                bad = (RANGE if not abs(x) < 1e300 else ILLCOND if not ok\n"
             "                       else POSITIVITY if not x + 1.0 > 0.0 else OK)")
    assert src.count(chain) == 1

    def status_of(x, u, w, kt, strict):
        dn = u - w
        ok = (kt * (abs(u) + abs(w)) * (abs(x + 1.0) + abs(x)) <= KAPPA_MAX * abs(dn) * abs(x + 1.0))
        pos = (x + 1.0 > 0.0) if strict else (x + 1.0 >= 0.0)
        return RANGE if not abs(x) < 1e300 else ILLCOND if not ok else POSITIVITY if not pos else OK

    n = 0
    for kt, u, tm in itertools.product((1.0, 3.0, 2.0 ** 24, math.inf, math.nan), (0.0, -3.5, 2.0 ** 60, 1e-300),
                                       (5e-324, 0.75, -4.0, 1e290)):
        w = u + tm
        dn = u - w
        if dn == 0.0 or not math.isfinite(dn) or tm / dn != -1.0:
            continue
        n += 1
        assert status_of(-1.0, u, w, kt, True) == status_of(-1.0, u, w, kt, False) == ILLCOND
    assert n > 20


COST_ONLY = [  # _slopes: a loop that runs in vain, a copy of equal values, a constant written to every member
    ("if nf > 0:\n        for j in range(N - 1):", "if nf >= 0:\n        for j in range(N - 1):"),   # :142
    ("if nf < B:", "if nf <= B:"),                                                                   # :146
    ("if nf > 0:\n            for j in range(1, N):", "if nf > 0:\n            for j in range(0, N):"),   # :155
    ("Bm[k] = -1.0", "Bm[k - 1] = -1.0"),                                                            # :67
    ("D[k] = 0.0", "D[k - 1] = 0.0"),                                                                # :69
    ("sc[k] = 1.0", "sc[k - 1] = 1.0"),                                                              # :76
]


@pytest.mark.parametrize("old,new", COST_ONLY)
def test_slopes_cost_only_mutants_are_equivalent(old, new):
    # mutants-equivalent.toml, kernels_block:142/146/155/67/69/76.  :142 (`nf >= 0`): with nf == 0 the forward
    # loop also runs and writes u[1:], which the backward transport (dst = u when nf == 0) then overwrites with
    # the same values it writes in the original.  :146 (`nf <= B`): with nf == B the backward transport also runs,
    # into tmp (nf > 0), and the copy back takes only members with fw == 0 -- none.  :155 (`range(0, N)`): the
    # copy also takes row 0, tmp[0, k] = u1[k] = u[0, k].  :67/69/76: `X[k - 1] = c` in the loop over k writes the
    # constant c to the indices -1, 0, ..., B - 2, i.e. every member (-1 is B - 1), and the loop body never reads
    # X: the same array when the loop ends.  Checked: the planted _slopes against the original on blocks with
    # nf = 0, 1, B - 1 and B forward members, both signs: every output bit for bit (tmp, scratch, excepted).
    fn = planted(kernels_block._slopes, old, new)
    p0, q0 = (-20.0, 10.0, 1.0), (1.0, 0.0, 0.9)
    r0 = [math.exp(q0[(j + 1) % 3] - q0[j]) for j in range(3)]
    lams = {"neg": [15.0, 5.0, 9.0], "pos": [21.0, 25.0, 30.0]}     # traces < 0 and > 0 at the paper's state
    for s in (1, -1):
        for mix in (lams["neg"], lams["pos"], lams["neg"][:2] + lams["pos"][:1], lams["neg"][:1] + lams["pos"][:2]):
            B = len(mix)
            p = np.tile(np.array(p0)[:, None], (1, B))
            r = np.tile(np.array(r0)[:, None], (1, B))
            a, b = _run_slopes(kernels_block._slopes, s, p, r, np.array(mix)), _run_slopes(fn, s, p, r, np.array(mix))
            for name in a:
                if name != "tmp":
                    assert a[name].tobytes() == b[name].tobytes(), (name, mix, s)


def test_flush_range_of_the_log_factor_is_equivalent():
    # mutants-equivalent.toml, kernels:361 and kernels_block:167 (`not abs(s) < 1e300` -> `not s < 1e300`, and
    # `<= 1e300`) on s = _logf(fh, fl): NaN outside fh in (1e-300, 1e300) -- both forms refuse it -- and inside
    # log(fh) + log1p(fl / fh) with |fl / fh| <= 2**-20 (the roundings of at most ANCHOR factors, each relative
    # eps (|x| + |1 + x|) / |1 + x| <= eps (1 + KAPPA_MAX), the read-out test's bound): |s| < 692, so the forms agree.
    # Checked: the line in both sources; _logf at the ends of its range with fl = +-2**-20 fh; the trusted rule
    # refuses |x| / |1 + x| > KAPPA_MAX for every kt >= 1.
    from symbt.numeric.core.limits import KAPPA_MAX

    for fn in (kernels._anchor1, kernels_block._anchor):
        assert inspect.getsource(fn).count("if not abs(s) < 1e300:") == 1
    for fh in (math.nextafter(1e-300, 1.0), 1e-200, 1.0, 1e250, math.nextafter(1e300, 0.0)):
        for fl in (0.0, fh * 2.0 ** -20, -fh * 2.0 ** -20):
            s = kernels._logf(fh, fl)
            assert abs(s) < 692 and (not abs(s) < 1e300) == (not s < 1e300) == (not abs(s) <= 1e300)
    for fh in (1e-300, 0.0, -1.0, 1e300, math.inf, math.nan):
        s = kernels._logf(fh, 0.0)
        assert math.isnan(s) and (not abs(s) < 1e300) == (not s < 1e300) == (not abs(s) <= 1e300)
    for x in (-1.0 + 2.0 ** -25, -1.0 - 2.0 ** -25, -1.0 + 2.0 ** -40):
        assert abs(x) / abs(1 + x) > KAPPA_MAX
        for u in (3.0, -0.5):
            w = u - 2.0 / x                                      # tm = 2, dn = u - w, x = tm / dn
            assert not kernels._trusted(1.0, u, w, u - w, x)


@pytest.mark.parametrize("func,old,new", [
    ("orbit", "wide = outQ.shape[1] > N", "wide = outQ.shape[1] < N"),                         # kernels:409
    ("orbit", "if i % anchor == 0:", "if i % anchor != 0:"),                                   # kernels:418
    ("_anchor1", "jn = j + 1 if j + 1 < N else 0", "jn = j + 1 if j + 1 < N else 1"),       # kernels:367
    ("orbit", "_dd_low(qh[j], ql[j], fh[j], fl[j], y)", "_dd_low(qh[j], ql[j - 1], fh[j], fl[j], y)"),   # kernels:430
    ("orbit", "outQ[0, j] = q0[j]", "outQ[0, j] = q0[j - 1]"),                                # kernels:404
])
def test_block_driver_sees_a_single_state_driver_mutant(monkeypatch, func, old, new):
    # the single-state driver (kernels.orbit, as python_orbit runs it) against the block: the statuses and rows differ
    from symbt.numeric.core.compile import clone

    monkeypatch.setattr(kernels, func, planted(getattr(kernels, func), old, new))
    monkeypatch.setattr(kernels, "_orbit_on_rows", clone(kernels.orbit, np=kernels._Rows))
    assert status("paths.block_driver.n3") == "failed"


def test_cheap_kernels_are_plain_python():
    # seed 41's kernels:338 (`jit=True` in cheap_kernels, uncovered: no claim builds it): a cost and route change
    # only -- numba's kernels are bit-identical -- but cheap_kernels' docstring promises plain Python (the boundary
    # of the emitted code in tests and benchmarks, runnable without numba): killed by this test, not by verify
    step = kernels.cheap_kernels()["step"]
    assert inspect.isfunction(step) and step.__module__ != "numba"
