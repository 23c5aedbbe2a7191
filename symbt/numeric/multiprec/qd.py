r"""High precision, compiled: the Bäcklund orbit in quad-double arithmetic (numba), mpmath in and out.

A quad-double (:mod:`symbt.numeric.multiprec.qd_arith`) carries ``QD_BITS = 209`` bits
with the exponent range of a double; the step (:mod:`symbt.numeric.multiprec.qd_step`)
performs the operations of the Arb midpoint step in the same order.  This
module compiles both with numba on first use (``cache=True``; a few seconds the
first time, then loaded from numba's cache) and converts:

* mpf -> quad-double, exactly: the mantissa of ``x._mpf_`` peeled into 53-bit
  chunks (an mpf of at most ``212`` bits and exponent inside ``2**+-600``;
  anything else does not fit);
* quad-double -> mpf rounded to nearest at ``mp.prec``: the four doubles as
  integer mantissas and exponents (one compiled call for all stored values),
  summed exactly as one Python integer, rounded by ``mpmath.libmp.from_man_exp``.

Precision rule (:func:`qd_fits`): the orbit is used when
``mp.prec + QD_GUARD + 2 * n.bit_length() <= QD_BITS`` (``QD_GUARD = 16``),
the orbit guard growing like the Arb path's (error ``~ n**2`` ulps).
Measured (120-digit reference; paper example and random gap states,
``N = 2, 3, 5``, both branches): the unrounded quad-double orbit is within
``2**-216 .. 2**-220`` (relative to the largest state component) after one
step, ``2**-213`` after 10, ``2**-205`` after 100, ``2**-203.4`` after 1000 and
``2**-200.8`` after 10**4 steps, i.e. below ``2**(-209 - 8 + 2 n.bit_length())``
everywhere.  At the rule's boundary the quad-double error is therefore at most
``2**-24`` ulps of ``mp.prec``: the rounded result equals the Arb path's (in all
the cases above bit for bit), with 24 bits to spare for an ill-conditioned map
(near a band edge, condition ``4e7``, 10 steps: ``2**-179``, still ``2**-10``
ulps at 50 digits).  At ``mp.dps = 50`` (169 bits) the rule admits
``n <= 4095`` steps; one step up to ``mp.prec = 191`` (57 digits).

Numba missing, or ``SYMBT_NO_NUMBA=1``: :func:`qd_available` is False, and
:mod:`symbt.numeric.backends` does not choose this backend.

Example
-------
>>> import mpmath
>>> from symbt.numeric.multiprec.qd import qd_fits, qd_orbit_mp
>>> with mpmath.workdps(50):
...     print(qd_fits(mpmath.mp.prec, 10), qd_fits(mpmath.mp.prec + 40, 10))
...     P, Q = qd_orbit_mp([mpmath.mpf(-20), 10, 1], [1, 0, mpmath.mpf("0.9")], 10, 5, 10, every=10)
...     print(mpmath.nstr(Q[-1][0], 20))
True False
0.49085150918338141214
"""

from __future__ import annotations

import hashlib
import math
import os
import threading
from collections.abc import Callable, Sequence
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

import mpmath
import numpy as np

from ..core.compile import numba_available
from ..core.errors import InvalidInputError, MissingDependencyError, NoRealMapError, NumericRangeError
from ..core.limits import MAX_DQ_QD
from ..float64.kernels import orbit_rows

if TYPE_CHECKING:
    import numpy.typing as npt

    F64 = npt.NDArray[np.float64]

__all__ = ["qd_available", "qd_ready", "warm", "qd_fits", "qd_need", "qd_orbit_mp", "qd_kernel", "to_qd", "from_qd",
           "QD_GUARD", "QD_BITS"]

QD_BITS = 209
#: guard bits of the quad-double orbit beyond the caller's precision (plus ``2 * n.bit_length()``)
QD_GUARD = 16
_MAX_EXP = 600                           # |x| inside 2**+-600 (low components stay normal doubles)

_compiled: dict[str, Callable[..., Any]] = {}
_LOCK = threading.Lock()

#: always inlined (numba IR level)
_SMALL = ("two_sum", "quick_two_sum", "three_sum", "three_sum2", "neg", "mul_pwr2", "ldexp_qd", "_qrow")
#: inlined into the transcendental functions and the division, called from the step (compile time)
_BASIC = ("add", "sub", "add_d", "mul", "mul_d")
_FUNCS = ("div", "sqrt", "exp_parts", "exp", "expm1", "log1p")


def qd_available() -> bool:
    """True if the quad-double backend can run (numba importable and ``SYMBT_NO_NUMBA`` unset).

    >>> isinstance(qd_available(), bool)
    True
    """
    return numba_available()


_MARKER = "symbt-qd-ready"


def _marker_dirs() -> list[Path]:
    """Where the ready-marker may live: numba's cache locations for this package (``NUMBA_CACHE_DIR``,
    the ``__pycache__`` next to the sources), then a per-user directory."""
    dirs = [Path(os.environ["NUMBA_CACHE_DIR"])] if os.environ.get("NUMBA_CACHE_DIR") else []
    return dirs + [Path(__file__).parent / "__pycache__", Path.home() / ".cache" / "symbt"]


@cache
def _digest() -> str:
    """The quad-double sources' hash (and numba's version): a marker of other sources is stale."""
    from importlib.metadata import PackageNotFoundError, version

    h = hashlib.sha256()
    # numba freezes globals at compile time and checks only the calling file's time stamp, so the limits
    # the step reads (core/limits.py) belong to the sources whose hash marks the cache current
    here = Path(__file__).parent
    core = here.parent / "core"
    for path in (here / "qd.py", here / "qd_arith.py", here / "qd_step.py", core / "limits.py", core / "fused.py",
                 core / "compile.py"):
        h.update(path.read_bytes())
    try:
        h.update(version("numba").encode())
    except PackageNotFoundError:  # pragma: no cover
        pass
    return h.hexdigest()


def qd_ready() -> bool:
    """True if the compiled orbit is loaded in this process, or numba's disk cache holds it for the
    current sources (a marker written after the first successful compile, see :func:`warm`).

    ``backend="auto"`` takes the quad-double path only when it is ready: the first compile takes
    15-30 s (once per installation; loading it later under 1 s), which ``auto`` never imposes.

    >>> isinstance(qd_ready(), bool)
    True
    """
    if getattr(_compiled.get("qd_orbit"), "signatures", None):
        return True
    want = _digest()
    for d in _marker_dirs():
        try:
            if (d / _MARKER).read_text(encoding="utf-8").strip() == want:
                return True
        except OSError:
            continue
    return False


def _mark_ready() -> None:
    for d in _marker_dirs():
        try:
            d.mkdir(parents=True, exist_ok=True)
            tmp = d / (_MARKER + ".%d.tmp" % os.getpid())
            tmp.write_text(_digest() + "\n", encoding="utf-8")
            os.replace(tmp, d / _MARKER)
            return
        except OSError:
            continue


def _drop_stale_cache() -> None:
    """numba checks only the calling file's time stamp: after an edit of ``qd_arith.py`` it would load
    a kernel compiled from the old arithmetic.  Without a current marker, drop the cached quad-double
    kernels next to the sources so that they are compiled from the current ones."""
    if qd_ready():
        return
    cache_dir = Path(__file__).parent / "__pycache__"
    for f in list(cache_dir.glob("qd*.nbi")) + list(cache_dir.glob("qd*.nbc")):
        try:
            f.unlink()
        except OSError:
            pass


def warm() -> float:
    """Compile (or load) the quad-double orbit now; returns the seconds it took.

    Run once after installing (``python -m symbt.numeric.multiprec.qd``; 15-30 s, then cached on disk):
    from then on ``backend="auto"`` uses it for mpmath input whenever the precision fits.
    """
    import time

    t = time.perf_counter()
    with mpmath.workdps(50):
        qd_orbit_mp([mpmath.mpf(-20), mpmath.mpf(10), mpmath.mpf(1)], [mpmath.mpf(1), mpmath.mpf(0),
                    mpmath.mpf("0.9")], mpmath.mpf(10), mpmath.mpf(5), 2)
    return time.perf_counter() - t


def qd_need(prec: int, n: int) -> int:
    """Bits an ``n``-step orbit at ``prec`` bits needs: ``prec + QD_GUARD + 2 * n.bit_length()``.

    >>> qd_need(169, 10) == 169 + QD_GUARD + 8
    True
    """
    return prec + QD_GUARD + 2 * int(n).bit_length()


def qd_fits(prec: int, n: int) -> bool:
    """True if an ``n``-step quad-double orbit is as accurate as the Arb path at ``prec`` bits
    (``qd_need(prec, n) <= QD_BITS``).

    >>> qd_fits(169, 10), qd_fits(169, 10**6), qd_fits(200, 1)
    (True, False, False)
    """
    return qd_need(prec, n) <= QD_BITS


def _fma_intrinsic() -> Callable[..., Any]:
    """``fma(a, b, c)`` as LLVM's ``llvm.fma.f64`` (one rounding; hardware FMA where the CPU has it)."""
    from llvmlite import ir
    from numba import types
    from numba.extending import intrinsic

    @intrinsic
    def fma(typingctx: Any, a: Any, b: Any, c: Any) -> Any:
        sig = types.float64(types.float64, types.float64, types.float64)

        def codegen(context: Any, builder: Any, signature: Any, args: Any) -> Any:
            fn = builder.module.declare_intrinsic("llvm.fma", [ir.DoubleType()])
            return builder.call(fn, args)

        return sig, codegen

    return fma


def _two_prod_fma(a: float, b: float) -> tuple[float, float]:
    p = a * b
    return p, _fma(a, b, -p)             # type: ignore[name-defined]  # noqa: F821 - the compiled intrinsic


def _decompose(x: F64, out: Any) -> None:
    """Row ``i`` of ``x`` (``(k, 4)`` doubles) -> ``out[i] = (m0, m1, m2, m3, s1, s2, s3, e)``: integer mantissas
    (``|m| < 2**53``), shifts and exponent with ``sum x[i] = ((((m0 << s1) + m1) << s2) + m2 << s3) + m3) 2**e``
    (components sorted by exponent, zeros dropped)."""
    k = x.shape[0]
    for i in range(k):
        cnt = 0
        ms = np.zeros(4, np.int64)
        es = np.zeros(4, np.int64)
        for c in range(4):
            v = x[i, c]
            if v != 0.0:
                f, e = math.frexp(v)
                m = np.int64(f * 9007199254740992.0)            # f * 2**53, exact
                e -= 53
                pos = cnt
                while pos > 0 and es[pos - 1] < e:             # insertion sort, exponents descending
                    ms[pos] = ms[pos - 1]
                    es[pos] = es[pos - 1]
                    pos -= 1
                ms[pos] = m
                es[pos] = e
                cnt += 1
        for c in range(4):
            out[i, c] = ms[c]
        last = es[0]
        for c in range(1, 4):
            if c < cnt:
                out[i, 3 + c] = es[c - 1] - es[c]
                last = es[c]
            else:
                out[i, 3 + c] = 0
        out[i, 7] = last


def _compile() -> None:
    from ..core.compile import clone, instantiate, njit
    from ..core.fused import SOURCE
    from . import qd_arith as A
    from . import qd_step as S

    inl: dict[str, Callable[..., Any]] = {}
    try:
        fma = _fma_intrinsic()
        tp = njit(clone(_two_prod_fma, "two_prod_fma", _fma=fma), inline="always")
        tp(1.0 + 2.0 ** -30, 1.0 + 2.0 ** -30)
    except Exception:  # pragma: no cover - no FMA intrinsic: Dekker's split (same bits, slower)
        tp = njit(A.two_prod, inline="always")
    inl["two_prod"] = tp
    for name in _SMALL:
        inl[name] = njit(clone(getattr(A, name), **inl), inline="always")
    for name in ("renorm5", "renorm4"):      # branchy: a call (inlining it everywhere costs minutes of compile time)
        inl[name] = njit(clone(getattr(A, name), **inl))
    done = dict(inl)
    for name in _BASIC:
        fn = getattr(A, name)
        inl[name] = njit(clone(fn, name + "_inl", **inl), inline="always")
        done[name] = njit(clone(fn, **done))
    for name in _FUNCS:
        done[name] = njit(clone(getattr(A, name), **{**done, **inl}))
    # the fused step (core/fused.py) with the quad-double operations (calls) and hooks
    for name in ("_row", "_put", "_finite"):
        done[name] = njit(getattr(S, name))
    hooks = {name: njit(clone(fn, **done)) for name, fn in S.HOOKS.items()}
    ops = {name: done[fn] for name, fn in S.OPERATIONS.items()}
    fused = instantiate(SOURCE, {**ops, **hooks}, tag="qd", jit=True, extra=S._EXTRA)
    done["qd_orbit"] = njit(clone(S.qd_orbit, step=fused["step"], **done))
    done["decompose"] = njit(_decompose)
    _compiled.update(done)


def qd_kernel(name: str = "qd_orbit") -> Callable[..., Any]:
    """The compiled function ``name`` (an arithmetic function of :mod:`symbt.numeric.multiprec.qd_arith`,
    ``"qd_orbit"`` or ``"decompose"``); :class:`MissingDependencyError` without numba."""
    if not qd_available():
        raise MissingDependencyError("the qd backend needs numba: pip install 'symbt[fast]'")
    if not _compiled:
        with _LOCK:
            if not _compiled:
                _drop_stale_cache()
                _compile()
    return _compiled[name]


_M53 = (1 << 53) - 1
_LIMB_SHIFT = np.array([159, 106, 53, 0])


def to_qd(values: Sequence[Any]) -> F64 | None:
    """mpf values -> ``(k, 4)`` array of exact, non-overlapping chunks (the mantissa's 53-bit limbs, highest
    first; renormalised by the kernel), or ``None`` if one does not fit (more than 212 bits, exponent
    beyond ``2**+-600``, inf/nan).

    >>> to_qd([mpmath.mpf(3)]).tolist()
    [[0.0, 0.0, 0.0, 3.0]]
    """
    limbs, exps, signs = [], [], []
    for v in values:
        sign, man, exp, bc = v._mpf_
        if not man:
            if exp:                                       # inf or nan
                return None
            limbs.append((0, 0, 0, 0))
            exps.append(0)
            signs.append(1.0)
            continue
        if bc > 212 or not -_MAX_EXP <= exp + bc <= _MAX_EXP:
            return None
        m = int(man)
        limbs.append((m >> 159, (m >> 106) & _M53, (m >> 53) & _M53, m & _M53))
        exps.append(exp)
        signs.append(-1.0 if sign else 1.0)
    out = np.ldexp(np.array(limbs, dtype=np.float64).reshape(-1, 4),
                   np.array(exps, dtype=np.int64)[:, None] + _LIMB_SHIFT)
    return out * np.array(signs)[:, None]


def from_qd(x: F64, prec: int) -> list[Any]:
    """Quad-doubles (rows of ``x``, any shape ``(..., 4)``) -> mpf rounded to nearest at ``prec`` bits.

    >>> from_qd(np.array([[1.0, 2.0 ** -80, 0.0, 0.0]]), 53) == [mpmath.mpf(1)]
    True
    """
    flat = np.ascontiguousarray(x, dtype=np.float64).reshape(-1, 4)
    ints = np.empty((flat.shape[0], 8), np.int64)
    qd_kernel("decompose")(flat, ints)
    fme, new, cls = mpmath.libmp.from_man_exp, object.__new__, mpmath.mp.mpf
    out = []
    for m0, m1, m2, m3, s1, s2, s3, e in ints.tolist():
        v = new(cls)
        v._mpf_ = fme((((((m0 << s1) + m1) << s2) + m2) << s3) + m3, e, prec, "n")
        out.append(v)
    return out


def qd_orbit_mp(P: Sequence[Any], Q: Sequence[Any], lam0: Any, mu: Any, n: int, *, branch: int = 1,
                every: int = 1) -> tuple[list[list[Any]], list[list[Any]]]:
    """``n`` steps in quad-double from mpf inputs (as :func:`~symbt.numeric.multiprec.runners.flint_orbit`,
    real states).

    Raises :class:`NoRealMapError` as the Arb path, :class:`NumericRangeError` for values outside the
    quad-double range (inputs beyond ``2**+-600``, neighbour distances beyond 300, non-finite
    intermediates: the Arb path handles those), :class:`InvalidInputError` if ``mp.prec`` is too
    high for ``n`` steps (:func:`qd_fits`).
    """
    prec = mpmath.mp.prec
    if not qd_fits(prec, n):
        raise InvalidInputError("the qd backend carries %d bits: mp.prec = %d with %d steps needs %d "
                                "(use backend='flint' or 'auto')" % (QD_BITS, prec, n, qd_need(prec, n)))
    N = len(P)
    x = to_qd([mpmath.mpf(v) for v in list(P) + list(Q) + [lam0, mu]])
    if x is None:
        raise NumericRangeError("an input does not fit a quad-double (exponent beyond 2**+-%d)" % _MAX_EXP)
    rows = orbit_rows(n, every)
    outP, outQ = np.empty((rows, N, 4)), np.empty((rows, N, 4))
    fresh = not qd_ready()
    st, i = qd_kernel()(x[:N], x[N:2 * N], x[2 * N:], branch, n, every, outP, outQ)
    if fresh:
        _mark_ready()                    # compiled (and cached by numba) from the current sources
    if st == 1 or st == 2:
        raise NoRealMapError("no real Bäcklund map: |tr L(%s)| <= 2, the spectral parameter lies in a band"
                             % ("lam1 = lam0 + mu" if st == 1 else "lam2 = lam0 - mu"), condition="trace")
    if st == 3:
        raise NoRealMapError("no real Bäcklund map: some Etilde_j = E_j - x_j <= 0 (lam1 and lam2 lie in "
                             "different spectral gaps)", condition="positivity")
    if st != 0:
        raise NumericRangeError("quad-double step %d left the double exponent range (|q_{j+1} - q_j| > %g "
                                "or a non-finite intermediate)" % (i, MAX_DQ_QD))
    vals = from_qd(np.stack([outP, outQ], axis=1), prec)            # (rows, 2, N) values
    out: tuple[list[list[Any]], list[list[Any]]] = ([], [])
    for r in range(rows):
        base = 2 * N * r
        out[0].append(vals[base:base + N])
        out[1].append(vals[base + N:base + 2 * N])
    return out


if __name__ == "__main__":  # pragma: no cover - ``python -m symbt.numeric.multiprec.qd``
    if not qd_available():
        raise SystemExit("the quad-double backend needs numba: pip install 'symbt[fast]'")
    print("quad-double orbit compiled/loaded in %.1f s; backend='auto' now uses it for mpmath input" % warm())
