"""symbt: Zullo's 'Bäcklund transformations and Hamiltonian flows', re-derived and checked.

Layers (each imports only those above it):

* :mod:`symbt.symbolic`  -- SymPy derivations (Toda model, Darboux matrices, F)
* :mod:`symbt.proof`     -- deciding identities (exact reduction + 50-digit screen)
* :mod:`symbt.claims`    -- the paper's statements as claims, grouped in scenes
* :mod:`symbt.engine`    -- running scenes with caching and parallelism
* :mod:`symbt.numeric`   -- sympy-free numeric runtime (float64 / mpmath)
* :mod:`symbt.cli`       -- ``symbt verify``, ``symbt scenes``, ...

Importing ``symbt`` is cheap: heavy submodules load on first use.
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

_LAZY = {
    "check_identity": ("symbt.proof.identity", "check_identity"),
    "IdentityResult": ("symbt.proof.identity", "IdentityResult"),
    "decide": ("symbt.proof", "decide"),
    "verify": ("symbt.engine", "run"),
}

__all__ = ["__version__", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        mod, attr = _LAZY[name]
        return getattr(importlib.import_module(mod), attr)
    raise AttributeError(f"module 'symbt' has no attribute {name!r}")
