"""Zullo's modules through `symbt.emit` (issue 24 item 4), and the typed form of `emit` a user can declare.

* the closed-form toda2/toda3 rendered from the `emit` declarations of `symbt.codegen.zullo` are
  byte-identical to what the package's own generator wrote before (kept here, verbatim, as the oracle:
  `_legacy_module_body`, on the old printer and CSE helper) on everything that oracle can print -- all
  but the conditioning guards added after it (issue 21), which are left out on both sides -- and
  `symbt codegen` writes exactly the emit path's text;
* the transfer-matrix toda{N} (N >= 4) declared as `Loop` bodies: Python and C byte-identical to the
  direct assembly they replaced (its wrappers kept here as the oracle);
* the typed form in a user's module: array and sign arguments validated with typed errors, named
  outputs, ordered guards raising NoRealMapError / NumericRangeError or masking, the mpmath flavour;
  the values against numpy computed by hand.
"""
from __future__ import annotations

import ctypes
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

from symbt.codegen import provenance
from symbt.codegen.user import EMISSIONS, EmitError, Guard, emit, module_template
from symbt.codegen.user.files import render as user_render

ROOT = Path(__file__).resolve().parents[1]
GEN = ROOT / "symbt" / "generated"
_HASH_LINE = re.compile(r"^# symbt-codegen-(derivation|content)-sha256: [0-9a-f]{64}$", re.M)


# ---------------------------------------------------------------- the pre-dogfooding generator (oracle)

def _legacy_names(spec):
    names = {}
    for a in spec.args:
        if a.kind == "state":
            for s in a.symbols:
                names[s] = str(s)
        else:
            names[a.symbols[0]] = a.name
    return names


def _legacy_numpy(spec, N):
    from symbt.codegen.printer import cse_block
    from symbt.codegen.pymodule import numpy_epilogue, numpy_prologue

    lines = numpy_prologue(spec, N, "closed")
    for a in spec.args:
        if a.kind == "state":
            lines += [f"    {s} = {a.name}[..., {i}]" for i, s in enumerate(a.symbols)]
    exprs = [g.expr for g in spec.guards] + [e for o in spec.outputs for e in o.exprs]
    body, outs = cse_block(exprs, _legacy_names(spec), "numpy")
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in body]
    k, res = len(spec.guards), []
    for o in spec.outputs:
        lines.append(f"        {o.name} = _pack([{', '.join(outs[k:k + len(o.exprs)])}], _batch, {o.shape!r})")
        k += len(o.exprs)
        res.append(o.name)
    gl = ", ".join(f"({g.condition!r}, {g.label!r}, {t})" for g, t in zip(spec.guards, outs))
    return "\n".join(lines + numpy_epilogue(spec, res, f"[{gl}]"))


def _legacy_mpmath(spec, N):
    from symbt.codegen.printer import cse_block
    from symbt.codegen.pymodule import function_doc, signature

    lines = [f"def {spec.name}_mp({signature(spec, 'mpmath')}):", function_doc(spec, N, "mpmath", "closed")]
    for a in spec.args:
        if a.kind == "state":
            lines.append(f"    {', '.join(str(s) for s in a.symbols)} = _mp_state({a.name}, {N}, {a.name!r})")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = _mp_value({a.name}, {a.name!r})")
    lines.append("    try:")
    for stage in (0, 1):
        gs = [g for g in spec.guards if g.stage == stage]
        exprs = [g.expr for g in gs] + ([e for o in spec.outputs for e in o.exprs] if stage else [])
        if not exprs:
            continue
        body, outs = cse_block(exprs, _legacy_names(spec), "mpmath", prefix="s" if stage == 0 else "t")
        lines += [f"        {ln}" for ln in body]
        lines += [f"        _mp_guard({g.condition!r}, {g.label!r}, {t})" for g, t in zip(gs, outs)]
    outs = outs[len(gs):]
    res, k = [], 0
    for o in spec.outputs:
        items = [f"mpmath.mpf({t})" if re.match(r"^\(?-?\d+\)?$", t) else t for t in outs[k:k + len(o.exprs)]]
        k += len(o.exprs)
        if o.shape == ():
            val = items[0]
        elif len(o.shape) == 1:
            val = "[" + ", ".join(items) + "]"
        else:
            n = o.shape[1]
            val = "[" + ", ".join("[" + ", ".join(items[r * n:(r + 1) * n]) + "]" for r in range(o.shape[0])) + "]"
        lines.append(f"        {o.name} = {val}")
        res.append(o.name)
    lines += ["    except ZeroDivisionError as exc:",
              "        raise NumericRangeError('division by zero (degenerate eigenvector)') from exc",
              f"    return {', '.join(res)}"]
    return "\n".join(lines)


def _legacy_module_body(N, specs):
    """``symbt.codegen.emit.module_body(N)`` for the closed form as it was before the emit path (2026-11-26),
    of the functions ``specs``."""
    from symbt.codegen.pymodule import module_head
    from symbt.codegen.runtime import ORBIT

    parts = module_head(N, "closed")
    for s in specs:
        parts += ["", "", _legacy_numpy(s, N)]
    for s in specs:
        parts += ["", "", _legacy_mpmath(s, N)]
    parts.append(ORBIT.rstrip("\n"))
    return "\n".join(parts) + "\n"


def _legacy_c_function(spec, N):
    from symbt.codegen.emit_c import _CODES, _OUT_PTRS, _SIGNATURES
    from symbt.codegen.printer import cse_block

    names = {}
    checks_ptr, checks_fin = [], []
    for a in spec.args:
        if a.kind == "state":
            checks_ptr.append(a.name)
            checks_fin.append(f"!toda{N}_finite({a.name}, NS)")
            for i, s in enumerate(a.symbols):
                names[s] = f"{a.name}[{i}]"
        elif a.kind == "branch":
            names[a.symbols[0]] = "b"
        else:
            checks_fin.append(f"!isfinite({a.name})")
            names[a.symbols[0]] = a.name
    outs = _OUT_PTRS[spec.name]
    lines = [_SIGNATURES[spec.name].format(N=N), "{"]
    lines.append(f"    if ({' || '.join('!' + x for x in checks_ptr + list(outs))})")
    lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    if any(a.kind == "branch" for a in spec.args):
        lines.append("    if (branch != 1 && branch != -1)")
        lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    lines.append(f"    if ({' || '.join(checks_fin)})")
    lines.append("        return SYMBT_TODA_INVALID_INPUT;")
    if any(a.kind == "branch" for a in spec.args):
        lines.append("    const double b = (double)branch;")
    exprs = [g.expr for g in spec.guards] + [e for o in spec.outputs for e in o.exprs]
    body, printed = cse_block(exprs, names, "c")
    lines += [f"    const double {ln};" for ln in body]
    gl, vals = printed[:len(spec.guards)], printed[len(spec.guards):]
    # in the spec's order, as the Python flavour decides: a non-finite guard is a range problem (and
    # decides nothing after it), a finite value <= 0 no real map ("range" guards need only be finite)
    for g, t in zip(spec.guards, gl):
        lines.append(f"    if (!isfinite({t}))")
        lines.append("        return SYMBT_TODA_RANGE;")
        if g.condition != "range":
            lines.append(f"    if (!({t} > 0.0))")
            lines.append(f"        return {_CODES[g.condition]};")
    lines.append(f"    const double out[{len(vals)}] = {{{', '.join(vals)}}};")
    lines.append(f"    if (!toda{N}_finite(out, {len(vals)}))")
    lines.append("        return SYMBT_TODA_RANGE;")
    k = 0
    for o, ptr in zip(spec.outputs, outs):
        n = len(o.exprs)
        lines.append(f"    for (int i = 0; i < {n}; i++)")
        lines.append(f"        {ptr}[i] = out[{k} + i];")
        k += n
    lines += ["    return SYMBT_TODA_OK;", "}"]
    return "\n".join(lines)


def _legacy_c_files(N, specs):
    """``symbt.codegen.emit_c.c_files(N)`` for the closed form as it was before the emit path, of ``specs``."""
    from symbt.codegen.c_template import COMMON, HEADER
    from symbt.codegen.emit_c import C_FUNCTIONS, _fill

    header, src = _fill(HEADER.replace("@@KAPPA@@", "16777216"), N, "closed"), _fill(COMMON, N, "closed")
    by_name = {s.name: s for s in specs}
    src += "\n/* ---- closed form: CSE of the SymPy expressions of symbt.codegen.derive ---- */\n"
    body = "".join("\n" + _legacy_c_function(by_name[name], N) + "\n" for name in C_FUNCTIONS)
    if "sgn(" in body:
        src += "\nstatic double sgn(double x) { return (double)((x > 0.0) - (x < 0.0)); }\n"
    return src + body, header


def _printable(N):
    """The closed-form specs of ``toda{N}`` restricted to what the legacy oracle can print: without the
    conditioning guards (issue 21, after the oracle was frozen; their ``Max`` is beyond its printer)."""
    from dataclasses import replace

    from symbt.codegen.derive import specs

    out = [replace(s, guards=tuple(g for g in s.guards if g.condition != "illcond")) for s in specs(N)]
    cut = {s.name for s, r in zip(specs(N), out) if s != r}
    assert cut == {"bt_step", "dapp_xy"}                   # the oracle still prints everything else as it is
    return out


@pytest.mark.parametrize("N", [2, 3])
def test_emit_declarations_reproduce_the_legacy_generator_where_it_can_print(N):
    """The oracle restricted to the parts it can print: every function, the conditioning guards of
    bt_step/dapp_xy left out on both sides, byte for byte (the Python module and the C target)."""
    from symbt.codegen.c_template import COMMON, HEADER
    from symbt.codegen.emit_c import _emit_path_c_files, _fill
    from symbt.codegen.user.render import python_module
    from symbt.codegen.zullo import declaration, declarations

    reduced = _printable(N)
    ems = [declaration(s, N) for s in reduced]
    _, template = declarations(N)
    assert python_module(f"toda{N}", ems, "symbt.codegen.zullo", template) == _legacy_module_body(N, reduced)
    header, common = _fill(HEADER.replace("@@KAPPA@@", "16777216"), N, "closed"), _fill(COMMON, N, "closed")
    assert _emit_path_c_files(N, header, common, ems) == _legacy_c_files(N, reduced)
    full, _ = declarations(N)
    assert all(e.typed and not e.optimize for e in full)
    assert not any(m == f"toda{N}" for m, _ in EMISSIONS)      # symbt's own: not in a user's registry


@pytest.mark.parametrize("N", [2, 3])
def test_the_legacy_oracle_cannot_print_the_conditioning_guards(N):
    """Why the oracle is restricted: its printer has no Max (the conditioning guards' condition estimate)."""
    from symbt.codegen.derive import specs

    with pytest.raises(ValueError):
        _legacy_module_body(N, specs(N))


# ---------------------------------------------------------------- the transfer-matrix form as Loop declarations

def _legacy_loop_numpy(spec, N):
    from symbt.codegen.emit_loop import NUMPY_CALL
    from symbt.codegen.pymodule import numpy_epilogue, numpy_prologue

    lines = numpy_prologue(spec, N, "transfer-matrix", "N")
    lines.append("    _g = []")
    call, items = NUMPY_CALL[spec.name]
    lines.append("    with np.errstate(all=\"ignore\"):")
    lines += [f"        {ln}" for ln in call.split("\n")]
    for o in spec.outputs:
        lines.append(f"        {o.name} = _pack({items[o.name]}, _batch, {o.shape!r})")
    lines += numpy_epilogue(spec, [o.name for o in spec.outputs], "_g")
    return "\n".join(lines)


def _legacy_loop_mp(spec, N):
    from symbt.codegen.emit_loop import MP_CALL
    from symbt.codegen.pymodule import function_doc, signature

    lines = [f"def {spec.name}_mp({signature(spec, 'mpmath')}):", function_doc(spec, N, "mpmath", "transfer-matrix")]
    for a in spec.args:
        if a.kind == "state":
            lines.append(f"    {a.name} = _mp_state({a.name}, N, {a.name!r})")
        elif a.kind == "branch":
            lines.append(f"    {a.name} = _mp_branch({a.name})")
        else:
            lines.append(f"    {a.name} = _mp_value({a.name}, {a.name!r})")
    call, ret = MP_CALL[spec.name]
    lines.append("    try:")
    lines += [f"        {ln}" for ln in call.split("\n")]
    lines.append("    except ZeroDivisionError as exc:")
    lines.append("        raise NumericRangeError('division by zero (degenerate eigenvector)') from exc")
    lines.append(f"    return {ret}")
    return "\n".join(lines)


def _legacy_loop_module(N):
    """``symbt.codegen.emit_loop.loop_module_body(N)`` as it was before the Loop declarations (2026-11-26)."""
    from symbt.codegen.derive import FUNCTIONS, interface
    from symbt.codegen.emit_loop import core
    from symbt.codegen.pymodule import module_head
    from symbt.codegen.runtime import ORBIT

    spec = interface(N)
    parts = module_head(N, "transfer-matrix") + [core().rstrip("\n")]
    for name in FUNCTIONS:
        parts += ["", "", _legacy_loop_numpy(spec[name], N)]
    for name in FUNCTIONS:
        parts += ["", "", _legacy_loop_mp(spec[name], N)]
    return "\n".join(parts + [ORBIT.rstrip("\n")]) + "\n"


@pytest.mark.parametrize("N", [4, 5, 8])
def test_the_loop_form_through_loop_declarations_is_byte_identical(N):
    """toda{N} (N >= 4) is declared like toda2/toda3 (typed emit, a Loop body each) and rendered by the same
    python_module / typed C renderer; Python and C equal the direct assembly they replace."""
    from symbt.codegen.c_template import COMMON, LOOP
    from symbt.codegen.emit import module_body
    from symbt.codegen.emit_c import _fill, c_files
    from symbt.codegen.zullo import declarations

    ems, _ = declarations(N, "transfer-matrix")
    assert all(e.typed and e.loop is not None for e in ems)
    assert [bool(e.loop.c) for e in ems] == [e.name in ("invariants", "spectral_trace", "flow_field", "bt_step")
                                             for e in ems]
    assert module_body(N) == _legacy_loop_module(N)
    direct = _fill(COMMON, N, "transfer-matrix") + _fill(LOOP.replace("@@KAPPA@@", "16777216"), N, "transfer-matrix")
    assert c_files(N)[0] == direct


def test_a_user_loop_declaration(tmp_path):
    """The Loop kind is public: fixed template code placed with the typed conventions (validation, errors)."""
    from symbt.codegen.user import Loop

    x, y = sp.symbols("x y", real=True)
    body = Loop(outputs=(("total", ()),), numpy="_s = z[..., 0] + z[..., 1]", items=(("total", "[_s]"),),
                mpmath="total = mpmath.fsum(z)",
                c="int lp_total(const double *z, double *total)\n{\n    if (!z || !total || !lp_finite(z, 2))\n"
                  "        return LP_INVALID_INPUT;\n    *total = z[0] + z[1];\n    return LP_OK;\n}")
    e = emit("total", body, args=(("z", (x, y)),), module="lp", register=False)
    files = {**user_render([e], tmp_path, tmp_path), **user_render([e], tmp_path, tmp_path, "c")}
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    spec = importlib.util.spec_from_file_location("lp", tmp_path / "lp.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.total(np.array([[1.0, 2.0], [3.0, 4.5]])).tolist() == [3.0, 7.5]
    assert mod.total_mp(["0.25", 1]) == mpmath.mpf("1.25")
    with pytest.raises(mod.InvalidInputError):
        mod.total([1.0, 2.0, 3.0])
    assert "int lp_total(const double *z, double *total);" in files["lp.h"]
    if shutil.which("cc"):
        subprocess.run(["cc", "-std=c99", "-Wall", "-Wextra", "-pedantic", "-Werror", "-c", "-o",
                        str(tmp_path / "lp.o"), str(tmp_path / "lp.c")], check=True, timeout=120)
    from symbt import Domain

    with pytest.raises(EmitError, match="no SymPy source"):
        emit("total", body, args=(("z", (x, y)),), module="lp", domain=Domain({"z": (0, 1)}), register=False)


@pytest.mark.parametrize("N", [2, 3])
def test_symbt_codegen_writes_the_emit_path_files_identical_but_for_the_hashes(N):
    """The committed file is the emit path's text under the header; only the two hash lines are not fixed."""
    import sympy

    from symbt.codegen.files import render
    from symbt.codegen.zullo import module_text

    written = render((N,))[f"toda{N}.py"]
    committed = (GEN / f"toda{N}.py").read_text()
    assert written == committed
    desc = f"toda{N} (N={N}, closed form)"
    expected = provenance.with_header(module_text(N), desc, "0" * 64, sympy.__version__, "#")
    assert _HASH_LINE.sub("", written) == _HASH_LINE.sub("", expected)
    assert _HASH_LINE.sub("", committed) != committed                  # the two lines were there to drop


def test_renderer_sources_are_derivation_sources():
    """toda{2,3}.py are rendered by symbt/codegen/user/*: an edit there makes them stale."""
    srcs = {p.relative_to(provenance.PACKAGE).as_posix() for p in provenance.derivation_sources()}
    assert {"codegen/zullo.py", "codegen/user/render_typed.py", "codegen/user/typed.py"} <= srcs


# ---------------------------------------------------------------- the typed form in a user's module

def _typed_module(tmp_path: Path, mask_module: str = "typedmod"):
    x, y, s, b = sp.symbols("x y s b", real=True)
    ems = [
        emit("scale", {"v": [b * x / y, b * s], "n": sp.log(y)}, args=(("z", (x, y)), s, ("b", b, "sign")),
             module=mask_module, guards=[Guard("positive", "y", y, early=True), Guard("range", "x/y", x / y)],
             register=False),
        emit("plain", x + 1, args=(x,), module=mask_module, register=False),
    ]
    text = user_render(ems, tmp_path, tmp_path)[f"{mask_module}.py"]
    path = tmp_path / f"{mask_module}.py"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(mask_module, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod, text


def test_typed_user_function_values_shapes_and_errors(tmp_path):
    mod, text = _typed_module(tmp_path)
    assert "def scale(z, s, b, errors=\"raise\"):" in text and "def scale_mp(z, s, b):" in text
    z = np.array([[3.0, 2.0], [1.0, 4.0], [-5.0, 0.5]])
    v, n = mod.scale(z, 0.25, -1)
    assert v.shape == (3, 2) and n.shape == (3,)
    np.testing.assert_array_equal(v[:, 0], -z[:, 0] / z[:, 1])
    np.testing.assert_array_equal(v[:, 1], np.full(3, -0.25))
    np.testing.assert_array_equal(n, np.log(z[:, 1]))
    assert mod.plain(np.array([1.0, 2.0])).tolist() == [2.0, 3.0]                 # plain ones still plain

    for bad, what in (([1.0, 2.0, 3.0], "shape"), (["a", "b"], "real"), ([1 + 1j, 2.0], "real"),
                      ([np.nan, 1.0], "finite")):
        with pytest.raises(mod.InvalidInputError, match=what):
            mod.scale(bad, 1.0, 1)
    with pytest.raises(mod.InvalidInputError, match="branch"):
        mod.scale([1.0, 2.0], 1.0, 0.5)
    with pytest.raises(mod.InvalidInputError, match="errors"):
        mod.scale([1.0, 2.0], 1.0, 1, errors="ignore")

    zb = np.array([[1.0, 2.0], [1.0, -2.0], [1.0, 3.0], [1e300, 1e-300]])
    with pytest.raises(mod.NoRealMapError) as info:
        mod.scale(zb, 1.0, 1)
    assert info.value.condition == "positive" and info.value.where == ((1,),) and "guard positive" in str(info.value)
    with pytest.raises(mod.NumericRangeError):
        mod.scale(zb[[0, 3]], 1.0, 1)                                            # x/y overflows: the range guard
    v, n = mod.scale(zb, 1.0, 1, errors="mask")
    assert isinstance(v, np.ma.MaskedArray) and v.mask[:, 0].tolist() == [False, True, False, True]
    assert n.mask.tolist() == [False, True, False, True] and v[2, 0] == 1.0 / 3.0


def test_typed_user_function_mpmath_flavour(tmp_path):
    mod, _ = _typed_module(tmp_path)
    with mpmath.workdps(40):
        v, n = mod.scale_mp(["1", "3"], "0.5", 1)
        assert v[0] == mpmath.mpf(1) / 3 and v[1] == mpmath.mpf("0.5") and n == mpmath.log(3)
        with pytest.raises(mod.NoRealMapError) as info:
            mod.scale_mp([1, -3], 1, 1)
        assert info.value.condition == "positive"
        with pytest.raises(mod.InvalidInputError):
            mod.scale_mp([1, 2, 3], 1, 1)
        with pytest.raises(mod.InvalidInputError):
            mod.scale_mp([1, 2], 1, 1 + 0j)


def test_a_module_template_places_hand_written_parts(tmp_path):
    x = sp.Symbol("x", real=True)
    from symbt.codegen.runtime import RUNTIME

    head = '"""Hand-written head."""\n' + RUNTIME + "\n_WHY = {'pos': 'x = %s <= 0'}\n\nHELPER = 41"
    t = module_template("tmpl", head=head, tail="\n\ndef helper():\n    return HELPER + 1", register=False)
    e = emit("root", {"r": sp.sqrt(x)}, args=(("v", (x,)),), module="tmpl", guards=[Guard("pos", "v", x)],
             register=False)
    from symbt.codegen.user.render import python_module

    text = python_module("tmpl", [e], "here", t)
    assert text.startswith('"""Hand-written head."""') and text.rstrip().endswith("return HELPER + 1")
    ns: dict = {}
    exec(compile(text, "tmpl.py", "exec"), ns)
    assert ns["helper"]() == 42 and ns["root"]([4.0]) == 2.0


def test_bad_typed_declarations_are_emit_errors():
    x, y = sp.symbols("x y", real=True)
    cases = [
        (dict(expr={"a": x}, args=(("v", (x,)),), guards=["x > 0"]), "Guard"),
        (dict(expr={"a": x}, args=(("v", [x]), ("w", [x])),), "distinct"),
        (dict(expr={"a": x + y}, args=(("v", (x,)),)), "symbol y is not among args"),
        (dict(expr={"1a": x}, args=(("v", (x,)),)), "identifier"),
        (dict(expr={"a": x}, args=(("v", (x,)),), guards=[Guard("pos", "x", sp.oo * x)]), "non-finite"),
        (dict(expr={"a": x}, args=(("b", x, "sign"), ("b2", (y,), "weird"))), "argument"),
        (dict(expr={"a": x}, args=(("t0", (x,)),)), "reserved"),
        (dict(expr={"a": x}, args=(("v", (x,)),), guards=[Guard("ok", "x", x)]), "other than ok"),
    ]
    for kw, words in cases:
        with pytest.raises(EmitError, match=words):
            emit("f", kw.pop("expr"), module="m", register=False, **kw)
    from symbt import Domain

    # domain= is sampled over the array's elements now (tests/test_codegen_user_typed.py); a bad one is refused
    assert set(emit("f", {"a": x}, args=(("v", (x,)),), module="m", domain=Domain({"v": (0, 1)}),
                    register=False).domain.variables) == {"x"}
    with pytest.raises(EmitError, match="lacks the array v"):
        emit("f", {"a": x}, args=(("v", (x,)),), module="m", domain=Domain({"w": (0, 1)}), register=False)
    from symbt.codegen.user.render import c_source

    e = emit("f", {"a": x}, args=(("v", (x,)),), module="m", register=False)
    mixed = c_source("m", [e, emit("g", x, args=(x,), module="m", register=False)])   # one source, both ABIs
    assert "int m_f(const double *v, double *a)" in mixed and "int m_g(const double *in, double *out)" in mixed


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler (cc) on PATH")
def test_typed_user_function_c_target(tmp_path):
    x, y, s, b = sp.symbols("x y s b", real=True)
    e = emit("scale", {"v": [b * x / y, b * s], "n": sp.log(y)}, args=(("z", (x, y)), s, ("b", b, "sign")),
             module="typedc", guards=[Guard("positive", "y", y, early=True), Guard("range", "x/y", x / y)],
             register=False)
    files = user_render([e], tmp_path, tmp_path, "c")
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    h = files["typedc.h"]
    assert "int typedc_scale(const double *z, double s, int b, double *v, double *n);" in h
    assert "#define TYPEDC_NO_REAL_POSITIVE 1" in h and "#define TYPEDC_RANGE 2" in h
    lib = tmp_path / "libtypedc.so"
    subprocess.run(["cc", "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC",
                    "-o", str(lib), str(tmp_path / "typedc.c"), "-lm"], check=True, timeout=120)
    f = ctypes.CDLL(str(lib)).typedc_scale
    dp = ctypes.POINTER(ctypes.c_double)
    f.argtypes = [dp, ctypes.c_double, ctypes.c_int, dp, dp]

    def call(z, s_, b_):
        zz, v, n = (ctypes.c_double * 2)(*z), (ctypes.c_double * 2)(7.0, 7.0), (ctypes.c_double * 1)(7.0)
        return f(zz, s_, b_, v, n), list(v), n[0]

    assert call([3.0, 2.0], 0.25, -1) == (0, [-1.5, -0.25], float(np.log(2.0)))
    assert call([3.0, -2.0], 0.25, 1) == (1, [7.0, 7.0], 7.0)                  # guard: outputs untouched
    assert call([1e300, 1e-300], 0.25, 1)[0] == 2                              # range guard
    assert call([1.0, 2.0], 0.25, 0)[0] == 3 and call([np.nan, 2.0], 0.25, 1)[0] == 3


def test_generated_zullo_modules_still_import_without_sympy():
    """The emit path changed nothing the emitted modules need (numpy and mpmath only)."""
    code = ("import sys; sys.modules['sympy'] = None\n"
            "import importlib.util as u\n"
            f"s = u.spec_from_file_location('t3', {str(GEN / 'toda3.py')!r}); m = u.module_from_spec(s)\n"
            "s.loader.exec_module(m); print(m.bt_step([-20.0, 10.0, 1.0], [1.0, 0.0, 0.9], 10.0, 5.0, 1)[1][0])")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and float(r.stdout) != 1.0, r.stderr
