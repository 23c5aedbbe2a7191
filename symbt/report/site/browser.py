"""A headless Chromium for looking at the site: the browser tests and the screenshots in ``docs/report/``.

Uses Debian's ``chromium`` and ``chromium-driver`` through Selenium (``pip install 'symbt[report]'``),
with the driver at ``/usr/bin/chromedriver`` -- Selenium is never allowed to download one -- and a
fresh profile, no background networking, no sync, no first-run screens.

>>> isinstance(missing(), (str, type(None)))
True
"""
from __future__ import annotations

import shutil
import tempfile
from pathlib import Path
from typing import Any

__all__ = ["missing", "open_browser", "CHROMIUM", "CHROMEDRIVER", "FLAGS"]

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--no-first-run")


def _find(path: str) -> str | None:
    return path if Path(path).is_file() else shutil.which(Path(path).name)


def missing() -> str | None:
    """Why a browser cannot be opened here (``None``: it can)."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install 'symbt[report]')"
    if _find(CHROMIUM) is None:
        return "chromium is not installed (apt-get install -y chromium chromium-driver)"
    if _find(CHROMEDRIVER) is None:
        return "chromedriver is not installed (apt-get install -y chromium-driver)"
    return None


def open_browser(width: int = 1200, height: int = 900) -> Any:
    """A headless Chromium WebDriver (the caller quits it); :class:`RuntimeError` if :func:`missing`."""
    why = missing()
    if why is not None:
        raise RuntimeError(why)
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    for flag in FLAGS:
        options.add_argument(flag)
    options.add_argument(f"--user-data-dir={tempfile.mkdtemp(prefix='symbt-chromium-')}")
    options.add_argument(f"--window-size={width},{height}")
    options.binary_location = _find(CHROMIUM) or CHROMIUM
    return webdriver.Chrome(service=Service(_find(CHROMEDRIVER) or CHROMEDRIVER), options=options)
