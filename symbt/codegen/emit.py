"""Render the emitted Python modules: closed form or transfer-matrix form (:mod:`.emit_loop`).

Every module has the same surface: ``N``, ``FORM``, the typed errors, and for each
function of :data:`~symbt.codegen.derive.FUNCTIONS` a numpy flavour ``name(...)``
and an mpmath flavour ``name_mp(...)``, plus ``bt_orbit``/``bt_orbit_mp``.  Both forms go
through ``symbt.emit``: the functions are declared in :mod:`.zullo` (closed form: expressions of
:mod:`.derive`; transfer-matrix form: ``Loop`` bodies calling :mod:`.emit_loop`'s core) and
rendered by the user path (:func:`symbt.codegen.user.render.python_module`).

>>> "def bt_step_mp(" in module_body(2)
True
"""
from __future__ import annotations

from .forms import FORMS, form_of
from .pymodule import package_init_body

__all__ = ["module_body", "package_init_body", "form_of"]


def module_body(N: int, form: str | None = None) -> str:
    """Everything after the provenance header of ``toda{N}.py``; ``form`` defaults to :func:`form_of`."""
    form = form_of(N) if form is None else form
    if form not in FORMS:
        raise ValueError(f"unknown form {form!r}")
    from .zullo import module_text

    return module_text(N, form)
