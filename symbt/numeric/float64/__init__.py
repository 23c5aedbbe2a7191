"""float64 backends: the vectorised numpy rows, the fused single-state and block kernels (plain
Python or compiled by numba on first use), orbits of one state or an ensemble, and dask chunks.
"""
