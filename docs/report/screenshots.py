"""Regenerate the screenshots of docs/report.md: the summary, one erratum with its cell grid, the graph.

    python docs/report/screenshots.py [--from verify.json] [--out docs/report]

Without ``--from`` it runs ``symbt verify --json`` (Zullo's paper; cached outcomes are reused),
then ``symbt report --html`` into a temporary directory, and photographs three pages in headless
Chromium (``symbt.report.site.browser``; needs ``symbt[report]`` and Debian's chromium and
chromium-driver).
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from symbt.cli import main as symbt
from symbt.report.site.browser import missing, open_browser

#: (file name, page, CSS selector scrolled to the top or None)
SHOTS = (("summary.png", "index.html", None),
         ("erratum.png", "label-spe.html", "table.cells"),
         ("graph.png", "graph.html", None))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--from", dest="source", help="a verify JSON (default: run symbt verify)")
    ap.add_argument("--out", default=str(Path(__file__).parent), help="where the PNGs go (default: docs/report)")
    args = ap.parse_args(argv)
    why = missing()
    if why:
        print(f"screenshots: {why}", file=sys.stderr)
        return 2
    work = Path(tempfile.mkdtemp(prefix="symbt-report-"))
    source = args.source or str(work / "verify.json")
    if not args.source and symbt(["verify", "--json", source, "-q"]) not in (0, 1):
        return 2
    if symbt(["report", "--html", str(work / "site"), "--from", source]) != 0:
        return 2
    driver = open_browser(1200, 860)
    try:
        for name, page, selector in SHOTS:
            driver.get((work / "site" / page).as_uri())
            if selector:
                driver.execute_script("const e = document.querySelector(arguments[0]);"
                                      "if (e) { e.closest('section').scrollIntoView(); }", selector)
            driver.save_screenshot(str(Path(args.out) / name))
            print(f"screenshots: {Path(args.out) / name}")
    finally:
        driver.quit()
    return 0


if __name__ == "__main__":
    sys.exit(main())
