"""Numerics for the Bäcklund maps of the periodic Toda chain (float64 and mpmath).

Placeholder -- full docstring below is filled in later.
"""
from .errors import InvalidInputError, NoRealMapError, NumericRangeError, QuadratureError
from .lax import invariants, spectral_trace
from .step import bt_step
from .orbit import bt_orbit
from .phi import flow_coefficients, phi
