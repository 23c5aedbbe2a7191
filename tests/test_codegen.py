"""`symbt codegen`: deterministic output, --check (missing / edited / stale, any --n), sympy-free
imports, the command acting on the checkout it is run in, one-line usage errors."""
from __future__ import annotations

import os
import re
import shutil
import stat
import subprocess
import sys
from pathlib import Path

import pytest

import symbt.codegen as cg
from symbt.codegen import provenance

ROOT = Path(__file__).resolve().parents[1]
GEN = ROOT / "symbt" / "generated"
FILES = ("__init__.py", "toda2.py", "toda3.py")


def _env(pythonpath=ROOT, **extra):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(pythonpath) + os.pathsep + env.get("PYTHONPATH", "")
    env.pop(cg.project.DELEGATED_ENV, None)
    env.update(extra)
    return env


@pytest.fixture(scope="session")
def launcher(tmp_path_factory):
    """Like the `symbt` console script: sys.path[0] is the script's directory, not the working directory
    (`python -m symbt` run from a checkout would import that checkout)."""
    path = tmp_path_factory.mktemp("bin") / "symbt_launcher.py"
    path.write_text("import sys\nfrom symbt.cli import main\nsys.exit(main())\n")
    return path


def _run(args, cwd=ROOT, pythonpath=ROOT, timeout=600, **extra):
    return subprocess.run([sys.executable, str(_LAUNCHER[0]), "codegen", *args], cwd=cwd,
                          env=_env(pythonpath, **extra), capture_output=True, text=True, timeout=timeout)


_LAUNCHER: list = []


@pytest.fixture(autouse=True)
def _use_launcher(launcher):
    _LAUNCHER[:] = [launcher]


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """Default files and toda5 (transfer-matrix form), generated in-process into a temporary directory."""
    out = tmp_path_factory.mktemp("gen")
    assert cg.main(["--project", str(ROOT), "--out", str(out), "-q"]) == 0
    assert cg.main(["--project", str(ROOT), "--out", str(out), "--n", "5", "-q"]) == 0
    return out


def _copy(src, dst, names=FILES):
    dst.mkdir(exist_ok=True)
    for name in names:
        shutil.copy2(src / name, dst / name)
    return dst


# --------------------------------------------------------------------------- determinism

def test_generation_is_deterministic(fresh, tmp_path):
    # a second run in another process with a different hash seed: byte-identical output
    out2 = tmp_path / "gen2"
    r = _run(["--out", str(out2), "--n", "2", "3", "5", "-q"], PYTHONHASHSEED="12345")
    assert r.returncode == 0, r.stderr
    for name in FILES + ("toda5.py",):
        assert (fresh / name).read_bytes() == (out2 / name).read_bytes(), name


def test_committed_files_equal_fresh_generation(fresh):
    for name in FILES:
        assert (GEN / name).read_bytes() == (fresh / name).read_bytes(), \
            f"symbt/generated/{name} differs from a fresh `symbt codegen`"


def test_no_temporary_files_left(fresh):
    assert sorted(p.name for p in fresh.iterdir()) == sorted(FILES + ("toda5.py",))


def test_forms_and_package_listing(fresh):
    assert cg.form_of(3) == "closed" and cg.form_of(cg.LOOP_FROM) == "transfer-matrix"
    assert cg.read_header((fresh / "toda3.py").read_text())["target"] == "toda3 (N=3, closed form)"
    assert cg.read_header((fresh / "toda5.py").read_text())["target"] == "toda5 (N=5, transfer-matrix form)"
    from symbt.generated import modules
    assert modules() == ("toda2", "toda3")


# --------------------------------------------------------------------------- --check

def test_check_passes_on_committed_files():
    assert cg.check() == []
    assert cg.main(["--check", "--project", str(ROOT), "-q"]) == 0


def test_check_via_python_m_symbt():
    r = subprocess.run([sys.executable, "-m", "symbt", "codegen", "--check"], cwd=ROOT, env=_env(),
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "up to date" in r.stdout and str(ROOT) in r.stdout
    assert _run(["--check"]).returncode == 0


def test_check_detects_hand_edit(tmp_path, capsys):
    out = _copy(GEN, tmp_path / "g")
    f = out / "toda2.py"
    text = f.read_text()
    assert "t0 = " in text
    f.write_text(text.replace("t0 = ", "t0 = 1.0 + ", 1))
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "toda2.py" in err and "edited by hand" in err
    assert "toda3.py" not in err


def test_check_detects_missing_file(tmp_path, capsys):
    out = _copy(GEN, tmp_path / "g")
    (out / "toda3.py").unlink()
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "toda3.py" in err and "missing" in err


def test_check_detects_stale_derivation(tmp_path, monkeypatch, capsys):
    out = _copy(GEN, tmp_path / "g")
    # simulate an edit of a derivation source: one more (changed) file among the sources
    extra = tmp_path / "changed_derivation.py"
    extra.write_text("x = 1\n")
    real = provenance.derivation_sources
    monkeypatch.setattr(provenance, "derivation_sources", lambda pkg=None: real(pkg) + [extra])
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    for name in FILES:
        assert f"{name}: stale" in err
    # and through an explicit hash
    assert all("stale" in m for m in cg.check(out, dhash="0" * 64))


def test_check_takes_the_n_list(fresh, tmp_path, capsys):
    out = _copy(fresh, tmp_path / "g", ("__init__.py", "toda5.py"))
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out), "--n", "5", "-q"]) == 0
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out), "-q"]) == 1   # default 2 3: missing
    assert "toda2.py: missing" in capsys.readouterr().err
    f = out / "toda5.py"
    f.write_text(f.read_text().replace("for j in range(N - 1):", "for j in range(N - 2):", 1))
    assert cg.main(["--check", "--project", str(ROOT), "--out", str(out), "--n", "5"]) == 1
    assert "toda5.py: edited by hand" in capsys.readouterr().err


def test_header_format():
    text = (GEN / "toda3.py").read_text()
    head = cg.read_header(text)
    assert head["generator"] == cg.GENERATOR_VERSION
    assert head["target"] == "toda3 (N=3, closed form)"
    assert len(head["derivation-sha256"]) == 64 and len(head["content-sha256"]) == 64
    assert head["content-sha256"] == cg.content_hash(text)
    assert head["derivation-sha256"] == cg.derivation_hash()


# --------------------------------------------------------------------------- sympy-free

def test_generated_modules_import_without_sympy(fresh):
    code = ("import sys, importlib.util\n"
            f"for path in ({str(GEN / 'toda2.py')!r}, {str(GEN / 'toda3.py')!r}, {str(fresh / 'toda5.py')!r}):\n"
            "    spec = importlib.util.spec_from_file_location('m', path)\n"
            "    m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)\n"
            "    m.bt_step(([-20.0, 10.0, 1.0] + [0.0] * 5)[:m.N], ([1.0, 0.0, 0.9] + [0.0] * 5)[:m.N], 10.0, 5.0, 1)\n"
            "import symbt.generated.toda2, symbt.generated.toda3\n"
            "import symbt.codegen; assert symbt.codegen.check() == []   # --check needs no SymPy\n"
            "assert 'sympy' not in sys.modules, 'sympy was imported'\n"
            "print('ok')\n")
    r = subprocess.run([sys.executable, "-c", code], env=_env(), capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "ok" in r.stdout, r.stderr


def test_emitted_imports_are_numpy_and_mpmath_only(fresh):
    for path in (GEN / "toda2.py", GEN / "toda3.py", fresh / "toda5.py"):
        imports = re.findall(r"^\s*(?:import|from)\s+([\w.]+)", path.read_text(), re.M)
        assert set(imports) == {"mpmath", "numpy"}, (path.name, imports)


_FLOAT = re.compile(r"(?<![\w.])\d+\.\d*(?![\w])|\de[-+]?\d")


def test_mpmath_flavour_has_no_float_literals(fresh):
    for name in ("toda2.py", "toda3.py"):
        text = (GEN / name).read_text()
        body = text[text.index("def invariants_mp"):text.index("def bt_orbit(")]
        assert not _FLOAT.search(body), name
    # transfer-matrix form: the code shared with the mpmath flavour (ops, polynomials, core loops)
    text = (fresh / "toda5.py").read_text()
    shared = (text[text.index("class _MpOps"):text.index("_NP, _MP =")]
              + text[text.index("class _ListPoly"):text.index("class _ArrayPoly")]
              + text[text.index("def _cols("):text.index("def invariants(")])
    assert not _FLOAT.search(shared)


# --------------------------------------------------------------------------- usage errors

def _one_line_error(r):
    assert r.returncode == 2, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("symbt codegen: error:"), r.stderr
    assert "Traceback" not in r.stderr
    return lines[0]


def test_no_project_found_is_a_one_line_error(tmp_path):
    msg = _one_line_error(_run(["--check"], cwd=tmp_path))
    assert "no symbt checkout" in msg and "--installed" in msg
    msg = _one_line_error(_run(["--check", "--project", str(tmp_path)], cwd=tmp_path))
    assert "not a symbt checkout" in msg


@pytest.mark.skipif(os.name != "posix" or os.geteuid() == 0, reason="needs a non-root POSIX user for permissions")
def test_unwritable_output_is_a_one_line_error(tmp_path):
    out = tmp_path / "ro"
    out.mkdir()
    out.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        msg = _one_line_error(_run(["--out", str(out), "--n", "5"]))
        assert "cannot write" in msg
    finally:
        out.chmod(stat.S_IRWXU)


def test_output_path_that_is_a_file_is_a_one_line_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory\n")
    msg = _one_line_error(_run(["--out", str(blocker / "sub"), "--n", "5"]))
    assert "cannot write" in msg


@pytest.mark.parametrize("args, text", [(["--n", "1"], ">= 2"), (["--target", "c"], "--out"),
                                        (["--target", "fortran"], "invalid choice"), (["--bogus"], "unrecognized")])
def test_bad_options_are_one_line_errors(args, text):
    assert text in _one_line_error(_run(args))


# --------------------------------------------------------------------------- the checkout, not site-packages

@pytest.fixture(scope="module")
def checkout(tmp_path_factory):
    """A copy of the source tree (pyproject.toml + symbt/); Python imports ROOT's symbt, not the copy's,
    as after `pip install .`."""
    root = tmp_path_factory.mktemp("checkout")
    shutil.copy2(ROOT / "pyproject.toml", root / "pyproject.toml")
    shutil.copytree(ROOT / "symbt", root / "symbt", ignore=shutil.ignore_patterns("__pycache__"))
    (root / "docs").mkdir()
    return root


def test_checkout_check_acts_on_the_checkout(checkout):
    r = _run(["--check"], cwd=checkout / "docs")          # found by walking up from a subdirectory
    assert r.returncode == 0, r.stderr
    assert f"checkout {checkout}" in r.stdout


def test_checkout_hand_edit_and_stale_derivation_are_caught(checkout):
    gen = checkout / "symbt" / "generated" / "toda2.py"
    original = gen.read_text()
    gen.write_text(original.replace("t0 = ", "t0 = 2*", 1))
    try:
        r = _run(["--check"], cwd=checkout)
        assert r.returncode == 1 and f"{gen}: edited by hand" in r.stderr, r.stdout + r.stderr
        r = _run(["--check", "--installed"], cwd=checkout)   # the imported package is untouched
        assert r.returncode == 0 and str(GEN) in r.stdout, r.stdout + r.stderr
    finally:
        gen.write_text(original)
    src = checkout / "symbt" / "symbolic" / "toda.py"
    src.write_text(src.read_text() + "\n# an edit of a derivation source\n")
    r = _run(["--check"], cwd=checkout)
    assert r.returncode == 1 and f"{gen}: stale" in r.stderr, r.stdout + r.stderr
    # regenerating writes into the checkout, from the checkout's sources; the imported package is untouched
    before = {p.name: p.read_bytes() for p in GEN.glob("*.py")}
    r = _run(["--n", "2", "-q"], cwd=checkout)
    assert r.returncode == 0, r.stderr
    assert cg.read_header(gen.read_text())["derivation-sha256"] == provenance.derivation_hash(pkg=checkout / "symbt")
    assert cg.read_header(gen.read_text())["derivation-sha256"] != cg.derivation_hash()
    assert {p.name: p.read_bytes() for p in GEN.glob("*.py")} == before
    r = _run(["--check", "--n", "2"], cwd=checkout)
    assert r.returncode == 0, r.stderr


def test_out_dir_outside_any_checkout_uses_the_installed_derivations(tmp_path):
    """Code for a project of your own: `--out DIR` outside a checkout emits from the imported package; writing
    the package's own symbt/generated there is refused (exit 2, one line)."""
    import os
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[1]
    env = dict(os.environ, PYTHONPATH=str(root))
    run = lambda *a: subprocess.run([sys.executable, "-m", "symbt", "codegen", *a], cwd=tmp_path, env=env,
                                    capture_output=True, text=True, timeout=300)
    ok = run("--n", "2", "--out", "gen", "-q")
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "gen" / "toda2.py").is_file()
    assert run("--check", "--n", "2", "--out", "gen").returncode == 0
    refused = run("--check")
    assert refused.returncode == 2 and len(refused.stderr.strip().splitlines()) == 1
    assert "no symbt checkout" in refused.stderr
