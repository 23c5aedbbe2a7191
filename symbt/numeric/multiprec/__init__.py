"""Backends for mpmath input: the step and orbit of each (:mod:`~symbt.numeric.multiprec.runners`), quad-double
arithmetic compiled by numba, python-flint's Arb (midpoints, and certified ball orbits).
"""
