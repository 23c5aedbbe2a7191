r"""Ensembles out of core: :func:`dask_orbit` maps :func:`~symbt.numeric.bt_orbit` onto dask chunks.

Recipe.  The states are independent, so an ensemble ``(M, N)`` is chunked
along the state axis only and every chunk runs the fused ensemble kernel
(:mod:`symbt.numeric.float64.orbit`) through ``dask.array.map_blocks``; with
``every=k`` each chunk stores ``rows = 1 + ceil(n / k)`` states, so the
result ``(rows, M, N)`` can stay on disk / in a cluster (``.to_zarr``,
reductions such as ``Q[-1].mean(axis=0)`` without materialising it).
Per-state ``lam0, mu`` travel with the chunk as two extra columns.  Errors
are raised when a chunk is computed; :class:`NoRealMapError`'s ``where``
then holds indices of the whole ensemble (the chunk offset is added).

dask is optional: without it :func:`dask_orbit` raises
:class:`~symbt.numeric.core.errors.MissingDependencyError` (an ``ImportError``).

Example
-------
>>> import numpy as np
>>> from symbt.numeric import bt_orbit, dask_orbit
>>> p = np.array([-20.0, 10.0, 1.0]) + 0.01 * np.arange(6)[:, None]
>>> q = np.tile([1.0, 0.0, 0.9], (6, 1))
>>> P, Q = dask_orbit(p, q, 10.0, 5.0, 100, chunks=4, every=50)   # lazy dask arrays
>>> P.shape, P.chunks[1]
((3, 6, 3), (4, 2))
>>> bool(np.array_equal(P.compute(), bt_orbit(p, q, 10.0, 5.0, 100, every=50)[0]))
True
"""

from __future__ import annotations

from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.errors import InvalidInputError, MissingDependencyError, NoRealMapError
from ..core.inputs import check_steps
from ..core.problem import Float64Backend
from .kernels import orbit_rows

if TYPE_CHECKING:
    import dask.array as da
    import numpy.typing as npt

__all__ = ["dask_orbit"]


def _import_dask() -> ModuleType:
    try:
        import dask.array as da
    except ImportError as exc:
        raise MissingDependencyError("dask_orbit needs dask: pip install 'dask[array]'") from exc
    return da


def _chunk(block: npt.NDArray[np.float64], N: int, n: int, branch: int, every: int, backend: Float64Backend,
           block_info: dict[Any, Any] | None = None) -> npt.NDArray[np.float64]:
    from .orbit import float_orbit

    start = block_info[0]["array-location"][0][0] if block_info else 0
    try:
        P, Q = float_orbit(block[:, :N], block[:, N:2 * N], block[:, 2 * N], block[:, 2 * N + 1], n,
                           branch=branch, every=every, backend=backend)
    except NoRealMapError as exc:
        where = [(w[0] + start,) + tuple(w[1:]) for w in exc.where]
        raise NoRealMapError("%s [chunk starting at state %d]" % (exc, start), condition=exc.condition,
                             where=where) from None
    return np.stack([P, Q])


# p, q, lam0, mu: numpy array-likes or dask arrays (rebound to dask arrays below, hence Any)
def dask_orbit(p: Any, q: Any, lam0: Any, mu: Any, n: int, *, chunks: int | tuple[int, ...] | str = "auto",
               branch: int = 1, every: int = 1, backend: Float64Backend = "auto") -> tuple[da.Array, da.Array]:
    """Lazy ``bt_orbit`` of an ensemble: dask arrays ``P, Q`` of shape ``(rows, M, N)``.

    ``p, q``: ``(M, N)`` numpy or dask arrays; ``lam0, mu``: scalars or
    length-``M`` arrays; ``chunks``: states per chunk (an int, a tuple of
    chunk sizes or ``"auto"``; ignored for dask input, whose row chunks are
    used).  ``every``, ``branch`` as for :func:`~symbt.numeric.bt_orbit`; ``backend`` one of its float64
    names (:data:`~symbt.numeric.Float64Backend`), checked here (:class:`InvalidInputError`), not when a
    chunk is computed.

    >>> P, Q = dask_orbit(np.tile([-20.0, 10, 1], (3, 1)), np.tile([1.0, 0, 0.9], (3, 1)), 10.0, 5.0, 4,
    ...                   chunks=2, every=4)
    >>> P.shape, [round(float(v), 6) for v in P[-1, 0].compute()] == [round(float(v), 6) for v in P[-1, 2].compute()]
    ((2, 3, 3), True)
    """
    from ..core.inputs import check_branch
    from .orbit import check_orbit_backend

    check_orbit_backend(backend)
    da = _import_dask()
    branch = check_branch(branch)
    n, every = check_steps(n, every)
    p = p if isinstance(p, da.Array) else da.from_array(np.asarray(p, dtype=np.float64), chunks=(chunks, -1))
    q = q if isinstance(q, da.Array) else da.from_array(np.asarray(q, dtype=np.float64), chunks=p.chunks)
    if p.ndim != 2 or p.shape != q.shape:
        raise InvalidInputError("dask_orbit takes p, q of equal shape (M, N)")
    M, N = p.shape
    cols = []
    for name, v in (("lam0", lam0), ("mu", mu)):
        a = np.asarray(v, dtype=np.float64) if not isinstance(v, da.Array) else v
        if a.ndim == 0:
            a = da.full((M,), float(a), chunks=(p.chunks[0],))
        elif a.shape != (M,):
            raise InvalidInputError("%s must be a scalar or have shape (M,) = (%d,)" % (name, M))
        elif not isinstance(a, da.Array):
            a = da.from_array(a, chunks=(p.chunks[0],))
        cols.append(a.rechunk((p.chunks[0],))[:, None])
    X = da.concatenate([p.rechunk((p.chunks[0], N)), q.rechunk((p.chunks[0], N))] + cols, axis=1)
    X = X.rechunk((p.chunks[0], 2 * N + 2))
    rows = orbit_rows(n, every)
    out = da.map_blocks(_chunk, X, N, n, branch, every, backend, dtype=np.float64, new_axis=[0, 1],
                        chunks=((2,), (rows,), X.chunks[0], (N,)))
    return out[0], out[1]
