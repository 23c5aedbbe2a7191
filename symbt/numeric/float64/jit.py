"""Lazy numba compilation of the fused kernels of :mod:`symbt.numeric.float64.kernels`.

Nothing here imports numba at module import time: :func:`kernel` compiles on
first use (a few seconds, then cached on disk) with the helpers of
:mod:`symbt.numeric.core.compile`, shared with the quad-double kernels: the
single-state orbit is the fused step of :mod:`symbt.numeric.core.fused`
instantiated with the float64 operators and the hooks of
:mod:`symbt.numeric.float64.kernels`.  Set
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

from collections.abc import Callable
from typing import Any

from ..core.compile import clone, instantiate, njit, numba_available
from ..core.errors import MissingDependencyError
from ..core.fused import SOURCE

__all__ = ["numba_available", "kernel", "orbit_with", "BACKENDS"]

BACKENDS = ("auto", "numba", "python")

_compiled: dict[str, Callable[..., Any]] = {}
_LOCK: dict[str, Any] = {}


def _small() -> dict[str, Callable[..., Any]]:
    """The double-double helpers of :mod:`.kernels`, compiled to be inlined."""
    from . import kernels as K

    small = {name: njit(getattr(K, name), inline="always") for name in ("_logf", "_dd_add")}
    small["_dd_position"] = njit(clone(K._dd_position, **small), inline="always")
    small["_dd_low"] = njit(clone(K._dd_low, **small), inline="always")
    return small


def _fused_step(replaced: dict[str, Callable[..., Any]] | None = None) -> Callable[..., Any]:
    """The fused step of :mod:`symbt.numeric.core.fused` in float64: the operators and the hooks of
    :mod:`.kernels` (hooks inlined; ``replaced`` hooks instead of some)."""
    from . import kernels as K

    shrunk = njit(K._shrunk, inline="always")
    hooks = {name: njit(clone(fn, _shrunk=shrunk, sharp_trace_kappa=K.sharp_compiled()), inline="always")
             for name, fn in {**K.HOOKS, **(replaced or {})}.items()}
    return instantiate(SOURCE, {**K.OPERATIONS, **hooks}, tag="f64", jit=True, inline=("slopes", "step"),
                       extra=K._EXTRA)["step"]


def _orbit(small: dict[str, Callable[..., Any]], hooks: dict[str, Callable[..., Any]] | None = None
           ) -> Callable[..., Any]:
    """The single-state driver :func:`.kernels.orbit` around the compiled fused step (named after what it
    inlines, so that numba's cache never serves a driver built on other helpers)."""
    from . import kernels as K

    env = {"step": _fused_step(hooks), **small}
    env["_anchor1"] = instantiate({"_anchor1": K._anchor1}, small, tag="f64", jit=True, extra=K._EXTRA)["_anchor1"]
    return instantiate({"orbit": K.orbit}, env, tag="f64", jit=True, extra=K._EXTRA)["orbit"]


def orbit_with(hooks: dict[str, Callable[..., Any]] | None = None, **overrides: Callable[..., Any]
               ) -> Callable[..., Any]:
    """The single-state kernel :func:`~symbt.numeric.float64.kernels.orbit` compiled with some of its
    helpers replaced (plain-Python functions, compiled here to be inlined; they may call ``_logf`` and
    ``_dd_add``), e.g. ``_dd_position``, the read-out of a stored position, and ``hooks`` replacing some of
    :data:`~symbt.numeric.float64.kernels.HOOKS` (measuring devices of the benchmarks).  Needs numba."""
    small = _small()
    for name, fn in overrides.items():
        small[name] = njit(clone(fn, **small), inline="always")
    return _orbit(small, hooks)


def _compile_all() -> None:
    import numba

    from ..core.compile import sources_digest
    from . import kernels as K
    from . import kernels_block as KB

    small = _small()
    la = {name: njit(getattr(KB, name), inline="always") for name in ("lam_add", "lam_split", "root_slope")}
    # named by a digest of every file it compiles in (numba's disk cache only watches kernels_block.py)
    deps = sources_digest([KB._slopes, KB.lam_add, K.sharp_trace_kappa], K._EXTRA)
    block = {"_slopes": njit(clone(KB._slopes, "_slopes_f64_" + deps, _shrink=njit(KB._shrink, inline="always"),
                                   lam_add=la["lam_add"], root_slope=la["root_slope"],
                                   sharp_trace_kappa=K.sharp_compiled()))}
    block["_anchor"] = njit(clone(KB._anchor, **small))
    block["sharp_trace_kappa"] = K.sharp_compiled()      # the sharp tier of the condition (run_block too)
    run_block = instantiate({"run_block": KB.run_block}, {**block, **small, "lam_split": la["lam_split"]},
                            tag="f64", jit=True, extra=K._EXTRA)["run_block"]
    ens = njit(clone(KB.ensemble, run_block=run_block, prange=numba.prange), parallel=True)
    _compiled.update(orbit=_orbit(small), run_block=run_block, ensemble=ens)


def kernel(name: str, backend: str = "auto") -> tuple[Callable[..., Any], str]:
    """The kernel ``name`` (``"orbit"``, ``"run_block"`` or ``"ensemble"``) for ``backend`` and the backend used.

    ``backend``: ``"auto"`` (numba when available, else plain Python),
    ``"numba"`` (:class:`MissingDependencyError` without numba) or ``"python"``.

    >>> kernel("ensemble", "python")[0].__name__
    'ensemble'
    """
    if backend == "python" or (backend == "auto" and not numba_available()):
        from . import block_python, kernels

        return (kernels.python_orbit if name == "orbit" else block_python.kernel(name)), "python"
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
