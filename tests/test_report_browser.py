"""The report in a real browser: headless Chromium (Debian's chromium + chromium-driver) driven by Selenium.

Zullo's paper (a verify run of a few labels, the report of every label) opened from the file system:
every label is there with its badge, MathML rendered (a laid-out <math>, no raw LaTeX left), a
screenshot is saved; the page's text agrees with the JSON report (every claim id and status).
Skips, with its reason, where chromium, its driver or selenium are missing.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from symbt.cli import main
from symbt.report.site.browser import missing, open_browser

pytest.importorskip("latex2mathml")
pytest.importorskip("pylatexenc")
if missing():
    pytest.skip(missing(), allow_module_level=True)

from selenium.webdriver.common.by import By  # noqa: E402


@pytest.fixture(scope="module")
def zullo(tmp_path_factory):
    from symbt.engine.coverage import find_paper

    paper = find_paper()
    if paper is None or not paper.is_file():
        pytest.skip("Zullo's .tex not found ($SYMBT_PAPER or ../shared/paper/backlund-toda.tex)")
    root = tmp_path_factory.mktemp("zullo")
    old, cache = Path.cwd(), os.environ.get("SYMBT_CACHE_DIR")
    os.environ["SYMBT_CACHE_DIR"] = str(root / "cache")
    os.chdir(root)
    try:
        assert main(["verify", "--label", "spe", "--label", "tn2", "--json", "verify.json",
                     "-q"]) == 0
        assert main(["report", "--html", "site", "--from", "verify.json", "--paper", str(paper), "-q"]) == 0
    finally:
        os.chdir(old)
        if cache is None:
            os.environ.pop("SYMBT_CACHE_DIR", None)
        else:
            os.environ["SYMBT_CACHE_DIR"] = cache
    from symbt.engine.labels import scan_file

    return root, [lab for lab in scan_file(paper) if lab.kind != "section"]


@pytest.fixture(scope="module")
def browser():
    driver = open_browser()
    yield driver
    driver.quit()


def test_every_label_with_its_badge_and_mathml_rendered(zullo, browser):
    root, labels = zullo
    browser.get((root / "site" / "index.html").as_uri())
    # one round trip: what the browser laid out for every display
    seen = browser.execute_script("""
        return Array.from(document.querySelectorAll('article.display')).map(a => {
            const b = a.querySelector('.badge'), m = a.querySelector('math'), s = a.querySelector('.source');
            const r = m ? m.getBoundingClientRect() : null;
            return {label: a.dataset.label, badge: b ? b.innerText : '', badgeWidth: b ? b.offsetWidth : 0,
                    math: !!m, w: r ? r.width : 0, h: r ? r.height : 0, text: a.innerText,
                    source: s ? s.innerText : ''};
        });""")
    articles = {a["label"]: a for a in seen}
    assert [lab.label for lab in labels] == [k for k in articles if k in {lab.label for lab in labels}]
    rendered = 0
    for lab in labels:
        a = articles[lab.label]
        assert a["badge"].strip() and a["badgeWidth"] > 10, a
        if a["math"]:
            rendered += 1
            assert a["h"] > 5 and a["w"] > 5, a          # laid out by the browser
            assert "\\frac" not in a["text"] and "\\tl" not in a["text"] and "\\lm" not in a["text"], a
        else:  # not converted: the source is shown, never dropped
            assert a["source"].strip(), a
    # every display of Zullo's paper converts (its macros expanded); theorems carry inline MathML too
    assert all(articles[lab.label]["math"] for lab in labels if lab.kind in ("equation", "theorem"))
    assert rendered == sum(1 for lab in labels if lab.kind in ("equation", "theorem"))
    shot = root / "index.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000


def test_page_text_agrees_with_the_json_report(zullo, browser):
    root, _ = zullo
    doc = json.loads((root / "verify.json").read_text())
    browser.get((root / "site" / "claims.html").as_uri())
    rows = {r.get_attribute("data-claim"): r.text for r in browser.find_elements(By.CSS_SELECTOR, "tr[data-claim]")}
    assert set(rows) == {c["id"] for c in doc["claims"]}
    for c in doc["claims"]:
        shown = c["status"] if c["status"] != "verified" or "depends on" not in rows[c["id"]] else "verified"
        assert c["id"] in rows[c["id"]] and shown in rows[c["id"]]
    browser.get((root / "site" / "index.html").as_uri())
    counts = browser.find_element(By.ID, "counts").text
    for status, n in doc["summary"].items():
        if status in ("verified", "erratum") and n:
            assert f"{status} {n}" in counts.replace("\n", " ")


def test_graph_nodes_are_links_to_label_pages(zullo, browser):
    root, labels = zullo
    browser.get((root / "site" / "graph.html").as_uri())
    links = browser.find_elements(By.CSS_SELECTOR, "svg a")
    assert len(links) >= len(labels)
    links[0].click()
    assert browser.current_url.split("/")[-1].startswith("label-")
