"""The emitted step's conditioning guard at its boundary (issue 21): just inside ``KAPPA_MAX`` a state, just
outside a refusal (``IllConditionedError``, C status ``SYMBT_TODA_ILL_CONDITIONED``).

The boundary is located independently of the emitted code: on the free chain (``p = 0``, ``q = 0``, a band
edge at ``lambda = 2``) by bisection on the status of ``symbt.numeric``'s plain-Python fused kernel (status
``ILLCOND`` against ``OK``), whose condition estimate is written separately from the emitted one.  The two
implementations round the estimate differently, so the tests stand a relative 2 % in ``lambda_2 - 2`` on
either side of the kernel's flip (the estimate moves ~2 % there, far above the rounding of either).
"""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest
from test_codegen_edges import CC, CStep, _compile

import symbt.codegen as cg
from symbt.claims.seed16 import GUARD_MU as MU
from symbt.claims.seed16 import cheap_flip
from symbt.generated import toda2, toda3
from symbt.numeric.core.limits import KAPPA_MAX

ILL_C = 5          # SYMBT_TODA_ILL_CONDITIONED


def flip(N):
    """``delta`` where the kernel's status turns from ILLCOND (closer to the edge) to OK (the bisection of the claim
    shipped.guard_boundary, which checks the shipped closed forms there)."""
    d = cheap_flip(N)
    assert d is not None                # the premise: ILLCOND at 1e-12, OK at 1e-2
    return d


def _args(N, delta):
    lam2 = 2.0 + delta
    return [0.0] * N, [0.0] * N, lam2 + MU, MU, 1


@pytest.mark.parametrize("mod", [toda2, toda3], ids=["toda2", "toda3"])
def test_closed_form_refuses_just_outside_and_steps_just_inside(mod):
    N = mod.N
    d = flip(N)
    assert 1e-9 < d * KAPPA_MAX < 1e3          # the flip is the 2**24 limit's: delta ~ 1/KAPPA_MAX
    inside, outside = _args(N, d * 1.02), _args(N, d / 1.02)
    pt, qt = mod.bt_step(*inside)
    from symbt.numeric import bt_step
    pn, qn = bt_step(*inside[:4], branch=1)
    assert np.allclose(pt, pn, rtol=0, atol=1e-6) and np.allclose(qt, qn, rtol=0, atol=1e-6)
    with pytest.raises(mod.IllConditionedError, match="ill-conditioned"):
        mod.bt_step(*outside)
    assert issubclass(mod.IllConditionedError, mod.NumericRangeError)
    # errors="mask": the refused element masked, the other one the same numbers as alone
    P = np.zeros((2, N))
    got = mod.bt_step(P, P, np.array([inside[2], outside[2]]), MU, 1, errors="mask")
    assert got[0].mask[:, 0].tolist() == [False, True] and np.array_equal(got[0][0].data, pt)


def test_c_closed_form_status_at_the_boundary(tmp_path):
    if CC is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    assert cg.main(["--target", "c", "--n", "2", "3", "--out", str(tmp_path), "-q"]) == 0
    for N in (2, 3):
        _compile(CC, tmp_path / f"toda{N}.c", tmp_path / f"libtoda{N}.so")
        step = CStep(tmp_path / f"libtoda{N}.so", N)
        d = flip(N)
        assert step(*_args(N, d * 1.02))[0] == 0
        assert step(*_args(N, d / 1.02))[0] == ILL_C


def test_loop_form_boundary_numpy_and_c(tmp_path):
    N = 5
    assert cg.main(["--n", str(N), "--out", str(tmp_path), "-q"]) == 0
    spec = importlib.util.spec_from_file_location("toda5_illcond", tmp_path / "toda5.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    d = flip(N)
    mod.bt_step(*_args(N, d * 1.02))
    with pytest.raises(mod.IllConditionedError):
        mod.bt_step(*_args(N, d / 1.02))
    if CC is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    assert cg.main(["--n", str(N), "--target", "c", "--out", str(tmp_path), "-q"]) == 0
    _compile(CC, tmp_path / "toda5.c", tmp_path / "libtoda5.so")
    step = CStep(tmp_path / "libtoda5.so", N)
    assert step(*_args(N, d * 1.02))[0] == 0
    assert step(*_args(N, d / 1.02))[0] == ILL_C
