"""pytest plugin (entry point ``pytest11``, name ``symbt``): the paper's claims as test items.

``pytest --symbt`` adds one test item per claim to the session (after your own
tests), with the claim cache of ``symbt verify``:

* ``verified`` -> passes;
* ``erratum`` -> passes (the paper is wrong, the corrected statement holds); the
  printed and corrected statements and the scope are recorded as the item's
  user properties (``--junitxml`` writes them as ``<property>``) and listed in a
  "symbt errata" section of the terminal summary;
* ``failed`` -> fails, with the statement, counterexample and residual;
* ``inconclusive`` (cannot tell at the precision or budget given) and ``todo`` (no
  check written yet) -> fail too, with a message naming the status and why;
* ``skipped`` -> skipped with its reason (e.g. an optional extra is missing).

Which claims: ``--symbt-claims MODULE_OR_PATH`` (repeatable; your claims module, a
``.py`` file or a package), else the ``claims`` of ``[tool.symbt]`` in the ``pyproject.toml``
found from the working directory, else Zullo's paper -- the same rule as ``symbt verify``
(:mod:`symbt.engine.project`).  Options: ``--symbt-scene NAME`` (repeatable; a scene, claim
id or ``nK``), ``--symbt-label LABEL`` (repeatable; a paper label's claims), ``--symbt-deep``
(add the minutes-long claims), ``--symbt-no-cache``, ``--symbt-budget SECONDS`` (each
check's time limit, default ``[tool.symbt] budget`` or 300: past it the item fails as
``inconclusive (timed out ...)``); each of them implies ``--symbt``.  Claims run in
worker processes kept for the session.  Items are named ``symbt/<scene>::<claim id>``
and match ``-k`` on the claim id, the scene and the equation label, and ``-m symbt``;
``-x``, ``--junitxml`` and pytest-xdist's ``-n`` work as for any test.

Without these options the plugin does nothing but offer the ``symbt_identity``
fixture (:func:`symbt.testing.assert_identity`, imported on first use): this
module imports only pytest and the standard library, so loading it costs nothing.
"""
from __future__ import annotations

from typing import Any

import pytest

__all__ = ["symbt_identity"]


def pytest_addoption(parser: pytest.Parser) -> None:
    g = parser.getgroup("symbt", "symbt: the paper's claims as test items")
    g.addoption("--symbt", action="store_true", default=False, help="collect symbt's claims as test items")
    g.addoption("--symbt-claims", action="append", default=None, metavar="MODULE_OR_PATH",
                help="your claims module or path (repeatable; default: [tool.symbt] claims, else Zullo's paper; "
                     "implies --symbt)")
    g.addoption("--symbt-scene", action="append", default=None, metavar="NAME",
                help="only this scene / claim id / nK (repeatable; implies --symbt)")
    g.addoption("--symbt-label", action="append", default=None, metavar="LABEL",
                help="only the claims of this paper label (repeatable; implies --symbt)")
    g.addoption("--symbt-deep", action="store_true", default=False,
                help="include the minutes-long deep claims (implies --symbt)")
    g.addoption("--symbt-no-cache", action="store_true", default=False,
                help="recompute every claim (implies --symbt)")
    g.addoption("--symbt-budget", type=float, default=None, metavar="SECONDS",
                help="time limit of each claim's check (default 300; implies --symbt)")


def pytest_configure(config: pytest.Config) -> None:
    opt = config.getoption
    budget = opt("symbt_budget")
    if budget is not None and not 0 < budget < float("inf"):
        raise pytest.UsageError(f"--symbt-budget: expected a positive number of seconds, got {budget}")
    if any(opt(o) for o in ("symbt", "symbt_claims", "symbt_scene", "symbt_label", "symbt_deep",
                            "symbt_no_cache")) or budget is not None:
        config.addinivalue_line("markers", "symbt: a claim of symbt (added by pytest --symbt)")
        config.pluginmanager.register(_SymbtSession(config), "symbt-session")


@pytest.fixture
def symbt_identity():
    """:func:`symbt.testing.assert_identity`: ``symbt_identity(lhs, rhs=0, **kw)`` asserts an identity.

    Raises ``AssertionError`` with the statement, the relative residual and a
    counterexample when it is false; returns the ``IdentityResult`` otherwise.
    """
    from symbt.testing import assert_identity

    return assert_identity


class ClaimFailed(Exception):
    """A claim's check failed; the message carries the counterexample and residual."""


def _failure_message(claim: Any, out: Any) -> str:
    from symbt.report.text import field_lines, residual_text

    verb = {"inconclusive": "is inconclusive (cannot tell)", "todo": "is a todo stub (no check written yet)"}
    lines = [f"claim {claim.id} (eq. {claim.equation}) {verb.get(out.status, 'failed')}: {claim.statement}",
             f"  status:    {out.status}",
             f"  residual:  {residual_text(out)}",
             f"  method:    {out.method}",
             f"  evidence:  {out.evidence or '-'}"]
    lines += field_lines(out, "  ", limit=20)
    if out.detail:
        lines.append("  detail:\n    " + "\n    ".join(out.detail.strip().splitlines()))
    return "\n".join(lines)


class ClaimItem(pytest.Item):
    """One claim as a test item."""

    def __init__(self, *, claim: Any, outcome: Any = None, use_cache: bool = True, deep: bool = False, **kw: Any):
        super().__init__(**kw)
        self.claim = claim
        self._outcome = outcome  # known from the cache at collection (warm path)
        self._use_cache = use_cache
        self._deep = deep
        self.add_marker("symbt")
        self.extra_keyword_matches.update({claim.scene, claim.equation})

    def runtest(self) -> None:
        out = self._outcome
        if out is None:
            from symbt.claims import REGISTRY
            from symbt.engine.runner import run

            budget = self.config.getoption("symbt_budget")
            session = self.config.pluginmanager.get_plugin("symbt-session")
            if session is not None:
                session.keep_workers()
                if budget is None and session.project is not None:
                    budget = session.project.budget  # [tool.symbt] budget
            out = run([REGISTRY[self.claim.id]], use_cache=self._use_cache, manifest=False,
                      deep=self._deep, **({} if budget is None else {"budget": budget}))[0].outcome
        props = [("symbt_status", out.status), ("symbt_evidence", out.evidence or "-"),
                 ("symbt_method", out.method), ("symbt_residual", repr(out.residual)),
                 ("symbt_cached", str(bool(out.cached)).lower())]
        if out.status == "erratum":
            props += [("symbt_printed", out.printed or ""), ("symbt_corrected", out.corrected or ""),
                      ("symbt_scope", out.scope or ""), ("symbt_equation", self.claim.equation)]
        self.user_properties.extend(props)
        if out.status == "skipped":
            pytest.skip(f"{self.claim.id}: {(out.detail or 'skipped').strip()}")
        if out.status in ("failed", "inconclusive", "todo"):  # not ok: symbt.claims.base.NOT_OK
            raise ClaimFailed(_failure_message(self.claim, out))

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, ClaimFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self):
        return self.path, None, f"symbt claim {self.claim.id} (eq. {self.claim.equation})"


class _SymbtSession:
    """Active only with ``--symbt``: adds the items, collects the errata for the summary."""

    def __init__(self, config: pytest.Config):
        self.config = config
        self.errata: list[dict[str, str]] = []
        self.project: Any = None    # the project whose claims were collected (symbt.engine.project)
        self._workers: Any = None   # the claims' worker processes, kept from item to item (and their memos)

    def keep_workers(self) -> None:
        if self._workers is None:
            from symbt.engine.runner import keep_workers

            self._workers = keep_workers()
            self._workers.__enter__()

    @pytest.hookimpl(tryfirst=True)  # before -k / -m deselect
    def pytest_collection_modifyitems(self, session: pytest.Session, config: pytest.Config,
                                      items: list[pytest.Item]) -> None:
        from symbt.engine.project import ConfigError, discover
        from symbt.engine.select import select
        from symbt.engine.warm import cached_results

        names = config.getoption("symbt_scene")
        labels = config.getoption("symbt_label") or ()
        deep = config.getoption("symbt_deep")
        use_cache = not config.getoption("symbt_no_cache")
        try:
            project = self.project = discover(claims=config.getoption("symbt_claims") or ())
            warm = cached_results(names, deep=deep, project=project, labels=labels) if use_cache else None
            pairs: list[tuple[Any, Any]]
            if warm is not None:
                pairs = [(r.claim, r.outcome) for r in warm]
            else:
                pairs = [(c, None) for c in select(names, include_deep=deep, project=project, labels=labels)]
        except ConfigError as exc:
            raise pytest.UsageError(f"symbt: {exc}") from None
        except KeyError as exc:
            raise pytest.UsageError(f"--symbt-scene/--symbt-label: {exc.args[0]}") from None
        new: list[pytest.Item | pytest.Collector] = [
            ClaimItem.from_parent(session, name=claim.id, nodeid=f"symbt/{claim.scene}::{claim.id}", claim=claim,
                                  outcome=outcome, use_cache=use_cache, deep=deep)
            for claim, outcome in pairs]
        # report them as collected (the terminal's "collected N items", like any collector's items)
        session.ihook.pytest_collectreport(report=pytest.CollectReport("symbt", "passed", None, new))
        items.extend(i for i in new if isinstance(i, pytest.Item))

    def pytest_runtest_logreport(self, report: pytest.TestReport) -> None:
        props = dict(report.user_properties)
        if report.when == "call" and props.get("symbt_status") == "erratum":
            self.errata.append({"nodeid": report.nodeid, **{k: str(v) for k, v in props.items()}})

    def pytest_sessionfinish(self, session: pytest.Session) -> None:
        if self._workers is not None:
            self._workers.__exit__(None, None, None)
            self._workers = None
        try:
            from symbt.engine.runner import refresh_manifest

            refresh_manifest()
        except Exception:  # pragma: no cover - the cache is an optimisation
            pass

    def pytest_terminal_summary(self, terminalreporter, exitstatus, config) -> None:
        if not self.errata:
            return
        tr = terminalreporter
        tr.section(f"symbt errata ({len(self.errata)}): the paper's statement fails, the correction holds")
        for e in self.errata:
            cid = e["nodeid"].rpartition("::")[2]
            tr.write_line(f"{cid} (eq. {e.get('symbt_equation', '?')}) [{e.get('symbt_evidence', '-')}]")
            tr.write_line(f"    printed:   {e.get('symbt_printed', '')}")
            tr.write_line(f"    corrected: {e.get('symbt_corrected', '')}")
            if e.get("symbt_scope"):
                tr.write_line(f"    scope:     {e['symbt_scope']}")
