"""The note's claims through ``symbt.verify``: which displays hold, which are errata, and the generated scope."""
from __future__ import annotations

import shutil
from pathlib import Path

import symbt

PROJECT = Path(__file__).resolve().parents[1]


def results():
    return {r.claim.id: r.outcome for r in symbt.verify(claims=[str(PROJECT / "drag_claims.py")])}


def test_statuses_and_evidence():
    got = {cid: (o.status, o.evidence) for cid, o in results().items()}
    # the [tool.symbt] table's codegen source (drag_emit.py) adds the emitted function's claims: the files in
    # generated/ against their SymPy source; the C one is skipped where no C compiler is installed
    has_cc = any(shutil.which(c) for c in ("cc", "gcc", "clang"))
    assert got == {"drag.vT": ("verified", "proof"), "drag.v": ("verified", "proof"),
                   "drag.x": ("verified", "proof"), "drag.v2x": ("verified", "proof"),
                   "drag.t99": ("erratum", "proof"), "drag.v0": ("erratum", "sampled"),
                   "emit.drag_numeric.velocity.numpy": ("verified", "sampled"),
                   "emit.drag_numeric.velocity.mpmath": ("verified", "sampled"),
                   "emit.drag_numeric.velocity.c": ("verified", "sampled") if has_cc else ("skipped", None)}


def test_scope_of_the_thrown_solution_is_generated_from_its_cells():
    out = results()["drag.v0"]
    table = {(c["cell"]["regime"], c["cell"]["sign(v0)"]): (c["n"], c["printed_holds"], c["corrected_holds"])
             for c in out.cells}
    assert table == {("|v0|<v_T", "v0>0"): (16, 16, 16), ("|v0|<v_T", "v0<0"): (16, 16, 16),
                     ("|v0|>v_T", "v0>0"): (16, 0, 16), ("|v0|>v_T", "v0<0"): (16, 0, 16)}
    assert out.scope.startswith("printed statement holds exactly in cells {|v0|<v_T, v0<0}, {|v0|<v_T, v0>0} ")
    assert out.scope.endswith("corrected statement holds in all 4 cells")
    assert "|v0|>v_T" in out.counterexample["cell"]


def test_the_artanh_form_would_hold_in_every_cell():
    # the tutorial's remark: written with artanh(v0/v_T) instead of the log of an absolute value, the
    # formula holds for every v0 under principal complex branches (tanh(u + i pi/2) = coth u), so the
    # same cells and residual call it verified -- the absolute value is what breaks eq. v0
    import sympy as sp

    from drag_claims import DOMAIN, SPLITS, solution_residual
    from drag_model import RATE, V_T, t, v0

    table = DOMAIN.evaluate(*SPLITS, printed=solution_residual(V_T * sp.tanh(RATE * t + sp.atanh(v0 / V_T))), dps=50)
    assert table.printed_holds_everywhere() and len(table.cells()) == 4
