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
from .user.typed import Arg, Guard, Loop, ModuleTemplate, module_template

__all__ = ["declaration", "declarations", "loop_declarations", "module_text", "KIND", "ZERO_DIVISION"]

#: :class:`~symbt.codegen.derive.ArgSpec` kind -> argument kind of the typed ``emit``
KIND = {"state": "array", "scalar": "scalar", "branch": "sign"}
#: the message of the mpmath flavours' NumericRangeError on a division by zero
ZERO_DIVISION = "division by zero (degenerate eigenvector)"


def _docstring(spec: FunctionSpec, N: int, flavour: str, form: str = "closed") -> str:
    """The text between the triple quotes of :func:`~symbt.codegen.pymodule.function_doc`."""
    text = function_doc(spec, N, flavour, form)
    return text[len('    """'):-len('"""')]


def _value(o: Output) -> sp.Expr | list[sp.Expr]:
    if o.shape == ():
        return o.exprs[0]
    if len(o.shape) == 1:
        return list(o.exprs)
    return sp.Matrix(*o.shape, list(o.exprs))


def declaration(s: FunctionSpec, N: int) -> Emission:
    """The typed ``emit`` declaration of one closed-form function of ``toda{N}`` (not registered)."""
    args = tuple(Arg(a.name, tuple(a.symbols), KIND[a.kind]) for a in s.args)
    guards = [Guard(g.condition, g.label, g.expr, early=g.stage == 0) for g in s.guards]
    return emit(s.name, {o.name: _value(o) for o in s.outputs}, args=args, module=f"toda{N}",
                doc={"numpy": _docstring(s, N, "numpy"), "mpmath": _docstring(s, N, "mpmath")},
                optimize=False, equation=s.equation, guards=guards, register=False)


@cache
def declarations(N: int, form: str = "closed") -> tuple[list[Emission], ModuleTemplate]:
    """The ``emit`` declarations of ``toda{N}`` in ``form`` and its module template (not registered:
    they are symbt's own, not a user project's).  ``symbt codegen`` uses the closed form for N < 4 only
    (:func:`~symbt.codegen.forms.form_of`); larger N serve the size benchmarks.  The transfer-matrix
    form: :func:`loop_declarations`."""
    if form == "transfer-matrix":
        return loop_declarations(N)
    if form != "closed":
        raise ValueError(f"unknown form {form!r}")
    module = f"toda{N}"
    ems = [declaration(s, N) for s in specs(N)]
    template = module_template(module, head="\n".join(module_head(N, "closed")), tail=ORBIT,
                               zero_division=ZERO_DIVISION, register=False)
    return ems, template


def loop_declarations(N: int) -> tuple[list[Emission], ModuleTemplate]:
    """The transfer-matrix ``toda{N}`` as typed ``emit`` declarations with a :class:`~.user.typed.Loop` body
    each (the calls into the hand-written loops of :mod:`.loop_template`, the C of
    :func:`~.emit_c_fill.loop_c_parts`) and its module template (head, printed loop core, ``bt_orbit``)."""
    from .derive import FUNCTIONS, interface
    from .emit_c_fill import loop_c_parts
    from .emit_loop import MP_CALL, NUMPY_CALL, core

    module, spec = f"toda{N}", interface(N)
    _, c_parts = loop_c_parts(N)
    ems = []
    for name in FUNCTIONS:
        s = spec[name]
        (np_call, items), (mp_call, ret) = NUMPY_CALL[name], MP_CALL[name]
        if ret != ", ".join(o.name for o in s.outputs):
            raise AssertionError(f"{name}: the mpmath call returns {ret}, not the outputs")
        body = Loop(outputs=tuple((o.name, o.shape) for o in s.outputs), numpy=np_call,
                    items=tuple((o.name, items[o.name]) for o in s.outputs), mpmath=mp_call,
                    guards="_g" if s.guards else "", setup="_g = []", size="N", c=c_parts.get(name, ""))
        args = tuple(Arg(a.name, tuple(a.symbols), KIND[a.kind]) for a in s.args)
        ems.append(emit(name, body, args=args, module=module, equation=s.equation, register=False,
                        doc={fl: _docstring(s, N, fl, "transfer-matrix") for fl in ("numpy", "mpmath")}))
    head = "\n".join([*module_head(N, "transfer-matrix"), core().rstrip("\n")])
    return ems, module_template(module, head=head, tail=ORBIT, zero_division=ZERO_DIVISION, register=False)


def module_text(N: int, form: str = "closed") -> str:
    """Everything after the provenance header of ``toda{N}.py`` in ``form``, through ``symbt.emit``."""
    ems, template = declarations(N, form)
    return python_module(f"toda{N}", ems, "symbt.codegen.zullo", template)
