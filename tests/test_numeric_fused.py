"""The fused step written once (``core/fused.py``) and the one compile helper (``core/compile.py``).

The float64 kernel and the quad-double orbit are instantiations of one source; what differs is the
arithmetic and its hooks.  The numbers of each instantiation are tested elsewhere against independent
routes (``test_numeric_fast.py``: float64 against the 50-digit literal map and the general path;
``test_numeric_qd.py``: quad-double against 120 digits and Arb); here: that there is one source, that
each arithmetic keeps its own decisions, and that the compile helper keys every clone by what it is.
"""

import math
import operator

import mpmath
import numpy as np
import pytest

from symbt.numeric.core import fused
from symbt.numeric.core.compile import clone, instantiate, numba_available, sources_digest
from symbt.numeric.core.limits import ILLCOND, OK
from symbt.numeric.float64 import kernels
from symbt.numeric.multiprec import qd_step
from symbt.numeric.multiprec.qd import from_qd, to_qd
from symbt.reference.literal import reference_step

needs_numba = pytest.mark.skipif(not numba_available(), reason="numba not installed")


def test_float64_and_quad_double_steps_are_one_source():
    for name in ("step", "slopes"):
        src = getattr(fused, name).__code__
        assert qd_step.python_kernels()[name].__code__ is src
        # plain-Python float64: the same source with its single operations written inline (core/inline.py)
        f64 = kernels.python_kernels()[name].__code__
        assert (f64.co_filename, f64.co_firstlineno) == (src.co_filename, src.co_firstlineno)
        assert not {"add", "sub", "mul", "div", "ld", "st", "hi"} & set(f64.co_names)
        assert {"add", "ld"} <= set(src.co_names)
    # and the drivers call those instances
    assert kernels.orbit.__globals__["step"] is kernels.python_kernels()["step"]
    assert qd_step.qd_orbit.__globals__["step"] is qd_step.python_kernels()["step"]


@needs_numba
def test_compiled_kernels_run_the_one_source():
    from symbt.numeric.float64.jit import kernel
    from symbt.numeric.multiprec.qd import qd_kernel

    f64_step = kernel("orbit", "numba")[0].py_func.__globals__["step"]
    qd_step_ = qd_kernel("qd_orbit").py_func.__globals__["step"]
    for step in (f64_step, qd_step_):
        assert step.py_func.__code__ is fused.step.__code__
    assert f64_step.py_func.__name__ != qd_step_.py_func.__name__        # own numba cache entries


def test_the_source_alone_does_not_run():
    with pytest.raises(TypeError, match="instantiated"):
        fused.step(np.zeros(2), np.ones(2), None, 1.0, 0.0, 1.0, 1, *[np.empty(2)] * 4, np.zeros(4))


def _near_edge_state():
    """The paper's example with lam0 moved so that tr L(lam1) is 2 + 1e-9 (mpmath root of tr - 2)."""
    p, q = [-20.0, 10.0, 1.0], [1.0, 0.0, 0.9]
    from symbt.numeric import spectral_trace

    with mpmath.workdps(40):
        P, Q = [mpmath.mpf(x) for x in p], [mpmath.mpf(x) for x in q]
        edge = mpmath.findroot(lambda lam: spectral_trace(lam, P, Q) - 2, 10.3)
        slope = mpmath.diff(lambda lam: spectral_trace(lam, P, Q), edge)
        lam1 = edge + mpmath.mpf("1e-9") / slope
    return np.array(p), np.array(q), float(lam1)


def test_each_arithmetic_keeps_its_own_decisions_near_a_band_edge():
    # float64 cannot decide |tr| > 2 at tr - 2 ~ 1e-9 (its hook answers ILLCOND); the quad-double hooks
    # have no condition test: the same source decides and its slopes match the 40-digit literal map
    p, q, lam1 = _near_edge_state()
    r = np.exp(np.diff(np.r_[q, q[0]]))
    tt = np.zeros(4)
    assert kernels.python_kernels()["slopes"](p, r, lam1, 0.0, 1, np.empty(3), 1, tt, 0) == ILLCOND
    assert abs(tt[0] - 2) < 1e-6
    mu = 0.5
    lam0 = lam1 - mu
    with mpmath.workdps(60):
        x = to_qd([mpmath.mpf(v) for v in list(p) + list(q) + [lam0, mu]])
        outP, outQ = np.empty((2, 3, 4)), np.empty((2, 3, 4))
        status, _ = qd_step.qd_orbit(x[:3], x[3:6], x[6:], 1, 1, 1, outP, outQ)
        assert status == OK
        got = from_qd(np.stack([outP[1], outQ[1]]), 200)
        ref_p, ref_q = reference_step([mpmath.mpf(v) for v in p], [mpmath.mpf(v) for v in q],
                                      mpmath.mpf(lam0), mpmath.mpf(mu))
        err = max(abs(a - b) for a, b in zip(got, list(ref_p) + list(ref_q)))
        # the map's condition near the edge is ~1/sqrt(tr - 2) ~ 3e4 (x 1e2 for the inputs): 2**-190 leaves
        # the quad-double's 209 bits minus that, and fails if a decision (branch, direction) were wrong
        assert err < 2.0 ** -170, float(err)


def _hyp(a, b):
    return sqrt(add(mul(a, a), mul(b, b)))  # noqa: F821 - bound by instantiate


def test_instantiate_binds_the_arithmetic_and_names_each_clone_by_it(tmp_path):
    float_ops = {"add": operator.add, "mul": operator.mul, "sqrt": math.sqrt}
    f = instantiate({"hyp": _hyp}, float_ops, tag="t", jit=False)["hyp"]
    g = instantiate({"hyp": _hyp}, {**float_ops, "add": operator.sub}, tag="t", jit=False)["hyp"]
    assert f(3.0, 4.0) == 5.0 and g(5.0, 4.0) == 3.0
    assert f.__name__ != g.__name__                 # another arithmetic: another cache entry
    swapped = instantiate({"hyp": _hyp}, {**float_ops, "add": operator.mul, "mul": operator.add}, tag="t",
                          jit=False)["hyp"]
    assert swapped.__name__ != f.__name__           # same functions in other roles
    limit = tmp_path / "limits.py"
    limit.write_text("X = 1\n")
    a = instantiate({"hyp": _hyp}, float_ops, tag="t", jit=False, extra=[limit])["hyp"].__name__
    limit.write_text("X = 2\n")
    b = instantiate({"hyp": _hyp}, float_ops, tag="t", jit=False, extra=[limit])["hyp"].__name__
    assert a != b                                   # an edited dependency is never loaded from a stale cache
    assert sources_digest([_hyp]) == sources_digest([_hyp])


def test_clone_leaves_the_original_alone():
    h = clone(_hyp, "hyp2", add=operator.add, mul=operator.mul, sqrt=math.sqrt)
    assert h(6.0, 8.0) == 10.0 and h.__name__ == "hyp2"
    with pytest.raises(NameError):
        _hyp(1.0, 1.0)


@needs_numba
def test_jit_instances_with_other_globals_do_not_share_machine_code():
    float_ops = {"add": operator.add, "mul": operator.mul, "sqrt": math.sqrt}
    f = instantiate({"hyp": _hyp}, float_ops, tag="t", jit=True)["hyp"]
    g = instantiate({"hyp": _hyp}, {**float_ops, "add": operator.sub}, tag="t", jit=True)["hyp"]
    assert (f(3.0, 4.0), g(5.0, 4.0)) == (5.0, 3.0)
