"""Deciding identities: one :class:`Verdict` type, exact and sampled deciders, identity checking.

* :func:`decide` -- exact reduction first (:mod:`.exact`), randomized
  high-precision evaluation as the screen (:mod:`.screen`);
* :func:`check_identity` -- the same engine for users, with relations and assumptions;
* :class:`Worst` -- the worst residual over sampled points, as a verdict.

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
    "Worst": ".sampling",
}

__all__ = ["Verdict", "EVIDENCE", "decide", "reduce_modulo", "check_identity", "IdentityResult", "Worst"]


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, __all__)
