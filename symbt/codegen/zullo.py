r"""Zullo's closed-form modules ``toda{N}.py`` as ``symbt.emit`` declarations (dogfooding).

Every function of :func:`symbt.codegen.derive.specs` is declared with the typed form of
:func:`symbt.emit` (:mod:`symbt.codegen.user.typed`): the states ``p``, ``q`` (and the
coefficients ``c``) are array arguments of length N, ``branch`` a sign argument, the outputs
named (``p_new``, ``q_new``, ...), the guards ordered as derived (conditioning, trace, gap sign,
range, positivity); the docstrings are given verbatim.  The hand-written parts -- module docstring,
``N``/``FORM``/``__all__``, the typed runtime (:data:`~symbt.codegen.runtime.RUNTIME`) and
``bt_orbit`` (:data:`~symbt.codegen.runtime.ORBIT`) -- are the module template.
:func:`module_text` renders them with the user path's
:func:`~symbt.codegen.user.render.python_module`; ``symbt codegen`` writes
``symbt/generated/toda{2,3}.py`` so (:func:`symbt.codegen.emit.module_body`).

The closed-form C target goes through the same declarations (:mod:`symbt.codegen.emit_c`, Zullo's
ABI and status codes as a C template).  Not through declarations: the transfer-matrix form
(N >= :data:`~symbt.codegen.forms.LOOP_FROM`, :mod:`symbt.codegen.emit_loop`: per-function wrappers of
hand-written loop code, not expressions).

>>> ems, template = declarations(2)
>>> [e.name for e in ems][-2:], [a.kind for a in ems[-1].params], [o.name for o in ems[-1].outputs]
(['dapp_xy', 'bt_step'], ['array', 'array', 'scalar', 'scalar', 'sign'], ['p_new', 'q_new'])
>>> [g.condition for g in ems[-1].guards][:4], template.tail.lstrip().startswith("def bt_orbit(")
(['illcond', 'trace', 'illcond', 'trace'], True)
"""
from __future__ import annotations

from functools import cache

import sympy as sp

from .derive import FunctionSpec, Output, specs
from .pymodule import function_doc, module_head
from .runtime import ORBIT
from .user.declare import Emission, emit
from .user.render import python_module
from .user.typed import Arg, Guard, ModuleTemplate, module_template

__all__ = ["declarations", "module_text", "KIND", "ZERO_DIVISION"]

#: :class:`~symbt.codegen.derive.ArgSpec` kind -> argument kind of the typed ``emit``
KIND = {"state": "array", "scalar": "scalar", "branch": "sign"}
#: the message of the mpmath flavours' NumericRangeError on a division by zero
ZERO_DIVISION = "division by zero (degenerate eigenvector)"


def _docstring(spec: FunctionSpec, N: int, flavour: str) -> str:
    """The text between the triple quotes of :func:`~symbt.codegen.pymodule.function_doc`."""
    text = function_doc(spec, N, flavour, "closed")
    return text[len('    """'):-len('"""')]


def _value(o: Output) -> sp.Expr | list[sp.Expr]:
    if o.shape == ():
        return o.exprs[0]
    if len(o.shape) == 1:
        return list(o.exprs)
    return sp.Matrix(o.shape[0], o.shape[1], list(o.exprs))


@cache
def declarations(N: int) -> tuple[list[Emission], ModuleTemplate]:
    """The ``emit`` declarations of ``toda{N}`` in closed form and its module template (not registered:
    they are symbt's own, not a user project's).  ``symbt codegen`` uses the closed form for N < 4 only
    (:func:`~symbt.codegen.forms.form_of`); larger N serve the size benchmarks."""
    module = f"toda{N}"
    ems = []
    for s in specs(N):
        args = tuple(Arg(a.name, tuple(a.symbols), KIND[a.kind]) for a in s.args)
        guards = [Guard(g.condition, g.label, g.expr, early=g.stage == 0) for g in s.guards]
        ems.append(emit(s.name, {o.name: _value(o) for o in s.outputs}, args=args, module=module,
                        doc={"numpy": _docstring(s, N, "numpy"), "mpmath": _docstring(s, N, "mpmath")},
                        optimize=False, equation=s.equation, guards=guards, register=False))
    template = module_template(module, head="\n".join(module_head(N, "closed")), tail=ORBIT,
                               zero_division=ZERO_DIVISION, register=False)
    return ems, template


def module_text(N: int) -> str:
    """Everything after the provenance header of the closed-form ``toda{N}.py``, through ``symbt.emit``."""
    ems, template = declarations(N)
    return python_module(f"toda{N}", ems, "symbt.codegen.zullo", template)
