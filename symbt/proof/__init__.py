"""Deciding identities: one :class:`Verdict` type, exact and sampled deciders, identity checking.

* :func:`decide` -- exact reduction first (:mod:`.exact`), randomized
  high-precision evaluation as the screen (:mod:`.screen`);
* :func:`check_identity` -- the same engine for users, with relations and assumptions;
* :class:`Worst` -- the worst residual over sampled points, as a verdict.

Every decider returns a :class:`Verdict` whose ``evidence`` says how it was
reached (``"proof"``, ``"certified"`` or ``"sampled"``).
"""
from __future__ import annotations

from .decide import decide
from .exact import reduce_modulo
from .identity import IdentityResult, check_identity
from .sampling import Worst
from .verdict import EVIDENCE, Verdict

__all__ = ["Verdict", "EVIDENCE", "decide", "reduce_modulo", "check_identity", "IdentityResult", "Worst"]
