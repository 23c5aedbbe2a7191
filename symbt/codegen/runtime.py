"""Hand-written runtime pasted into every emitted Python module (part of the derivation hash).

Emitted modules may import only numpy and mpmath, so they carry their own copies
of the typed errors of :mod:`symbt.numeric` -- same names, same builtin
bases, same meaning, same ``condition``/``where`` attributes -- and of the
input checks.  ``errors="raise"`` (default) raises them; ``errors="mask"``
returns :class:`numpy.ma.MaskedArray` results masked at the batch elements where
the real function does not exist or a value is not finite (documented in each
function).  The mpmath flavour always raises.

:data:`ORBIT` is the orbit helper: ``bt_orbit`` iterates ``bt_step`` with the
centre of mass carried separately (as :func:`symbt.numeric.bt_orbit`): the map
only sees ``q - mean(q)``, the mean is accumulated with a compensated
(two-sum) sum, so the rounding of ``q~ = q + dq`` at ``|q| ~ 500`` does not
perturb the relative coordinates.

>>> "class NoRealMapError(ValueError)" in RUNTIME
True
"""
from __future__ import annotations

from ..numeric.core.limits import KAPPA_MAX

__all__ = ["RUNTIME", "ORBIT"]

RUNTIME = '''
import mpmath
import numpy as np


class InvalidInputError(ValueError):
    """Malformed input: non-finite values, bad shapes, branch not +-1, bad ``errors`` mode."""


class NoRealMapError(ValueError):
    """The real function does not exist here.

    ``condition`` is ``"trace"`` (``|tr L(lam_i)| <= 2``: a spectral parameter in a band) or
    ``"positivity"`` (some ``Etilde_j = E_j - x_j <= 0``: lam1, lam2 in different gaps);
    ``where`` holds up to five offending batch indices (empty for a single state).
    """

    def __init__(self, message, condition="", where=()):
        super().__init__(message)
        self.condition = condition
        self.where = tuple(where)


class NumericRangeError(OverflowError):
    """A value (intermediate or result) is outside the float64 range, or a division by zero."""


class IllConditionedError(NumericRangeError):
    """float64 cannot decide or compute the result here: a guard ``"illcond"`` failed (for the step, its
    condition estimate exceeds KAPPA_MAX = @@KAPPA@@).  ``symbt.numeric`` recomputes such states at higher
    precision; the ``_mp`` flavour at more digits does too.  ``where`` as for NoRealMapError."""

    def __init__(self, message, where=()):
        super().__init__(message)
        self.where = tuple(where)


_WHY = {"trace": "|tr L(%s)| <= 2, the spectral parameter lies in a band",
        "positivity": "%s = E - x <= 0 (lam1 and lam2 lie in different spectral gaps)"}
#: the likely causes of a non-finite value, named in NumericRangeError's message (a module of a user's
#: expressions sets its own after this runtime)
_RANGE_CAUSE = "overflow, |q_i - q_j| too large, or a degenerate eigenvector"
_ILLCOND = ("ill-conditioned: %s beyond the float64 condition limit KAPPA_MAX = @@KAPPA@@ (the result would "
            "not be trusted); symbt.numeric recomputes such states at higher precision, or call the _mp "
            "flavour at more digits")


def _Q(p, q):
    """Exact rational constant p/q at the caller's mpmath precision."""
    return mpmath.mpf(p) / q


def _array(x, name):
    try:
        raw = np.asarray(x)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"{name} must be a real numeric array") from exc
    if np.iscomplexobj(raw) or raw.dtype.kind in "US":      # never cast complex or parse text
        raise InvalidInputError(f"{name} must be real numbers")
    try:
        a = np.asarray(x, dtype=np.float64)
    except OverflowError as exc:                                # e.g. 10**400
        raise InvalidInputError(f"{name}: an integer beyond the float64 range; use the mpmath flavour") from exc
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"{name} must be a real numeric array") from exc
    if not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{name} must be finite (found NaN or inf)")
    return a


def _state(x, n, name):
    a = _array(x, name)
    if a.ndim < 1 or a.shape[-1] != n:
        raise InvalidInputError(f"{name} must have shape (..., {n}), got {a.shape}")
    return a


def _scalar(x, name="argument"):
    return _array(x, name)


def _branch(b):
    try:
        a = np.asarray(b, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError("branch must be +1 or -1") from exc
    if not np.all((a == 1.0) | (a == -1.0)):
        raise InvalidInputError("branch must be +1 or -1")
    return a


def _mode(errors):
    if errors not in ("raise", "mask"):
        raise InvalidInputError(f"errors must be 'raise' or 'mask', got {errors!r}")
    return errors


def _batch_of(shapes):
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError as exc:
        raise InvalidInputError(f"arguments do not broadcast: {shapes}") from exc


def _where(bad, batch):
    idx = np.flatnonzero(bad)
    if not batch or idx.size == 0:
        return (), ""
    where = [tuple(int(i) for i in np.unravel_index(k, batch)) for k in idx[:5]]
    return where, " (batch index %s%s)" % (", ".join(map(str, where)), ", ..." if idx.size > 5 else "")


def _guard(errors, batch, guards):
    """``guards``: (condition, label, value) with ``value > 0`` exactly where the real function exists.
    A non-finite value is a range problem (left to ``_finish``: NumericRangeError or masked); a finite
    value <= 0 raises NoRealMapError (errors='raise') or is masked: returns the mask of bad elements.
    A ``"range"`` guard's value need only be finite (an intermediate that must not overflow).  The guards
    are decided in order: after a non-finite one, later guards decide nothing for that element (their
    values are computed from it)."""
    bad = np.zeros(batch, dtype=bool)
    for condition, label, value in guards:
        v = np.broadcast_to(np.asarray(value, dtype=np.float64), batch)
        fin = np.isfinite(v)
        nok = fin & ~(v > 0) & ~bad if condition != "range" else np.zeros(batch, dtype=bool)
        if nok.any() and errors == "raise":
            where, txt = _where(nok, batch)
            if condition == "illcond":      # float64 cannot decide here (a guard "illcond": IllConditionedError)
                raise IllConditionedError(_ILLCOND % label + txt, where)
            raise NoRealMapError("no real map: " + _WHY[condition] % label + txt, condition, where)
        bad = bad | nok | ~fin
    return bad


def _finish(errors, bad, batch, outs):
    """Non-finite results (or guards) raise NumericRangeError, or are masked with ``bad`` (errors='mask')."""
    fin = np.ones(batch, dtype=bool) if bad is None else ~bad
    for o in outs:
        f = np.isfinite(o)
        # the trailing size spelled out: -1 cannot be inferred for an empty batch
        fin = fin & (f.reshape(batch + (int(np.prod(o.shape[len(batch):])),)).all(axis=-1)
                     if o.ndim > len(batch) else f)
    if errors == "raise":
        if not fin.all():
            where, txt = _where(~fin, batch)
            raise NumericRangeError("non-finite value in the float64 evaluation (" + _RANGE_CAUSE + "); use "
                                    "the mpmath flavour" + txt)
        return outs
    bad = ~fin
    res = []
    for o in outs:
        m = np.broadcast_to(bad.reshape(batch + (1,) * (o.ndim - len(batch))), o.shape)
        res.append(np.ma.masked_array(np.where(m, 0.0, o), mask=m.copy()))
    return res


def _pack(items, batch, shape):
    out = np.empty(batch + (len(items),), dtype=np.float64)
    for k, v in enumerate(items):
        out[..., k] = v
    return out.reshape(batch + shape)


def _mp_value(v, name):
    try:
        w = mpmath.mpmathify(v)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError(f"{name}: cannot convert {v!r}") from exc
    if isinstance(w, mpmath.mpc) or not mpmath.isfinite(w):
        raise InvalidInputError(f"{name} must be finite and real, got {v!r}")
    return w


def _mp_state(x, n, name):
    if isinstance(x, np.ndarray):
        x = x.tolist()
    try:
        v = [_mp_value(t, name) for t in x]
    except TypeError as exc:
        raise InvalidInputError(f"{name} must be a sequence of length {n}") from exc
    if len(v) != n:
        raise InvalidInputError(f"{name} must have length {n}, got {len(v)}")
    return v


def _mp_branch(b):
    # 1+0j == 1 in Python: refuse complex (and bool) by type before comparing
    if isinstance(b, (bool, complex, np.complexfloating, mpmath.mpc)) or b not in (1, -1):
        raise InvalidInputError("branch must be +1 or -1")
    return int(b)


def _div(a, b):
    """``a/b`` IEEE-style in mpmath (``x/0 = +-inf``; mpmath's ``x/inf = 0``): a slope through infinity."""
    if b:
        return a / b
    return mpmath.inf * mpmath.sign(a) if a else mpmath.nan


def _mp_guard(condition, label, value):
    if condition == "range":
        if not mpmath.isfinite(value):
            raise NumericRangeError("non-finite intermediate " + label)
    elif not value > 0:   # mpmath values are finite
        raise NoRealMapError("no real map: " + _WHY[condition] % label, condition)
'''.replace("@@KAPPA@@", str(int(KAPPA_MAX)))

ORBIT = '''

def bt_orbit(p, q, lam0, mu, n, branch=1):
    """``n`` Backlund steps from ``(p, q)``: arrays ``P, Q`` of shape ``(n + 1,) + p.shape``, ``P[0] = p``.

    float64, with the centre of mass carried separately: the step sees ``q - mean(q)``
    (the map commutes with ``q -> q + c``) and the mean is accumulated with a compensated
    (two-sum) sum, so the rounding of ``q`` at large ``|mean q|`` does not enter the dynamics.
    Raises the errors of ``bt_step`` (the map preserves the spectrum: if the first step exists,
    all do, up to round-off at the boundary of existence); ``n`` must be an integer >= 0.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidInputError(f"n must be a non-negative integer, got {n!r}")
    p0 = _state(p, N, "p")
    q0 = _state(q, N, "q")
    pn, qn = bt_step(p0, q0, lam0, mu if n else 0.0, branch)      # validates every argument
    P = np.empty((n + 1,) + pn.shape)
    Q = np.empty_like(P)
    P[0] = np.broadcast_to(p0, pn.shape)
    Q[0] = np.broadcast_to(q0, pn.shape)
    c_hi = np.mean(Q[0], axis=-1, keepdims=True)
    c_lo = np.zeros_like(c_hi)
    qr = Q[0] - c_hi
    pc = P[0]
    for i in range(1, n + 1):
        pc, qr = bt_step(pc, qr, lam0, mu, branch)
        s = np.mean(qr, axis=-1, keepdims=True)
        qr = qr - s
        t = c_hi + s                                   # two-sum (Knuth): c_hi + c_lo = exact sum
        bp = t - c_hi
        c_lo = c_lo + ((c_hi - (t - bp)) + (s - bp))
        c_hi = t
        P[i] = pc
        Q[i] = c_hi + (c_lo + qr)
    return P, Q


def bt_orbit_mp(p, q, lam0, mu, n, branch=1):
    """``n`` steps in mpmath at the current precision: two lists of ``n + 1`` states (lists of mpf)."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 0:
        raise InvalidInputError(f"n must be a non-negative integer, got {n!r}")
    P, Q = [_mp_state(p, N, "p")], [_mp_state(q, N, "q")]
    for _ in range(n):
        pn, qn = bt_step_mp(P[-1], Q[-1], lam0, mu, branch)
        P.append(pn)
        Q.append(qn)
    return P, Q
'''
