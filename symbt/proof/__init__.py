"""Deciding identities: one :class:`Verdict` type, exact and sampled deciders, identity checking.

* :func:`decide` -- exact reduction first (:mod:`.exact`), randomized
  high-precision evaluation as the screen (:mod:`.screen`);
* :func:`check_identity` -- the same engine for users, with relations and assumptions;
* :class:`Worst` -- the worst residual over sampled points, as a verdict;
* :class:`Domain` with :func:`sign`, :func:`choice`, :func:`regime` -- a sampled statement's
  cells, filled by a seeded sampler, evaluated into a :class:`CellTable` (:mod:`.domain`);
* :func:`solves_ode` -- a closed form solves an ODE: exactly, or per cell at high precision (:mod:`.ode`).

Every decider returns a :class:`Verdict` whose ``evidence`` says how it was
reached (``"proof"``, ``"certified"`` or ``"sampled"``).  The names load on
first use: importing :mod:`symbt.proof.verdict` (the record type) does not
import SymPy.
"""
from __future__ import annotations

from .._lazy import lazy_attributes

_LAZY = {
    "Verdict": ".verdict", "EVIDENCE": ".verdict",
    "decide": ".decider", "reduce_modulo": ".exact",
    "check_identity": ".identity", "IdentityResult": ".identity",
    "Worst": ".sampling", "CellTable": ".cells",
    "Domain": ".domain", "sign": ".domain", "choice": ".domain", "regime": ".domain",
    "UnfilledCellError": ".domain", "uniform": ".ranges", "log_uniform": ".ranges", "integers": ".ranges",
    "complex_box": ".ranges", "solves_ode": ".ode", "ode_residual": ".ode",
}

__all__ = ["Verdict", "EVIDENCE", "decide", "reduce_modulo", "check_identity", "IdentityResult", "Worst",
           "CellTable", "Domain", "sign", "choice", "regime", "UnfilledCellError", "uniform", "log_uniform",
           "integers", "complex_box", "solves_ode", "ode_residual"]


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)
