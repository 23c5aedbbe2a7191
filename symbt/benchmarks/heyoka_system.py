"""heyoka (optional peer): the same Hamilton's equations as the other contenders, as heyoka expressions.

heyoka is imported lazily (:func:`load`); without it every heyoka row is skipped with a message.
:func:`load` switches heyoka's on-disk JIT cache off for the process, so the reported build
times are those of a first run (the in-memory cache still serves identical systems).

* :func:`polynomial_system` (N <= 8): ``qdot_j = dG/dp_j``, ``pdot_j = -dG/dq_j`` for
  ``G = sum_k c_k H_k`` with the ``H_k`` as explicit polynomials in ``p_j`` and
  ``a_j = exp(q_{j+1} - q_j)`` (:func:`symbt.reference.taylor.hamilton_equations`); the constants
  are float64 or ``heyoka.real`` at a given precision (``const``).
* :func:`transfer_system` (any N): the field of :class:`symbt.numeric.flow.field.FlowField` --
  ``sum_i W_i grad tr L(lam_i)`` by the same forward/backward transfer sweeps
  (:func:`symbt.numeric.flow.field.transfer_gradient`) on expressions, the same nodes and weights.

State order: ``(q_1..q_N, p_1..p_N)``.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..numeric.flow.field import FlowField, transfer_gradient
from ..reference.taylor import hamilton_equations

__all__ = ["load", "polynomial_system", "parametric_system", "transfer_system", "real_prec"]


def load() -> tuple[Any, str]:
    """``(heyoka module or None, message)``."""
    try:
        import heyoka
    except Exception as exc:               # ImportError, or a broken LLVM runtime
        return None, "heyoka not available (pip install 'heyoka>=7'): %s" % exc
    try:                                   # cold JIT times: no on-disk cache of earlier runs (heyoka >= 7.10)
        heyoka.llvm_state.set_diskcache_enabled(False)
    except AttributeError:
        pass
    return heyoka, "heyoka %s (on-disk JIT cache disabled for this process)" % getattr(heyoka, "__version__", "?")


def real_prec(digits: int) -> int:
    """Bits of a ``heyoka.real`` for ``digits`` decimal digits (plus 4 guard bits)."""
    return int(np.ceil(digits * np.log2(10.0))) + 4


def _variables(hy: Any, N: int) -> tuple[list, list]:
    qs = list(hy.make_vars(*["q%d" % j for j in range(N)]))
    ps = list(hy.make_vars(*["p%d" % j for j in range(N)]))
    return qs, ps


def _poly(hy: Any, vals: list, P: dict, const: Callable[[Any], Any]) -> Any:
    terms = []
    for e, v in P.items():
        t = hy.expression(const(v))
        for x, k in zip(vals, e):
            for _ in range(k):
                t = t * x
        terms.append(t)
    return hy.sum(terms) if terms else hy.expression(const(0))


def polynomial_system(hy: Any, N: int, c: Sequence[Any], const: Callable[[Any], Any] = float) -> list:
    """``[(q_j, qdot_j)..., (p_j, pdot_j)...]`` for ``G = sum_k c_k H_k`` (explicit polynomials, N <= 8)."""
    qs, ps = _variables(hy, N)
    vals = ps + [hy.exp(qs[(j + 1) % N] - qs[j]) for j in range(N)]
    eqs = hamilton_equations(N, list(c))[: 2 * N]
    rhs = [_poly(hy, vals, P, const) for P in eqs]
    return list(zip(qs + ps, rhs))


def parametric_system(hy: Any, N: int) -> list:
    """As :func:`polynomial_system` with ``c_k`` = the runtime parameter ``par[k]`` (k < N)."""
    qs, ps = _variables(hy, N)
    vals = ps + [hy.exp(qs[(j + 1) % N] - qs[j]) for j in range(N)]
    rhs: list = [[] for _ in range(2 * N)]
    for k in range(N):
        unit = [0] * N
        unit[k] = 1
        for i, P in enumerate(hamilton_equations(N, unit)[: 2 * N]):
            if P:
                rhs[i].append(hy.par[k] * _poly(hy, vals, P, float))
    return list(zip(qs + ps, [hy.sum(t) if t else hy.expression(0.0) for t in rhs]))


def transfer_system(hy: Any, field: FlowField) -> list:
    """The :class:`~symbt.numeric.flow.field.FlowField` vector field as heyoka expressions (any N)."""
    N = field.N
    qs, ps = _variables(hy, N)
    R = [hy.exp(qs[(j + 1) % N] - qs[j]) for j in range(N)]
    gp: list = [[] for _ in range(N)]
    gr: list = [[] for _ in range(N)]
    for lam, ls, w in zip(field.nodes, field.log2_scale, field.weights):
        inv = float(np.ldexp(1.0, -int(ls)))
        a = [ps[j] * inv + float(lam) * inv for j in range(N)]
        r = [R[j] * inv for j in range(N)]
        da, dr = transfer_gradient(a, r, inv)
        for j in range(N):
            gp[j].append(float(w) * da[j])
            gr[j].append(float(w) * dr[j])
    GP = [hy.sum(x) for x in gp]
    rr = [R[j] * hy.sum(gr[j]) for j in range(N)]
    return [(qs[j], GP[j]) for j in range(N)] + [(ps[j], rr[j] - rr[(j - 1) % N]) for j in range(N)]
