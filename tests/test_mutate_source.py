"""``symbt mutate --source``: the operators, the mutant ids, the equivalents file, the line -> claim
selection, the budget, bad input, and one run end to end on a small project of its own."""
from __future__ import annotations

import ast
import hashlib
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from symbt.engine import mutate_source as ms
from symbt.engine.mutants import OPERATORS, find_mutants, module_level_lines
from symbt.engine.source_tree import Mutated, verify_changes
from symbt.report.mutation_source import schema, summary

ROOT = Path(ms.__file__).resolve().parents[2]   # this checkout: the subprocesses must use its symbt


def mutated(src: str, operator: str) -> list[str]:
    """Every mutated file of ``src`` by ``operator``, as text."""
    data = src.encode()
    return [m.apply(data).decode() for m in find_mutants(src, "m") if m.operator == operator]


# --------------------------------------------------------------------------- operators

@pytest.mark.parametrize("operator, src, expected", [
    ("sign", "y = a + b\n", ["y = a - b\n"]),
    ("sign", "y = a - (b)\n", ["y = a + (b)\n"]),
    ("unary-minus", "y = -a\n", ["y = a\n"]),
    ("index-shift", "y = v[j]\n", ["y = v[j + 1]\n", "y = v[j - 1]\n"]),
    ("index-shift", "y = v[j + 1]\n", ["y = v[j]\n"]),
    ("compare", "y = a < b\n", ["y = a <= b\n", "y = a > b\n"]),
    ("compare", "y = a >= b\n", ["y = a > b\n", "y = a <= b\n"]),
    ("compare", "y = a == b\n", ["y = a != b\n"]),
    ("branch", "if a:\n    y = 2\n", ["if not (a):\n    y = 2\n"]),
    ("branch", "if not a:\n    y = 2\n", ["if a:\n    y = 2\n"]),
    ("branch", "y = b if a else c\n", ["y = b if not (a) else c\n"]),
    ("branch", "if not (a\n        and b):\n    y = 2\n", ["if (a\n        and b):\n    y = 2\n"]),
    ("drop-factor", "y = x / 2\n", ["y = x\n"]),
    ("drop-factor", "y = 0.5 * x\n", ["y = x\n"]),
    ("tolerance", "tol = 1e-12\n", ["tol = 1e-06\n"]),
    ("tolerance", "tol = 10.0 ** -(d - 8)\n", ["tol = 10.0 ** (-(d - 8)) / 2\n"]),
    ("constant", "y = f(0, True)\n", ["y = f(1, True)\n", "y = f(0, False)\n"]),
    ("min-max", "y = min(a, b) + np.maximum(a, b)\n", ["y = max(a, b) + np.maximum(a, b)\n",
                                                      "y = min(a, b) + np.minimum(a, b)\n"]),
    ("abs", "y = abs(a) + np.abs(b)\n", ["y = a + np.abs(b)\n", "y = abs(a) + b\n"]),
])
def test_each_operator_makes_the_single_point_bug(operator, src, expected):
    assert sorted(mutated(src, operator)) == sorted(expected)
    for text in expected:
        ast.parse(text)


def test_the_operators_are_those_documented():
    doc = find_mutants.__module__ and sys.modules[find_mutants.__module__].__doc__
    assert all(f"``{op}``" in doc for op in OPERATORS)


def test_strings_annotations_messages_type_checking_and_main_blocks_are_left_alone():
    src = textwrap.dedent('''\
        """Doc 1 + 2."""
        from typing import TYPE_CHECKING
        __all__ = ["a" + "b"]
        if TYPE_CHECKING:
            X = 1
        def f(x: int = 0) -> int:
            "doc"
            if x > 3:
                raise ValueError(f"{x + 1} too big")
            print(x - 1)
            return x
        if __name__ == "__main__":
            f(1 + 2)
        if "__main__" == __name__:
            f(3 - 1)
        ''')
    ms_ = find_mutants(src, "m")
    touched = {src.splitlines()[m.line - 1].strip() for m in ms_}
    # only the default value 0 (a constant) and the comparison/branch of `if x > 3`
    assert touched == {"def f(x: int = 0) -> int:", "if x > 3:"}, touched


def test_a_mutant_changes_exactly_one_spot_and_its_diff_shows_the_line():
    src = "def f(a, b):\n    # a comment: a + b\n    return a + b  # sum\n"
    (m,) = [m for m in find_mutants(src, "m") if m.operator == "sign"]
    assert m.apply(src.encode()).decode() == src.replace("return a + b", "return a - b")
    assert m.diff == "-     return a + b  # sum\n+     return a - b  # sum"
    assert m.line == 3


def test_non_ascii_text_before_a_site_does_not_shift_the_edit():
    src = "# λ₀ and μ\ny = 'λ' ; z = a + b\n"
    (m,) = [m for m in find_mutants(src, "m") if m.operator == "sign"]
    assert m.apply(src.encode()).decode().endswith("z = a - b\n")


def test_module_level_lines_are_import_time_code_not_function_bodies():
    src = "TOL = 1e-12\nif X:\n    def g():\n        return 1\ndef f(x, t=2):\n    return x\nclass C:\n    K = 3\n"
    assert module_level_lines(src) == {1, 2, 5, 8}


# --------------------------------------------------------------------------- ids

def test_ids_are_stable_when_lines_move_and_change_when_the_line_changes():
    src = "def f(a, b):\n    return a + b\n"
    before = {m.id for m in find_mutants(src, "pkg.mod")}
    after = {m.id for m in find_mutants("import os\n\n" + src, "pkg.mod")}
    assert {i.replace(":2:", ":4:") for i in before} == after
    edited = {m.key for m in find_mutants(src.replace("a + b", "a + b * 1"), "pkg.mod")}
    assert not {m.key for m in find_mutants(src, "pkg.mod") if m.operator == "sign"} & edited


def test_identical_lines_give_distinct_ids_and_the_same_mutated_file_is_kept_once():
    src = "x = a + b\ny = a + b\n"
    ids = [m.id for m in find_mutants(src, "m") if m.operator == "sign"]
    assert len(ids) == len(set(ids)) == 2
    files = [m.apply(src.encode()) for m in find_mutants(src, "m")]
    assert len(files) == len(set(files))


def test_the_shipped_modules_give_mutants_with_unique_ids():
    import symbt

    root = Path(symbt.__file__).parent
    found = [(f, m) for f in sorted((root / "proof").glob("*.py")) for m in find_mutants(f.read_bytes(), f.stem)]
    ids = [m.id for _, m in found]
    assert len(ids) > 500 and len(ids) == len(set(ids))
    import random

    for f, m in random.Random(0).sample(found, 150):   # every edit keeps the file valid Python (not re-parsed)
        ast.parse(m.apply(f.read_bytes()))


# --------------------------------------------------------------------------- equivalents file

def test_equivalents_file_parses_and_matches_moved_lines_and_reports_stale_marks():
    src = "def f(a, b):\n    return a + b\n"
    (m,) = [m for m in find_mutants(src, "pkg.mod") if m.operator == "sign"]
    text = (f'[[mutant]]\nid = "{m.id}"\nreason = "same"\n'
            f'[[mutant]]\nid = "pkg.mod:9:compare:0123abcd"\nreason = "gone"\n'
            f'[[mutant]]\nid = "other.mod:9:compare:0123abcd"\nreason = "not in play"\n')
    marked = ms.parse_equivalents(text)
    moved = find_mutants("\n\n" + src, "pkg.mod")
    found, stale = ms.match_equivalents(marked, moved, {"pkg"})
    (mid,) = found
    assert mid.startswith("pkg.mod:4:sign:") and "the line moved" in found[mid]
    assert stale == [{"id": "pkg.mod:9:compare:0123abcd", "reason": "gone"}]


@pytest.mark.parametrize("text, says", [
    ("[[mutant]\nid = 1", "not TOML"),
    ('[[mutant]]\nid = "m:1:sign:0123abcd"\n', "exactly the strings"),
    ('[[mutant]]\nid = "m:1:sign:0123abcd"\nreason = 3\n', "exactly the strings"),
    ('[[mutant]]\nid = "nonsense"\nreason = "r"\n', "not module:line:operator:hash"),
    ('[[mutant]]\nid = "m:1:sign:0123abcd"\nreason = "  "\n', "reason is empty"),
    ('[[mutant]]\nid = "m:1:sign:0123abcd"\nreason = "r"\n[[mutant]]\nid = "m:1:sign:0123abcd"\nreason = "r"\n',
     "marked twice"),
    ('[other]\nx = 1\n', "unknown table"),
])
def test_a_malformed_equivalents_file_is_a_usage_error(text, says):
    with pytest.raises(ms.UsageError, match=says):
        ms.parse_equivalents(text)


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "symbt", "mutate", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


def test_bad_input_is_one_line_and_exit_2(tmp_path, capsys):
    bad = tmp_path / "eq.toml"
    bad.write_text("[[mutant]]\nid = 3\n")
    for args in (["--source", "no_such_module"], ["--source", "proof", "--equivalents", str(bad)],
                 ["--source", "proof", "--equivalents", str(tmp_path / "missing.toml")],
                 ["--source", "proof", "--sample", "0"], ["--source", "proof", "-j", "999"],
                 ["--source", "proof", "--budget", "-1"], ["--source", "proof", "--scene", "no_such_scene"],
                 ["--source", "proof", "--json", str(tmp_path / "no/such/x.json")]):
        assert ms.main(args) == 2, args
        err = capsys.readouterr().err
        assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    r = _cli("--source", "no_such_module")     # through the command line: symbt mutate hands --source over
    assert r.returncode == 2 and r.stderr.strip() == f"symbt mutate --source: no module 'no_such_module' under {ROOT}"


def test_a_budget_spent_before_the_map_reports_every_mutant_not_run(tmp_path, monkeypatch, capsys):
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\nclaims = ["lib_claims.py"]\n')
    (tmp_path / "mylib.py").write_text(LIB)
    (tmp_path / "lib_claims.py").write_text(CLAIMS)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("PYTHONPATH", str(ROOT))
    monkeypatch.setenv("SYMBT_CACHE_DIR", str(tmp_path / "cache"))
    assert ms.main(["--source", "mylib", "--budget", "0.2", "--json", str(tmp_path / "o.json"), "-q"]) == 0
    doc = json.loads((tmp_path / "o.json").read_text())
    assert {r["result"] for r in doc["mutants"]} == {"not run"} and doc["summary"]["total"]["not_run"] == 8
    assert doc["summary"]["total"]["score"] is None


def test_list_is_seeded_and_bounded_by_the_sample():
    a = _cli("--source", "proof.screen", "symbt.proof.exact", "--sample", "4", "--seed", "3", "--list")
    b = _cli("--source", "proof.screen", "symbt.proof.exact", "--sample", "4", "--seed", "3", "--list")
    c = _cli("--source", "proof.screen", "symbt.proof.exact", "--sample", "4", "--seed", "4", "--list")
    ids = [ln.split()[0] for ln in a.stdout.splitlines() if not ln.startswith(" ")]
    assert a.returncode == 0 and a.stdout == b.stdout != c.stdout
    assert len(ids) == 8 and sum(i.startswith("symbt.proof.screen:") for i in ids) == 4


# --------------------------------------------------------------------------- selection, copies, verdicts

def test_a_line_runs_the_claims_that_cover_it_every_claim_at_import_time_none_if_uncovered():
    lm = {"import": {"a.py": [1, 2]}, "claims": {"c1": {"lines": {"a.py": [10, 11]}},
                                                 "c2": {"lines": {"a.py": [11], "b.py": [10]}}}}
    assert ms.claims_of_line(lm, "a.py", 10, False) == ["c1"]
    assert ms.claims_of_line(lm, "a.py", 11, False) == ["c1", "c2"]
    assert ms.claims_of_line(lm, "a.py", 2, False) is None
    assert ms.claims_of_line(lm, "a.py", 30, True) is None
    assert ms.claims_of_line(lm, "a.py", 30, False) == []


TABLED = '''\
def build(n):
    return [k * k for k in range(n)]


TAB = build(4)


def look(i):
    return TAB[i]
'''

LAZY_CLAIMS = '''\
import sympy as sp
from symbt import claim, decide, from_decision


@claim("lazy.first", equation="t", scene="lazy", statement="TAB[2] = 4")
def first():
    import tabled
    return from_decision(decide(sp.Integer(tabled.look(2)), sp.Integer(4)))


@claim("lazy.second", equation="t", scene="lazy", statement="TAB[3] = 9")
def second():
    import tabled
    return from_decision(decide(sp.Integer(tabled.TAB[3]), sp.Integer(9)))
'''


def _line_map(tmp_path, files: dict[str, str], tracer=("-m", "symbt.engine.linemap")) -> tuple[dict, str]:
    """The line map of ``files`` (a target module, then its claims module, by name and text) written into
    ``tmp_path``, and the target's resolved path."""
    (target, text), (claims, claims_text) = files.items()
    (tmp_path / target).write_text(text)
    (tmp_path / claims).write_text(claims_text)
    out = tmp_path / "map.json"
    r = subprocess.run([sys.executable, *tracer, "--out", str(out), "--claims", str(tmp_path / claims),
                        str(tmp_path / target)], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                       env={**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(tmp_path)])})
    assert r.returncode == 0, r.stderr
    return json.loads(out.read_text()), str((tmp_path / target).resolve())


@pytest.mark.slow
def test_lines_run_while_a_lazily_imported_module_loads_are_import_lines(tmp_path):
    # build()'s body runs once, when `tabled` is imported -- inside lazy.first's check.  Credited to lazy.first,
    # a mutant there would run lazy.first alone, though TAB is what lazy.second reads.
    lm, f = _line_map(tmp_path, {"tabled.py": TABLED, "lazy_claims.py": LAZY_CLAIMS})
    assert {2, 5} <= set(lm["import"][f])                      # build's body and the table's line
    assert ms.claims_of_line(lm, f, 2, False) is None          # every claim runs for a mutant there
    assert ms.claims_of_line(lm, f, 9, False) == ["lazy.first"]   # look() is run by lazy.first only
    assert lm["failed"] == {}


SHARED = '''\
import functools


def row(k):
    return k * k


@functools.lru_cache(maxsize=None)
def table(n):
    return tuple(row(k) for k in range(n))


def outside(n):
    return table(n)[-1]
'''

SHARED_CLAIMS = '''\
import sympy as sp
from symbt import claim, decide, from_decision
from shared import table


@claim("shared.first", equation="t", scene="shared", statement="table(4)[2] = 4")
def first():
    return from_decision(decide(sp.Integer(table(4)[2]), sp.Integer(4)))


@claim("shared.second", equation="t", scene="shared", statement="table(4)[3] = 9")
def second():
    import shared
    return from_decision(decide(sp.Integer(shared.outside(4)), sp.Integer(9)))


@claim("shared.third", equation="t", scene="shared", statement="1 = 1")
def third():
    return from_decision(decide(sp.Integer(1), sp.Integer(1)))
'''


_NO_COVERAGE = ("import sys; sys.modules['coverage'] = None; from symbt.engine.linemap import main; "
                "sys.exit(main(sys.argv[1:]))")


@pytest.mark.slow
@pytest.mark.parametrize("tracer", [["-m", "symbt.engine.linemap"], ["-c", _NO_COVERAGE]],
                         ids=["coverage", "settrace"])
def test_lines_a_shared_cache_runs_are_credited_to_every_claim_that_reads_it(tmp_path, tracer):
    # table(4) is filled by shared.first; shared.second only reads it (through outside()).  In a mutant's run
    # shared.second starts cold and runs row() itself, so a mutant in row() must run both claims.
    lm, f = _line_map(tmp_path, {"shared.py": SHARED, "shared_claims.py": SHARED_CLAIMS}, tracer)
    assert ms.claims_of_line(lm, f, 5, False) == ["shared.first", "shared.second"]   # row()'s body
    assert ms.claims_of_line(lm, f, 10, False) == ["shared.first", "shared.second"]  # the fill
    assert ms.claims_of_line(lm, f, 14, False) == ["shared.second"]                  # outside(): its own
    assert lm["caches"]["cache:shared.table"]["callers"] == ["shared.first", "shared.second"]
    assert lm["claims"]["shared.first"]["status"] == lm["claims"]["shared.second"]["status"] == "verified"


def test_mutated_file_is_restored_with_its_time_stamp(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("x = 1\n")
    before = f.stat().st_mtime_ns
    with Mutated(f, b"x = 0\n"):
        assert f.read_text() == "x = 0\n" and int(f.stat().st_mtime) != int(before / 1e9)
    assert f.read_text() == "x = 1\n" and f.stat().st_mtime_ns == before


def test_a_changed_status_evidence_or_scope_kills():
    base = {"a": {"status": "erratum", "evidence": "sampled", "scope": "holds for b > 0"}}
    assert verify_changes(base, {"a": dict(base["a"], scope="holds everywhere")}, ["a"]) == \
        ["a: scope holds for b > 0 -> holds everywhere"]
    assert verify_changes(base, {"a": dict(base["a"], evidence="proof")}, ["a"])
    assert verify_changes(base, None, ["a"]) == ["a: no result"]


def test_score_counts_equivalents_out_and_budget_left_outs_in_neither():
    recs = [{"module": "m", "result": r} for r in ("killed", "tests", "survived", "equivalent", "not run")]
    t = summary(recs)["total"]
    assert (t["mutants"], t["not_run"], t["score"], t["verify_score"]) == (4, 1, 2 / 3, 1 / 3)


# --------------------------------------------------------------------------- end to end, on a project of its own

LIB = '''\
def double(x):
    return 2 * x


def count_to(n):
    i = 0
    while i < n:
        i += 1
    return i


def unused(x):
    return x - 1


def never(x):
    return x * 3
'''

CLAIMS = '''\
import sympy as sp
from symbt import claim, decide, from_decision

import mylib


@claim("lib.double", equation="double", scene="lib", statement="double(3) = 6")
def lib_double():
    return from_decision(decide(sp.Integer(mylib.double(3)), sp.Integer(6)))


@claim("lib.count", equation="count", scene="lib", statement="count_to(5) = 5")
def lib_count():
    return from_decision(decide(sp.Integer(mylib.count_to(5)), sp.Integer(5)))
'''


def _tree_digest(root: Path) -> str:
    h = hashlib.sha256()
    for p in sorted(root.rglob("*.py")):
        if "__pycache__" not in p.parts:
            h.update(p.read_bytes())
    return h.hexdigest()


@pytest.mark.slow
def test_end_to_end_on_a_small_project(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[tool.symbt]\nclaims = ["lib_claims.py"]\n')
    (tmp_path / "mylib.py").write_text(LIB)
    (tmp_path / "lib_claims.py").write_text(CLAIMS)
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_lib.py").write_text("from mylib import unused\n\n\ndef test_unused():\n"
                                                    "    assert unused(3) == 2\n")
    ids = {m.line_text.strip() + " " + m.description: m.id for m in find_mutants(LIB, "mylib")}
    (tmp_path / "mutants-equivalent.toml").write_text(
        f'[[mutant]]\nid = "{ids["i = 0 0 -> 1"]}"\nreason = "count_to(n) = n for n >= 1 either way"\n'
        '[[mutant]]\nid = "mylib:99:sign:0123abcd"\nreason = "a mark that matches nothing"\n')
    before = _tree_digest(tmp_path)
    out = tmp_path / "out.json"
    env_cache = tmp_path / "cache"
    r = subprocess.run([sys.executable, "-m", "symbt", "mutate", "--source", "mylib", "--mutant-timeout", "45",
                        "--tests", "--json", str(out), "-j", "1"], cwd=tmp_path, capture_output=True, text=True,
                       timeout=900, env={**os.environ, "SYMBT_CACHE_DIR": str(env_cache), "PYTHONPATH": str(ROOT)})
    assert r.returncode == 1, r.stderr   # survivors: unused() is run by no claim, only by a test
    doc = json.loads(out.read_text())
    import jsonschema

    jsonschema.validate(doc, schema())
    result = {(rec["line"], rec["diff"].splitlines()[1][2:].strip()): rec["result"] for rec in doc["mutants"]}
    assert result == {
        (2, "return x"): "killed",                   # double: 2 * x -> x
        (6, "i = 1"): "equivalent",                  # marked, not run
        (7, "while i <= n:"): "killed", (7, "while i > n:"): "killed",
        (8, "i += 0"): "timeout",                    # an endless loop, stopped at the limit
        (13, "return x + 1"): "tests", (13, "return x - 0"): "tests",   # no claim runs unused(); its test does
        (17, "return x"): "uncovered"}               # nothing runs never()
    assert doc["stale_equivalents"] == [{"id": "mylib:99:sign:0123abcd", "reason": "a mark that matches nothing"}]
    t = doc["summary"]["modules"]["mylib"]
    assert (t["equivalent"], t["uncovered"], t["timeouts"], t["killed_tests"]) == (1, 1, 1, 2)
    assert _tree_digest(tmp_path) == before                    # the real tree was never written
