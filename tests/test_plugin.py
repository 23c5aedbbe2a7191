"""The pytest plugin: ``pytest --symbt`` turns claims into test items; ``symbt_identity`` for users."""
from __future__ import annotations

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from importlib import metadata

import pytest

pytest_plugins = ["pytester"]

CONFTEST = '''
import sympy as sp
from symbt.claims.base import REGISTRY, claim, from_decision, scene
from symbt.proof import decide

x = sp.Symbol("x", real=True)
scene("zz", "claims of the plugin test")
if "zz.fails" not in REGISTRY:
    @claim("zz.fails", equation="zz-eq", scene="zz", statement="(x+1)^2 = x^2 + 1")
    def _fails():
        return from_decision(decide((x + 1) ** 2, x ** 2 + 1))

    @claim("zz.holds", equation="zz-eq", scene="zz", statement="(x+1)^2 = x^2 + 2x + 1")
    def _holds():
        return from_decision(decide((x + 1) ** 2, x ** 2 + 2 * x + 1))

    @claim("zz.needs", equation="zz-eq", scene="zz", statement="needs an extra", requires=("no_such_module_zz",))
    def _needs():
        raise AssertionError("never run")
'''


def _plugin_args(*, xdist: bool = False) -> list[str]:
    """``-p symbt.pytest_plugin`` unless the installed distribution already registers the entry point;
    hypothesis' plugin (seconds per in-process run) and xdist are left out where not needed."""
    eps = metadata.entry_points(group="pytest11")
    args = [] if any(ep.value == "symbt.pytest_plugin" for ep in eps) else ["-p", "symbt.pytest_plugin"]
    return args + ["-p", "no:hypothesispytest", "-p", "no:cacheprovider"] + ([] if xdist else ["-p", "no:xdist"])


@pytest.fixture(scope="module")
def loaded():
    """Import the claims (numpy, sympy, ...) before any pytester exists: pytester drops the modules
    imported while it lives, and numpy cannot be imported twice in one process."""
    import symbt.testing  # noqa: F401
    from symbt.claims import load_all

    load_all()


@pytest.fixture
def zz(loaded, pytester):
    """A pytester directory whose conftest registers three test claims (removed afterwards)."""
    pytester.makeconftest(CONFTEST)
    yield pytester
    from symbt.claims.base import REGISTRY, SCENES

    for cid in ("zz.fails", "zz.holds", "zz.needs"):
        REGISTRY.pop(cid, None)
    SCENES.pop("zz", None)


def test_claims_become_items_with_statuses_junit_and_errata_summary(zz):
    junit = zz.path / "out.xml"
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "zz", "--symbt-scene", "n3-hamiltonians.tra",
                     "-rs", f"--junitxml={junit}")
    r.assert_outcomes(passed=2, failed=1, skipped=1)
    out = r.stdout.str()
    # failed -> test failure naming the claim, with counterexample and residual
    assert "claim zz.fails (eq. zz-eq) failed" in out
    assert "counterexample: x = " in out and "residual:" in out
    # skipped -> its reason
    assert "optional dependency missing: no_such_module_zz" in out
    # erratum -> passes, listed with printed / corrected statements in the terminal summary
    assert "symbt errata (1)" in out and "n3-hamiltonians.tra (eq. n3-hamiltonians) [proof]" in out
    assert "printed:" in out and "corrected:" in out
    root = ET.parse(junit).getroot()
    cases = {tc.get("name"): tc for tc in root.iter("testcase")}
    assert cases["zz.fails"].get("classname") == "symbt.zz"
    assert "counterexample" in cases["zz.fails"].find("failure").get("message", "") + \
        (cases["zz.fails"].find("failure").text or "")
    props = {p.get("name"): p.get("value") for p in cases["n3-hamiltonians.tra"].iter("property")}
    assert props["symbt_status"] == "erratum" and props["symbt_evidence"] == "proof"
    assert props["symbt_printed"] and props["symbt_corrected"] and props["symbt_cached"] == "false"
    assert cases["zz.needs"].find("skipped") is not None
    # the claim cache is shared with `symbt verify`: a second run reads it
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "n3-hamiltonians.tra", f"--junitxml={junit}")
    r.assert_outcomes(passed=1)
    props = {p.get("name"): p.get("value") for p in ET.parse(junit).getroot().iter("property")}
    assert props["symbt_cached"] == "true"


def test_keyword_selection_and_exitfirst(zz):
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "zz", "-k", "holds")
    r.assert_outcomes(passed=1, deselected=2)
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "zz", "-k", "zz-eq and not fails")
    r.assert_outcomes(passed=1, skipped=1, deselected=1)       # -k matches the equation label too
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "zz", "-x")
    r.assert_outcomes(failed=1)                                # stopped after the first (failing) claim
    r = zz.runpytest(*_plugin_args(), "--symbt", "--symbt-scene", "zz", "-m", "symbt", "--co", "-q")
    assert "symbt/zz::zz.fails" in r.stdout.str() and "symbt/zz::zz.needs" in r.stdout.str()


def test_unknown_scene_is_a_usage_error(zz):
    r = zz.runpytest(*_plugin_args(), "--symbt-scene", "no-such-scene")
    assert r.ret == pytest.ExitCode.USAGE_ERROR
    assert "unknown scene or claim 'no-such-scene'" in r.stderr.str() + r.stdout.str()


def test_without_the_option_nothing_happens_and_nothing_heavy_is_imported(pytester):
    pytester.makepyfile(test_plain='''
        import sys

        def test_plain():
            assert "sympy" not in sys.modules and "symbt.engine" not in sys.modules
    ''')
    r = pytester.runpytest_subprocess(*_plugin_args(), "-v")
    r.assert_outcomes(passed=1)
    assert "collected 1 item" in r.stdout.str() and "symbt/" not in r.stdout.str()


def test_symbt_identity_fixture(loaded, pytester):
    pytester.makepyfile(test_ids='''
        import sympy as sp
        x = sp.Symbol("x", real=True)

        def test_true(symbt_identity):
            assert symbt_identity(sp.cosh(x)**2 - sp.sinh(x)**2, 1).status == "proved"

        def test_false(symbt_identity):
            symbt_identity(sp.sqrt(x**2), x)
    ''')
    r = pytester.runpytest(*_plugin_args())
    r.assert_outcomes(passed=1, failed=1)
    assert "identity does not hold" in r.stdout.str() and "counterexample" in r.stdout.str()


def test_xdist_with_a_warm_cache(loaded, pytester):
    """-n 2: the workers collect the same items and read the outcomes from the shared cache."""
    pytest.importorskip("xdist")
    ids = ["--symbt-scene=tn2", "--symbt-scene=tra.n2", "--symbt-scene=Hj.n2"]
    pytester.runpytest(*_plugin_args(), "--symbt", *ids).assert_outcomes(passed=3)   # fills the cache
    junit = pytester.path / "x.xml"
    r = pytester.runpytest_subprocess(*_plugin_args(xdist=True), "-n", "2", "--symbt", *ids, f"--junitxml={junit}")
    r.assert_outcomes(passed=3)
    cached = [p.get("value") for p in ET.parse(junit).getroot().iter("property") if p.get("name") == "symbt_cached"]
    assert cached == ["true"] * 3


def test_plugin_module_is_cheap_to_import():
    code = "import sys, symbt.pytest_plugin; print(sorted(m for m in ('sympy', 'numpy', 'mpmath', 'symbt.engine', " \
           "'symbt.claims') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
    assert out.stdout.strip() == "[]"
