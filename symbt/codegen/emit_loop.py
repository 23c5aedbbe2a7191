"""The transfer-matrix (O(N)) form of ``toda{N}.py``: :data:`~.loop_template.CORE` with the kernels of
:mod:`.kernels` printed in (:func:`core`, the module template's head), and per function the calls into
it (:data:`NUMPY_CALL`, :data:`MP_CALL`) that :func:`symbt.codegen.zullo.loop_declarations` declares as
``Loop`` bodies; the user path's renderers wrap them with the same signatures, guards and errors as
the closed form.

Cost per state: O(N) for the trace, Phi and its gradient, the step and Dapp's x, y; O(N^2) for
the invariants; O(N^3) for the Hamiltonian fields and the flow field (products of polynomials in
lambda).  Emission itself is independent of N up to the constant ``N = ...``.

>>> "def _monodromy(av, R):" in core()
True
"""
from __future__ import annotations

import re

from ..numeric.core.limits import KAPPA_MAX
from .kernels import kernels
from .loop_template import CORE
from .printer import ExprPrinter

__all__ = ["printed_kernels", "core", "NUMPY_CALL", "MP_CALL"]

#: numpy: (statements computing the outputs as lists/scalars, output item expressions)
NUMPY_CALL = {
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

#: mpmath: (statements assigning the outputs, the outputs returned)
MP_CALL = {
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


def core() -> str:
    """:data:`~.loop_template.CORE` with the printed kernels and ``KAPPA_MAX`` filled in."""
    ks = printed_kernels()
    text = CORE.replace("@@KAPPA_MAX@@", str(int(KAPPA_MAX)))      # the one limit, printed in
    for name in sorted(set(re.findall(r"@@(\w+)@@", text))):
        text = text.replace(f"@@{name}@@", ks[name])
    return text
