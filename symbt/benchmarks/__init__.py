r"""``symbt bench``: the Bäcklund map as an exact integrator, benchmarked (one concept per module).

Problem.  By Theorem 2 of the paper (claims ``Hdiscr.n3``, ``Hdiscr.deep.n3`` of scene
``theorem2``) ``n`` Bäcklund steps with ``(lam0, mu, branch)`` are *exactly* the time-``n`` flow of
``G = sum_k c_k H_k``, ``c_k = -b int_{lam0-mu}^{lam0+mu} lam^k / sqrt(tr^2 - 4) dlam``.  So the BT
orbit at 50 digits is the reference solution of Hamilton's equations ``qdot = dG/dp``,
``pdot = -dG/dq`` and every ODE integrator can be scored against it.

Modules.  :mod:`~symbt.benchmarks.cases` (problems), :mod:`~symbt.benchmarks.reference`
(reference orbits, ``c_k``), :mod:`~symbt.benchmarks.metrics` (errors, invariant drift),
:mod:`~symbt.benchmarks.timing`, :mod:`~symbt.benchmarks.integrators` (Gauss--Legendre, scipy),
:mod:`~symbt.benchmarks.contenders` (BT and ODE runs of a case),
:mod:`~symbt.benchmarks.heyoka_system` / :mod:`~symbt.benchmarks.heyoka_peer` (heyoka, optional),
:mod:`~symbt.benchmarks.runner` (one case, headline ratios), :mod:`~symbt.benchmarks.precision`
(50 and 100 digits), :mod:`~symbt.benchmarks.ensemble` (M = 1e4 states),
:mod:`~symbt.benchmarks.throughput`, :mod:`~symbt.benchmarks.band_edge`,
:mod:`~symbt.benchmarks.drift` (invariant-drift experiment), :mod:`~symbt.benchmarks.figure`,
:mod:`~symbt.benchmarks.tables`, :mod:`~symbt.benchmarks.cli` (``main(argv)``).

The rest of symbt's performance code lives here too, each module runnable with ``python -m``:
:mod:`~symbt.benchmarks.numeric_timings` (kernel vs ``bt_orbit``, ensembles, mpmath vs Arb vs
quad-double, certified orbits), :mod:`~symbt.benchmarks.codegen_scaling` (size and time of the
emitted code as N grows), :mod:`~symbt.benchmarks.drift_figure` (the invariant-drift figure) and
:mod:`~symbt.benchmarks.throughput` (the throughput part of ``symbt bench`` on its own).

Importing this package needs numpy and mpmath only; scipy, heyoka and matplotlib are imported
where they are used, and missing ones skip their rows with a message.

>>> from symbt.benchmarks import cases
>>> [c.N for c in cases()]
[3, 3, 2, 64, 256]
"""
from __future__ import annotations

from typing import Any

from .band_edge import band_edge_case, map_condition, run_band_edge
from .cases import Case, cases
from .cli import main
from .integrators import gauss_legendre_orbit, scipy_orbit
from .throughput import run_throughput

__all__ = ["main", "Case", "cases", "gauss_legendre_orbit", "scipy_orbit", "band_edge_case", "map_condition",
           "run_band_edge", "invariant_drift_curve", "run_throughput"]


def __getattr__(name: str) -> Any:
    # drift is imported on first use, not with the package: `python -m symbt.benchmarks.drift` would
    # otherwise find its own module already imported (runpy's RuntimeWarning)
    if name == "invariant_drift_curve":
        from .drift import invariant_drift_curve
        return invariant_drift_curve
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
