"""``symbt init --paper``: one todo stub per labelled display, a [tool.symbt] table, and the round trip
init -> verify says todo -> coverage exit 1 -> a stub filled with a real check -> that label covered."""
from __future__ import annotations

import json

import pytest
from test_coverage_any_paper import NOTE, fresh  # noqa: F401  (the fixture is used by name)

from symbt.engine import coverage, init
from symbt.engine.project import discover, read_config

pytest.importorskip("pylatexenc", reason="the 'latex' extra (pylatexenc) reads the paper's labels")

DISPLAYS = ["eq-energy", "eq-qdot", "eq-newton", "eq-square", "fig-phase"]


def paper(tmp_path, name="note", tex=NOTE):
    tmp_path.mkdir(parents=True, exist_ok=True)
    p = tmp_path / f"{name}.tex"
    p.write_text(tex)
    return p


def test_init_writes_stubs_with_the_public_api_and_the_config(tmp_path, capsys):
    tex = paper(tmp_path / "a", "alpha")
    assert init.main(["--paper", str(tex)]) == 0
    module = tmp_path / "a" / "alpha_claims.py"
    text = module.read_text()
    compile(text, str(module), "exec")
    assert "from symbt import claim, todo\n" in text and "symbt." not in text.replace("symbt init", "")
    assert text.count("@claim(") == len(DISPLAYS) and text.count("\n    return todo()\n") == len(DISPLAYS)
    for label in DISPLAYS:
        assert f'equation="{label}"' in text
    assert "eq-commented" not in text and "sec-model" not in text  # a comment, a section: no stubs
    assert "#   \\dot q &= p\n" in text  # the row's LaTeX source above its stub
    assert "(Section 1, equation, tag N)" in text
    cfg = read_config(tmp_path / "a" / "pyproject.toml")
    assert cfg["claims"] == (str(module),) and cfg["paper"] == tex.resolve()
    assert "wrote" in capsys.readouterr().out


def test_claim_ids_and_function_names_are_valid_and_unique(tmp_path, fresh):  # noqa: F811
    tex = paper(tmp_path / "b", "beta", r"""\begin{document}
\begin{equation}\label{a b}x\end{equation}\begin{equation}\label{a-b}y\end{equation}
\begin{equation}\label{fig:1}z\end{equation}\begin{equation}\label{a_b}w\end{equation}\end{document}""")
    assert init.main(["--paper", str(tex)]) == 0
    from symbt.engine.project import load

    claims = load(discover(start=tmp_path / "b"))
    assert [c.id for c in claims] == ["a-b", "a-b-2", "fig:1", "a_b"]
    assert [c.equation for c in claims] == ["a b", "a-b", "fig:1", "a_b"]
    assert len({c.func.__name__ for c in claims}) == 4


def test_refuses_to_overwrite_without_force(tmp_path, capsys):
    tex = paper(tmp_path / "c", "gamma")
    module = tmp_path / "c" / "gamma_claims.py"
    module.write_text("# my checks\n")
    assert init.main(["--paper", str(tex)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--force" in err
    assert module.read_text() == "# my checks\n"
    assert init.main(["--paper", str(tex), "--force"]) == 0
    assert "return todo()" in module.read_text()


def test_out_and_existing_pyproject(tmp_path, capsys):
    tex = paper(tmp_path / "d", "delta")
    pyproject = tmp_path / "d" / "pyproject.toml"
    pyproject.write_text('[project]\nname = "mine"\n')
    (tmp_path / "d" / "checks").mkdir()
    assert init.main(["--paper", str(tex), "--out", str(tmp_path / "d" / "checks" / "mine.py")]) == 0
    text = pyproject.read_text()
    assert text.startswith('[project]\nname = "mine"\n')  # kept as it was
    assert read_config(pyproject)["claims"] == (str(tmp_path / "d" / "checks" / "mine.py"),)
    assert 'claims = ["checks/mine.py"]' in text
    # a [tool.symbt] table is never rewritten: the lines to add are printed
    pyproject.write_text('[tool.symbt]\nclaims = ["other.py"]\n')
    assert init.main(["--paper", str(tex), "--force"]) == 0
    assert pyproject.read_text() == '[tool.symbt]\nclaims = ["other.py"]\n'
    out = capsys.readouterr().out
    assert 'claims = ["delta_claims.py"]' in out and 'paper = "delta.tex"' in out


@pytest.mark.parametrize("tex, words", [
    (NOTE.replace(r"\end{align}", ""), "does not parse"),
    (r"\begin{document}\section{A}\label{s} text \end{document}", "no labelled display"),
    (None, "cannot read"),
])
def test_bad_paper_exits_2_in_one_line(tmp_path, capsys, tex, words):
    from symbt.cli import main

    path = tmp_path / "e" / "eps.tex"
    if tex is not None:
        paper(tmp_path / "e", "eps", tex)
    assert main(["init", "--paper", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err
    assert not (tmp_path / "e" / "eps_claims.py").exists()


def test_invalid_pyproject_exits_2_and_writes_nothing(tmp_path, capsys):
    tex = paper(tmp_path / "f", "phi")
    (tmp_path / "f" / "pyproject.toml").write_text("[project\n")
    assert init.main(["--paper", str(tex)]) == 2
    assert "not valid TOML" in capsys.readouterr().err
    assert not (tmp_path / "f" / "phi_claims.py").exists()


def test_round_trip(tmp_path, monkeypatch, capsys, fresh):  # noqa: F811
    from symbt import engine
    from symbt.engine.cache import load_cached

    root = tmp_path / "g"
    tex = paper(root, "note")
    monkeypatch.chdir(root)
    assert init.main(["--paper", str(tex)]) == 0
    capsys.readouterr()

    # verify: every stub is todo, none verified, none cached
    claims = engine.select(project=discover())
    results = engine.run(claims, manifest=False)
    assert [(r.claim.equation, r.outcome.status) for r in results] == [(label, "todo") for label in DISPLAYS]
    assert all(load_cached(c) is None for c in claims)

    # coverage: exit 1, every display a todo
    assert coverage.main(["--json", "-", "-q"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["todo"] == DISPLAYS and data["uncovered"] == []

    # fill one stub with a real check
    module = root / "note_claims.py"
    text = module.read_text()
    stub = "def check_eq_square():\n    return todo()\n"
    assert stub in text
    module.write_text("import sympy as sp\nfrom symbt import decide, from_decision\n" + text.replace(
        stub, "def check_eq_square():\n    a, b = sp.symbols('a b')\n"
              "    return from_decision(decide((a + b)**2, a**2 + 2*a*b + b**2))\n"))
    fresh()  # a new process would import the edited module
    assert coverage.main(["--json", "-", "-q"]) == 1  # the other four are still stubs
    data = json.loads(capsys.readouterr().out)
    assert data["coverage"]["eq-square"] == {"claims": [{"id": "eq-square", "status": "verified"}]}
    assert data["todo"] == [label for label in DISPLAYS if label != "eq-square"]


@pytest.mark.parametrize("argv", [["init"], ["init", "--paper"], ["coverage", "--bogus"]])
def test_usage_errors_are_one_line(argv, capsys):
    from symbt.cli import main

    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"symbt {argv[0]}: ")
