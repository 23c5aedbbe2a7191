"""Lazy numba compilation of the fused kernels of :mod:`symbt.numeric.float64.kernels`.

Nothing here imports numba at module import time: :func:`kernel` compiles on
first use (a few seconds; cached on disk by numba's ``cache=True`` in a
``__pycache__`` next to the source, or in numba's user-wide cache directory /
``NUMBA_CACHE_DIR`` when the package directory is read-only; if no cache
location works the kernels are compiled without caching).  Set
``SYMBT_NO_NUMBA=1`` to force the numba-free paths (plain-Python single-orbit
kernel, vectorised numpy ensembles).

Example
-------
>>> from symbt.numeric.float64.jit import kernel
>>> run_block, backend = kernel("run_block", "python")
>>> backend
'python'
"""

from __future__ import annotations

import os
import types
from collections.abc import Callable
from typing import Any

from ..core.errors import MissingDependencyError, importable

__all__ = ["numba_available", "kernel", "BACKENDS"]

BACKENDS = ("auto", "numba", "python")

_compiled: dict[str, Callable[..., Any]] = {}
_LOCK: dict[str, Any] = {}


def numba_available() -> bool:
    """True if numba imports (tried once) and ``SYMBT_NO_NUMBA`` is not set.

    >>> isinstance(numba_available(), bool)
    True
    """
    return os.environ.get("SYMBT_NO_NUMBA", "") in ("", "0") and importable("numba")


def _njit(fn: Callable[..., Any], **opts: Any) -> Callable[..., Any]:
    import numba

    try:
        return numba.njit(cache=True, fastmath=False, error_model="numpy", **opts)(fn)
    except Exception:  # pragma: no cover - no writable cache location
        return numba.njit(cache=False, fastmath=False, error_model="numpy", **opts)(fn)


def _clone(fn: Callable[..., Any], **overrides: Any) -> Callable[..., Any]:
    """``fn`` with its module globals overridden (to call the compiled helpers)."""
    g = dict(fn.__globals__)
    g.update(overrides)
    return types.FunctionType(fn.__code__, g, fn.__name__, fn.__defaults__, fn.__closure__)


def _compile_all() -> None:
    import numba

    from . import kernels as K
    from . import kernels_block as KB

    small = {name: _njit(getattr(K, name), inline="always") for name in ("_logf", "_dd_add")}
    small["_dd_position"] = _njit(_clone(K._dd_position, **small), inline="always")
    slopes1 = _njit(K._slopes1)
    anchor1 = _njit(_clone(K._anchor1, **small))
    orbit = _njit(_clone(K.orbit, _slopes1=slopes1, _anchor1=anchor1, **small))
    slopes = _njit(_clone(KB._slopes, _shrink=_njit(KB._shrink, inline="always")))
    anchor = _njit(_clone(KB._anchor, **small))
    run_block = _njit(_clone(KB.run_block, _slopes=slopes, _anchor=anchor, **small))
    ens = _njit(_clone(KB.ensemble, run_block=run_block, prange=numba.prange), parallel=True)
    _compiled.update(orbit=orbit, run_block=run_block, ensemble=ens)


def kernel(name: str, backend: str = "auto") -> tuple[Callable[..., Any], str]:
    """The kernel ``name`` (``"orbit"``, ``"run_block"`` or ``"ensemble"``) for ``backend`` and the backend used.

    ``backend``: ``"auto"`` (numba when available, else plain Python),
    ``"numba"`` (:class:`MissingDependencyError` without numba) or ``"python"``.

    >>> kernel("ensemble", "python")[0].__name__
    'ensemble'
    """
    if backend == "python" or (backend == "auto" and not numba_available()):
        from . import kernels, kernels_block

        return getattr(kernels if name == "orbit" else kernels_block, name), "python"
    if backend not in BACKENDS:
        from ..core.errors import InvalidInputError

        raise InvalidInputError("backend must be one of %s, got %r" % (BACKENDS, backend))
    if not numba_available():
        raise MissingDependencyError("the numba backend needs numba: pip install 'symbt[fast]'")
    if not _compiled:
        import threading

        with _LOCK.setdefault("lock", threading.Lock()):
            if not _compiled:
                _compile_all()
    return _compiled[name], "numba"
