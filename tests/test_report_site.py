"""symbt report --html: the annotated paper as a static site (symbt/report/site, symbt/engine/site.py).

A tiny user paper (tmp dir with [tool.symbt]) and Zullo's paper (a real verify run of a few labels);
the pages parse as strict HTML5, every label is there with its badge, MathML where the LaTeX converts,
escaped source where it does not, statuses propagate along the \\eqref graph and the declared uses.
"""
from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest

from symbt.cli import main

html5lib = pytest.importorskip("html5lib")
pytest.importorskip("latex2mathml")
pytest.importorskip("pylatexenc")

PAPER = r"""\documentclass{article}
\newcommand{\half}{\frac{1}{2}}
\def\tl{\tilde}
\newtheorem{thm}{Theorem}
\begin{document}
\section{Model}
\begin{equation}\label{eq-H} H = \half p^2 + \cosh(\tl{q}) \end{equation}
\begin{equation}\label{eq-E} E < 3 \end{equation}
\begin{equation}\label{eq-D} \dot q = \frac{\partial H}{\partial p}, \quad \text{by } \eqref{eq-H} \end{equation}
\begin{equation}\label{eq-X} \weirdmacro{q} = <b>\&</b> \end{equation}
\begin{equation}\label{eq-R} \text{a definition} \end{equation}
\begin{thm}\label{th-A} If $E < \tl{E}_0$ then \eqref{eq-D} holds.\end{thm}
\end{document}
"""

CLAIMS = '''
from symbt import Outcome, claim


@claim("h.half", equation="eq-H", scene="note", statement="H = p^2/2 + cosh q <script>alert(1)</script>")
def h_half():
    return Outcome("erratum", "demo: sampled", evidence="sampled", printed="H = p^2", corrected="H = p^2/2",
                   counterexample={"q": "<script>x</script>"}, residual=0.5, scope="printed holds for s > 0",
                   cells=[{"cell": {"sign": 1}, "n": 4, "printed_holds": 4, "corrected_holds": 4},
                          {"cell": {"sign": -1}, "n": 4, "printed_holds": 0, "corrected_holds": 4}])


@claim("e.bound", equation="eq-E", scene="note", statement="E < 3 & more")
def e_bound():
    return Outcome("verified", "demo: exact", evidence="proof")


@claim("d.flow", equation="eq-D", scene="note", statement="the flow")
def d_flow():
    return Outcome("verified", "demo: exact", evidence="proof")


@claim("x.other", equation="eq-X", scene="note", statement="uses e.bound only", uses=("e.bound",))
def x_other():
    return Outcome("verified", "demo: exact", evidence="proof")
'''

PYPROJECT = '''[tool.symbt]
claims = ["note_claims.py"]
paper = "note.tex"
[tool.symbt.reasons]
eq-R = "a definition"
'''


def _strict(text: str) -> None:
    html5lib.HTMLParser(strict=True, namespaceHTMLElements=False).parse(text)


@pytest.fixture(scope="module")
def user_site(tmp_path_factory):
    import os

    root = tmp_path_factory.mktemp("note")
    (root / "note.tex").write_text(PAPER)
    (root / "note_claims.py").write_text(CLAIMS)
    (root / "pyproject.toml").write_text(PYPROJECT)
    old = Path.cwd()
    os.chdir(root)
    try:
        assert main(["verify", "--json", "verify.json", "-q"]) == 0
        assert main(["report", "--html", "site", "--from", "verify.json", "-q"]) == 0
    finally:
        os.chdir(old)
    return root


def test_every_page_is_strict_html5(user_site):
    pages = sorted((user_site / "site").glob("*.html"))
    assert {p.name for p in pages} >= {"index.html", "graph.html", "claims.html", "label-eq-H.html"}
    for p in pages:
        _strict(p.read_text())


def test_labels_badges_mathml_and_escaped_fallback(user_site):
    index = (user_site / "site" / "index.html").read_text()
    for label in ("eq-H", "eq-E", "eq-D", "eq-X", "eq-R"):
        assert f'data-label="{label}"' in index
    block = re.search(r'data-label="eq-H".*?</article>', index, re.S).group()
    assert "<math" in block and "<mfrac>" in block and "\\half" not in block and "\\frac" not in block
    x = re.search(r'data-label="eq-X".*?</article>', index, re.S).group()
    assert "<math" not in x and "\\weirdmacro{q} = &lt;b&gt;" in x      # shown as escaped source, not dropped
    assert 'data-status="reason"' in re.search(r'data-label="eq-R".*?>', index).group()
    d = re.search(r'data-label="eq-D".*?</article>', index, re.S).group()   # \eqref inside the math
    assert "<math" in d and "(eq-H)" in d and "\\eqref" not in d
    th = re.search(r'data-label="th-A".*?</article>', index, re.S).group()   # a theorem's prose
    assert '<math xmlns="http://www.w3.org/1998/Math/MathML" display="inline">' in th and "\\tl" not in th
    assert '<a href="label-eq-D.html">eq-D</a> holds.' in th


def test_everything_from_claims_is_escaped(user_site):
    page = (user_site / "site" / "label-eq-H.html").read_text()
    assert "<script>" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "&lt;script&gt;x&lt;/script&gt;" in page


def test_status_propagates_along_eqref_not_along_unrelated_uses(user_site):
    index = (user_site / "site" / "index.html").read_text()
    status = dict(re.findall(r'data-label="([^"]+)" data-status="([^"]+)"', index))
    assert status == {"eq-H": "erratum", "eq-E": "verified", "eq-D": "depends", "eq-X": "verified",
                      "eq-R": "reason", "th-A": "statement"}
    d = re.search(r'data-label="eq-D".*?</header>', index, re.S).group()
    assert "verified, depends on eq-H" in d


def test_cell_grid_and_claim_fields(user_site):
    page = (user_site / "site" / "label-eq-H.html").read_text()
    grid = re.search(r'<table class="cells">.*?</table>', page, re.S).group()
    assert grid.count('class="c holds"') == 3 and grid.count('class="c fails"') == 1
    for field in ("printed", "corrected", "counterexample", "scope", "method", "time", "n_scope"):
        assert f"<dt>{field}</dt>" in page


def test_graph_is_svg_with_links_and_subgraph_pages(user_site):
    graph = (user_site / "site" / "graph.html").read_text()
    assert "<svg" in graph and "label-eq-D.html" in graph
    sub = (user_site / "site" / "label-eq-D.html").read_text()
    assert "label-eq-H.html" in sub and "label-eq-E.html" not in sub.split("<h2>Dependencies</h2>")[1]


def test_declared_uses_in_the_json_and_a_verified_user_of_an_erratum_depends(tmp_path):
    from symbt.report.site import build_site

    class Lab:
        def __init__(self, label):
            self.label, self.section, self.kind = label, "1", "equation"

    doc = {"claims": [{"id": "a", "equation": "A", "status": "erratum"},
                      {"id": "b", "equation": "B", "status": "verified", "uses": ["a"]},
                      {"id": "c", "equation": "C", "status": "verified", "uses": ["B"]}]}
    out = build_site(doc, [Lab("A"), Lab("B"), Lab("C")], tmp_path, prefer_graphviz=False)
    assert out["statuses"] == {"A": "erratum", "B": "verified, depends on", "C": "verified, depends on"}
    assert out["site"].problems("C") == ["a"] and out["graph"] == "fallback"
    _strict((tmp_path / "graph.html").read_text())


def test_verify_json_records_uses_and_run(user_site):
    doc = json.loads((user_site / "verify.json").read_text())
    uses = {c["id"]: c["uses"] for c in doc["claims"]}
    assert uses["x.other"] == ["e.bound"] and uses["h.half"] == []
    assert doc["schema_version"] == "1.3" and doc["run"]["cpus"] >= 1 and "sympy" in doc["run"]["libraries"]
    jsonschema = pytest.importorskip("jsonschema")
    from symbt.report.json import schema

    jsonschema.validate(doc, schema())


def test_mutation_score_on_the_summary(user_site, tmp_path):
    mutate = {"summary": {"mutants": 40, "killed": 37, "equivalent": 2, "survivors": 1, "score": 0.974}}
    (tmp_path / "mutate.json").write_text(json.dumps(mutate))
    out = tmp_path / "site"
    assert main(["report", "--html", str(out), "--from", str(user_site / "verify.json"), "--paper",
                 str(user_site / "note.tex"), "--mutate", str(tmp_path / "mutate.json"), "-q"]) == 0
    index = (out / "index.html").read_text()
    assert re.search(r'id="mutation">0.974 \(40 mutants, 37 killed, 2 equivalent, 1 survivors\)', index)
    assert 'data-label="eq-H"' in index and "<mfrac>" in index
    assert 'id="mutation"' not in (user_site / "site" / "index.html").read_text()


def test_uses_survive_the_warm_path(user_site, monkeypatch):
    """A second verify reads every outcome from the cache and the claims from the manifest: uses stay."""
    monkeypatch.chdir(user_site)
    assert main(["verify", "--json", "cold.json", "-q"]) == 0        # this test's own cache: fill it
    assert not any(c["cached"] for c in json.loads((user_site / "cold.json").read_text())["claims"])
    assert main(["verify", "--json", "warm.json", "-q"]) == 0
    warm = json.loads((user_site / "warm.json").read_text())
    assert all(c["cached"] for c in warm["claims"])
    assert {c["id"]: c["uses"] for c in warm["claims"]}["x.other"] == ["e.bound"]


@pytest.mark.parametrize("argv, message", [
    (["--html", "out", "--from", "missing.json"], "cannot read missing.json"),
    (["--html", "out", "--from", "bad.json"], "is not JSON"),
    (["--html", "out", "--from", "other.json"], "is not a symbt verify report"),
    (["--html", "out"], "required"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.json").write_text("{not json")
    (tmp_path / "other.json").write_text('{"a": 1}')
    try:
        code = main(["report", *argv])
    except SystemExit as exc:  # argparse's own errors exit from the parser, as in every delegated command
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def _three_labels():
    class Lab:
        def __init__(self, label, refs=()):
            self.label, self.section, self.kind, self.refs = label, "1", "equation", refs

    doc = {"claims": [{"id": "a", "equation": "A", "status": "erratum"},
                      {"id": "b", "equation": "B", "status": "verified"}]}
    return doc, [Lab("A"), Lab("B", refs=("A",))]


def test_graph_layout_by_graphviz_when_installed_else_the_fallback(tmp_path, monkeypatch):
    import shutil

    from symbt.report.site import build_site

    doc, labels = _three_labels()
    if shutil.which("dot") and importlib.util.find_spec("graphviz"):
        out = build_site(doc, labels, tmp_path / "dot")
        assert out["graph"] == "graphviz"
        assert 'class="node"' in (tmp_path / "dot" / "graph.html").read_text()
    monkeypatch.setenv("PATH", str(tmp_path))       # no dot on the PATH: the fallback draws the same nodes
    out = build_site(doc, labels, tmp_path / "plain")
    page = (tmp_path / "plain" / "graph.html").read_text()
    assert out["graph"] == "fallback" and 'href="label-A.html"' in page and 'href="label-B.html"' in page
    assert "#9e9d24" in page   # B is verified but uses the erratum A: the "depends" colour
    _strict(page)
