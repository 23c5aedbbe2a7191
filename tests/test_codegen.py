"""`symbt codegen`: deterministic output, --check (missing / edited / stale), sympy-free
imports, and float64 vs mpmath agreement of the generated modules."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

import symbt.codegen as cg
from symbt.generated import toda2, toda3

ROOT = Path(__file__).resolve().parents[1]
GEN = ROOT / "symbt" / "generated"
FILES = ("__init__.py", "toda2.py", "toda3.py")


def _env(**extra):
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    env.update(extra)
    return env


@pytest.fixture(scope="module")
def fresh(tmp_path_factory):
    """Generate once in-process into a temporary directory."""
    out = tmp_path_factory.mktemp("gen")
    assert cg.main(["--out", str(out), "-q"]) == 0
    return out


def _copy(src, dst):
    dst.mkdir(exist_ok=True)
    for name in FILES:
        shutil.copy2(src / name, dst / name)
    return dst


# --------------------------------------------------------------------------- determinism

def test_generation_is_deterministic(fresh, tmp_path):
    # a second run in another process with a different hash seed: byte-identical output
    out2 = tmp_path / "gen2"
    r = subprocess.run([sys.executable, "-m", "symbt.codegen", "--out", str(out2), "-q"],
                       env=_env(PYTHONHASHSEED="12345"), capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    for name in FILES:
        assert (fresh / name).read_bytes() == (out2 / name).read_bytes(), name


def test_committed_files_equal_fresh_generation(fresh):
    for name in FILES:
        assert (GEN / name).read_bytes() == (fresh / name).read_bytes(), \
            f"symbt/generated/{name} differs from a fresh `symbt codegen`"


def test_no_temporary_files_left(fresh):
    assert sorted(p.name for p in fresh.iterdir()) == sorted(FILES)


# --------------------------------------------------------------------------- --check

def test_check_passes_on_committed_files(capsys):
    assert cg.main(["--check"]) == 0
    assert cg.check() == []


def test_check_via_python_m_symbt():
    r = subprocess.run([sys.executable, "-m", "symbt", "codegen", "--check"], env=_env(),
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr


def test_check_detects_hand_edit(tmp_path, capsys):
    out = _copy(GEN, tmp_path / "g")
    f = out / "toda2.py"
    f.write_text(f.read_text().replace("t0 = q1 - q2", "t0 = q2 - q1", 1))
    assert cg.main(["--check", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "toda2.py" in err and "edited by hand" in err
    assert "toda3.py" not in err


def test_check_detects_missing_file(tmp_path, capsys):
    out = _copy(GEN, tmp_path / "g")
    (out / "toda3.py").unlink()
    assert cg.main(["--check", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "toda3.py" in err and "missing" in err


def test_check_detects_stale_derivation(tmp_path, monkeypatch, capsys):
    out = _copy(GEN, tmp_path / "g")
    # simulate an edit of a derivation source: one more (changed) file among the sources
    extra = tmp_path / "changed_derivation.py"
    extra.write_text("x = 1\n")
    real = cg.derivation_sources
    monkeypatch.setattr(cg, "derivation_sources", lambda: real() + [extra])
    assert cg.main(["--check", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    for name in FILES:
        assert f"{name}: stale" in err
    # and through an explicit hash
    assert all("stale" in m for m in cg.check(out, dhash="0" * 64))


def test_header_format():
    text = (GEN / "toda3.py").read_text()
    head = cg.read_header(text)
    assert head["generator"] == cg.GENERATOR_VERSION
    assert head["target"] == "toda3 (N=3)"
    assert len(head["derivation-sha256"]) == 64 and len(head["content-sha256"]) == 64
    assert head["content-sha256"] == cg.content_hash(text)


# --------------------------------------------------------------------------- sympy-free

def test_generated_modules_import_without_sympy():
    code = ("import sys, importlib.util\n"
            "for name in ('toda2', 'toda3'):\n"
            f"    spec = importlib.util.spec_from_file_location(name, {str(GEN)!r} + '/' + name + '.py')\n"
            "    m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)\n"
            "    m.bt_step([-20.0, 10.0, 1.0][:m.N], [1.0, 0.0, 0.9][:m.N], 10.0, 5.0, 1)\n"
            "import symbt.generated.toda2, symbt.generated.toda3\n"
            "assert 'sympy' not in sys.modules, 'sympy was imported'\n"
            "print('ok')\n")
    r = subprocess.run([sys.executable, "-c", code], env=_env(), capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "ok" in r.stdout, r.stderr


def test_mpmath_flavour_has_no_float_literals():
    import re
    for name in ("toda2.py", "toda3.py"):
        text = (GEN / name).read_text()
        body = text[text.index("def invariants_mp"):]
        assert not re.search(r"(?<![\w.])\d+\.\d*(?![\w])|\de[-+]?\d", body), name


# --------------------------------------------------------------------------- float64 vs mpmath

def _states(N, n, seed):
    from symbt.reference.samples import admissible_states
    with mp.workdps(30):
        st = admissible_states(N, 1, n, seed=seed) + admissible_states(N, -1, n, seed=seed)
    P = np.array([[float(v) for v in s[0]] for s in st])
    Q = np.array([[float(v) for v in s[1]] for s in st])
    return P, Q, np.array([float(s[2]) for s in st]), np.array([float(s[3]) for s in st])


def _flat(x):
    outs = x if isinstance(x, tuple) else (x,)
    res = []
    for o in outs:
        if isinstance(o, list):
            for v in o:
                res += [float(t) for t in v] if isinstance(v, list) else [float(v)]
        else:
            res.append(float(o))
    return res


@pytest.mark.parametrize("mod", [toda2, toda3], ids=["n2", "n3"])
def test_float64_matches_mpmath_on_random_points(mod):
    N = mod.N
    rng = np.random.default_rng(N)
    P, Q, L0, MU = _states(N, 3, seed=5)
    B = np.where(np.arange(len(P)) % 2 == 0, 1.0, -1.0)
    C = rng.uniform(-1, 1, size=P.shape)
    calls = {
        "invariants": lambda i: (P[i], Q[i]),
        "spectral_trace": lambda i: (L0[i] + MU[i], P[i], Q[i]),
        "hamiltonian_fields": lambda i: (P[i], Q[i]),
        "flow_field": lambda i: (C[i], P[i], Q[i]),
        "phi": lambda i: (P[i], Q[i], L0[i], MU[i], int(B[i])),
        "phi_grad": lambda i: (P[i], Q[i], L0[i], MU[i], int(B[i])),
        "ck_integrand": lambda i: (L0[i] - MU[i], P[i], Q[i]),
        "dapp_xy": lambda i: (P[i], Q[i], L0[i], MU[i], int(B[i])),
        "bt_step": lambda i: (P[i], Q[i], L0[i], MU[i], int(B[i])),
    }
    batch_args = {
        "invariants": (P, Q), "spectral_trace": (L0 + MU, P, Q), "hamiltonian_fields": (P, Q),
        "flow_field": (C, P, Q), "phi": (P, Q, L0, MU, B), "phi_grad": (P, Q, L0, MU, B),
        "ck_integrand": (L0 - MU, P, Q), "dapp_xy": (P, Q, L0, MU, B), "bt_step": (P, Q, L0, MU, B),
    }
    for name, args_of in calls.items():
        fb = getattr(mod, name)(*batch_args[name])          # vectorised over the batch
        fb = fb if isinstance(fb, tuple) else (fb,)
        for i in range(len(P)):
            with mp.workdps(40):
                ref = _flat(getattr(mod, name + "_mp")(*[list(a) if isinstance(a, np.ndarray) else a
                                                           for a in args_of(i)]))
            got = np.concatenate([np.asarray(o[i]).reshape(-1) for o in fb])
            single = np.concatenate([np.asarray(o).reshape(-1) for o in
                                     (lambda r: r if isinstance(r, tuple) else (r,))(getattr(mod, name)(*args_of(i)))])
            np.testing.assert_array_equal(got, single, err_msg=f"{name}: batch != single")
            np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12, err_msg=f"{name}[{i}]")
    # phi_tr (no state)
    t1, t2 = np.array([2.5, -7.0, 31.0]), np.array([-2.2, 3.0, -40.0])
    got = mod.phi_tr(t1, t2, np.array([1, -1, 1]))
    for k in range(3):
        with mp.workdps(40):
            ref = mod.phi_tr_mp(t1[k], t2[k], [1, -1, 1][k])
        assert abs(got[k] - float(ref)) <= 1e-13 * max(1, abs(float(ref)))


def test_broadcasting_and_paper_example():
    p = np.array([[-20.0, 10.0, 1.0]] * 4).reshape(2, 2, 3)
    q = np.array([[1.0, 0.0, 0.9]] * 4).reshape(2, 2, 3)
    pt, qt = toda3.bt_step(p, q, 10.0, np.array([[5.0], [2.0]]), 1)
    assert pt.shape == (2, 2, 3) and qt.shape == (2, 2, 3)
    np.testing.assert_allclose(pt[0, 0], [-19.99656766, 9.78635495, 1.21021272], atol=5e-9)
    H = toda3.invariants(p, q)
    Ht = toda3.invariants(pt, qt)
    np.testing.assert_allclose(H, Ht, rtol=1e-12, atol=1e-10)   # the step preserves tr L
    with pytest.raises(ValueError):
        toda3.bt_step(p, q, 10.0, 5.0, 0)
    with pytest.raises(ValueError):
        toda3.invariants([1.0, 2.0], [0.0, 0.0])
