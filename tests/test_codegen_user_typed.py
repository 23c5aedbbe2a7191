"""Typed `symbt.emit` declarations with `domain=`: their `emit.*` claims (issue 24, item 3, typed form).

Arrays are sampled by component (one range per array or one per element), every sign is a cell, and
a point where a guard refuses on the reference must be refused by the emitted code too (counted, not
compared).  Two-sided: planted bugs in the emitted file and a wrong derivation make the comparison fail.
"""
from __future__ import annotations

import ctypes
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

from symbt import Domain
from symbt.codegen.user import EmitError, Guard, emit
from symbt.codegen.user.check import Comparison, compare, compiler
from symbt.codegen.user.files import generate

ROOT = Path(__file__).resolve().parents[1]

MODEL = '''
import sympy as sp
from symbt import Domain, emit
from symbt.codegen.user import Guard

x, y, s, b = sp.symbols("x y s b", real=True)
emit("scale", {"v": [b * x / y, b * s], "n": sp.log(y)}, args=(("z", (x, y)), s, ("b", b, "sign")),
     module="tmodel", guards=[Guard("positive", "y", y, early=True), Guard("range", "x/y", x / y)],
     domain=Domain({"z": (-2, 2), "s": (-1, 1)}, seed=3))
emit("shift", {"w": [sp.Piecewise((x - y, x > y), (sp.exp(y) - 1, True))]}, args=(("z", (x, y)),),
     module="tmodel", domain=Domain({"x": (-1, 1), "y": (-1e-3, 1e-3)}, seed=4))
emit("energy", sp.log(1 + x**2) / 2 + sp.sign(y) * (sp.exp(y) - 1), args=(x, y), module="tmodel",
     domain=Domain({"x": (-2, 2), "y": (-1, 1)}, seed=5))       # a plain declaration in the same module
'''


def run(cwd: Path, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return subprocess.run([sys.executable, "-m", "symbt", *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=600)


def verify(cwd: Path) -> dict[str, dict]:
    r = run(cwd, "verify", "--no-cache", "-q", "--json", str(cwd / "out.json"))
    assert r.returncode in (0, 1), r.stderr
    return {c["id"]: c for c in json.loads((cwd / "out.json").read_text())["claims"]}


def _scale(module: str = "probe", factor: sp.Expr = sp.S.One):
    x, y, s, b = sp.symbols("x y s b", real=True)
    return emit("scale", {"v": [factor * b * x / y, b * s], "n": sp.log(y)}, args=(("z", (x, y)), s, ("b", b, "sign")),
                module=module, guards=[Guard("positive", "y", y, early=True), Guard("range", "x/y", x / y)],
                domain=Domain({"z": (-2, 2), "s": (-1, 1)}, seed=3), register=False)


def test_domain_forms_of_a_typed_declaration() -> None:
    x, y, s, b = sp.symbols("x y s b", real=True)
    e = _scale()
    assert set(e.domain.variables) == {"x", "y", "s"}                       # the array by component
    assert [c.name for c in e.cells] == ["b"] and e.cells[0].values == (1, -1)     # every sign a cell
    box = emit("g", {"r": x + y}, args=(("z", (x, y)),), module="m", register=False,
               domain=Domain({"x": (0, 1), "y": (5, 6)}))
    assert str(box.domain.variables["y"]) == "uniform(5, 6)"
    pw = emit("h", {"r": sp.Piecewise((x, x > y), (y, True))}, args=(("z", (x, y)),), module="m", register=False,
              domain=Domain({"z": (0, 1)}))
    assert [c.kind for c in pw.cells] == ["sign"]                           # the Piecewise's branches


@pytest.mark.parametrize("domain, words", [
    ({"z": (0, 1), "s": (0, 1), "b": (0, 1)}, "sign argument 'b'"),
    ({"x": (0, 1), "s": (0, 1)}, "lacks the array z"),
    ({"z": (0, 1), "x": (0, 1), "s": (0, 1)}, "both one range and ranges of its elements"),
    ({"z": (0, 1), "s": (0, 1), "w": (0, 1)}, "names w, which is no argument"),
    ({"z": (0, 1)}, "lacks the argument s"),
])
def test_bad_typed_domains_are_emit_errors(domain: dict, words: str) -> None:
    x, y, s, b = sp.symbols("x y s b", real=True)
    with pytest.raises(EmitError, match=words):
        emit("f", {"a": b * x + y + s}, args=(("z", (x, y)), s, ("b", b, "sign")), module="m",
             domain=Domain(domain), register=False)


def test_bad_typed_domain_exits_2_with_one_line(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = ["bad.py"]\n')
    (tmp_path / "bad.py").write_text(MODEL.replace('Domain({"z": (-2, 2), "s": (-1, 1)}, seed=3)',
                                                   'Domain({"z": (-2, 2), "s": (-1, 1), "b": (-1, 1)})'))
    r = run(tmp_path, "codegen")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "sign argument 'b'" in r.stderr, r.stderr
    assert "Traceback" not in r.stderr


def _flavours() -> tuple[str, ...]:
    return ("numpy", "mpmath", "c") if compiler() is not None else ("numpy", "mpmath")


def test_a_typed_project_gets_its_claims_through_verify(tmp_path: Path) -> None:
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\ncodegen = ["model_emit.py"]\n')
    (tmp_path / "model_emit.py").write_text(MODEL)
    assert run(tmp_path, "codegen").returncode == 0
    if compiler() is not None:
        assert run(tmp_path, "codegen", "--target", "c").returncode == 0
    res = verify(tmp_path)
    for name in ("scale", "shift", "energy"):
        for fl in _flavours():
            c = res[f"emit.tmodel.{name}.{fl}"]
            assert c["status"] == "verified", c
    scale = res["emit.tmodel.scale.numpy"]
    assert {tuple(sorted(c["cell"].items())) for c in scale["cells"]} == {(("b", 1),), (("b", -1),)}
    # y < 0 at about half the points: refused on both sides, counted, not compared
    assert "refused by a guard on both sides (positive " in scale["detail"], scale["detail"]
    assert len(res["emit.tmodel.shift.mpmath"]["cells"]) == 2                  # both branches sampled

    # a changed derivation: the file is stale until regenerated (the claim fails on provenance)
    (tmp_path / "model_emit.py").write_text(MODEL.replace('"v": [b * x / y', '"v": [b * x / y / 2'))
    assert verify(tmp_path)["emit.tmodel.scale.numpy"]["status"] == "failed"
    assert run(tmp_path, "codegen").returncode == 0
    assert verify(tmp_path)["emit.tmodel.scale.numpy"]["status"] == "verified"


def _edited(tmp_path: Path, e, flavour: str, old: str, new: str) -> bool:
    """Does ``compare`` accept the emitted file of ``e`` with ``old`` replaced by ``new`` (a planted bug)?"""
    out = tmp_path / flavour
    out.mkdir()
    generate([e], out, out, "c" if flavour == "c" else "python")
    path = out / f"{e.module}.{'c' if flavour == 'c' else 'py'}"
    text = path.read_text()
    if old:
        assert old in text, (old, text)
        path.write_text(text.replace(old, new))
    return compare(e, path, flavour, per_cell=8).printed_holds_everywhere()


@pytest.mark.parametrize("flavour, old, new", [
    ("numpy", "", ""),                                                     # the control: accepted as emitted
    ("numpy", "np.log(y)", "np.log(y*1.0000000001)"),                     # an output off by 1e-10
    ("numpy", "('positive', 'y', y)", "('positive', 'y', y + 1)"),        # a guard that lets y in (-1, 0] through
    ("numpy", "('positive', 'y', y)", "('positive', 'y', y - 0.5)"),      # a guard that refuses valid points
    ("mpmath", "", ""),
    ("mpmath", "mpmath.log(y)", "mpmath.log(y) + mpmath.mpf(10)**-30"),
    ("c", "", ""),
    ("c", "log(z[1])", "log(z[1])*(1.0 + 1e-10)"),
    ("c", "return TMC_NO_REAL_POSITIVE", "return TMC_RANGE"),             # the wrong status for a refusal
])
def test_planted_bugs_in_the_emitted_file_fail_the_comparison(tmp_path: Path, flavour: str, old: str,
                                                              new: str) -> None:
    if flavour == "c" and compiler() is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH")
    e = _scale("tmc")
    assert _edited(tmp_path, e, flavour, old, new) == (old == "")


def test_a_wrong_derivation_fails_the_comparison(tmp_path: Path) -> None:
    """The file emitted from a derivation off by a relative 1e-12 is rejected by the right declaration."""
    right, wrong = _scale("wd"), _scale("wd", 1 + sp.Rational(1, 10**12))
    generate([wrong], tmp_path, tmp_path)
    seen = Comparison()
    assert not compare(right, tmp_path / "wd.py", "numpy", per_cell=8, seen=seen).printed_holds_everywhere()
    assert seen.refused > 0 and seen.conditions.keys() == {"positive"}
    generate([right], tmp_path, tmp_path)
    assert compare(right, tmp_path / "wd.py", "numpy", per_cell=8).printed_holds_everywhere()


@pytest.mark.skipif(compiler() is None, reason="no C compiler (cc, gcc or clang) on PATH")
def test_a_module_mixing_typed_and_plain_declarations_is_one_c_source(tmp_path: Path) -> None:
    """Both ABIs in one .c/.h: compiled with -Wall -Wextra -pedantic -Werror, each called by its own ABI."""
    x, y = sp.symbols("x y", real=True)
    typed = _scale("mixed")
    plain = emit("energy", sp.log(1 + x**2) / 2 + sp.sign(y) * (sp.exp(y) - 1), args=(x, y), module="mixed",
                 domain=Domain({"x": (-2, 2), "y": (-1, 1)}, seed=5), register=False)
    generate([typed, plain], tmp_path, tmp_path, "c")
    h = (tmp_path / "mixed.h").read_text()
    assert h.count("#ifndef SYMBT_EMITTED_MIXED_H") == 1 and "#define MIXED_NO_REAL_POSITIVE 1" in h
    assert "int mixed_scale(const double *z, double s, int b, double *v, double *n);" in h
    assert "int mixed_energy(const double *in, double *out);" in h and "#define MIXED_ENERGY_NIN 2" in h
    src = (tmp_path / "mixed.c").read_text()
    assert src.count("static double sgn(") == 1
    lib = tmp_path / "libmixed.so"
    r = subprocess.run([compiler(), "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-shared", "-fPIC",
                        "-o", str(lib), str(tmp_path / "mixed.c"), "-lm"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    energy = ctypes.CDLL(str(lib)).mixed_energy
    energy.argtypes = [ctypes.POINTER(ctypes.c_double)] * 2
    out = (ctypes.c_double * 1)()
    assert energy((ctypes.c_double * 2)(0.0, 0.0), out) == 0 and out[0] == 0.0
    for e in (typed, plain):                 # the claims' comparison through the compiled module
        assert compare(e, tmp_path / "mixed.c", "c", per_cell=8).printed_holds_everywhere(), e.name
