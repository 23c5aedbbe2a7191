"""Codegen for a user's own SymPy expressions: ``symbt.emit`` declarations, emitted files, their checks.

* :mod:`.declare` -- :func:`emit` and the declaration registry;
* :mod:`.typed` -- the typed form: array/sign arguments (:class:`Arg`), named outputs, ordered
  :class:`Guard` s, :class:`Loop` bodies (fixed template code), :func:`module_template` (hand-written
  module parts);
* :mod:`.render` -- the emitted numpy/mpmath module and the C99 source and header;
  :mod:`.render_typed` -- the Python flavours of a typed declaration;
* :mod:`.files` -- provenance (the declaring modules' sources), writing and ``--check``;
* :mod:`.check` -- an emitted file against its SymPy source at high precision, on a :class:`symbt.Domain`;
* :mod:`.cli` -- ``symbt codegen`` in a project whose ``[tool.symbt]`` lists ``codegen`` sources.

Zullo's closed-form modules are declared with it (:mod:`symbt.codegen.zullo`), so this package is
among their derivation sources: editing it makes ``symbt/generated`` stale (run ``symbt codegen``).

>>> import sympy as sp
>>> x = sp.Symbol("x")
>>> emit("root_demo", {"r": sp.sqrt(x)}, args=(("v", (x,)),), module="demo_user", guards=[Guard("domain", "x", x)],
...      register=False).typed
True
"""
from __future__ import annotations

from .declare import EMISSIONS, Emission, EmitError, emit
from .typed import TEMPLATES, Arg, Guard, Loop, ModuleTemplate, module_template

__all__ = ["emit", "Emission", "EmitError", "EMISSIONS", "Arg", "Guard", "Loop", "ModuleTemplate", "module_template",
           "TEMPLATES"]
