"""`symbt codegen --target c`: self-contained C99 (libm only), compiled with the system compiler and called
through ctypes, against the 50-digit step and the 50-digit SymPy sources; status codes; --check."""
from __future__ import annotations

import ctypes
import math
import re
import shutil
import subprocess
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

import symbt.codegen as cg
from symbt.codegen import verify
from symbt.numeric import bt_step as numeric_step
from symbt.numeric.core import errors as numeric_errors
from symbt.reference.literal import reference_step

ROOT = Path(__file__).resolve().parents[1]
CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
NS = (3, 5)       # closed form, transfer-matrix form
OK, TRACE, POSITIVITY, RANGE, INVALID = 0, 1, 2, 3, 4
PAPER = ([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0)

pytestmark = pytest.mark.skipif(CC is None, reason="no C compiler (cc, gcc or clang) on PATH")


@pytest.fixture(scope="module")
def c_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("c")
    assert cg.main(["--project", str(ROOT), "--target", "c", "--n", *map(str, NS), "--out", str(out), "-q"]) == 0
    return out


class Lib:
    """ctypes wrapper of one compiled toda{N}.c."""

    def __init__(self, so, N):
        self.N = N
        lib = ctypes.CDLL(str(so))
        D, P = ctypes.c_double, ctypes.POINTER(ctypes.c_double)
        self.step = getattr(lib, f"toda{N}_bt_step")
        self.step.argtypes = [P, P, D, D, ctypes.c_int, P, P]
        self.inv = getattr(lib, f"toda{N}_invariants")
        self.inv.argtypes = [P, P, P]
        self.tr = getattr(lib, f"toda{N}_spectral_trace")
        self.tr.argtypes = [D, P, P, P]
        self.flow = getattr(lib, f"toda{N}_flow_field")
        self.flow.argtypes = [P, P, P, P, P]
        for f in (self.step, self.inv, self.tr, self.flow):
            f.restype = ctypes.c_int

    def arr(self, x=None):
        return (ctypes.c_double * self.N)(*([0.0] * self.N if x is None else x))

    def bt_step(self, p, q, lam0, mu, branch):
        pt, qt = self.arr([7.0] * self.N), self.arr([7.0] * self.N)
        rc = self.step(self.arr(p), self.arr(q), lam0, mu, branch, pt, qt)
        return rc, list(pt), list(qt)


@pytest.fixture(scope="module")
def libs(c_dir):
    out = {}
    for N in NS:
        so = c_dir / f"libtoda{N}.so"
        cmd = [CC, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC",
               "-o", str(so), str(c_dir / f"toda{N}.c"), "-lm"]
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        assert r.returncode == 0, r.stderr
        out[N] = Lib(so, N)
    return out


def test_files_check_and_self_containment(c_dir, tmp_path, capsys):
    assert cg.check(c_dir, NS, "c") == []
    assert cg.main(["--check", "--project", str(ROOT), "--target", "c", "--n", "3", "5", "--out", str(c_dir)]) == 0
    for N in NS:
        src, hdr = (c_dir / f"toda{N}.c").read_text(), (c_dir / f"toda{N}.h").read_text()
        assert cg.read_header(src)["target"] == f"toda{N} (N={N}, C99, {cg.form_of(N)} form)"
        assert re.findall(r"#include\s*(\S+)", src) == ["<math.h>", f'"toda{N}.h"']
        assert re.findall(r"#include\s*(\S+)", hdr) == []
        assert "int toda%d_bt_step(const double *p, const double *q, double lam0, double mu, int branch," % N in hdr
    # a hand edit of the C source is caught
    out = tmp_path / "c"
    shutil.copytree(c_dir, out)
    f = out / "toda5.c"
    f.write_text(f.read_text().replace("return SYMBT_TODA_OK;", "return 0;", 1))
    assert cg.main(["--check", "--project", str(ROOT), "--target", "c", "--n", "5", "--out", str(out)]) == 1
    assert "toda5.c: edited by hand" in capsys.readouterr().err


@pytest.mark.parametrize("N", NS)
def test_step_matches_the_50_digit_step(libs, N):
    lib, worst = libs[N], 0.0
    for p, q, l0, m in verify.map_states(N):
        for b in (1, -1):
            rc, pt, qt = lib.bt_step(p, q, l0, m, b)
            assert rc == OK
            with mp.workdps(50):
                rp, rq = reference_step(p, q, l0, m, branch=b)
                err = mp.sqrt(mp.fsum((mp.mpf(a) - c) ** 2 for a, c in zip(pt + qt, rp + rq)))
                worst = max(worst, float(err / mp.sqrt(mp.fsum(c ** 2 for c in rp + rq))))
    assert worst <= 1e-12, worst


@pytest.mark.parametrize("N", NS)
def test_invariants_trace_and_flow_match_the_sympy_source(libs, N):
    lib = libs[N]
    rng = np.random.default_rng(N)
    for p, q, l0, m in verify.map_states(N):
        H = lib.arr()
        assert lib.inv(lib.arr(p), lib.arr(q), H) == OK
        ref = verify.evaluate_source(N, "invariants", dict(p=p, q=q), dps=50)
        for k in range(N):   # error scale of a polynomial: the sum of |terms|
            assert abs(H[k] - float(ref[k])) <= 16 * 2.0 ** -52 * _abs_terms(N, k, p, q), (k, H[k], ref[k])
        t = ctypes.c_double()
        assert lib.tr(l0 + m, lib.arr(p), lib.arr(q), ctypes.byref(t)) == OK
        ref_t = verify.evaluate_source(N, "spectral_trace", dict(lam=l0 + m, p=p, q=q), dps=50)[0]
        assert abs(t.value - float(ref_t)) <= 1e-13 * max(1.0, abs(float(ref_t)))
        c = list(rng.uniform(-1, 1, N))
        qd, pd = lib.arr(), lib.arr()
        assert lib.flow(lib.arr(c), lib.arr(p), lib.arr(q), qd, pd) == OK
        ref = verify.evaluate_source(N, "flow_field", dict(c=c, p=p, q=q), dps=50)
        got = list(qd) + list(pd)
        assert max(abs(a - float(r)) for a, r in zip(got, ref)) <= 1e-12 * max(1.0, max(abs(float(r)) for r in ref))


def _abs_terms(N, k, p, q):
    """sum over the monomials of H_k of |monomial| at (p, q)."""
    from symbt.codegen.derive import _trace_ring

    gens = [0.0] + [abs(v) for v in p] + [math.exp(v) for v in q] + [math.exp(-v) for v in q] + [0.0] * N
    return sum(abs(int(c)) * math.prod(g ** e for g, e in zip(gens, mon)) for mon, c in _trace_ring(N).H[k].terms())


def _in_a_band(p, q):
    """A lambda with |tr L(lambda)| < 1.5 (inside a band), from symbt.numeric's trace on a grid."""
    from symbt.numeric import spectral_trace

    lam = np.linspace(-30.0, 30.0, 60001)
    tr = spectral_trace(lam, np.broadcast_to(p, (lam.size, len(p))), np.broadcast_to(q, (lam.size, len(q))))
    return float(lam[np.flatnonzero(np.abs(tr) < 1.5)[0]])


def _state(N):
    return PAPER[0] + [0.5] * (N - 3), PAPER[1] + [0.2] * (N - 3)


@pytest.mark.parametrize("N", NS)
def test_status_codes(libs, N):
    lib = libs[N]
    p, q = _state(N)
    assert lib.bt_step(p, q, 10.0, 5.0, 1)[0] == OK
    assert lib.bt_step(p, q, 10.0, 5.0, 0)[0] == INVALID
    assert lib.bt_step([math.nan] + p[1:], q, 10.0, 5.0, 1)[0] == INVALID
    assert lib.bt_step(p, q, math.inf, 5.0, 1)[0] == INVALID
    assert lib.step(None, lib.arr(q), 10.0, 5.0, 1, lib.arr(), lib.arr()) == INVALID
    # a spectral parameter in a band, and lambda_1, lambda_2 in different gaps: as symbt.numeric classifies them
    lam_band = _in_a_band(p, q) - 0.25
    with pytest.raises(numeric_errors.NoRealMapError):
        numeric_step(p, q, lam_band, 0.25)
    rc, pt, qt = lib.bt_step(p, q, lam_band, 0.25, 1)
    assert rc == TRACE and pt == [7.0] * N and qt == [7.0] * N       # outputs untouched on failure
    with pytest.raises(numeric_errors.NoRealMapError) as exc:
        numeric_step(p, q, -13.0, 3.0)
    assert exc.value.condition == "positivity"
    assert lib.bt_step(p, q, -13.0, 3.0, 1)[0] == POSITIVITY
    q_far = list(q)
    q_far[1] = 800.0
    assert lib.bt_step(p, q_far, 10.0, 5.0, 1)[0] == RANGE
    assert lib.inv(lib.arr(p), lib.arr(q_far), lib.arr()) == RANGE
