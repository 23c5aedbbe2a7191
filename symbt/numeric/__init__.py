r"""Numerics of the two-parameter Bäcklund maps of the periodic Toda chain.

sympy-, scipy- and matplotlib-free; float64 (numpy, batched) and mpmath paths
share one implementation written against a small arithmetic *context*
(:mod:`symbt.numeric.core.context`; python-flint Arb balls in :mod:`symbt.numeric.multiprec.arb`,
``mpmath.iv`` intervals experimentally).

Backends (chosen automatically; optional extras are imported lazily)
--------------------------------------------------------------------
* float64, one state: the fused kernel :mod:`symbt.numeric.float64.kernels` (numba
  when installed, compiled on first use and cached; plain Python otherwise);
* float64 ensembles ``(M, N)``: the fused block kernel on all cores (numba) or
  vectorised numpy (:mod:`symbt.numeric.float64.orbit`); ``every=k`` stores every
  k-th state; :func:`dask_orbit` maps ensembles onto dask chunks;
* mpmath numbers: Arb at the caller's precision plus guard bits via
  python-flint (:mod:`symbt.numeric.backends`), else mpmath (gmpy2-backed when
  installed);
* ``bt_orbit(..., certified=True)`` / :func:`certified_orbit`: rigorous
  enclosures from Arb ball arithmetic (:mod:`symbt.numeric.multiprec.certified`).

Conventions
-----------
* State: ``p, q`` with a trailing site axis of length ``N >= 2`` and any
  leading batch axes (float64), or flat sequences of ``mpmath.mpf`` (one
  state; results are lists of mpf at the current ``mp.dps``).
* Lax matrix ``L(lam) = l_N ... l_1``, ``l_j = [[lam + p_j, -e^{q_j}], [e^{-q_j}, 0]]``;
  ``tr L(lam) = sum_k H_k lam^k``, ``H_N = 1`` (:func:`invariants` returns
  ``H_0..H_{N-1}``).  Spectral parameters ``lam1 = lam0 + mu``, ``lam2 = lam0 - mu``.
* ``branch`` in ``{+1, -1}`` is the sign of ``sqrt(tr^2 - 4)`` in the paper's
  eq. (xy).  Both branches are connected to the identity as ``mu -> 0``;
  ``branch = -1`` at ``mu`` equals ``branch = +1`` at ``-mu`` and is its inverse.
* Real Φ on the map (corrects eq. newkmu, which only holds for ``tr > 2``):
  ``Φ = sum_k ln|(eta_k+mu)/(eta_k-mu)| = branch * (-sgn(tr1) arccosh(|tr1|/2)
  - sgn(tr2) arccosh(|tr2|/2))``.
* Flow coefficients (eq. eqdisc): ``c_k = -branch * int_{lam0-mu}^{lam0+mu}
  lam^k / sqrt(tr^2 - 4) dlam``.

Errors
------
:class:`InvalidInputError` (non-finite input, mismatched shapes, ``N < 2``,
bad branch), :class:`NoRealMapError` (``|tr L(lam_i)| <= 2``, or some
``Etilde_j <= 0`` -- ``lam1``, ``lam2`` in different spectral gaps; its
``condition`` and ``where`` attributes say which and for which batch rows),
:class:`NumericRangeError` (beyond float64 range, e.g. ``|q_{j+1} - q_j| > 700``),
:class:`QuadratureError`, :class:`MissingDependencyError` (an ``ImportError``: a
requested optional backend is not installed).  Results are never silently NaN/inf.  ``mu = 0``
returns copies of the input.

Accuracy
--------
The float64 step is accurate to a few ulps of the state (normwise relative
error <= ~2e-15 against 50-digit references, for mu from 1e-14 to 1e2,
|q| ~ 800, lam0 = 1e5, N up to 64); see :mod:`symbt.numeric.core.step` for the
formulation and ``tests/test_numeric_*.py`` for the measurements.

Example
-------
>>> import numpy as np
>>> from symbt.numeric import bt_step, bt_orbit, invariants, phi
>>> p, q = np.array([-20.0, 10.0, 1.0]), np.array([1.0, 0.0, 0.9])
>>> pt, qt = bt_step(p, q, 10.0, 5.0)
>>> bool(np.allclose(invariants(pt, qt), invariants(p, q), rtol=1e-12))
True
>>> round(float(phi(p, q, 10.0, 5.0)), 8)
14.8058093
>>> P, Q = bt_orbit(p, q, 10.0, 5.0, 100)      # shape (101, 3)
"""

from .backends import BackendName
from .core.errors import InvalidInputError, MissingDependencyError, NoRealMapError, NumericRangeError, QuadratureError
from .core.problem import CertifiedMethod, Float64Backend
from .dispatch import bt_orbit, bt_step
from .float64.dask_orbit import dask_orbit
from .flow.coefficients import flow_coefficients
from .flow.field import FlowField
from .flow.invariants import invariants, spectral_trace
from .flow.phi import phi
from .multiprec.certified import certified_orbit

__all__ = [
    "bt_step",
    "bt_orbit",
    "certified_orbit",
    "dask_orbit",
    "invariants",
    "spectral_trace",
    "phi",
    "flow_coefficients",
    "FlowField",
    "InvalidInputError",
    "NoRealMapError",
    "NumericRangeError",
    "QuadratureError",
    "MissingDependencyError",
    "BackendName",
    "Float64Backend",
    "CertifiedMethod",
]
