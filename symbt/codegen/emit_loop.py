"""Render the transfer-matrix (O(N)) form of ``toda{N}.py``: :data:`~.loop_template.CORE` with the
kernels of :mod:`.kernels` printed in, plus numpy and mpmath wrappers with the same signatures,
guards and errors as the closed form.

Cost per state: O(N) for the trace, Phi and its gradient, the step and Dapp's x, y; O(N^2) for
the invariants; O(N^3) for the Hamiltonian fields and the flow field (products of polynomials in
lambda).  Emission itself is independent of N up to the constant ``N = ...``.

>>> "def _monodromy(av, R):" in loop_module_body(5)
True
"""
from __future__ import annotations

import re

from ..numeric.core.limits import KAPPA_MAX
from .derive import FUNCTIONS, FunctionSpec, interface
from .kernels import kernels
from .loop_template import CORE
from .printer import ExprPrinter
from .pymodule import function_doc, module_head, numpy_epilogue, numpy_prologue, signature
from .runtime import ORBIT
from .user.render import python_module
from .user.typed import ModuleTemplate

__all__ = ["loop_module_body", "printed_kernels"]

# numpy: (statements computing the outputs as lists/scalars, output item expressions)
_NUMPY_CALL = {
    "invariants": ("_H = _invariants(_NP, _cols(p), _cols(q))", {"H": "_H"}),
    "spectral_trace": ("_t = _spectral_trace(_NP, lam, _cols(p), _cols(q))", {"tr": "[_t]"}),
    "hamiltonian_fields": ("_dp, _dq = _fields(_NP, _cols(p), _cols(q))",
                           {"qdot": "[_dp[j].coeff(k) for k in range(N) for j in range(N)]",
                            "pdot": "[-_dq[j].coeff(k) for k in range(N) for j in range(N)]"}),
    "flow_field": ("_dp, _dq = _fields(_NP, _cols(p), _cols(q))\n_c = _cols(c)",
                   {"qdot": "[sum(_c[k] * _dp[j].coeff(k) for k in range(N)) for j in range(N)]",
                    "pdot": "[-sum(_c[k] * _dq[j].coeff(k) for k in range(N)) for j in range(N)]"}),
    "phi_tr": ("_v = _phi_tr(_NP, tr1, tr2, branch, _g)", {"phi": "[_v]"}),
    "phi": ("_v = _phi(_NP, _cols(p), _cols(q), lam0, mu, branch, _g)", {"phi": "[_v]"}),
    "phi_grad": ("_gp, _gq = _phi_grad(_NP, _cols(p), _cols(q), lam0, mu, branch, _g)",
                 {"dphi_dp": "_gp", "dphi_dq": "_gq"}),
    "ck_integrand": ("_v = _ck_integrand(_NP, lam, _cols(p), _cols(q), _g)", {"integrand": "_v"}),
    "dapp_xy": ("_x, _y = _dapp(_NP, _cols(p), _cols(q), lam0, mu, branch, _g)", {"x": "[_x]", "y": "[_y]"}),
    "bt_step": ("_pn, _qn = _step(_NP, _cols(p), _cols(q), lam0, mu, branch, _g)",
                {"p_new": "_pn", "q_new": "_qn"}),
}

# mpmath: (statements, returned expression)
_MP_CALL = {
    "invariants": ("H = [mpmath.mpf(h) for h in _invariants(_MP, p, q)]", "H"),
    "spectral_trace": ("tr = _spectral_trace(_MP, lam, p, q)", "tr"),
    "hamiltonian_fields": ("_dp, _dq = _fields(_MP, p, q)\n"
                           "qdot = [[mpmath.mpf(_dp[j].coeff(k)) for j in range(N)] for k in range(N)]\n"
                           "pdot = [[-mpmath.mpf(_dq[j].coeff(k)) for j in range(N)] for k in range(N)]",
                           "qdot, pdot"),
    "flow_field": ("_dp, _dq = _fields(_MP, p, q)\n"
                   "qdot = [mpmath.fsum(c[k] * _dp[j].coeff(k) for k in range(N)) for j in range(N)]\n"
                   "pdot = [-mpmath.fsum(c[k] * _dq[j].coeff(k) for k in range(N)) for j in range(N)]",
                   "qdot, pdot"),
    "phi_tr": ("phi = _phi_tr(_MP, tr1, tr2, branch, None)", "phi"),
    "phi": ("phi = _phi(_MP, p, q, lam0, mu, branch, None)", "phi"),
    "phi_grad": ("dphi_dp, dphi_dq = _phi_grad(_MP, p, q, lam0, mu, branch, None)", "dphi_dp, dphi_dq"),
    "ck_integrand": ("integrand = _ck_integrand(_MP, lam, p, q, None)", "integrand"),
    "dapp_xy": ("x, y = _dapp(_MP, p, q, lam0, mu, branch, None)", "x, y"),
    "bt_step": ("p_new, q_new = _step(_MP, p, q, lam0, mu, branch, None)", "p_new, q_new"),
}


def printed_kernels() -> dict[str, str]:
    """Kernel name -> printed flavour-neutral Python (``_X.`` functions, symbol names as variables)."""
    out = {}
    for name, k in kernels().items():
        exprs = k if isinstance(k, tuple) else (k,)
        names = {s: str(s) for e in exprs for s in getattr(e, "free_symbols", ())}
        pr = ExprPrinter("ops", names)
        out[name] = ", ".join(pr.text(e) for e in exprs)
    return out


def _core() -> str:
    ks = printed_kernels()
    text = CORE.replace("@@KAPPA_MAX@@", str(int(KAPPA_MAX)))      # the one limit, printed in
    for name in sorted(set(re.findall(r"@@(\w+)@@", text))):
        text = text.replace(f"@@{name}@@", ks[name])
    return text


def _numpy_wrapper(spec: FunctionSpec, N: int) -> str:
    lines = numpy_prologue(spec, N, "transfer-matrix", "N")
    lines.append("    _g = []")
    call, items = _NUMPY_CALL[spec.name]
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in call.split("\n")]
    res = [o.name for o in spec.outputs]
    for o in spec.outputs:
        lines.append(f"        {o.name} = _pack({items[o.name]}, _batch, {o.shape!r})")
    lines += numpy_epilogue(spec, res, "_g")
    return "\n".join(lines)


def _mp_wrapper(spec: FunctionSpec, N: int) -> str:
    lines = [f"def {spec.name}_mp({signature(spec, 'mpmath')}):",
             function_doc(spec, N, "mpmath", "transfer-matrix")]
    for a in spec.args:
        if a.kind == "state":
            lines.append(f"    {a.name} = _mp_state({a.name}, N, {a.name!r})")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = _mp_value({a.name}, {a.name!r})")
    call, ret = _MP_CALL[spec.name]
    lines.append("    try:")
    lines += [f"        {ln}" for ln in call.split("\n")]
    lines.append("    except ZeroDivisionError as exc:")
    lines.append("        raise NumericRangeError('division by zero (degenerate eigenvector)') from exc")
    lines.append(f"    return {ret}")
    return "\n".join(lines)


def loop_module_body(N: int) -> str:
    """Everything after the provenance header of ``toda{N}.py`` in the transfer-matrix form."""
    spec = interface(N)
    parts = module_head(N, "transfer-matrix")
    parts.append(_core().rstrip("\n"))
    for name in FUNCTIONS:
        parts += ["", "", _numpy_wrapper(spec[name], N)]
    for name in FUNCTIONS:
        parts += ["", "", _mp_wrapper(spec[name], N)]
    # placed by the user path's renderer as a module template: the wrappers call the hand-written loops,
    # they are not expressions an emit declaration could hold (no declarations: head + tail only)
    template = ModuleTemplate(head="\n".join(parts), tail=ORBIT.rstrip("\n"))
    return python_module(f"toda{N}", [], "symbt.codegen.emit_loop", template)
