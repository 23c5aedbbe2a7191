"""``symbt mutate`` on a user's claims: ``--claims`` / ``[tool.symbt]``, claims without mutants
reported, progress with an estimate, ``--budget`` and per-mutant time limits, exit statuses.

The user's project is ``tests/data/mutate_project`` (22 cheap claims of the usual kinds), copied to
a temporary directory.  The full run goes through a subprocess (its wall time is bounded here only
as a sanity ceiling, far above the few seconds it takes); the rest runs in this process and removes
the claims it registered afterwards.
"""
from __future__ import annotations

import io
import json
import os
import shutil
import subprocess
import sys
import time
import types
from pathlib import Path

import pytest
import sympy as sp

from symbt import cli
from symbt.claims.base import REGISTRY, SCENES, Parts, claim, from_decision
from symbt.engine import mutate
from symbt.engine.project import claim_module
from symbt.proof import Verdict, decide

DATA = Path(__file__).parent / "data" / "mutate_project"
REPO = Path(__file__).resolve().parents[1]
FILES = ("note_model.py", "note_claims.py")
NO_MUTANTS = ["note.isospectral", "note.cayley", "note.hessian"]


@pytest.fixture(scope="module")
def project(tmp_path_factory):
    """The user's project in a temporary directory; their claims leave the registry afterwards."""
    root = tmp_path_factory.mktemp("user-project")
    for f in FILES:
        shutil.copy(DATA / f, root / f)
    yield root
    for cid in [cid for cid, c in REGISTRY.items() if claim_module(c).startswith("note_")]:
        del REGISTRY[cid]
    SCENES.pop("note", None)
    for name in ("note_claims", "note_model"):
        sys.modules.pop(name, None)


@pytest.fixture
def registered():
    """Claims a test registers in scene ``zz-mut`` are removed afterwards (Zullo's, loaded meanwhile, stay)."""
    yield
    for cid in [cid for cid, c in REGISTRY.items() if c.scene == "zz-mut"]:
        del REGISTRY[cid]
    SCENES.pop("zz-mut", None)


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(REPO), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    return env


@pytest.fixture(scope="module")
def full_run(project, tmp_path_factory):
    """Every mutant of every claim of the user's project, through the command line (-j 2)."""
    out = tmp_path_factory.mktemp("mutate-out") / "m.json"
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "symbt", "mutate", "--claims", str(project / "note_claims.py"),
                           "-j", "2", "--json", str(out)], cwd=project, env=_env(), capture_output=True, text=True,
                          timeout=600)
    wall = time.perf_counter() - t0
    return proc, json.loads(out.read_text()) if out.exists() else None, wall


def test_claims_flag_mutates_only_the_users_claims(full_run):
    proc, report, wall = full_run
    assert proc.returncode == 0, proc.stderr
    ids = [r["id"] for r in report["claims"]]
    assert len(ids) == 22 and all(i.startswith("note.") for i in ids)
    s = report["summary"]
    assert s["mutants"] >= 250 and s["survivors"] == 0 and s["score"] == 1.0
    assert wall < 120, f"sanity ceiling: the fixture's mutation run took {wall:.0f}s"


def test_claims_without_mutants_are_reported_with_their_parts(full_run):
    proc, report, _ = full_run
    s, by_id = report["summary"], {r["id"]: r for r in report["claims"]}
    assert s["no_mutants"] == NO_MUTANTS
    assert not set(NO_MUTANTS) & set(s["claims_killing_none"])
    iso = by_id["note.isospectral"]
    assert iso["no_mutants"] and iso["mutants"] == 0
    assert iso["no_mutant_parts"] == [{"part": "printed.rhs", "why": iso["no_mutant_parts"][0]["why"]}]
    assert "it is 0" in iso["no_mutant_parts"][0]["why"] and "both sides" in iso["no_mutant_parts"][0]["why"]
    assert "matrix of bare symbols" in by_id["note.cayley"]["no_mutant_parts"][0]["why"]
    assert "parts=" in by_id["note.hessian"]["note"]
    # a part without mutants beside parts with mutants is named too, and the claim is scored as usual
    eom = by_id["note.eom"]
    assert not eom["no_mutants"] and eom["killed"] > 0
    assert {p["part"] for p in eom["no_mutant_parts"]} == {"printed.qdot1", "printed.qdot2"}
    text = proc.stdout
    assert "3 claims gave no mutants, not in the score" in text
    assert "part 'printed.rhs' gives no mutants: it is 0" in text
    assert "note.hessian" in text and "NO MUTANTS" in text


def test_progress_lines_with_an_estimate_when_not_a_terminal(full_run):
    proc, _, _ = full_run
    lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("[")]
    assert len(lines) == 22, proc.stderr
    assert lines[-1].startswith("[22/22] ")
    assert all(" mutants, " in ln and " elapsed" in ln for ln in lines)
    assert any(" left" in ln for ln in lines[:-1])   # an estimate of the remaining time
    assert "\r" not in proc.stderr


def test_tool_symbt_config_and_label(project, monkeypatch, capsys):
    (project / "pyproject.toml").write_text('[tool.symbt]\nclaims = ["note_claims.py"]\n')
    monkeypatch.chdir(project)
    out = project / "label.json"
    assert mutate.main(["--label", "cube", "-j", "1", "--json", str(out)]) == 0
    report = json.loads(out.read_text())
    [rec] = report["claims"]
    assert rec["id"] == "note.cube.erratum" and rec["status"] == "erratum" and rec["side"] == "corrected"
    assert rec["killed"] == rec["mutants"] > 0
    err = capsys.readouterr().err
    assert err.startswith("[1/1] note.cube.erratum: ")      # plain progress line (stderr is not a terminal)
    assert mutate.main(["--scene", "note.cubes", "-j", "1", "-q"]) == 0
    captured = capsys.readouterr()
    assert captured.err == "" and captured.out == ""      # -q: no progress, no report


def test_budget_stops_early_and_says_so(project, monkeypatch, capsys):
    monkeypatch.chdir(project)
    # the run's clock moves 10 ms more at every look, so the 1.5 s budget runs out within 150 looks whatever the
    # machine's speed (on a fast one with warm caches all 250 mutants took less than 1.5 s of real time)
    looks = iter(range(10 ** 6))
    clock = types.SimpleNamespace(perf_counter=time.perf_counter, time=lambda: time.time() + 0.01 * next(looks))
    monkeypatch.setattr(mutate, "time", clock)
    t0 = time.perf_counter()
    code = mutate.main(["--claims", "note_claims.py", "-j", "1", "--budget", "1.5", "--json", "-"])
    wall = time.perf_counter() - t0
    report = json.loads(capsys.readouterr().out)
    s = report["summary"]
    assert code == 0                                        # nothing that ran survived
    assert s["budget_reached"] and s["not_run"] > 0
    assert s["mutants"] + s["not_run"] == s["planned"] >= 250
    assert s["not_started"] and all(not r["started"] for r in report["claims"] if r["id"] in s["not_started"])
    assert wall < 1.5 + 15                                  # a running mutant finishes; none starts after
    text = mutate.format_text(report["claims"])
    assert f"budget reached after {s['mutants']} of {s['planned']} mutants" in text
    assert "not started" in text


def test_bad_claims_path_is_one_line_exit_2(capsys, tmp_path):
    assert cli.main(["mutate", "--claims", str(tmp_path / "missing.py")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("symbt mutate: ") and "does not exist" in err
    broken = tmp_path / "broken_claims.py"
    broken.write_text("raise RuntimeError('my typo')\n")
    assert cli.main(["mutate", "--claims", str(broken)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "does not import" in err and "my typo" in err
    assert cli.main(["mutate", "--budget", "-3"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "positive number of seconds" in err


# --------------------------------------------------------------------------- in-process claims

x = sp.Symbol("x", real=True)


def _sampled_in(parts: Parts) -> object:
    """A rejection sampler over lo < x < hi (the parts): a mutant that empties the interval loops forever."""
    import random

    rng = random.Random(1)
    lo, hi = parts.printed["lo"], parts.printed["hi"]
    n = 0
    while n < 8:
        if lo < rng.uniform(-4, 4) < hi:
            n += 1
    return from_decision(decide(sp.Integer(n), 8))


def test_a_mutant_that_loops_forever_is_killed_by_timeout():
    c = claim("zz.loop", equation="zz", scene="zz-mut", statement="8 samples in (lo, hi) = (1, 2)", register=False,
              parts=lambda: Parts(printed={"lo": 1, "hi": 2.0}))(_sampled_in)
    assert c.run().status == "verified"
    t0 = time.perf_counter()
    rec = mutate.mutate_claim(c, mutant_timeout=0.5)
    assert time.perf_counter() - t0 < 10
    ops = {t["mutation"] for t in rec.timeouts}
    assert "swap the branch +1 -> -1" not in ops            # lo = -1 keeps a nonempty interval: decided, not stuck
    assert "negate 2.0" in ops                              # (1, -2) is empty: the sampler never stops
    assert rec.killed >= len(rec.timeouts) >= 1 and rec.timeouts[0]["limit"] == 0.5
    assert "killed by timeout (> 0.5s): printed.hi: negate 2.0" in mutate.format_text([rec.to_dict()])


def test_a_survivor_fails_the_run_and_fail_under_relaxes_it(registered, capsys):
    @claim("zz.blind", equation="zz-blind", scene="zz-mut", statement="x + 1 > x (the check ignores the constant)",
           parts=lambda: Parts(printed={"rhs": x + 1}))
    def _blind(parts):   # sampled evidence: a check's own *proof* of a mutant would make it equivalent
        return from_decision(Verdict.sampled(abs(float(parts.printed["rhs"].coeff(x)) - 1), tol=1e-12))

    assert mutate.main(["--scene", "zz.blind", "-j", "1", "-q", "--json", "-"]) == 1
    s = json.loads(capsys.readouterr().out)["summary"]
    assert s["survivors"] >= 1 and s["score"] < 1
    assert mutate.main(["--scene", "zz.blind", "-j", "1", "-q", "--fail-under", f"{100 * s['score'] - 1}"]) == 0
    assert mutate.main(["--scene", "zz.blind", "-j", "1", "-q", "--fail-under", "100"]) == 1


def test_no_mutants_do_not_lower_the_score():
    recs = [{"id": "a", "status": "verified", "mutants": 4, "killed": 4, "equivalent_count": 0, "survivors": []},
            {"id": "b", "status": "verified", "mutants": 0, "killed": 0, "equivalent_count": 0, "survivors": [],
             "no_mutants": True, "note": "its printed parts give no mutants"}]
    s = mutate.summary(recs)
    assert s["score"] == 1.0 and s["no_mutants"] == ["b"] and s["claims_killing_none"] == []


def test_progress_on_a_terminal_rewrites_one_line():
    class Tty(io.StringIO):
        def isatty(self):
            return True

    buf = Tty()
    ticks = iter(float(i) for i in range(100))
    p = mutate.MutateProgress(["a", "b"], stream=buf, clock=ticks.__next__)
    p.event("start", "a", 3)
    p.event("mutant", "a", 1)
    p.event("mutant", "a", 2)
    p.claim_done({"id": "a", "mutants": 3, "killed": 3, "planned": 3, "seconds": 1.0})
    p.close()
    text = buf.getvalue()
    assert "\rmutate [0/2 claims] 1/~6 mutants" in text and "left" in text
    assert "[1/2] a: 3/3 mutants, 3 killed (1.0s) | 3/~6 mutants" in text
