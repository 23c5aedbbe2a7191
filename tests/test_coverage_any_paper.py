r"""Coverage of a user's paper: labels read with a LaTeX parser, joined with the user's claims and reasons.

A small note written here (a commented-out \label, an align with two labelled rows and a \nonumber
row, \tag, \eqref, a user macro for equations, a figure), its claims module and [tool.symbt] in a
tmp dir: the join, exit 0 when covered, 1 on a gap / todo stub / unknown label, 2 for a missing or
unparsable paper (one line on stderr, no traceback).
"""
from __future__ import annotations

import json
import sys
import textwrap
from pathlib import Path

import pytest

from symbt.engine import coverage
from symbt.engine.labels import LatexError, scan, scan_file
from symbt.paper import LABELS

pytest.importorskip("pylatexenc", reason="the 'latex' extra (pylatexenc) reads the paper's labels")

NOTE = r"""\documentclass{article}
\usepackage{amsmath}
\def\beq{\begin{equation}}
\def\eeq{\end{equation}}
\begin{document}
\section{Model}\label{sec-model}
% an old display, commented out: \label{eq-commented}
\begin{equation}\label{eq-energy}
E = \frac{p^2}{2} + V(q)
\end{equation}
\begin{align}
\dot q &= p \label{eq-qdot}\\
\dot p &= -V'(q) \nonumber\\
\ddot q &= -V'(q) \tag{N}\label{eq-newton} \quad\text{by \eqref{eq-qdot}}
\end{align}
\section{Results}
\beq\label{eq-square}
(a+b)^2 = a^2 + 2ab + b^2
\eeq
\begin{figure}\caption{Phase portrait of \eqref{eq-energy}}\label{fig-phase}\end{figure}
\end{document}
"""

CLAIMS = '''
import sympy as sp
from symbt import claim, decide, from_decision, todo

a, b = sp.symbols("a b")


@claim("square", equation="eq-square", scene="note", statement="(a+b)^2 = a^2 + 2ab + b^2")
def square():
    return from_decision(decide((a + b)**2, a**2 + 2*a*b + b**2))


@claim("qdot", equation="eq-qdot", scene="note", statement="dq/dt = p for H = p^2/2 + V")
def qdot():
    p, q = sp.symbols("p q")
    H = p**2/2 + sp.Function("V")(q)
    return from_decision(decide(sp.diff(H, p), p))
'''

REASONS = {"eq-energy": "a definition", "eq-newton": "follows from eq-qdot and its partner row",
           "fig-phase": "a figure"}


@pytest.fixture
def fresh(tmp_path_factory):
    """Undo what loading a user's claims module does to the process (registry, modules, active project)."""
    from symbt.claims.base import REGISTRY, SCENES
    from symbt.engine import project as proj

    saved = dict(REGISTRY), dict(SCENES), set(sys.modules), list(sys.path), list(proj._ACTIVE), dict(proj._OWNERS)

    def restore():
        reg, scenes, mods, path, active, owners = saved
        REGISTRY.clear()
        REGISTRY.update(reg)
        SCENES.clear()
        SCENES.update(scenes)
        # only the user's modules (files of the tests' projects) go: a library module first imported during the
        # test (a symbt submodule, sympy's) must stay, or the next import makes a second copy beside the old one
        # that the package attribute and other modules keep (monkeypatches and isinstance then see different ones)
        base = tmp_path_factory.getbasetemp().resolve()
        for name in set(sys.modules) - mods:
            file = getattr(sys.modules[name], "__file__", None)
            if file is not None and Path(file).resolve().is_relative_to(base):
                del sys.modules[name]
        sys.path[:] = path
        proj._ACTIVE[:] = active
        proj._OWNERS.clear()
        proj._OWNERS.update(owners)

    yield restore
    restore()


def write_project(root, *, claims: str = CLAIMS, reasons: dict | None = None, paper: str | None = "note.tex",
                  tex: str = NOTE, module: str = "note_claims"):
    root.mkdir(parents=True, exist_ok=True)
    (root / "note.tex").write_text(tex)
    (root / f"{module}.py").write_text(textwrap.dedent(claims))
    lines = ["[tool.symbt]", f'claims = ["{module}.py"]']
    if paper:
        lines.append(f'paper = "{paper}"')
    lines.append("[tool.symbt.reasons]")
    lines += [f'{k} = "{v}"' for k, v in (REASONS if reasons is None else reasons).items()]
    (root / "pyproject.toml").write_text("\n".join(lines) + "\n")
    return root


def run_coverage(capsys, *args: str):
    code = coverage.main(["--json", "-", "-q", *args])
    out = capsys.readouterr()
    return code, json.loads(out.out), out.err


# --------------------------------------------------------------------------- the parser

def test_scan_reads_rows_tags_refs_macros_and_skips_comments():
    labs = {lab.label: lab for lab in scan(NOTE)}
    assert list(labs) == ["sec-model", "eq-energy", "eq-qdot", "eq-newton", "eq-square", "fig-phase"]
    assert [(lab.section, lab.kind) for lab in labs.values()] == [
        ("1", "section"), ("1", "equation"), ("1", "equation"), ("1", "equation"), ("2", "equation"),
        ("2", "figure")]
    assert labs["eq-qdot"].source == r"\dot q &= p"  # its own row, not the align's other rows
    assert labs["eq-newton"].source == r"\ddot q &= -V'(q) \quad\text{by \eqref{eq-qdot}}"
    assert labs["eq-newton"].tag == "N" and labs["eq-newton"].refs == ("eq-qdot",)
    assert labs["eq-qdot"].refs == () and labs["eq-qdot"].numbered
    assert labs["eq-square"].source == "(a+b)^2 = a^2 + 2ab + b^2"  # \beq ... \eeq defined by \def
    assert labs["fig-phase"].refs == ("eq-energy",)
    assert labs["sec-model"].source == "Model"


def test_scan_nonumber_row_and_several_labels_per_environment():
    tex = r"""\begin{document}\begin{eqnarray} a &=& b \label{r1}\\ c &=& d \nonumber \label{r2}\\ e &=& f
    \end{eqnarray}\begin{gather} x \label{g1} \\ y \label{g2} \end{gather}\end{document}"""
    labs = scan(tex)
    assert [(lab.label, lab.source, lab.numbered) for lab in labs] == [
        ("r1", "a &=& b", True), ("r2", "c &=& d", False), ("g1", "x", True), ("g2", "y", True)]


def test_scan_user_environments_theorems_and_appendix():
    tex = r"""\newcommand{\eq}[1]{\begin{equation}#1\end{equation}}
    \newenvironment{myeq}{\begin{equation}}{\end{equation}}
    \newtheorem{lemma}{Lemma}
    \begin{document}\section*{Preface}\section{A}\subsection{B}
    \eq{E = m \label{wrapped}} \begin{myeq} F \label{env}\end{myeq}
    \begin{lemma}\label{lem} by \ref{env} \end{lemma}
    \begin{comment} \label{hidden} \end{comment}
    \appendix\section{C}\[ x \label{disp} \]\end{document}"""
    got = [(lab.label, lab.section, lab.kind) for lab in scan(tex)]
    assert got == [("wrapped", "1.1", "equation"), ("env", "1.1", "equation"), ("lem", "1.1", "theorem"),
                   ("disp", "A", "equation")]


@pytest.mark.parametrize("tex", [
    r"\begin{document}\begin{equation} x \label{a}\end{document}",  # unclosed environment
    r"\begin{document}\be x \label{a} \end{document}",                # \be never closed
    r"\begin{document} x \ee \end{document}",                          # \ee without \be
    r"\begin{document}{ x \end{document}",                             # unbalanced brace
])
def test_unparsable_tex_is_a_latex_error(tex):
    with pytest.raises(LatexError) as exc:
        scan(tex, where="note.tex")
    assert str(exc.value).startswith("note.tex:") and "\n" not in str(exc.value)


def test_zullo_paper_scans_to_the_label_list():
    paper = coverage.find_paper()
    if paper is None or not paper.is_file():
        pytest.skip("paper source not found (set SYMBT_PAPER)")
    assert [lab.as_label() for lab in scan_file(paper)] == list(LABELS)


# --------------------------------------------------------------------------- symbt coverage on the user's paper

def test_covered_paper_exits_0_and_joins_by_label(tmp_path, monkeypatch, capsys, fresh):
    monkeypatch.chdir(write_project(tmp_path / "p0", module="note0_claims"))
    code, data, err = run_coverage(capsys)
    assert code == 0, err
    cov = data["coverage"]
    assert list(cov) == ["eq-energy", "eq-qdot", "eq-newton", "eq-square", "fig-phase"]  # the note's, not Zullo's
    assert cov["eq-square"] == {"claims": [{"id": "square", "status": "verified"}]}
    assert cov["eq-qdot"] == {"claims": [{"id": "qdot", "status": "verified"}]}
    assert cov["eq-energy"] == {"reason": "a definition", "see": []}
    assert data["uncovered"] == [] and data["todo"] == []
    assert data["unknown"] == {"claims": {}, "reasons": []}


def test_gap_exits_1(tmp_path, monkeypatch, capsys, fresh):
    monkeypatch.chdir(write_project(tmp_path / "p1", module="note1_claims",
                                    reasons={"eq-energy": "a definition", "fig-phase": "a figure"}))
    code, data, err = run_coverage(capsys)
    assert code == 1
    assert data["uncovered"] == ["eq-newton"] and data["coverage"]["eq-newton"] == {}
    assert "neither claims nor a reason: eq-newton" in err


def test_unknown_labels_exit_1(tmp_path, monkeypatch, capsys, fresh):
    claims = CLAIMS + '''

@claim("typo", equation="eq-sqaure", scene="note", statement="a label with a typo")
def typo():
    return from_decision(decide(a, a))
'''
    monkeypatch.chdir(write_project(tmp_path / "p2", module="note2_claims", claims=claims,
                                    reasons={**REASONS, "eq-gone": "a display deleted from the note"}))
    code, data, err = run_coverage(capsys)
    assert code == 1
    assert data["unknown"] == {"claims": {"eq-sqaure": ["typo"]}, "reasons": ["eq-gone"]}
    assert "unknown label 'eq-sqaure': claims typo" in err
    assert "unknown label 'eq-gone': a reason" in err


def test_todo_stub_is_a_gap(tmp_path, monkeypatch, capsys, fresh):
    claims = CLAIMS + '''

@claim("newton", equation="eq-newton", scene="note", statement="q'' = -V'(q)")
def newton():
    return todo()
'''
    reasons = {k: v for k, v in REASONS.items() if k != "eq-newton"}
    monkeypatch.chdir(write_project(tmp_path / "p3", module="note3_claims", claims=claims, reasons=reasons))
    code, data, err = run_coverage(capsys)
    assert code == 1
    assert data["todo"] == ["eq-newton"] and data["uncovered"] == []
    assert data["coverage"]["eq-newton"] == {"claims": [{"id": "newton", "status": "todo"}]}
    assert "all todo stubs: eq-newton" in err
    code = coverage.main([])  # the text report says todo
    assert code == 1 and "TODO (stubs only): newton" in capsys.readouterr().out


def test_no_paper_configured_exits_2(tmp_path, monkeypatch, capsys, fresh):
    monkeypatch.chdir(write_project(tmp_path / "p4", module="note4_claims", paper=None))
    assert coverage.main(["-q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--paper" in err and "paper =" in err
    # --paper supplies it
    code, data, _ = run_coverage(capsys, "--paper", "note.tex")
    assert code == 0 and "eq-square" in data["coverage"]


@pytest.mark.parametrize("tex, words", [
    (NOTE.replace(r"\end{align}", ""), "does not parse"),
    (None, "cannot read"),
])
def test_unreadable_or_unparsable_paper_exits_2_in_one_line(tmp_path, monkeypatch, capsys, fresh, tex, words):
    from symbt.cli import main

    root = write_project(tmp_path / "p5", module="note5_claims", tex=tex or NOTE)
    if tex is None:
        (root / "note.tex").unlink()
    monkeypatch.chdir(root)
    assert main(["coverage"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err
    assert err.startswith("symbt coverage: ")


def test_missing_latex_extra_is_one_line_exit_2(tmp_path, monkeypatch, capsys, fresh):
    from symbt.cli import main

    monkeypatch.chdir(write_project(tmp_path / "p6", module="note6_claims"))
    monkeypatch.setitem(sys.modules, "pylatexenc", None)  # import pylatexenc -> ImportError
    assert main(["coverage"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "needs the optional extra 'latex'" in err


def test_zullo_coverage_needs_no_latex_extra(monkeypatch, capsys, tmp_path):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "pylatexenc", None)
    code = coverage.main(["--no-cache", "-q", "--json", "-"])
    out = capsys.readouterr()
    assert code == 0, out.err
    assert len(json.loads(out.out)["coverage"]) == 60  # from the LABELS data


def test_claims_option_and_verify_json_coverage(tmp_path, monkeypatch, capsys, fresh):
    """--claims names the module; coverage_of (verify's JSON) joins the run with the user's displays."""
    from symbt import engine
    from symbt.engine.project import discover

    root = write_project(tmp_path / "p7", module="note7_claims")
    (root / "pyproject.toml").write_text('[tool.symbt]\npaper = "note.tex"\n[tool.symbt.reasons]\n'
                                         'eq-energy = "a definition"\n')
    monkeypatch.chdir(root)
    code, data, _ = run_coverage(capsys, "--claims", "note7_claims.py")
    assert code == 1 and data["uncovered"] == ["eq-newton", "fig-phase"]
    project = discover(claims=["note7_claims.py"])
    results = engine.run(engine.select(project=project), manifest=False)
    cov = coverage.coverage_of(results, project)
    assert list(cov) == ["eq-energy", "eq-qdot", "eq-newton", "eq-square", "fig-phase"]
    assert cov["eq-square"] == {"claims": [{"id": "square", "status": "verified"}]}
    assert cov["eq-newton"] == {"claims": []} and cov["eq-energy"] == {"reason": "a definition", "see": []}


def test_a_users_tex_without_a_project_says_how_to_give_the_claims(tmp_path, monkeypatch, capsys):
    """No [tool.symbt]: the claims are Zullo's; a .tex of another paper is flagged, with what to do."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "note.tex").write_text(NOTE)
    assert coverage.main(["--paper", "note.tex", "--no-cache", "-q"]) == 1
    err = capsys.readouterr().err
    assert "shares no label with Zullo's paper" in err and "--claims" in err
