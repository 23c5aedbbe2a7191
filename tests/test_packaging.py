"""Packaging as the ecosystem expects: single-sourced version, SPDX license and LICENSE file, extras,
entry points (console script, pytest plugin), package data (py.typed, the report's JSON Schema), and a
wheel that builds offline from the checkout."""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import zipfile
from email.parser import Parser
from pathlib import Path

import pytest

import symbt

ROOT = Path(__file__).resolve().parents[1]
EXTRAS = {"scipy", "plot", "certified", "fast", "gmpy2", "peers", "dask", "notebooks", "rich", "latex", "report",
          "docs", "mutate", "test", "all"}


@pytest.fixture(scope="module")
def pyproject() -> dict:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        tomllib = pytest.importorskip("tomli")
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def test_version_is_single_sourced(pyproject):
    project = pyproject["project"]
    assert "version" not in project and "version" in project["dynamic"]
    assert pyproject["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "symbt.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+([ab]\d+|rc\d+|\.dev\d+)?", symbt.__version__)


def test_license_and_metadata(pyproject):
    project = pyproject["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License") and "Copyright (c) 2026 the symbt authors" in text
    assert not any(c.startswith("License ::") for c in project["classifiers"])   # superseded by the SPDX string
    assert {"Typing :: Typed", "Framework :: Pytest"} <= set(project["classifiers"])
    build = pyproject["build-system"]["requires"]
    assert any(re.fullmatch(r"setuptools>=(\d+)", r) and int(r.split(">=")[1]) >= 77 for r in build)


def test_extras_and_entry_points(pyproject):
    project = pyproject["project"]
    extras = project["optional-dependencies"]
    assert set(extras) == EXTRAS
    notebooks = {re.split(r"[<>=\[]", r)[0] for r in extras["notebooks"]}
    assert {"jupytext", "nbconvert", "nbclient", "ipykernel"} <= notebooks
    assert any(r.startswith("dask[") and "distributed" in r and "array" in r for r in extras["dask"])
    test_needs = {re.split(r"[<>=\[]", r)[0] for r in extras["test"]}
    assert {"pytest", "pytest-xdist", "jsonschema", "hypothesis"} <= test_needs
    assert {re.split(r"[<>=\[]", r)[0] for r in extras["report"]} <= test_needs   # the report's tests run in CI
    assert project["scripts"] == {"symbt": "symbt.cli:main"}
    assert project["entry-points"]["pytest11"] == {"symbt": "symbt.pytest_plugin"}


def test_package_data_is_declared_and_present(pyproject):
    data = pyproject["tool"]["setuptools"]["package-data"]["symbt"]
    assert "py.typed" in data and "report/*.json" in data
    assert (ROOT / "symbt" / "py.typed").is_file() and (ROOT / "symbt" / "report" / "verify.schema.json").is_file()


def _setuptools_at_least_77() -> bool:
    try:
        import setuptools
    except ImportError:
        return False
    return int(setuptools.__version__.split(".")[0]) >= 77


@pytest.mark.skipif(not _setuptools_at_least_77(), reason="building offline needs setuptools>=77 installed "
                    "(it is in the test extra)")
def test_wheel_builds_offline_and_carries_everything(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy(ROOT / name, src / name)
    shutil.copytree(ROOT / "symbt", src / "symbt", ignore=shutil.ignore_patterns("__pycache__"))
    env = {**os.environ, "PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    p = subprocess.run([sys.executable, "-m", "pip", "wheel", ".", "--no-deps", "--no-build-isolation", "-w",
                        str(tmp_path / "dist")], cwd=src, capture_output=True, text=True, env=env, timeout=600)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    (wheel,) = (tmp_path / "dist").glob("symbt-*.whl")
    assert wheel.name.startswith(f"symbt-{symbt.__version__}-py3-none-any")
    names = set(zipfile.ZipFile(wheel).namelist())
    dist = f"symbt-{symbt.__version__}.dist-info"
    assert {"symbt/py.typed", "symbt/report/verify.schema.json", "symbt/pytest_plugin.py",
            f"{dist}/licenses/LICENSE"} <= names
    assert not any(n.startswith(("tests/", "derivations/")) for n in names)
    meta = Parser().parsestr(zipfile.ZipFile(wheel).read(f"{dist}/METADATA").decode())
    assert meta["Version"] == symbt.__version__ and meta["License-Expression"] == "MIT"
    assert set(meta.get_all("Provides-Extra")) == EXTRAS
    eps = zipfile.ZipFile(wheel).read(f"{dist}/entry_points.txt").decode()
    assert "[pytest11]\nsymbt = symbt.pytest_plugin" in eps and "symbt = symbt.cli:main" in eps
    # the installed wheel answers --version with the single-sourced version
    target = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--target", str(target), str(wheel)],
                   check=True, capture_output=True, env=env, timeout=600)
    out = subprocess.run([sys.executable, "-m", "symbt", "--version"], capture_output=True, text=True,
                         env={**env, "PYTHONPATH": str(target)}, cwd=tmp_path, check=True)
    assert out.stdout.strip() == f"symbt {symbt.__version__}"
