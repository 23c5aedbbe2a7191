"""Render ``toda{N}.c`` and ``toda{N}.h`` (C99, libm only): ``bt_step``, ``invariants``, ``spectral_trace``,
``flow_field``, with the status codes of :data:`symbt.codegen.c_template.HEADER`.

* closed form (N < ``LOOP_FROM``): through ``symbt.emit`` -- the declarations of
  :mod:`symbt.codegen.zullo` rendered by :mod:`symbt.codegen.user.render_typed_c` under a C template
  holding Zullo's header, runtime, status codes and prototypes (the guards become status codes);
* transfer-matrix form: through ``symbt.emit`` too -- the ``Loop`` declarations of
  :func:`symbt.codegen.zullo.loop_declarations`, whose C is :data:`~symbt.codegen.c_template.LOOP`
  with the kernels printed in (:mod:`symbt.codegen.emit_c_fill`), placed by the same renderer.

>>> src, hdr = c_files(5)
>>> "int toda5_bt_step(" in src and "SYMBT_TODA_RANGE 3" in hdr
True
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from ..numeric.core.limits import KAPPA_MAX
from .c_template import COMMON, HEADER
from .emit_c_fill import fill as _fill
from .emit_c_fill import loop_c_parts
from .forms import form_of

if TYPE_CHECKING:
    from .user.declare import Emission

__all__ = ["c_files", "C_FUNCTIONS", "loop_c_parts"]

#: the emitted C functions (same meaning as the Python functions of the same name)
C_FUNCTIONS = ("bt_step", "invariants", "spectral_trace", "flow_field")

# --------------------------------------------------------------------------- closed form

_SIGNATURES = {
    "bt_step": "int toda{N}_bt_step(const double *p, const double *q, double lam0, double mu, int branch,\n"
               "                      double *pt, double *qt)",
    "invariants": "int toda{N}_invariants(const double *p, const double *q, double *H)",
    "spectral_trace": "int toda{N}_spectral_trace(double lam, const double *p, const double *q, double *tr)",
    "flow_field": "int toda{N}_flow_field(const double *c, const double *p, const double *q, double *qdot, "
                  "double *pdot)",
}
_OUT_PTRS = {"bt_step": ("pt", "qt"), "invariants": ("H",), "spectral_trace": ("tr",), "flow_field": ("qdot", "pdot")}
_CODES = {"trace": "SYMBT_TODA_NO_REAL_MAP_TRACE", "positivity": "SYMBT_TODA_NO_REAL_MAP_POSITIVITY",
          "illcond": "SYMBT_TODA_ILL_CONDITIONED"}


def c_files(N: int) -> tuple[str, str]:
    """``(toda{N}.c, toda{N}.h)`` bodies (without the provenance header)."""
    form = form_of(N)
    header = _fill(HEADER.replace("@@KAPPA@@", str(int(KAPPA_MAX))), N, form)   # the one limit, printed in
    src = _fill(COMMON, N, form)
    if form == "closed":
        return _emit_path_c_files(N, header, src)
    return _loop_c_files(N, header, src)


_SECTION = "\n/* ---- closed form: CSE of the SymPy expressions of symbt.codegen.derive ---- */\n"


def _emit_path_c_files(N: int, header: str, common: str, ems: list[Emission] | None = None) -> tuple[str, str]:
    """The closed form through ``symbt.emit``: the declarations of :mod:`.zullo` (or ``ems``) under a C template
    (Zullo's header, runtime, status codes and prototypes, hand-written once in :mod:`.c_template`)."""
    from .user.render_typed_c import CTemplate
    from .user.render_typed_c import c_files as typed_c_files
    from .zullo import declarations

    ems = declarations(N)[0] if ems is None else ems
    status = (("ok", "SYMBT_TODA_OK"), ("range", "SYMBT_TODA_RANGE"), ("invalid", "SYMBT_TODA_INVALID_INPUT"),
              *_CODES.items())
    t = CTemplate(f"toda{N}", header, common + _SECTION, status, f"toda{N}_finite", length="NS",
                  signatures=tuple((n, s.format(N=N)) for n, s in _SIGNATURES.items()), functions=C_FUNCTIONS,
                  sign_local="b", pointers=tuple(_OUT_PTRS.items()))
    return typed_c_files(ems, t)


def _loop_c_files(N: int, header: str, common: str) -> tuple[str, str]:
    """The transfer-matrix form through ``symbt.emit`` too: the ``Loop`` declarations of :mod:`.zullo` (their
    C text verbatim, :func:`loop_c_parts`) placed by the same renderer under the same kind of C template."""
    from .user.render_typed_c import CTemplate
    from .user.render_typed_c import c_files as typed_c_files
    from .zullo import declarations

    ems, _ = declarations(N, "transfer-matrix")
    helpers, parts = loop_c_parts(N)
    status = (("ok", "SYMBT_TODA_OK"), ("range", "SYMBT_TODA_RANGE"), ("invalid", "SYMBT_TODA_INVALID_INPUT"))
    t = CTemplate(f"toda{N}", header, common + helpers, status, f"toda{N}_finite", functions=tuple(parts))
    return typed_c_files(ems, t)
