"""A Sphinx extension that writes the site's generated pages before Sphinx reads the sources.

* ``_generated/claims-table.md`` -- ``symbt verify --markdown`` (the CLI's own table), and
  ``_generated/claims-summary.md`` -- the counts of the same run, from its ``--json`` report;
* ``_generated/coverage-table.md`` -- ``symbt coverage --json`` as a table, one row per labelled
  display (its section from :data:`symbt.paper.LABELS`);
* ``walkthroughs/NN_name.ipynb`` -- every jupytext script ``derivations/NN_*.py`` as a notebook,
  which MyST-NB then executes (``nb_execution_raise_on_error``: a failing cell fails the build).

The commands run in a subprocess with the checkout first on ``PYTHONPATH`` and a time budget; a
command that fails (a claim failed, a display uncovered) fails the build with its stderr.  The files
are written only when their text changes, and are not committed (``.gitignore``).

``python docs/_ext/symbt_pages.py`` writes them without Sphinx (what ``tests/test_docs_site.py`` reads).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
GENERATED = DOCS / "_generated"
WALKTHROUGHS = DOCS / "walkthroughs"
#: seconds for one CLI command: a cold ``symbt verify`` takes 15-60 s on two cores, a warm one 0.1 s
BUDGET = 900


class PageError(RuntimeError):
    """A command behind a generated page failed or ran past its budget."""


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env.setdefault("MPLBACKEND", "Agg")
    return env


def run_cli(*args: str, ok: tuple[int, ...] = (0,)) -> subprocess.CompletedProcess:
    """``python -m symbt ARGS`` from the checkout's root; :class:`PageError` on another exit status."""
    cmd = [sys.executable, "-m", "symbt", *args]
    try:
        proc = subprocess.run(cmd, cwd=ROOT, env=_env(), capture_output=True, text=True, timeout=BUDGET)
    except subprocess.TimeoutExpired as exc:
        raise PageError(f"`symbt {' '.join(args)}` ran past its budget of {BUDGET} s") from exc
    if proc.returncode not in ok:
        raise PageError(f"`symbt {' '.join(args)}` exited with {proc.returncode}:\n{proc.stderr[-3000:]}")
    return proc


def write_if_changed(path: Path, text: str) -> bool:
    """Write ``text`` to ``path`` unless it already holds it (Sphinx then keeps the page's cache)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.is_file() and path.read_text(encoding="utf-8") == text:
        return False
    path.write_text(text, encoding="utf-8")
    return True


def claims_summary(report: dict) -> str:
    """The counts of a verify JSON report, as a sentence."""
    s = report["summary"]
    evidence: dict[str, int] = {}
    for c in report["claims"]:
        if c["status"] in ("verified", "erratum") and c.get("evidence"):
            evidence[c["evidence"]] = evidence.get(c["evidence"], 0) + 1
    counts = ", ".join(f"{s[k]} {k if k != 'erratum' else 'errata'}"
                       for k in ("verified", "erratum", "failed", "inconclusive", "skipped", "todo") if s.get(k))
    how = ", ".join(f"{n} {k}" for k, n in sorted(evidence.items()))
    return (f"This build's run (`{report['generator']}`, `symbt verify`): **{s['total']} claims: {counts}**; "
            f"evidence: {how}.\n")


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def coverage_table(report: dict) -> str:
    """``symbt coverage --json``'s map as a Markdown table: label, section, claims or the reason."""
    from symbt.paper import LABELS

    section = {lab.label: lab.section for lab in LABELS}
    rows = ["| label | section | claims, or why none |", "|---|---|---|"]
    n_claims = n_reason = 0
    for label, entry in report["coverage"].items():
        if entry.get("claims"):
            n_claims += 1
            what = ", ".join(f"`{c['id']}`" for c in entry["claims"])
        elif "reason" in entry:
            n_reason += 1
            see = entry.get("see") or []
            what = f"*{_cell(entry['reason'])}*" + (f" (see {', '.join(f'`{c}`' for c in see)})" if see else "")
        else:
            what = "**uncovered**"
        rows.append(f"| `{_cell(label)}` | {section.get(label, '')} | {what} |")
    head = f"{len(report['coverage'])} displays: {n_claims} with claims, {n_reason} with a reason.\n\n"
    return head + "\n".join(rows) + "\n"


def walkthrough_notebooks(walkthroughs: Path = WALKTHROUGHS) -> list[Path]:
    """Every ``derivations/NN_*.py`` converted to ``walkthroughs/NN_*.ipynb`` (jupytext, unexecuted)."""
    import jupytext

    written = []
    scripts = sorted((ROOT / "derivations").glob("[0-9][0-9]_*.py"))
    for script in scripts:
        nb = jupytext.read(script, fmt="py:percent")
        target = walkthroughs / f"{script.stem}.ipynb"
        write_if_changed(target, jupytext.writes(nb, fmt="ipynb"))
        written.append(target)
    for stale in set(walkthroughs.glob("*.ipynb")) - set(written):
        stale.unlink()
    return written


def generate(generated: Path = GENERATED, walkthroughs: Path = WALKTHROUGHS) -> list[Path]:
    """Write every generated page (into ``docs/_generated`` and ``docs/walkthroughs``); returns their paths."""
    generated.mkdir(parents=True, exist_ok=True)
    table, report_json = generated / "claims-table.md", generated / "verify.json"
    run_cli("verify", "-q", "--markdown", str(table), "--json", str(report_json))
    report = json.loads(report_json.read_text(encoding="utf-8"))
    summary = generated / "claims-summary.md"
    write_if_changed(summary, claims_summary(report))
    cov = generated / "coverage.json"
    run_cli("coverage", "-q", "--json", str(cov))
    coverage = generated / "coverage-table.md"
    write_if_changed(coverage, coverage_table(json.loads(cov.read_text(encoding="utf-8"))))
    return [table, summary, coverage, *walkthrough_notebooks(walkthroughs)]


def _on_config_inited(app, config) -> None:
    from sphinx.errors import ExtensionError

    os.environ["PYTHONPATH"] = _env()["PYTHONPATH"]     # the notebooks' kernels import the checkout's symbt
    os.environ.setdefault("MPLBACKEND", "Agg")
    try:
        generate()
    except PageError as exc:
        raise ExtensionError(str(exc)) from exc


def setup(app):
    app.connect("config-inited", _on_config_inited)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


if __name__ == "__main__":
    for path in generate():
        print(path.relative_to(ROOT))
