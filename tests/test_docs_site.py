"""The README stays a first screen, and the documentation site's pages are what they say they are.

The site itself is built by CI with warnings as errors (``.ci/run``: ``python -m sphinx -W ...``); here:
the README's length, its install and test commands being CI's, every relative link of the README and of
``docs/`` resolving, every page being in a toctree, the README's examples printing what it says they
print, and the generated pages (``docs/_ext/symbt_pages.py``) listing every claim and every display.
"""
from __future__ import annotations

import contextlib
import importlib.util
import io
import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
MAX_README_LINES = 200


def _blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"^```{lang}\n(.*?)^```", text, flags=re.S | re.M)


def _section(text: str, heading: str) -> str:
    start = text.index(f"\n## {heading}")
    end = text.find("\n## ", start + 1)
    return text[start:end if end != -1 else None]


def test_readme_is_a_first_screen_of_at_most_200_lines():
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= MAX_README_LINES
    headings = re.findall(r"^## (.+)$", text, flags=re.M)
    # what symbt is, how to install, the two commands, where to go next -- in that order
    wanted = ["Install", "Check the paper: `symbt verify`", "Check your own derivation", "Where to go next"]
    assert [h for h in headings if h in wanted] == wanted
    assert "\n## " not in text.split("## Install")[0].split("\n", 1)[1]     # nothing before Install but the intro


def test_readme_installs_and_tests_as_ci_does():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    (block,) = _blocks(_section(README.read_text(encoding="utf-8"), "Install"), "bash")
    commands = [line.split("#")[0].strip() for line in block.splitlines() if line.strip()]
    assert 'pip install ".[test,notebooks]"' in commands and "python -m pytest -q -n 2" in commands
    ci_lines = [line.split("#")[0].strip() for line in ci.splitlines()]
    for command in commands[1:]:                    # the venv line differs on purpose (CI uses .venv-ci)
        assert command in ci_lines or f"python -m {command}" in ci_lines, command


def _pages() -> list[Path]:
    return [README, *sorted(DOCS.glob("*.md"))]


@pytest.mark.parametrize("page", _pages(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_relative_links_resolve(page):
    text = page.read_text(encoding="utf-8")
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)             # links in code are not links
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        path = target.split("#")[0]
        assert path and (page.parent / path).exists(), f"{page.name}: broken link {target}"
        if page.parent == DOCS:
            # in the site a link is a page or a file to download: Sphinx cannot link a directory
            assert (page.parent / path).is_file(), f"{page.name}: {target} is a directory"


def test_every_page_is_in_a_toctree():
    names = set()
    for page in DOCS.glob("*.md"):
        for block in re.findall(r"^```\{toctree\}\n(.*?)^```", page.read_text(encoding="utf-8"), flags=re.S | re.M):
            names |= {line.strip() for line in block.splitlines() if line.strip() and not line.startswith(":")}
    pages = {p.stem for p in DOCS.glob("*.md")} - {"index"}
    assert pages <= names, f"pages in no toctree: {sorted(pages - names)}"
    assert "walkthroughs/*" in names                 # the executed walkthroughs (generated at build time)


def test_readme_examples_print_what_it_says():
    pytest.importorskip("flint")                   # the first line names FLINT's exact reduction
    text = README.read_text(encoding="utf-8")
    identity, orbit, _ = _blocks(text, "python")
    after = text.split(identity, 1)[1].split("```", 1)[1]               # past the python block's fence
    shown = re.search(r"^```\n(.*?)^```", after, flags=re.S | re.M).group(1)   # the block after "prints ..."
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(identity, "README.md", "exec"), {})
    assert out.getvalue() == shown
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(orbit, "README.md", "exec"), {})
    drift = [float(x) for x in re.findall(r"[0-9.]+e[-+][0-9]+", out.getvalue())]
    assert len(drift) == 3 and max(drift) < 1e-12, out.getvalue()       # "relative drift ~1e-13"



def test_readme_emit_example_emits_the_field(tmp_path):
    """The README's ``symbt.emit`` block declares a function whose emitted numpy file computes (p, -e^q)."""
    from symbt.codegen.user import EMISSIONS
    from symbt.codegen.user.files import generate

    block = _blocks(README.read_text(encoding="utf-8"), "python")[2]
    before = dict(EMISSIONS)
    try:
        exec(compile(block, "README.md", "exec"), {})
        new = [e for k, e in EMISSIONS.items() if k not in before]
        assert [(e.module, e.name) for e in new] == [("mymodel", "flow_field")]
        (path,) = generate(new, tmp_path, tmp_path)
        spec = importlib.util.spec_from_file_location("mymodel", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        got = np.asarray(module.flow_field(0.5, 1.0), dtype=float).ravel()
        assert np.allclose(got, [0.5, -np.e], rtol=1e-15, atol=0), got
    finally:
        EMISSIONS.clear()
        EMISSIONS.update(before)

def _pages_module():
    spec = importlib.util.spec_from_file_location("symbt_pages", DOCS / "_ext" / "symbt_pages.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_generated_pages_list_every_claim_and_every_display(tmp_path):
    """The pages the site includes, generated by the CLI: every default claim, every labelled display."""
    pytest.importorskip("jupytext")
    from symbt.claims import REGISTRY, load_all
    from symbt.claims.coverage import REASONS
    from symbt.paper import LABELS

    pages = _pages_module()
    written = pages.generate(tmp_path / "generated", tmp_path / "walkthroughs")
    table = (tmp_path / "generated" / "claims-table.md").read_text(encoding="utf-8")
    load_all()
    default = [c.id for c in REGISTRY.values() if not c.deep]
    rows = re.findall(r"^\| `([^`]+)` \|", table, flags=re.M)
    assert sorted(rows) == sorted(default)
    summary = (tmp_path / "generated" / "claims-summary.md").read_text(encoding="utf-8")
    assert f"**{len(default)} claims:" in summary
    coverage = (tmp_path / "generated" / "coverage-table.md").read_text(encoding="utf-8")
    displays = [lab for lab in LABELS if lab.is_display]
    cov_rows = dict(re.findall(r"^\| `([^`]+)` \| [^|]* \| (.*) \|$", coverage, flags=re.M))
    assert list(cov_rows) == [lab.label for lab in displays]
    for label, reason in REASONS.items():
        assert reason.text.replace("|", "\\|") in cov_rows[label]
    notebooks = [p for p in written if p.suffix == ".ipynb"]
    assert [p.stem for p in notebooks] == sorted(p.stem for p in (ROOT / "derivations").glob("[0-9][0-9]_*.py"))
    assert all('"cell_type": "code"' in p.read_text(encoding="utf-8") and "wt.expect(" in p.read_text(encoding="utf-8")
               for p in notebooks)


def test_coverage_table_marks_an_uncovered_display():
    """A display with neither claims nor a reason is shown as uncovered, never dropped."""
    table = _pages_module().coverage_table({"coverage": {"intdis": {}, "rec": {"reason": "a | b", "see": []}}})
    assert "| `intdis` | 1 | **uncovered** |" in table and "*a \\| b*" in table
    assert table.startswith("2 displays: 0 with claims, 1 with a reason.")
