"""A user's own claims on every front end: [tool.symbt], --claims, --label, and a cache that is never wrong."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from symbt.engine import project as proj

ROOT = Path(__file__).resolve().parents[1]

MODEL = """\
import sympy as sp
p = sp.Symbol("p", real=True)
b = -p/2
"""

CLAIMS = """\
import sympy as sp
from symbt import claim, decide, from_decision
import note_model

p = note_model.p


@claim("note.b", equation="bdef", statement="b = -p/2", scene="note")
def check_b():
    return from_decision(decide(note_model.b, -p / 2))


@claim("note.square", equation="sq", statement="(p+1)^2 = p^2 + 2p + 1", scene="algebra")
def check_square():
    return from_decision(decide((p + 1) ** 2, p ** 2 + 2 * p + 1))
"""


def _write_project(tmp: Path, config: str = 'claims = ["note_claims.py"]\n') -> Path:
    (tmp / "pyproject.toml").write_text(f'[project]\nname = "note"\n\n[tool.symbt]\n{config}')
    (tmp / "note_model.py").write_text(MODEL)
    (tmp / "note_claims.py").write_text(CLAIMS)
    return tmp


def _symbt(cwd: Path, *args: str, cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "SYMBT_CACHE_DIR": str(cache), "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "symbt", *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)


@pytest.fixture
def note(tmp_path):
    (tmp_path / "note").mkdir()
    return _write_project(tmp_path / "note")


# --------------------------------------------------------------------------- configuration

def test_discover_reads_the_nearest_tool_symbt_table(note):
    sub = note / "deeper" / "still"
    sub.mkdir(parents=True)
    p = proj.discover(start=sub)
    assert p.config == note / "pyproject.toml" and p.root == note.resolve()
    assert p.claims == (str((note / "note_claims.py").resolve()),) and not p.is_package


def test_without_a_config_the_package_paper_is_the_project(tmp_path):
    p = proj.discover(start=tmp_path)
    assert p.is_package and p.config is None


def test_command_line_claims_win_over_the_config(note):
    p = proj.discover(claims=["symbt.claims"], start=note)
    assert p.is_package


@pytest.mark.parametrize("body, message", [
    ("claims = 3\n", "'claims' must be a non-empty list"),
    ("claims = []\n", "'claims' must be a non-empty list"),
    ("budget = -1\n", "'budget' must be a positive number"),
    ("budget = true\n", "'budget' must be a positive number"),
    ("reasons = {a = 1}\n", "'reasons' must be a table"),
    ("colour = 'red'\n", "unknown key(s) colour"),
    ("claims = [\n", "not valid TOML"),
])
def test_a_malformed_table_is_a_config_error(tmp_path, body, message):
    (tmp_path / "pyproject.toml").write_text("[tool.symbt]\n" + body)
    with pytest.raises(proj.ConfigError, match=message.replace("(", r"\(").replace(")", r"\)")):
        proj.discover(start=tmp_path)


def test_config_values_are_read_relative_to_the_file(tmp_path):
    (tmp_path / "pyproject.toml").write_text(textwrap.dedent("""\
        [tool.symbt]
        claims = ["pkg.claims", "more/extra.py"]
        paper = "tex/note.tex"
        budget = 12.5
        cache-dir = ".cache-here"
        [tool.symbt.reasons]
        def-H = "a definition"
        """))
    p = proj.discover(start=tmp_path)
    assert p.claims == ("pkg.claims", str(tmp_path.resolve() / "more" / "extra.py"))
    assert p.paper == tmp_path.resolve() / "tex" / "note.tex"
    assert p.budget == 12.5 and p.cache_dir == tmp_path.resolve() / ".cache-here"
    assert p.reasons == {"def-H": "a definition"}


def test_ownership_by_module_prefix():
    assert proj.owned("a.b.c", ["a.b"]) and proj.owned("a", ["a"])
    assert not proj.owned("ab", ["a"]) and not proj.owned("a", ["a.b"])


# --------------------------------------------------------------------------- the command line

def test_verify_runs_only_the_users_claims(note, tmp_path):
    r = _symbt(note, "verify", "--json", "-", "-q", cache=tmp_path / "c")
    assert r.returncode == 0, r.stderr
    ids = [c["id"] for c in json.loads(r.stdout)["claims"]]
    assert ids == ["note.b", "note.square"]


def test_label_and_scene_select_the_users_claims(note, tmp_path):
    r = _symbt(note, "verify", "--label", "sq", "--json", "-", "-q", cache=tmp_path / "c")
    assert [c["id"] for c in json.loads(r.stdout)["claims"]] == ["note.square"], r.stderr
    r = _symbt(note, "verify", "--scene", "note", "--json", "-", "-q", cache=tmp_path / "c")
    assert [c["id"] for c in json.loads(r.stdout)["claims"]] == ["note.b"], r.stderr
    r = _symbt(note, "verify", "--label", "nolabel", cache=tmp_path / "c")
    assert r.returncode == 2 and "nolabel" in r.stderr and "Traceback" not in r.stderr


def test_scenes_lists_the_users_scenes_only(note, tmp_path):
    r = _symbt(note, "scenes", cache=tmp_path / "c")
    assert r.returncode == 0, r.stderr
    assert "note.b" in r.stdout and "algebra" in r.stdout and "theorem1" not in r.stdout


def test_claims_flag_without_a_config(tmp_path):
    d = tmp_path / "plain"
    d.mkdir()
    (d / "note_model.py").write_text(MODEL)
    (d / "note_claims.py").write_text(CLAIMS)
    r = _symbt(tmp_path, "verify", "--claims", "plain/note_claims.py", "--json", "-", "-q", cache=tmp_path / "c")
    assert r.returncode == 0, r.stderr
    assert len(json.loads(r.stdout)["claims"]) == 2


@pytest.mark.parametrize("args, message", [
    (["verify", "--claims", "missing.py"], "does not exist"),
    (["verify", "--claims", "no_such_module_xyz"], "not found"),
    (["scenes", "--claims", "broken.py"], "does not import: ZeroDivisionError"),
    (["verify", "--claims", "empty.py"], "registers no claim"),
])
def test_bad_claims_sources_exit_2_with_one_line(tmp_path, args, message):
    (tmp_path / "broken.py").write_text("x = 1 / 0\n")
    (tmp_path / "empty.py").write_text("x = 1\n")
    r = _symbt(tmp_path, *args, cache=tmp_path / "c")
    assert r.returncode == 2 and message in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr


def test_a_malformed_config_exits_2_with_one_line(tmp_path):
    (tmp_path / "pyproject.toml").write_text("[tool.symbt]\nclaims = 3\n")
    r = _symbt(tmp_path, "verify", cache=tmp_path / "c")
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "'claims'" in r.stderr


def test_the_package_paper_through_the_same_mechanism(tmp_path):
    r = _symbt(tmp_path, "verify", "--claims", "symbt.claims", "--scene", "toy", "--json", "-", "-q",
               cache=tmp_path / "c")
    assert r.returncode == 0, r.stderr
    ids = [c["id"] for c in json.loads(r.stdout)["claims"]]
    assert ids and all(i.startswith("toy.") for i in ids)


# --------------------------------------------------------------------------- the cache is never wrong

def _status(note: Path, cache: Path) -> tuple[str, bool]:
    r = _symbt(note, "verify", "--scene", "note", "--json", "-", "-q", cache=cache)
    assert r.returncode in (0, 1), r.stderr
    c = json.loads(r.stdout)["claims"][0]
    return c["status"], c["cached"]


def test_editing_a_helper_module_recomputes_and_reverting_is_right(note, tmp_path):
    cache = tmp_path / "c"
    assert _status(note, cache) == ("verified", False)
    assert _status(note, cache) == ("verified", True)           # the warm path
    model = note / "note_model.py"
    model.write_text(MODEL.replace("-p/2", "-p/3"))
    assert _status(note, cache) == ("failed", False)             # the edit is seen, not served from the cache
    model.write_text(MODEL)
    assert _status(note, cache) == ("verified", False)           # reverting: right again
    assert _status(note, cache) == ("verified", True)


def test_a_new_helper_file_under_the_project_invalidates(note, tmp_path):
    cache = tmp_path / "c"
    _status(note, cache)
    (note / "later.py").write_text("# a new module the claims might import\n")
    assert _status(note, cache) == ("verified", False)


def test_a_foreign_entry_is_never_used(note, tmp_path):
    """The same claim id in another project (another model) does not share outcomes."""
    cache = tmp_path / "c"
    (tmp_path / "other").mkdir()
    other = _write_project(tmp_path / "other")
    (other / "note_model.py").write_text(MODEL.replace("-p/2", "-p/3"))
    assert _status(note, cache) == ("verified", False)
    assert _status(other, cache) == ("failed", False)
    assert _status(note, cache) == ("verified", False)


def test_a_stale_entry_with_a_forged_status_is_not_used(note, tmp_path):
    cache = tmp_path / "c"
    _status(note, cache)
    entry = cache / "note.b.json"
    data = json.loads(entry.read_text())
    data["key"] = "0" * 64
    data["outcome"]["status"] = "failed"
    entry.write_text(json.dumps(data))
    for m in cache.glob("manifest*.json"):
        m.unlink()
    assert _status(note, cache) == ("verified", False)


def test_library_versions_key_heyoka_and_numba():
    from symbt.engine.cache import library_versions

    text = library_versions()
    assert "heyoka" in text and "numba" in text


def test_pytest_plugin_collects_the_users_claims_from_the_config(note, tmp_path):
    env = {**os.environ, "SYMBT_CACHE_DIR": str(tmp_path / "c"), "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, "-m", "pytest", "--symbt", "-q", "-p", "no:cacheprovider", "--co"],
                       cwd=note, env=env, capture_output=True, text=True, timeout=300)
    assert "note.b" in r.stdout and "note.square" in r.stdout, r.stdout + r.stderr
    assert "theorem1" not in r.stdout
    r = subprocess.run([sys.executable, "-m", "pytest", "--symbt-claims", "symbt.claims", "--symbt-scene", "toy",
                        "-q", "-p", "no:cacheprovider", "--co"],
                       cwd=note, env=env, capture_output=True, text=True, timeout=300)
    assert "toy." in r.stdout and "note.b" not in r.stdout, r.stdout + r.stderr


def test_a_table_without_claims_says_so(tmp_path):
    """A [tool.symbt] table that names no claims does not silently run Zullo's paper."""
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\npaper = "note.tex"\n')
    with pytest.raises(proj.ConfigError, match="no 'claims'"):
        proj.discover(start=tmp_path)
    assert proj.discover(start=tmp_path, claims=["symbt.claims"]).is_package   # --claims is enough


def test_the_words_tool_symbt_in_a_comment_are_no_table(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"   # configured in [tool.symbt] one day\n')
    assert proj.find_config(tmp_path) is None
