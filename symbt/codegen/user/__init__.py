"""Codegen for a user's own SymPy expressions: ``symbt.emit`` declarations, emitted files, their checks.

* :mod:`.declare` -- :func:`emit` and the declaration registry;
* :mod:`.render` -- the emitted numpy/mpmath module and the C99 source and header;
* :mod:`.files` -- provenance (the declaring modules' sources), writing and ``--check``;
* :mod:`.check` -- an emitted file against its SymPy source at high precision, on a :class:`symbt.Domain`;
* :mod:`.cli` -- ``symbt codegen`` in a project whose ``[tool.symbt]`` lists ``codegen`` sources.

This package is not among Zullo's derivation sources (``symbt/codegen/*.py``): editing it does not
make ``symbt/generated`` stale.
"""
from __future__ import annotations

from .declare import EMISSIONS, Emission, EmitError, emit

__all__ = ["emit", "Emission", "EmitError", "EMISSIONS"]
