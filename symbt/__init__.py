"""symbt: Zullo's 'Bäcklund transformations and Hamiltonian flows', re-derived and checked.

Layers, lowest first.  A module imports only from its own layer and the layers
below it (``tests/test_architecture.py`` walks every import, function-level
ones included, and fails on an upward import or a cycle):

====  =========================================  =============================================
 0    :mod:`symbt.paper`, :mod:`symbt._files`    the paper's numbers; the one atomic writer;
      :mod:`symbt._lazy`                         lazy public names
 1    :mod:`symbt.symbolic`                      SymPy model of the lattice, Darboux matrices, F
 2    :mod:`symbt.proof`                         one Verdict type; exact and sampled deciders
 3    :mod:`symbt.numeric`                       sympy-free runtime: step, orbits, Phi, c_k
 4    :mod:`symbt.reference`                     independent high-precision routes (mpmath)
 5    :mod:`symbt.codegen`, :mod:`symbt.generated`  emitted numeric code and its generator
 6    :mod:`symbt.report`                        text, JSON, JUnit, Markdown, HTML, figures
 7    :mod:`symbt.claims`                        the paper's statements, as data, in scenes
 8    :mod:`symbt.engine`                        selection, cache, runner, walkthroughs
 9    :mod:`symbt.benchmarks`                    work-precision benchmarks
10    :mod:`symbt.testing`, :mod:`symbt.cli`     front ends
====  =========================================  =============================================

:mod:`symbt.numeric` and :mod:`symbt.reference` never import SymPy.  Importing
``symbt`` is cheap: the public names below load their layer on first use.

The public API for claims of *any* paper lives here, one import surface (the package's own
claims of Zullo's paper use the same objects): :func:`claim` and :func:`scene` declare,
:class:`Parts` holds what a claim checks (for ``symbt mutate``), :func:`decide` and
:func:`check_identity` decide identities (exact reduction first, a screen that knows its own
error), :class:`Domain` with the splits :func:`sign`, :func:`choice`, :func:`regime` samples every
cell of a domain into a :class:`CellTable`, :func:`solves_ode` checks a closed form against an
ODE, and :func:`judge` turns a verdict or a cell table into an :class:`Outcome` (``verified``,
``erratum`` with the generated scope, ``failed``, ``inconclusive``; :func:`todo` for a stub).
:func:`verify` runs claims (``claims=`` sources, as ``--claims``).  :func:`emit` declares a function of your own
derivation for ``symbt codegen`` to emit as verified numpy, mpmath and C code (``docs/codegen.md``).

>>> import sympy as sp
>>> from symbt import claim, decide, judge
>>> x = sp.Symbol("x", positive=True)
>>> @claim("demo.log", equation="demo-log", scene="demo", statement="log(x^2) = 2 log x", register=False)
... def demo_log():
...     return judge(decide(sp.log(x**2), 2*sp.log(x), exact=False), printed="log(x^2) = 2 log x")
>>> demo_log.run().status
'verified'

>>> import symbt
>>> symbt.verify                                  # doctest: +ELLIPSIS
<function verify at ...>
"""
from __future__ import annotations

from ._lazy import lazy_attributes

__version__ = "0.1.0"

#: the layers, lowest first (see the module docstring); names are relative to ``symbt``
LAYERS: tuple[tuple[str, ...], ...] = (
    ("paper", "_files", "_lazy"),
    ("symbolic",),
    ("proof",),
    ("numeric",),
    ("reference",),
    ("codegen", "generated"),
    ("report",),
    ("claims",),
    ("engine",),
    ("benchmarks",),
    ("testing", "pytest_plugin", "cli", "__main__"),
)

#: the public API for writing and running claims of any paper (see ``docs/your-paper.md``)
_LAZY = {"verify": ".engine", "check_identity": ".proof", "IdentityResult": ".proof", "Verdict": ".proof",
         "decide": ".proof",
         "claim": ".claims.base", "scene": ".claims.base", "Parts": ".claims.base", "Outcome": ".claims.base",
         "judge": ".claims.base", "from_decision": ".claims.base", "failed": ".claims.base",
         "skipped": ".claims.base", "inconclusive": ".claims.base", "todo": ".claims.base",
         "judge_cells": ".claims.base", "CellTable": ".proof.cells",
         "Domain": ".proof", "sign": ".proof", "choice": ".proof", "regime": ".proof", "uniform": ".proof",
         "log_uniform": ".proof", "integers": ".proof", "complex_box": ".proof", "UnfilledCellError": ".proof",
         "solves_ode": ".proof", "ode_residual": ".proof", "emit": ".codegen.user"}

__all__ = ["__version__", "LAYERS", *_LAZY]

__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)
