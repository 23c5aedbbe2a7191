"""`symbt.emit` in a user's project: `symbt codegen` writes, checks and verifies the user's own functions."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from symbt.codegen.user.check import compiler

ROOT = Path(__file__).resolve().parents[1]

MODEL = '''
import sympy as sp
from symbt import Domain, emit, log_uniform

x, y = sp.symbols("x y", real=True)
COEFF = sp.Rational(1, 2)

emit("softlog", sp.log(1 + x) + COEFF * y, args=(x, y), module="mymodel", doc="log(1 + x) + y/2",
     domain=Domain({"x": log_uniform(1e-14, 1e-2), "y": (-1, 1)}, seed=3))
emit("rotation", sp.Matrix([[sp.cos(y), -sp.sin(y)], [sp.sin(y), sp.cos(y)]]) * x, args=(x, y),
     module="mymodel", domain=Domain({"x": (0.5, 2), "y": (-3, 3)}, seed=4))
emit("ramp", sp.Piecewise((x**2, x < y), (sp.exp(y) - 1, True)), args=(x, y), module="mymodel",
     domain=Domain({"x": (-2, 2), "y": (-2, 2)}, seed=5))
'''


def run(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "symbt", *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=600)


@pytest.fixture()
def project(tmp_path: Path) -> Path:
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = ["model_emit.py"]\n')
    (tmp_path / "model_emit.py").write_text(MODEL)
    return tmp_path


def verify(cwd: Path) -> dict[str, dict]:
    r = run(cwd, "verify", "--no-cache", "-q", "--json", str(cwd / "out.json"))
    assert r.returncode in (0, 1), r.stderr
    return {c["id"]: c for c in json.loads((cwd / "out.json").read_text())["claims"]}


def test_emit_check_verify_stale_and_hand_edit(project: Path) -> None:
    r = run(project, "codegen")
    assert r.returncode == 0, r.stderr
    out = project / "generated" / "mymodel.py"
    text = out.read_text()
    assert "np.log1p(x)" in text and "symbt-codegen-derivation-sha256" in text   # the log1p rewrite helped
    assert run(project, "codegen", "--check").returncode == 0
    assert run(project, "codegen").stdout and out.read_text() == text             # deterministic

    res = verify(project)
    ids = {f"emit.mymodel.{n}.{f}" for n in ("softlog", "rotation", "ramp") for f in ("numpy", "mpmath", "c")}
    assert ids <= set(res)
    for n in ("softlog", "rotation", "ramp"):
        for f in ("numpy", "mpmath"):
            assert res[f"emit.mymodel.{n}.{f}"]["status"] == "verified", res[f"emit.mymodel.{n}.{f}"]
        assert res[f"emit.mymodel.{n}.c"]["status"] == "skipped"                 # not emitted for C
    ramp = res["emit.mymodel.ramp.numpy"]
    assert len(ramp["cells"]) == 2                                                # both branches sampled

    # a changed derivation: --check names the file stale (one line, exit 1), the claim fails until regenerated
    (project / "model_emit.py").write_text(MODEL.replace("Rational(1, 2)", "Rational(1, 3)"))
    r = run(project, "codegen", "--check")
    assert r.returncode == 1 and r.stderr.count("\n") == 1 and "mymodel.py: stale" in r.stderr, r.stderr
    assert verify(project)["emit.mymodel.softlog.numpy"]["status"] == "failed"
    assert run(project, "codegen").returncode == 0
    assert "(1/3)*y" in out.read_text() or "y/3" in out.read_text()
    assert verify(project)["emit.mymodel.softlog.numpy"]["status"] == "verified"

    # a hand edit: --check says edited by hand; the claim fails on provenance
    out.write_text(out.read_text().replace("np.log1p(x)", "np.log(1 + x)"))
    r = run(project, "codegen", "--check")
    assert r.returncode == 1 and r.stderr.count("\n") == 1 and "mymodel.py: edited by hand" in r.stderr, r.stderr


def test_the_comparison_fails_on_a_wrong_or_inaccurate_file(project: Path) -> None:
    """Two-sided: the check that passes the emitted file fails a naive log(1 + x) and a wrong constant."""
    import sympy as sp

    from symbt import Domain, log_uniform
    from symbt.codegen.user.check import compare
    from symbt.codegen.user.declare import emit

    x, y = sp.symbols("x y", real=True)
    dom = Domain({"x": log_uniform(1e-14, 1e-2), "y": (-1, 1)}, seed=3)
    lg = emit("lg", sp.log(1 + x), args=(x,), module="probe", domain=dom, register=False)
    e = emit("softlog", sp.log(1 + x) + y / 2, args=(x, y), module="probe", domain=dom, register=False)
    good = project / "good.py"
    good.write_text("import numpy as np\nimport mpmath\n"
                    "def lg(x):\n    return np.log1p(x)\n"
                    "def softlog(x, y):\n    return np.log1p(x) + y/2\n"
                    "def softlog_mp(x, y):\n    return mpmath.log1p(x) + mpmath.mpf(y)/2\n")
    naive = project / "naive.py"
    naive.write_text(good.read_text().replace("return np.log1p(x)\n", "return np.log(1 + x)\n"))
    wrong = project / "wrong.py"
    wrong.write_text(good.read_text().replace("mpmath.mpf(y)/2", "mpmath.mpf(y)*0.5000000001"))
    assert compare(lg, good, "numpy", per_cell=8).printed_holds_everywhere()
    assert compare(e, good, "numpy", per_cell=8).printed_holds_everywhere()
    assert compare(e, good, "mpmath", per_cell=8).printed_holds_everywhere()
    assert not compare(lg, naive, "numpy", per_cell=8).printed_holds_everywhere()   # log(1 + x) loses x
    assert not compare(e, wrong, "mpmath", per_cell=8).printed_holds_everywhere()


@pytest.mark.parametrize("body, words", [
    ("emit('f', x + z, args=(x,), module='m')", "symbol z is not among args"),
    ("emit('f', x + sp.oo, args=(x,), module='m')", "non-finite constant"),
    ("emit('f', sp.besselj(0, x), args=(x,), module='m')", "not supported by the C target"),
    ("emit('f', sp.Piecewise((x, x > 0)), args=(x,), module='m')", "default branch"),
    ("emit('f', x, args=(x,), module='m', domain=3)", "domain must be a symbt.Domain"),
])
def test_bad_declarations_exit_2_with_one_line(tmp_path: Path, body: str, words: str) -> None:
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = ["bad.py"]\n')
    (tmp_path / "bad.py").write_text("import sympy as sp\nfrom symbt import emit\nx, z = sp.symbols('x z')\n"
                                     + body + "\n")
    r = run(tmp_path, "codegen")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and words in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def test_bad_config_and_missing_source_exit_2(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = 3\n')
    r = run(tmp_path, "codegen", "--check")
    assert r.returncode == 2 and "'codegen' must be" in r.stderr and r.stderr.count("\n") == 1
    r = run(tmp_path, "codegen", "--codegen", "nowhere.py")
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr


@pytest.mark.skipif(compiler() is None, reason="no C compiler on PATH")
def test_c_target_compiled_and_verified(project: Path) -> None:
    assert run(project, "codegen").returncode == 0
    r = run(project, "codegen", "--target", "c")
    assert r.returncode == 0, r.stderr
    h = (project / "generated" / "mymodel.h").read_text()
    assert "int mymodel_rotation(const double *in, double *out);" in h and "#define MYMODEL_ROTATION_NOUT 4" in h
    assert run(project, "codegen", "--target", "c", "--check").returncode == 0
    res = verify(project)
    for n in ("softlog", "rotation", "ramp"):
        assert res[f"emit.mymodel.{n}.c"]["status"] == "verified", res[f"emit.mymodel.{n}.c"]
    # with the cache on: a hand edit of the C file is never served a cached verdict
    def cached_verify() -> dict[str, dict]:
        r = run(project, "verify", "-q", "--json", "-")
        return {x["id"]: x for x in json.loads(r.stdout)["claims"]}
    first = cached_verify()
    assert first["emit.mymodel.ramp.c"]["status"] == "verified"
    assert cached_verify()["emit.mymodel.ramp.c"]["cached"]
    c_file = project / "generated" / "mymodel.c"
    c_file.write_text(c_file.read_text().replace("return 0;", "return 0; "))
    again = cached_verify()["emit.mymodel.ramp.c"]
    assert again["status"] == "failed" and "edited by hand" in again["detail"] and not again["cached"], again
    # ... also off the warm path (no manifest: each cached entry is checked against its own key)
    assert run(project, "codegen", "--target", "c").returncode == 0           # the file regenerated
    assert cached_verify()["emit.mymodel.ramp.c"]["status"] == "verified"
    for manifest in Path(os.environ["SYMBT_CACHE_DIR"]).glob("manifest*.json"):
        manifest.unlink()
    c_file.write_text(c_file.read_text().replace("return 0;", "return 0; "))
    cold = cached_verify()["emit.mymodel.ramp.c"]
    assert cold["status"] == "failed" and not cold["cached"], cold
    # without a compiler the C claims are skipped, with the reason

    env = dict(os.environ, PATH=str(project / "empty"), PYTHONPATH=str(ROOT))
    r = subprocess.run([sys.executable, "-m", "symbt", "verify", "--no-cache", "-q", "--json", "-"], cwd=project,
                       env=env, capture_output=True, text=True, timeout=600)
    c = {x["id"]: x for x in json.loads(r.stdout)["claims"]}["emit.mymodel.ramp.c"]
    assert c["status"] == "skipped" and "no C compiler" in c["detail"], c


def test_derivation_sources_are_the_declaring_modules_and_what_they_import(tmp_path: Path) -> None:
    """A helper the declaring module imports makes the file stale; an unrelated file of the project does not."""
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = ["model_emit.py"]\ncodegen-out = "out"\n')
    (tmp_path / "helper.py").write_text("import sympy as sp\nK = sp.Rational(1, 2)\n")
    (tmp_path / "notes.py").write_text("X = 1\n")
    (tmp_path / "model_emit.py").write_text("import sympy as sp\nfrom symbt import emit\nfrom helper import K\n"
                                            "x = sp.Symbol('x')\nemit('half', K * x, args=(x,), module='h')\n")
    assert run(tmp_path, "codegen", "-q").returncode == 0 and (tmp_path / "out" / "h.py").is_file()
    (tmp_path / "notes.py").write_text("X = 2\n")
    assert run(tmp_path, "codegen", "--check").returncode == 0
    (tmp_path / "helper.py").write_text("import sympy as sp\nK = sp.Rational(1, 3)\n")
    r = run(tmp_path, "codegen", "--check")
    assert r.returncode == 1 and "h.py: stale" in r.stderr, r.stderr
    (tmp_path / "out" / "h.py").unlink()
    r = run(tmp_path, "codegen", "--check")
    assert r.returncode == 1 and "h.py: missing" in r.stderr, r.stderr


def test_without_a_user_config_codegen_is_the_package_s(tmp_path: Path) -> None:
    r = run(ROOT, "codegen", "--check")
    assert r.returncode == 0 and "generated files up to date" in r.stdout, r.stderr


def test_emit_is_public() -> None:
    import symbt

    assert "emit" in symbt.__all__ and symbt.emit.__module__ == "symbt.codegen.user.declare"


def test_equation_ties_the_emitted_claims_to_their_display(tmp_path: Path) -> None:
    """``emit(..., equation=LABEL)``: the three claims carry it as ``source_equation`` (coverage joins them there)."""
    import sympy as sp

    from symbt import emit
    from symbt.claims.base import REGISTRY, SCENES
    from symbt.codegen.user.declare import EmitError
    from symbt.engine.emitted_claims import register_emitted

    x = sp.Symbol("x")
    e = emit("tied", sp.exp(x) - 1, args=(x,), module="tiedmod", equation="eq1", register=False)
    untied = emit("untied", sp.exp(x) - 1, args=(x,), module="tiedmod", register=False)
    had_scene = "codegen" in SCENES
    ids = register_emitted([e, untied], tmp_path, tmp_path / "out")
    try:
        assert {REGISTRY[i].source_equation for i in ids if ".tied." in i} == {"eq1"}
        assert {REGISTRY[i].source_equation for i in ids if ".untied." in i} == {None}
        assert {REGISTRY[i].equation for i in ids if ".tied." in i} == {"tiedmod.tied"}
    finally:
        for i in ids:
            REGISTRY.pop(i, None)
        if not had_scene:
            SCENES.pop("codegen", None)
    with pytest.raises(EmitError, match="equation"):
        emit("bad_label", x, args=(x,), module="tiedmod", equation="  ", register=False)


def test_a_sum_of_thousands_of_terms_compiles_and_is_accurate(tmp_path: Path) -> None:
    """A sum of 6000 terms printed as one chain ``a + b + ...`` made Python's compiler raise RecursionError
    (the N >= 10 Toda trace); the balanced partial sums compile.  End to end, (1 + x + y)^40 expanded
    (861 terms) is emitted, imported and accurate to 16 eps S, S = sum of |terms| = (1 + |x| + |y|)^40."""
    import sympy as sp

    from symbt.codegen.user.check import load_python
    from symbt.codegen.user.declare import emit
    from symbt.codegen.user.files import generate
    from symbt.codegen.user.render import LONG_SUM, UserPrinter

    x, y = sp.symbols("x y", real=True)
    chain = sp.Add(*[x ** k for k in range(6000)])
    for flavour in ("numpy", "mpmath"):
        code = compile(UserPrinter(flavour, {x: "x"}).text(chain), "<sum>", "eval")
        assert abs(eval(code, {"x": 0.5}) - 2) <= 8 * 2.0 ** -52        # the geometric sum 2 - 2^-5999
    poly = sp.expand((1 + x + y) ** 40)
    assert len(poly.args) > 8 * LONG_SUM
    (path,) = generate([emit("big", poly, args=(x, y), module="bigsum", register=False)], tmp_path, tmp_path)
    mod = load_python(path)
    for xv, yv in ((0.01, 0.02), (-0.013, 0.007), (0.2, -0.15)):
        exact = (1 + sp.Rational(xv) + sp.Rational(yv)) ** 40
        S = float((1 + abs(sp.Rational(xv)) + abs(sp.Rational(yv))) ** 40)
        assert abs(float(mod.big(xv, yv)) - float(exact)) <= 16 * 2.0 ** -52 * S
        assert abs(float(mod.big_mp(xv, yv)) - float(exact)) <= 16 * 2.0 ** -52 * S


def test_rewriting_only_where_its_function_occurs() -> None:
    import sympy as sp
    from sympy.codegen.cfunctions import expm1

    from symbt.codegen.user.declare import emit
    from symbt.codegen.user.render import FACTOR_MAX_OPS, optimized

    x, y = sp.symbols("x y", real=True)
    big = sp.expand((1 + x + y) ** 30)            # no exp, no log: returned as declared (no factor())
    assert sp.count_ops(big) > FACTOR_MAX_OPS
    e = emit("f", [big, (big - 1) + sp.exp(x) - 1], args=(x, y), module="m", register=False)
    plain, rewritten = optimized(e)
    assert plain is e.exprs[0]
    assert rewritten.has(expm1) and not rewritten.has(sp.exp)   # exp(x) - 1 -> expm1(x), term by term
