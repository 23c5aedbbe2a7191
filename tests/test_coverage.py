"""Coverage of the paper: every labelled display has claims or a stated reason, and the label list
(symbt.paper.LABELS) is the paper's (when its LaTeX source is at hand)."""
from __future__ import annotations

import json

import pytest

from symbt.claims import REGISTRY, load_all
from symbt.claims.coverage import REASONS
from symbt.engine import coverage
from symbt.paper import DISPLAYS, LABEL, LABELS, SECTIONS, Label

PAPER = coverage.find_paper()


def _skeleton(labels) -> str:
    """A LaTeX file with the given labels in sections, equations, figures and theorems."""
    out = [r"\newtheorem{th1}{Theorem}", r"\begin{document}"]
    section, appendix = None, False
    for lab in labels:
        top = lab.section.split(".")[0]
        if top != section:
            if top.isalpha() and not appendix:
                out.append(r"\appendix")
                appendix = True
            out.append(r"\section{S}")
            section, sub = top, "0"
        if "." in lab.section and lab.section.split(".")[1] != sub:
            sub = lab.section.split(".")[1]
            out.append(r"\subsection{T}")
        if lab.kind == "section":
            out.append(rf"\label{{{lab.label}}}")
        elif lab.kind == "theorem":
            out.append(rf"\begin{{th1}}\label{{{lab.label}}} text \end{{th1}}")
        elif lab.kind == "figure":
            out.append(rf"\begin{{figure}}\caption{{c}}\label{{{lab.label}}}\end{{figure}}")
        else:
            out.append(rf"\be\label{{{lab.label}}} x % \label{{commented}}" "\n" r"\ee")
    out.append(r"\end{document}")
    return "\n".join(out)


def test_every_display_has_claims_or_a_reason():
    cmap = coverage.coverage_map(use_cache=False)
    assert list(cmap) == [lab.label for lab in DISPLAYS]
    uncovered = [label for label, entry in cmap.items() if not entry]
    assert not uncovered, f"displays with neither claims nor a reason: {uncovered}"
    for label, entry in cmap.items():
        assert ("claims" in entry) != ("reason" in entry), label


def test_reasons_are_for_uncovered_displays_and_name_real_claims():
    load_all()
    claimed = {c.equation for c in REGISTRY.values()} | {c.source_equation for c in REGISTRY.values()}
    for label, reason in REASONS.items():
        assert label in LABEL and LABEL[label].is_display, label
        assert label not in claimed, f"{label} has claims now: drop its reason"
        assert reason.text and reason.see, label
        assert set(reason.see) <= set(REGISTRY), (label, set(reason.see) - set(REGISTRY))


def test_labels_are_unique_and_sections_known():
    names = [lab.label for lab in LABELS]
    assert len(names) == len(set(names))
    assert {lab.section for lab in LABELS} <= set(SECTIONS)
    assert {lab.kind for lab in LABELS} == {"equation", "figure", "section", "theorem"}
    assert len(DISPLAYS) == 60 and sum(lab.kind == "equation" for lab in DISPLAYS) == 58


def test_scanner_reads_back_the_list():
    assert coverage.scan_labels(_skeleton(LABELS)) == list(LABELS)


def test_paper_labels_are_the_list():
    if PAPER is None:
        pytest.skip("paper source not found (set SYMBT_PAPER)")
    diff = coverage.compare(coverage.scan_labels(PAPER.read_text(encoding="utf-8")))
    assert diff == {"missing": [], "stale": [], "differ": []}


def test_compare_reports_missing_stale_and_differing_labels():
    scanned = [*LABELS[1:], Label("new-eq", "3", "equation")]
    scanned[0] = Label(scanned[0].label, "9", "figure")
    diff = coverage.compare(scanned)
    assert diff["missing"] == ["new-eq"]
    assert diff["stale"] == [LABELS[0].label]
    assert diff["differ"] == [f"{LABELS[1].label}: listed 1/equation, paper 9/figure"]


def test_command_json_and_exit_code(tmp_path, capsys):
    tex = tmp_path / "paper.tex"
    tex.write_text(_skeleton(LABELS))
    out = tmp_path / "cov.json"
    assert coverage.main(["--json", str(out), "--paper", str(tex), "--no-cache", "-q"]) == 0
    data = json.loads(out.read_text())
    assert list(data["coverage"]) == [lab.label for lab in DISPLAYS]
    assert data["uncovered"] == [] and data["paper"]["missing"] == []
    assert data["coverage"]["rec"]["see"] == list(REASONS["rec"].see)
    assert {c["id"] for c in data["coverage"]["intertwin"]["claims"]} == {"intertwin.n2", "intertwin.n3"}
    assert "toy.K" in data["unlabelled"]["toy-K"]


def test_command_fails_on_a_label_the_list_lacks(tmp_path, capsys):
    tex = tmp_path / "paper.tex"
    tex.write_text(_skeleton([*LABELS, Label("brand-new", "B", "equation")]))
    assert coverage.main(["--paper", str(tex), "--no-cache", "-q"]) == 1
    assert "brand-new" in capsys.readouterr().err
    assert coverage.main(["--paper", str(tmp_path / "absent.tex"), "-q"]) == 2


def test_cli_delegates_coverage(tmp_path):
    from symbt.cli import main

    tex = tmp_path / "paper.tex"
    tex.write_text(_skeleton(LABELS))
    assert main(["coverage", "--json", "-", "--paper", str(tex), "--no-cache"]) == 0


def test_statuses_are_filled_from_a_run():
    cmap = coverage.coverage_map({"speccurve": "verified"}, use_cache=False)
    assert cmap["speccurve"]["claims"] == [{"id": "speccurve", "status": "verified"}]
