"""Input normalisation and validation shared by the public functions.

float path: ``p, q`` are array-likes of identical shape ``batch + (N,)``; they
are turned into lists of N contiguous 1-D float64 arrays over the flattened
batch.  mpmath path (any argument an ``mpf``/``mpc``): ``p, q`` are flat
sequences of length N, converted with ``mpmath.mpf``; ``mpmath.iv`` intervals
select the interval context.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Sequence
from typing import TypeAlias, cast

import mpmath
import numpy as np
import numpy.typing as npt

from .context import FLOAT, IV, MP, Context, MPValue, Value
from .errors import InvalidInputError, NumericRangeError

#: a state as the public functions take it: float64 array-likes of shape ``batch + (N,)``, or a flat
#: sequence of mpmath numbers
StateLike: TypeAlias = npt.ArrayLike | Sequence[MPValue]
#: a real parameter (``lam0``, ``mu``) as the public functions take it: a real number or an array
#: broadcasting to the batch shape, or an mpmath number
ParamLike: TypeAlias = npt.ArrayLike | MPValue

_MP_TYPES = (mpmath.mpf, mpmath.mpc)
_REAL_SCALARS = frozenset([float, int, np.float64, np.float32, np.int64, np.int32])
_IV_TYPE = type(mpmath.iv.mpf(1))


def _kind(x: object) -> str | None:
    """'iv', 'mp' or None for the mpmath-ness of a (possibly nested) object."""
    if isinstance(x, np.ndarray):
        if x.dtype != object:
            return None
        x = x.ravel().tolist()
    if isinstance(x, _IV_TYPE):
        return "iv"
    if isinstance(x, _MP_TYPES):
        return "mp"
    if isinstance(x, (list, tuple)):
        kinds = {_kind(v) for v in x}
        if "iv" in kinds:
            return "iv"
        if "mp" in kinds:
            return "mp"
    return None


def pick_context(*objs: object) -> Context:
    """The context of the inputs: interval, mpmath or float64.

    >>> import mpmath
    >>> type(pick_context([1.0, 2.0], [mpmath.mpf(1), 0])).__name__
    'MPContext'
    """
    for o in objs:      # fast path: float arrays and Python floats are float64 input (no nested walk)
        if not (type(o) is float or (type(o) is np.ndarray and o.dtype.kind == "f")):
            break
    else:
        return FLOAT
    kinds = {_kind(o) for o in objs}
    if "iv" in kinds:
        return IV
    if "mp" in kinds:
        return MP
    return FLOAT


def _to_mp(ctx: Context, seq: StateLike, name: str) -> list[MPValue]:
    if isinstance(seq, np.ndarray):
        seq = seq.tolist()
    if not isinstance(seq, (list, tuple)):
        raise InvalidInputError("%s must be a flat sequence for mpmath inputs" % name)
    out = []
    for v in seq:
        if isinstance(v, (list, tuple, np.ndarray)):
            raise InvalidInputError("%s: mpmath inputs must be a single state (flat sequence)" % name)
        out.append(_mp_value(ctx, v, name, "%s: complex input is not supported", "%s contains a non-finite value"))
    return out


def _mp_value(ctx: Context, v: object, name: str, complex_msg: str, finite_msg: str) -> MPValue:
    """``v`` as an mpf (or an interval in the IV context); complex or non-finite values refused."""
    try:
        w = mpmath.iv.mpf(v) if ctx is IV else mpmath.mpmathify(v)
    except (TypeError, ValueError) as exc:
        raise InvalidInputError("%s: cannot convert %r" % (name, v)) from exc
    if ctx is IV:
        ok = mpmath.isfinite(w.a) and mpmath.isfinite(w.b)
    else:
        if isinstance(w, mpmath.mpc):
            raise InvalidInputError(complex_msg % name)
        ok = mpmath.isfinite(w)
    if not ok:
        raise InvalidInputError(finite_msg % name)
    return w


def as_state_pair(p: StateLike, q: StateLike,
                  *extra: object) -> tuple[Context, list[Value], list[Value], tuple[int, ...]]:
    """Return ``(ctx, P, Q, batch_shape)`` with P, Q lists of per-site values.

    >>> ctx, P, Q, shape = as_state_pair([[1.0, 2.0]] * 3, [[0.0, 0.0]] * 3)
    >>> len(P), P[0].shape, shape
    (2, (3,), (3,))
    """
    ctx = pick_context(p, q, *extra)
    if ctx is not FLOAT:
        P, Q = _to_mp(ctx, p, "p"), _to_mp(ctx, q, "q")
        if len(P) != len(Q):
            raise InvalidInputError("p and q have different lengths %d != %d" % (len(P), len(Q)))
        if len(P) < 2:
            raise InvalidInputError("need N >= 2 sites, got N = %d" % len(P))
        return ctx, P, Q, ()
    pa, qa, shape = validate_float_pair(p, q)
    return FLOAT, sites(pa), sites(qa), shape


def sites(a2d: npt.NDArray[np.float64]) -> list[npt.NDArray[np.float64]]:
    """Rows of the (N, B) transpose of a (B, N) array, as a list of contiguous arrays.

    >>> [x.tolist() for x in sites(np.array([[1.0, 2.0], [3.0, 4.0]]))]
    [[1.0, 3.0], [2.0, 4.0]]
    """
    t = np.ascontiguousarray(a2d.T)
    return [t[j] for j in range(t.shape[0])]


def _is_complex(x: object) -> bool:
    """True for complex input of any kind (numpy complex arrays/scalars, Python complex, mpc)."""
    if isinstance(x, (complex, np.complexfloating, mpmath.mpc)):
        return True
    if isinstance(x, np.ndarray):
        if x.dtype.kind == "c":
            return True
        if x.dtype != object:
            return False
        x = x.ravel().tolist()
    if isinstance(x, (list, tuple)):
        return any(_is_complex(v) for v in x)
    return False


def _has_text(x: object) -> bool:
    """True if ``x`` is, or contains, a string (numpy would parse ``"1.5"`` as a number)."""
    if isinstance(x, (str, bytes)):
        return True
    if isinstance(x, np.ndarray):
        if x.dtype.kind in "US":
            return True
        if x.dtype != object:
            return False
        x = x.ravel().tolist()
    if isinstance(x, (list, tuple)):
        return any(_has_text(v) for v in x)
    return False


def float_array(x: npt.ArrayLike, name: str) -> npt.NDArray[np.float64]:
    """``x`` as a float64 array, or :class:`InvalidInputError` -- the one conversion of real input.

    Refused, never cast: complex values, strings, dicts and other non-numbers (arrays of dates,
    durations or records too), ragged nesting, and integers beyond the float64 range
    (``10**400``: use mpmath inputs).
    Finiteness is left to the caller.

    >>> float_array([1, 2], "p").tolist()
    [1.0, 2.0]
    >>> float_array([10**400, 0], "p")
    Traceback (most recent call last):
    ...
    symbt.numeric.core.errors.InvalidInputError: p: an integer beyond the float64 range; use mpmath inputs
    """
    if isinstance(x, np.ndarray) and x.dtype.kind in "fiub":      # fast path: already numeric
        return np.asarray(x, dtype=np.float64)
    if _is_complex(x):
        raise InvalidInputError("%s: complex input is not supported (the real map takes real states)" % name)
    if _has_text(x) or isinstance(x, dict):
        raise InvalidInputError("%s must be a real numeric array, not text or a mapping" % name)
    try:
        a = np.asarray(x)
        kind = a.dtype.kind
        if kind not in "mMV":                   # dates, durations, records: numpy would cast them to numbers
            return np.asarray(a, dtype=np.float64)
    except OverflowError as exc:
        raise InvalidInputError("%s: an integer beyond the float64 range; use mpmath inputs" % name) from exc
    except (TypeError, ValueError) as exc:
        raise InvalidInputError("%s must be a real numeric array (same length in every row)" % name) from exc
    raise InvalidInputError("%s must be a real numeric array, not of dtype %s" % (name, a.dtype))


#: arrays up to this size are summed as Python floats by :func:`validate_float_pair` (cheaper than a reduction)
_FEW = 64


def validate_float_pair(p: npt.ArrayLike,
                        q: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], tuple[int, ...]]:
    """Validated float64 ``(pa, qa, batch_shape)`` with ``pa``, ``qa`` of shape (B, N).

    Complex input of any kind is refused (:class:`InvalidInputError`), never cast.

    >>> validate_float_pair([1.0, 2.0], [0.0, 0.0])[2]
    ()
    """
    pa = float_array(p, "p")
    qa = float_array(q, "q")
    if pa.shape != qa.shape:
        raise InvalidInputError("p and q shapes differ: %s vs %s" % (pa.shape, qa.shape))
    if pa.ndim == 0:
        raise InvalidInputError("p and q need a trailing site axis of length N >= 2")
    N = pa.shape[-1]
    if N < 2:
        raise InvalidInputError("need N >= 2 sites, got N = %d" % N)
    # a finite sum means finite entries; NaN, inf or an overflowed sum take the exact test (math.isfinite
    # and a list sum for a few sites: a numpy scalar reduction costs more than the step at N = 3)
    few = pa.size <= _FEW
    sp = sum(pa.ravel().tolist()) if few else pa.sum()
    sq = sum(qa.ravel().tolist()) if few else qa.sum()
    if not (math.isfinite(sp) and math.isfinite(sq)):
        if not (np.all(np.isfinite(pa)) and np.all(np.isfinite(qa))):
            raise InvalidInputError("p and q must be finite (found NaN or inf)")
    return pa.reshape(-1, N), qa.reshape(-1, N), pa.shape[:-1]


def prepare_scalar(ctx: Context, x: ParamLike, shape: tuple[int, ...], name: str) -> Value:
    """A real parameter (lam0, mu, lam) as a context value broadcast to the batch.

    >>> prepare_scalar(FLOAT, 2, (), "lam0")
    2.0
    """
    if ctx is not FLOAT:
        if isinstance(x, (list, tuple, np.ndarray)):
            raise InvalidInputError("%s must be a scalar for mpmath inputs" % name)
        return _mp_value(ctx, x, name, "%s must be a finite real number", "%s must be a finite real number")
    if type(x) in _REAL_SCALARS:          # fast path: plain real scalars
        try:
            v = float(cast(float, x))         # a real scalar type, just checked
        except OverflowError as exc:
            raise InvalidInputError("%s: an integer beyond the float64 range; use mpmath inputs" % name) from exc
        if not math.isfinite(v):
            raise InvalidInputError("%s must be finite" % name)
        return v
    if _is_complex(x):
        raise InvalidInputError("%s must be real" % name)
    if isinstance(x, _MP_TYPES):
        x = float(x)
    a = float_array(x, name)
    if not np.all(np.isfinite(a)):
        raise InvalidInputError("%s must be finite" % name)
    if a.ndim == 0:
        return float(a)
    try:
        b = np.broadcast_to(a, shape)
    except ValueError as exc:
        raise InvalidInputError("%s of shape %s does not broadcast to the batch shape %s"
                                % (name, a.shape, shape)) from exc
    return np.ascontiguousarray(b).reshape(-1)


def check_branch(branch: object) -> int:
    """``branch`` as +1 or -1, else :class:`InvalidInputError`.

    >>> check_branch(-1)
    -1
    """
    if isinstance(branch, bool) or not isinstance(branch, numbers.Integral) or branch not in (1, -1):
        raise InvalidInputError("branch must be +1 or -1, got %r" % (branch,))
    return int(branch)


def mp_output(P: Sequence[Value]) -> list[Value]:
    """The output list of an mpmath-arithmetic route: each value rounded afresh to the working precision (``+v``),
    so that a result never aliases an input or carries more digits than ``mp.dps``.

    >>> import mpmath
    >>> with mpmath.workdps(5):
    ...     mp_output([mpmath.pi])
    [mpf('3.1415939')]
    """
    return [+v for v in P]


def prepare_spectral_pair(ctx: Context, lam0: ParamLike, mu: ParamLike, shape: tuple[int, ...]) -> tuple[Value, Value]:
    """``(lam0, mu)`` as context values, with ``lam0 +- mu`` checked to be finite.

    Each of ``lam0`` and ``mu`` may be finite while ``lam0 + mu`` overflows; that is a range
    problem (:class:`NumericRangeError`), not a statement about the spectrum.

    >>> prepare_spectral_pair(FLOAT, 10, 5, ())
    (10.0, 5.0)
    """
    lam0 = prepare_scalar(ctx, lam0, shape, "lam0")
    mu = prepare_scalar(ctx, mu, shape, "mu")
    if ctx is FLOAT and type(lam0) is float and type(mu) is float:
        if not (math.isfinite(lam0 + mu) and math.isfinite(lam0 - mu)):
            raise NumericRangeError("lam0 +- mu overflows float64")
    elif ctx is FLOAT:
        with np.errstate(over="ignore", invalid="ignore"):
            ok = np.all(np.isfinite(lam0 + mu)) and np.all(np.isfinite(lam0 - mu))
        if not ok:
            raise NumericRangeError("lam0 +- mu overflows float64")
    return lam0, mu


_MAX_STEPS = 2 ** 62        # the kernels count steps in int64; far beyond any run


def check_steps(n: object, every: object) -> tuple[int, int]:
    """Validated ``(n, every)``: non-negative and positive integers.

    ``every > n`` stores the same rows as ``every = n`` (the initial and the final state) and
    is returned as such, so that any Python integer works; ``n`` must fit an int64.

    >>> check_steps(10, 3), check_steps(10, 10**20)
    ((10, 3), (10, 10))
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidInputError("n must be a non-negative integer, got %r" % (n,))
    if n > _MAX_STEPS:
        raise InvalidInputError("n = %d steps is beyond the int64 range of the kernels" % n)
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise InvalidInputError("every must be a positive integer, got %r" % (every,))
    return int(n), int(min(every, max(n, 1)))
