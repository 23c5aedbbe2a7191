"""The one compile helper of the fused kernels: lazy numba, functions cloned with substituted globals.

The fused step (:mod:`symbt.numeric.core.fused`) is plain Python written against the names of an
arithmetic (``add``, ``mul``, ``sqrt``, the hooks of each arithmetic); :func:`instantiate` turns it into
float64 kernels (:mod:`symbt.numeric.float64.jit`) and quad-double kernels
(:mod:`symbt.numeric.multiprec.qd`) by cloning each function with that arithmetic's functions as its
globals, compiled by numba or left as plain Python.  Nothing here imports numba at module import time.

numba compiles with ``cache=True`` (a ``__pycache__`` next to the source, or numba's user-wide cache
directory / ``NUMBA_CACHE_DIR`` when the package directory is read-only; without any writable location
it compiles without caching), ``fastmath=False`` (IEEE results, the same bits as plain Python) and
``error_model="numpy"`` (``x / 0`` is ``inf``, as in every context of :mod:`symbt.numeric.core.context`).

numba's disk cache keys a function by its file, name and line, and checks only that file's time stamp:
a clone of one source with other globals needs a name of its own, and one whose globals changed (an
edited arithmetic) must not load the old machine code.  :func:`instantiate` therefore names each clone
after the arithmetic and a digest of the files its globals come from.

Example
-------
>>> import math
>>> def hyp(a, b):
...     return sqrt(add(mul(a, a), mul(b, b)))
>>> f = instantiate({"hyp": hyp}, {"add": float.__add__, "mul": float.__mul__, "sqrt": math.sqrt},
...                 tag="float", jit=False)["hyp"]
>>> f(3.0, 4.0), f.__name__.startswith("hyp_float_")
(5.0, True)
"""

from __future__ import annotations

import hashlib
import inspect
import os
import types
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import Any

from .errors import importable

__all__ = ["numba_available", "njit", "clone", "instantiate", "sources_digest"]


def numba_available() -> bool:
    """True if numba imports (tried once) and ``SYMBT_NO_NUMBA`` is not set.

    >>> isinstance(numba_available(), bool)
    True
    """
    return os.environ.get("SYMBT_NO_NUMBA", "") in ("", "0") and importable("numba")


def njit(fn: Callable[..., Any], **opts: Any) -> Callable[..., Any]:
    """``fn`` compiled by numba (lazily, on its first call), with the disk cache if a location is writable.

    ``opts`` go to ``numba.njit`` (``inline="always"``, ``parallel=True``).  Needs numba
    (:func:`numba_available`).
    """
    import numba

    try:
        return numba.njit(cache=True, fastmath=False, error_model="numpy", **opts)(fn)
    except Exception:  # pragma: no cover - no writable cache location
        return numba.njit(cache=False, fastmath=False, error_model="numpy", **opts)(fn)


def clone(fn: Callable[..., Any], name: str | None = None, /, **overrides: Any) -> Callable[..., Any]:
    """A copy of ``fn`` whose module globals are overridden by ``overrides`` (``fn`` itself is unchanged).

    ``name`` renames the copy (its own numba cache entry).

    >>> def f(x):
    ...     return g(x) + 1
    >>> clone(f, "f2", g=abs)(-2), clone(f, g=float)(2)
    (3, 3.0)
    """
    g = dict(fn.__globals__)
    g.update(overrides)
    out = types.FunctionType(fn.__code__, g, fn.__name__, fn.__defaults__, fn.__closure__)
    out.__kwdefaults__ = fn.__kwdefaults__
    out.__module__ = fn.__module__
    if name is not None:
        out.__name__ = out.__qualname__ = name
    return out


def sources_digest(functions: Iterable[Any], extra: Iterable[Path] = ()) -> str:
    """A short hash of what the given functions are: the source files they come from (and ``extra``
    files), the qualified names of those without a source (builtins such as ``operator.add``).

    >>> import operator
    >>> sources_digest([operator.add]) != sources_digest([operator.mul])
    True
    >>> len(sources_digest([sources_digest]))
    10
    """
    files = set(extra)
    names = set()
    for fn in functions:
        py = getattr(fn, "py_func", fn)             # a numba dispatcher: its Python function
        try:
            src = inspect.getsourcefile(py)
        except TypeError:                            # a builtin: its name says what it computes
            src = None
        if src and Path(src).is_file():              # (not a doctest's or an interpreter's pseudo-file)
            files.add(Path(src))
        else:
            names.add("%s.%s" % (getattr(py, "__module__", None), getattr(py, "__qualname__", repr(py))))
    h = hashlib.sha256()
    for path in sorted(files):
        h.update(path.read_bytes())
    for name in sorted(names):
        h.update(name.encode())
    return h.hexdigest()[:10]


def _role(v: Any) -> str:
    py = getattr(v, "py_func", v)
    opts = getattr(v, "targetoptions", {})
    return "%s.%s%s" % (getattr(py, "__module__", ""), getattr(py, "__qualname__", repr(py)), sorted(opts.items()))


def instantiate(source: Mapping[str, Callable[..., Any]], arithmetic: Mapping[str, Any], *, tag: str,
                jit: bool, inline: Iterable[str] = (), extra: Iterable[Path] = (),
                operations: Mapping[str, str] | None = None) -> dict[str, Callable[..., Any]]:
    """Clone the functions of ``source`` (in dependency order: callees first) with ``arithmetic`` as globals.

    Each function sees the arithmetic and the functions instantiated before it; with ``jit`` each is
    compiled by numba (:func:`njit`; those named in ``inline`` with ``inline="always"``) and the
    arithmetic's functions must already be compiled.  Clones are named ``name_tag_digest``
    (:func:`sources_digest` of the source, the arithmetic and ``extra`` files, e.g. the limits the
    source reads), so that no two arithmetics and no two versions share a numba cache entry.
    ``operations`` (plain Python only, e.g. :data:`~.inline.FLOAT64_INLINE`): the arithmetic's calls that
    are single operations are written inline (:func:`~.inline.inlined`; bit-identical, without a Python
    call per operation).
    """
    inline = set(inline)
    digest = sources_digest(list(source.values()) + [v for v in arithmetic.values() if callable(v)], extra)
    # which function plays which role (add_d = operator.add), and how it is compiled, belong to the
    # arithmetic too: a caller inlines the callee's code, so its cache entry depends on both
    roles = sorted((k, _role(v)) for k, v in arithmetic.items()) + sorted((k, k in inline) for k in source)
    digest = hashlib.sha256((digest + repr(roles)).encode()).hexdigest()[:10]
    env = dict(arithmetic)
    out: dict[str, Callable[..., Any]] = {}
    for name, fn in source.items():
        cname = "%s_%s_%s" % (name, tag, digest)
        if operations is not None and not jit:
            from .inline import inlined

            f = inlined(fn, cname, operations, env)
        else:
            f = clone(fn, cname, **env)
        if jit:
            f = njit(f, inline="always") if name in inline else njit(f)
        env[name] = out[name] = f
    return out
