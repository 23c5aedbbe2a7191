"""Backends for mpmath input: the chooser (:mod:`~symbt.numeric.multiprec.choose`), quad-double
arithmetic compiled by numba, python-flint's Arb (midpoints, and certified ball orbits).
"""
