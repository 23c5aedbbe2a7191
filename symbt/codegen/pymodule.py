"""The parts of an emitted ``toda{N}.py`` shared by both forms: module head, signatures, docstrings.

>>> module_head(3, "closed")[2]
'N = 3'
"""
from __future__ import annotations

from collections.abc import Sequence

from .derive import FUNCTIONS, FunctionSpec
from .runtime import RUNTIME

__all__ = ["signature", "function_doc", "module_head", "package_init_body"]


def signature(spec: FunctionSpec, flavour: str) -> str:
    """Argument list; guarded numpy functions take ``errors="raise"`` (or ``"mask"``)."""
    sig = ", ".join(a.name for a in spec.args)
    return sig + (', errors="raise"' if spec.guards and flavour == "numpy" else "")


def numpy_prologue(spec: FunctionSpec, N: int, form: str, n_text: str | None = None) -> list[str]:
    """Header, docstring and argument validation of an emitted numpy function, up to ``_batch``.

    ``n_text`` is the source text of the state length checked by ``_state`` (default ``str(N)``;
    ``"N"`` in the transfer-matrix module, where N is a module constant).  Both forms share it.
    """
    n_size = str(N) if n_text is None else n_text
    from .user.render_typed import validation_lines

    kind = {"state": "array", "branch": "sign"}
    lines = [f"def {spec.name}({signature(spec, 'numpy')}):", function_doc(spec, N, "numpy", form)]
    return lines + validation_lines([(a.name, kind.get(a.kind, "scalar"), n_size) for a in spec.args],
                                    bool(spec.guards))


def numpy_epilogue(spec: FunctionSpec, res: Sequence[str], guard_list: str) -> list[str]:
    """Closing lines of an emitted numpy function, shared by both forms: the guard check
    (``guard_list``: source text of the guards' list), ``_finish`` and the return."""
    names = ", ".join(res)
    if not spec.guards:
        return [f"    {names}, = _finish('raise', None, _batch, [{names}])", f"    return {names}"]
    return [f"        _bad = _guard(errors, _batch, {guard_list})",
            f"    {names}, = _finish(errors, _bad, _batch, [{names}])", f"    return {names}"]


def function_doc(spec: FunctionSpec, N: int, flavour: str, form: str) -> str:
    args = "\n".join(f"        {a.name}: {a.doc}" for a in spec.args)
    if flavour == "numpy":
        shape = lambda o: "batch" + ("" if not o.shape else " + " + str(o.shape))  # noqa: E731
        kind = ("float64, vectorised: state arguments have shape (..., N), scalars broadcast "
                "against the batch shape")
        if spec.guards:
            args += ("\n        errors: 'raise' (default): NoRealMapError where the real function does not exist, "
                     "NumericRangeError on a non-finite value; 'mask': numpy.ma.MaskedArray results, masked "
                     "at those batch elements")
            if spec.name in ("bt_step", "dapp_xy"):
                args = args.replace("NumericRangeError on a non-finite value", "NumericRangeError on a non-finite "
                                    "value, IllConditionedError (a NumericRangeError) where the condition "
                                    "estimate exceeds KAPPA_MAX (float64 cannot decide)")
            conds = sorted({g.condition for g in spec.guards} - {"range", "illcond"})
            kind += "; real domain: " + " and ".join(
                {"trace": "|tr L| > 2 at each spectral parameter", "positivity": "every Etilde_j > 0"}[c]
                for c in conds)
        else:
            kind += "; NumericRangeError if a value overflows"
    else:
        shape = lambda o: {0: "mpf", 1: "list", 2: "list of lists"}[len(o.shape)]  # noqa: E731
        kind = "mpmath at the current precision (single state)"
        if spec.guards:
            kind += "; NoRealMapError outside the real domain"
    outs = "\n".join(f"        {o.name} ({shape(o)}): {o.doc}" for o in spec.outputs)
    return (f'    """{spec.summary} (eq. {spec.equation}, N={N}, {form} form).\n\n'
            f"    {kind}.\n\n    Arguments:\n{args}\n\n    Returns:\n{outs}\n    \"\"\"")


def _module_doc(N: int, form: str) -> str:
    return (f'"""Generated numeric code for the N={N} periodic Toda lattice, {form} form '
            "(do not edit; run `symbt codegen`).\n\n"
            "Two flavours of every function: ``name(...)`` (numpy, float64, vectorised over leading\n"
            "batch axes) and ``name_mp(...)`` (mpmath at the current precision, exact rational\n"
            "constants).  Conventions: {p_i, q_j} = delta_ij, xdot = {H, x}; L = l_N ... l_1,\n"
            "tr L = sum_k H_k lambda^k (H_N = 1); branch b = +-1 means gamma_i = b sqrt(tr_i^2 - 4)\n"
            "(positive root) at lambda_1 = lambda_0 + mu, lambda_2 = lambda_0 - mu.\n"
            "Outside the real domain: NoRealMapError (or masked results with errors='mask');\n"
            "overflow: NumericRangeError; bad input: InvalidInputError (same names and meaning as\n"
            "symbt.numeric; subclasses of ValueError / OverflowError).  An empty batch\n"
            "(state arguments of shape (0, N)) gives empty results of the matching shape.\n\n"
            "Functions: " + ", ".join(FUNCTIONS) + ", bt_orbit (centre of mass carried separately).\n"
            '"""')


def module_head(N: int, form: str) -> list[str]:
    all_names = ([n for f in FUNCTIONS for n in (f, f + "_mp")] + ["bt_orbit", "bt_orbit_mp", "N", "FORM",
                 "IllConditionedError", "InvalidInputError", "NoRealMapError", "NumericRangeError"])
    return [_module_doc(N, form), "", f"N = {N}", f"FORM = {form!r}", f"__all__ = {all_names!r}",
            RUNTIME.rstrip("\n")]


def package_init_body() -> str:
    return ('"""Generated numeric modules (``symbt codegen``); see docs/codegen.md.\n\n'
            "Each ``toda{N}`` module holds numpy and mpmath (``*_mp``) functions emitted from\n"
            "the SymPy derivations of :mod:`symbt.codegen`.  Import a module lazily:\n"
            "``from symbt.generated import toda3`` (nothing is imported here); ``modules()``\n"
            "lists the ``toda{N}`` modules present (``symbt codegen --n 2 3 4 5 8`` adds more).\n"
            '"""\n\n'
            "import os as _os\n"
            "import re as _re\n\n"
            "__all__ = ['modules']\n\n\n"
            "def modules():\n"
            "    \"\"\"Names of the generated ``toda{N}`` modules in this package, by N.\"\"\"\n"
            "    here = _os.path.dirname(_os.path.abspath(__file__))\n"
            "    names = (_re.fullmatch(r'(toda(\\d+))\\.py', f) for f in _os.listdir(here))\n"
            "    found = [m.group(1) for m in names if m]\n"
            "    return tuple(sorted(found, key=lambda s: int(s[4:])))\n")
