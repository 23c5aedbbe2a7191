"""The plain-Python fused step with float64's operations and hooks written inline (``core/inline.py``).

The rewrite must change how the step runs, never what it computes: the inlined instance (what
``backend="python"`` and ``auto`` without numba run) is compared bit for bit with the called form (the
same source and hooks, every hook a Python call: no rewrite at all) and with the numba instance, on cases
chosen so that each inlined hook does real work -- ``lam_split``'s low parts non-zero, the power-of-two
``rescale``, the sharp tier of the two-tier condition estimate -- each of which is checked to happen,
and on the failure statuses.  The rewrite's own rules are tested on small functions.
"""

import dis
import inspect
import math
import operator

import numpy as np
import pytest

from symbt.benchmarks.cases import cases
from symbt.numeric import bt_orbit
from symbt.numeric.core import fused
from symbt.numeric.core.compile import clone, instantiate, numba_available
from symbt.numeric.core.inline import FLOAT64_INLINE, inlined
from symbt.numeric.core.limits import ILLCOND
from symbt.numeric.core.spectral_sum import lam_split
from symbt.numeric.float64 import kernels as K

needs_numba = pytest.mark.skipif(not numba_available(), reason="numba not installed")
CASES = {c.name: c for c in cases(quick=True)}


def _called(**hooks):
    """The float64 step as the called form: every operation and hook a Python call (no rewrite)."""
    return instantiate(fused.SOURCE, {**K.OPERATIONS, **K.HOOKS, **hooks}, tag="f64called", jit=False,
                       extra=K._EXTRA)


def _orbit(step, p, q, lam0, mu, n, branch=1):
    """:func:`kernels.orbit` driving ``step``; (status, P, Q with the low parts)."""
    N = len(p)
    P, Q = np.empty((n + 1, N)), np.empty((n + 1, 2 * N))
    st = clone(K.orbit, step=step)(np.asarray(p, float), np.asarray(q, float), lam0 + mu, lam0 - mu, 2.0 * mu,
                                   branch, n, 1, K.ANCHOR, P, Q)
    return st, P, Q


def _same_bits(a, b):
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def test_the_inlined_step_calls_no_hook():
    hooks = set(K.HOOKS) | set(K.OPERATIONS) - {"sqrt"}
    for name in ("step", "slopes"):
        names = set(K.python_kernels()[name].__code__.co_names)
        assert not hooks & names, hooks & names
    # what stays a call: the sharp tier (large, rare), the step's call of slopes, sqrt, builtins
    assert {"sharp_trace_kappa", "slopes"} <= set(K.python_kernels()["step"].__code__.co_names)


def _counting(fn, counter, key):
    def wrapped(*a):
        counter[key] = counter.get(key, 0) + 1
        return fn(*a)
    return wrapped


# (case, steps): the paper's example with lam1 - lam2 != 2 mu in float64; the benchmark chains (n256-chain:
# lam0 = 3.4, mu = 0.3, the monodromy beyond 2**400, the cheap condition failing; n64-chain: the sharp tier)
HOOK_CASES = [("paper-lo", ([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 0.3, 60, 1)),
              ("n2-inner-gap", None), ("n64-chain", None), ("n256-chain", None)]


def _args(name, given):
    if given is not None:
        return given
    c = CASES[name]
    return list(c.p), list(c.q), c.lam0, c.mu, c.n, c.branch


@pytest.mark.parametrize("name,given", HOOK_CASES, ids=[n for n, _ in HOOK_CASES])
def test_inlined_step_equals_the_called_form_bit_for_bit(name, given):
    p, q, lam0, mu, n, branch = _args(name, given)
    seen: dict[str, int] = {}
    shrink = _counting(K._shrunk, seen, "rescale")
    sharp = _counting(K.sharp_trace_kappa, seen, "sharp")
    called = _called(rescale=clone(K._rescale, _shrunk=shrink), rescale_last=clone(K._rescale_last, _shrunk=shrink),
                     decided=clone(K._decided, sharp_trace_kappa=sharp),
                     sharpen=clone(K._sharpen, sharp_trace_kappa=sharp))["step"]
    st_c, P_c, Q_c = _orbit(called, p, q, lam0, mu, n, branch)
    st_i, P_i, Q_i = _orbit(K.python_kernels()["step"], p, q, lam0, mu, n, branch)
    assert st_c == st_i == 0
    assert _same_bits(P_c, P_i) and _same_bits(Q_c, Q_i)
    # each case exercises what it is here for
    lo1, _ = lam_split(lam0 + mu, lam0 - mu, 2.0 * mu)
    if name in ("paper-lo", "n256-chain"):
        assert lo1 != 0.0
    if name == "n256-chain":
        assert seen.get("rescale", 0) >= n
    if name in ("n64-chain", "n256-chain"):
        assert seen.get("sharp", 0) >= n


@needs_numba
@pytest.mark.parametrize("name,given", HOOK_CASES, ids=[n for n, _ in HOOK_CASES])
def test_python_and_numba_orbits_bit_identical_where_the_hooks_work(name, given):
    p, q, lam0, mu, n, branch = _args(name, given)
    Pp, Qp = bt_orbit(np.array(p), np.array(q), lam0, mu, n, branch=branch, backend="python")
    Pn, Qn = bt_orbit(np.array(p), np.array(q), lam0, mu, n, branch=branch, backend="numba")
    assert _same_bits(Pp, Pn) and _same_bits(Qp, Qn)


def _rows(a):
    return K._Row(a.tolist())


@pytest.mark.filterwarnings("ignore::RuntimeWarning")     # numpy scalars divided by zero (lam + p_j = 0)
def test_failure_statuses_are_those_of_the_called_form():
    # the called and the inlined step on numpy arrays, and the inlined step on lists of Python floats (what
    # python_orbit runs: its divisions by zero are IEEE's, not ZeroDivisionError)
    p = np.array([-20.0, 10.0, 1.0])
    r = np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    inl, called = K.python_kernels()["step"], _called()["step"]
    statuses = set()
    grid = np.r_[np.linspace(-25.0, 25.0, 2001) + 0.01, 20.0, -10.0, -1.0]     # and lam1 + p_j = 0 exactly
    for lam1 in grid:
        for lam2 in (lam1 - 0.5, lam1 - 3.0):
            out = []
            for step, conv in ((inl, np.copy), (called, np.copy), (inl, _rows)):
                w = [conv(np.zeros(3)) for _ in range(4)]
                tt = conv(np.zeros(4))
                pp, rr, pos = conv(p), conv(r), (conv(np.ones(3)), conv(np.zeros(3)))
                st = step(pp, rr, pos, float(lam1), float(lam2), float(lam1 - lam2), 1, *w, tt)
                out.append((st,) + tuple(np.asarray(x, np.float64).tobytes() for x in (pp, rr, *pos, tt)))
            assert out[0] == out[1] == out[2], (lam1, lam2)
            statuses.add(out[0][0])
    assert statuses >= {0, 1, 2, 3, ILLCOND}


def test_the_python_backend_runs_the_orbit_on_lists():
    from symbt.numeric.float64.jit import kernel

    assert kernel("orbit", "python")[0] is K.python_orbit


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@pytest.mark.parametrize("name,given", HOOK_CASES, ids=[n for n, _ in HOOK_CASES])
def test_python_orbit_on_lists_equals_the_orbit_on_arrays(name, given):
    p, q, lam0, mu, n, branch = _args(name, given)
    outs = []
    for orbit in (K.orbit, K.python_orbit):
        P, Q = np.empty((n + 1, len(p))), np.empty((n + 1, 2 * len(p)))
        st = orbit(np.array(p), np.array(q), lam0 + mu, lam0 - mu, 2.0 * mu, branch, n, 1, K.ANCHOR, P, Q)
        outs.append((st, P.tobytes(), Q.tobytes()))
    assert outs[0] == outs[1] and outs[0][0] == 0


def _trace_minus_two(lam):
    p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    tt = np.zeros(4)
    _called()["slopes"](p, r, lam, 0.0, 1, np.empty(3), 1, tt, 0)
    return abs(tt[0]) - 2.0


def test_near_a_band_edge_the_inlined_slopes_decline_as_the_called_form():
    lo, hi = -10.4, -10.28              # the paper's example: a band edge (|tr L| = 2) in between
    assert (_trace_minus_two(lo) > 0) != (_trace_minus_two(hi) > 0)
    for _ in range(60):                 # bisection to the computed edge: neither tier can decide there
        mid = 0.5 * (lo + hi)
        if (_trace_minus_two(mid) > 0) == (_trace_minus_two(lo) > 0):
            lo = mid
        else:
            hi = mid
    p, r = np.array([-20.0, 10.0, 1.0]), np.exp(np.diff([1.0, 0.0, 0.9, 1.0]))
    out = []
    for form in (K.python_kernels(), _called()):
        tt = np.zeros(4)
        out.append((form["slopes"](p, r, hi, 0.0, 1, np.empty(3), 1, tt, 0), tt.tobytes()))
    assert out[0] == out[1] and out[0][0] == ILLCOND


# the rewrite's rules, on small functions -------------------------------------------------------------

def _sign_scaled(x, c):
    if x < 0.0:
        y = c * x
        return -y
    return c * x


def _uses_sign(a, b):
    return add(_sign_scaled(sub(a, b), 0.5), 1.0)  # noqa: F821 - bound by inlined


def _writes(u, j, x):
    u[j] = x
    return True


def _nested_write(u, a):
    return add(_writes_ret(u, 0, a), 1.0)  # noqa: F821


def _root_write(u, a):
    if not _writes_ret(u, 0, a):  # noqa: F821
        return -1.0
    return u[0]


def test_bodies_with_early_returns_and_rebound_parameters():
    f = inlined(_uses_sign, "f", {**FLOAT64_INLINE, "_sign_scaled": "body"},
                {**{k: getattr(operator, k) for k in ("add", "sub")}, "_sign_scaled": _sign_scaled})
    g = clone(_uses_sign, add=operator.add, sub=operator.sub)
    for a, b in ((1.0, 3.0), (3.0, 1.0), (0.0, 0.0), (-0.0, 0.0), (math.inf, 1.0), (math.nan, 0.0)):
        assert repr(f(a, b)) == repr(g(a, b))
    assert "_sign_scaled" not in f.__code__.co_names and "add" not in f.__code__.co_names


def _ratio(a, b, c):
    return add(a, div(b, sub(c, a)))  # noqa: F821


def test_divisions_are_ieee_on_python_floats():
    f = inlined(_ratio, "f", FLOAT64_INLINE, K.OPERATIONS)
    assert f(1.0, 2.0, 3.0) == 2.0
    assert f(1.0, 2.0, 1.0) == math.inf and f(1.0, -2.0, 1.0) == -math.inf      # no ZeroDivisionError
    assert math.isnan(f(1.0, 0.0, 1.0))
    with pytest.raises(ZeroDivisionError):
        clone(_ratio, **K.OPERATIONS)(1.0, 2.0, 1.0)      # what the called form does on Python floats


def test_a_body_that_writes_is_written_inline_only_at_the_root_of_its_statement():
    env = {"add": operator.add, "_writes_ret": _writes}
    kinds = {**FLOAT64_INLINE, "_writes_ret": "body"}
    with pytest.raises(ValueError, match="root of its statement"):
        inlined(_nested_write, "f", kinds, env)
    f = inlined(_root_write, "f", kinds, env)
    u = np.zeros(1)
    assert f(u, 2.5) == 2.5 and u[0] == 2.5 and "_writes_ret" not in f.__code__.co_names


def test_tracebacks_of_inlined_code_name_the_source_lines_of_the_fused_step():
    code = K.python_kernels()["step"].__code__
    assert code.co_filename == fused.step.__code__.co_filename
    first = fused.step.__code__.co_firstlineno
    last = first + len(inspect.getsource(fused.step).splitlines())
    lines = {ln for _, _, ln in code.co_lines() if ln is not None}
    assert lines and all(first <= ln <= last for ln in lines)     # the hooks' code sits at their calls


def _keep(x, y):
    return x, y


def _uses_keep(a, b):
    a, b = _keep(a, b)
    return a + b


def test_a_self_assignment_a_substitution_leaves_is_dropped():
    # a body that returns its arguments leaves `a, b = a, b` at the call: the rewrite drops it (module docstring),
    # so the inlined function stores nothing.  Kills inline:185 (`_same` with `!=`: the same values, more work).
    g = inlined(_uses_keep, "uses_keep_inline", {"_keep": "body"}, {"_keep": _keep})
    assert g(1.0, 2.0) == 3.0
    assert [i.opname for i in dis.get_instructions(g) if i.opname.startswith("STORE")] == []
