r"""A guard that no claim stretched and the staleness check's exit status (issue 21, seed 12's ``literal:276``,
``codegen.cli:81`` and ``:125``).

* ``library.guard_far_trace`` -- :func:`symbt.reference.literal.reference_step` chooses its guard digits from the
  larger of ``|tr L(lam1)|``, ``|tr L(lam2)|`` (the forward transport loses about twice their ``log10``).  At the
  paper-like state ``p = (0.3, -0.2, 0.1)``, ``q = (0, 0.5, 0.2)`` with ``lam1 = -2.5`` just below the lowest band
  (``|tr| ~ 6``) and ``lam2 = -1e13`` or ``-1e20`` in the same outer gap (``|tr L(lam2)| ~ |lam2|^3``), both
  branches, 30 digits: the step with ``verify=True`` (the same computation with 25 more digits agrees to 30
  digits), and within ``1e-28`` of ``bt_step``'s mpmath backend at 60 digits (the scaled formulation of
  ``symbt.numeric``, another route) relative to ``1 + |x|``.  A guard sized from ``lam1`` alone loses every digit
  at ``lam2 = -1e20``.
* ``library.codegen_check`` -- ``symbt codegen --check`` (what CI pipelines run to fail on a drifted generated
  file) on copies of the shipped ``toda2.py`` and ``__init__.py``: exit 0, also written ``symbt codegen --
  --check``; exit 1 naming "edited by hand" after a one-byte edit, and "missing" after the file is deleted.
"""
from __future__ import annotations

import mpmath as mp

from ._facts import Facts
from ._facts import facts_failed as _bad
from .base import Outcome, claim, failed

#: library.guard_far_trace: the state, lam1 below the lowest band, lam2 far in the same outer gap
GUARD_STATE = (("0.3", "-0.2", "0.1"), ("0", "0.5", "0.2"))
GUARD_LAMBDAS = (("-2.5", "-1e13"), ("-2.5", "-1e20"))


@claim("library.guard_far_trace", equation="checker", scene="library",
       where="symbt/reference/literal.py: reference_step's guard digits (from both traces)",
       statement="reference_step (30 digits, verify=True) at p = (0.3, -0.2, 0.1), q = (0, 0.5, 0.2), lam1 = -2.5, "
                 "lam2 = -1e13 and -1e20 (|tr L(lam2)| ~ |lam2|^3 far above |tr L(lam1)| ~ 6), both branches: "
                 "converged, and within 1e-28 (1 + |x|) of bt_step's mpmath backend at 60 digits")
def guard_far_trace() -> Outcome:
    from ..numeric import bt_step
    from ..reference.literal import reference_step

    bad, worst = [], mp.mpf(0)
    with mp.workdps(30):
        p, q = ([mp.mpf(v) for v in vs] for vs in GUARD_STATE)
        for l1, l2 in GUARD_LAMBDAS:
            lam1, lam2 = mp.mpf(l1), mp.mpf(l2)
            l0, m = (lam1 + lam2) / 2, (lam1 - lam2) / 2
            for b in (1, -1):
                try:
                    pt, qt = reference_step(p, q, l0, m, branch=b, verify=True)
                except AssertionError as exc:
                    bad.append(f"lam2 = {l2}, branch {b}: {exc}")
                    continue
                with mp.workdps(60):
                    pn, qn = bt_step(p, q, l0, m, branch=b, backend="mpmath")
                err = max(abs(x - y) / (1 + abs(y)) for x, y in zip(list(pt) + list(qt), list(pn) + list(qn)))
                worst = max(worst, err)
                if not err <= mp.mpf("1e-28"):
                    bad.append(f"lam2 = {l2}, branch {b}: {mp.nstr(err, 3)} from the mpmath backend")
    detail = f"{2 * len(GUARD_LAMBDAS)} steps converged; worst difference {mp.nstr(worst, 3)} relative to 1 + |x|."
    if bad:
        return failed("reference_step at a far trace", detail="; ".join(bad[:4]) + ". " + detail)
    return Outcome("verified", "reference_step (verify=True) vs bt_step's mpmath backend (60 digits)",
                   evidence="sampled", detail=detail, printed="converged, within 1e-28")


@claim("library.codegen_check", equation="checker", scene="library",
       where="symbt codegen --check (symbt.codegen.cli.main on the installed derivations)",
       statement="symbt codegen --check --installed --n 2 --out DIR, DIR holding copies of the shipped toda2.py and "
                 "__init__.py: exit 0 (also after a leading '--'); with toda2.py edited by one byte: exit 1 and a "
                 "message 'edited by hand'; with toda2.py deleted: exit 1 and 'missing'")
def codegen_check() -> Outcome:
    import contextlib
    import io
    import shutil
    import tempfile
    from pathlib import Path

    from ..codegen.cli import main
    from ..codegen.files import DEFAULT_OUT

    got: Facts = []
    with tempfile.TemporaryDirectory(prefix="symbt-codegen-check-") as tmp:
        for name in ("toda2.py", "__init__.py"):
            shutil.copy(DEFAULT_OUT / name, tmp)
        module = Path(tmp) / "toda2.py"

        def run(*lead: str) -> tuple[int, str]:
            err = io.StringIO()
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                code = main([*lead, "--check", "--installed", "--n", "2", "--out", tmp])
            return code, err.getvalue()

        got.append(("the shipped files", run()[0], 0))
        got.append(("the shipped files, `symbt codegen -- --check`", run("--")[0], 0))
        module.write_text(module.read_text(encoding="utf-8") + " ", encoding="utf-8")
        code, msg = run()
        got.append(("toda2.py edited by hand", (code, "edited by hand" in msg), (1, True)))
        module.unlink()
        code, msg = run()
        got.append(("toda2.py deleted", (code, "missing" in msg), (1, True)))
    bad = _bad("symbt codegen --check", got)
    return bad or Outcome("verified", "symbt codegen --check on copies of the shipped files, edited and deleted",
                          evidence="proof", detail=f"{len(got)} runs, each exit status as documented")
