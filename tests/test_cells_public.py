"""Cells as public data: Domain, splits, the seeded sampler, evaluate() and judge(CellTable).

Cell truth is recomputed here in plain Python (cmath/float at the sampled points, the cell of a
point from its coordinates) and compared with the table and the generated scope.
"""
import cmath
import math

import mpmath as mp
import pytest

import symbt
from symbt import (
    CellTable,
    Domain,
    UnfilledCellError,
    choice,
    claim,
    complex_box,
    integers,
    judge,
    log_uniform,
    regime,
    sign,
    uniform,
)
from symbt.claims._common import judge_cells as zullo_judge_cells
from symbt.proof.cells import DEEP_PER_CELL, DEFAULT_PER_CELL

XY = Domain({"x": (-2, 2), "y": (-2, 2)}, seed=11)
SPLITS = (sign("x"), sign("y"))


def product_rule(x, y):
    """sqrt(x) sqrt(y) = sqrt(x y) with principal square roots: false exactly when x < 0 and y < 0."""
    return mp.sqrt(x) * mp.sqrt(y), mp.sqrt(x * y)


def plain_holds(x: float, y: float) -> bool:
    lhs, rhs = cmath.sqrt(x) * cmath.sqrt(y), cmath.sqrt(x * y)
    return abs(lhs - rhs) <= 1e-12 * max(1.0, abs(lhs), abs(rhs))


def plain_cell(x: float, y: float) -> str:
    return "{" + ("x<0" if x < 0 else "x>0") + ", " + ("y<0" if y < 0 else "y>0") + "}"


def test_a_statement_false_in_exactly_one_cell_gets_that_cell_in_its_scope():
    table = XY.evaluate(*SPLITS, printed=product_rule, dps=30)
    # independent truth: the same points, classified and evaluated in plain complex floats
    truth: dict[str, list[bool]] = {}
    for _cell, point in XY.sample(*SPLITS):
        x, y = float(point["x"]), float(point["y"])
        truth.setdefault(plain_cell(x, y), []).append(plain_holds(x, y))
    assert set(truth) == {"{x<0, y<0}", "{x<0, y>0}", "{x>0, y<0}", "{x>0, y>0}"}
    holds = [c for c, v in truth.items() if all(v)]
    fails = [c for c, v in truth.items() if not any(v)]
    assert fails == ["{x<0, y<0}"] and len(holds) == 3            # the test's own premise
    assert table.scope() == ("printed statement holds exactly in cells " + ", ".join(holds)
                             + " and fails in " + ", ".join(fails))
    out = judge(table, printed="sqrt(x) sqrt(y) = sqrt(xy)")
    assert (out.status, out.evidence, out.scope) == ("failed", "sampled", table.scope())
    assert out.counterexample["cell"] == "{x<0, y<0}"
    x, y = float(out.counterexample["x"]), float(out.counterexample["y"])
    assert x < 0 and y < 0 and not plain_holds(x, y)
    assert [c["printed_holds"] for c in out.cells] == [0, 16, 16, 16]


def test_judge_with_a_corrected_statement_gives_an_erratum():
    table = XY.evaluate(*SPLITS, printed=product_rule,
                        corrected=lambda x, y: ((mp.sqrt(x) * mp.sqrt(y)) ** 2, x * y))
    out = judge(table, printed="sqrt(x) sqrt(y) = sqrt(xy)", corrected="(sqrt(x) sqrt(y))^2 = xy")
    assert out.status == "erratum" and out.corrected == "(sqrt(x) sqrt(y))^2 = xy"
    assert out.scope.endswith("; corrected statement holds in all 4 cells")
    assert out.method.startswith("printed: numeric: mpmath 30 digits at 16 seeded points in each of 4 cells")


def test_judge_of_a_table_is_zulloes_judge_cells():
    # the claim modules' helper and the public judge give the same outcome on the same table
    table = XY.evaluate(*SPLITS, printed=product_rule, corrected=lambda x, y: 0)
    ours = judge(table, printed="p", corrected="c", detail="d").to_dict()
    theirs = zullo_judge_cells(table, method=table.method, printed="p", corrected="c", dps=30, detail="d").to_dict()
    assert ours == theirs


def test_judge_rejects_a_corrected_check_with_a_table():
    table = XY.evaluate(sign("x"), printed=lambda x: 0, per_cell=2)
    with pytest.raises(TypeError, match="corrected"):
        judge(table, printed="p", corrected_check=lambda: None)


def test_every_cell_is_filled_and_every_point_lies_in_its_cell():
    dom = Domain({"x": (-1, 1), "e": (-3, 1)}, where=lambda x: abs(x) > 0.05, seed=3)
    splits = (sign("x"), choice("branch", (1, -1)),
              regime("motion", lambda e: "bound" if e < 0 else "free", ("bound", "free")))
    pts = dom.sample(*splits)
    cells = dom.cells(*splits)
    assert len(cells) == 8
    for cell in cells:
        mine = [p for c, p in pts if c == cell]
        assert len(mine) == DEFAULT_PER_CELL
        for p in mine:
            x, e = float(p["x"]), float(p["e"])
            assert abs(x) > 0.05
            assert (x < 0) == (cell["sign(x)"] == "x<0")
            assert p["branch"] == cell["branch"]
            assert (e < 0) == (cell["motion"] == "bound")


def test_seeds_reproduce_the_points_and_deep_extends_them():
    a = XY.sample(*SPLITS)
    assert a == XY.sample(*SPLITS)
    assert a == Domain({"x": (-2, 2), "y": (-2, 2)}, seed=11).sample(*SPLITS)
    assert a != Domain({"x": (-2, 2), "y": (-2, 2)}, seed=12).sample(*SPLITS)
    deep = XY.sample(*SPLITS, deep=True)
    assert len(deep) == 4 * DEEP_PER_CELL
    for cell in XY.cells(*SPLITS):
        assert [p for c, p in deep if c == cell][:DEFAULT_PER_CELL] == [p for c, p in a if c == cell]


def test_deep_gives_64_per_cell_also_through_a_claim():
    @claim("demo.cells", equation="demo", scene="demo", statement="sqrt(x)sqrt(y) = sqrt(xy)", register=False)
    def demo(deep=False):
        return judge(XY.evaluate(*SPLITS, printed=product_rule, deep=deep), printed="sqrt(x)sqrt(y) = sqrt(xy)")

    assert [c["n"] for c in demo.run().cells] == [DEFAULT_PER_CELL] * 4
    deep = demo.run(deep=True)
    assert [c["n"] for c in deep.cells] == [DEEP_PER_CELL] * 4 == [64] * 4
    assert deep.status == "failed" and deep.counterexample["cell"] == "{x<0, y<0}"


def test_a_predicate_that_rejects_everything_raises_the_typed_error():
    dom = Domain({"x": (0, 1)}, where=lambda x: False, draws_per_point=5)
    with pytest.raises(UnfilledCellError, match=r"cannot fill cell \{\}: 0 of 16 points after 80 draws "
                                                r"\(80 outside the domain"):
        dom.evaluate(printed=lambda x: 0)


def test_an_unreachable_cell_is_named():
    dom = Domain({"x": (0, 1)})
    with pytest.raises(UnfilledCellError) as err:
        dom.sample(sign("x - 5"), per_cell=2)
    assert err.value.cell == {"sign(x - 5)": "x>5"} and err.value.filled == 0
    assert isinstance(err.value, ValueError) and "{x>5}" in str(err.value)


def test_ranges_draw_what_they_say():
    dom = Domain({"n": range(2, 5), "k": integers(-1, 1), "s": log_uniform(1e-3, 1e3), "u": uniform(3, 4),
                  "z": complex_box(re=(-1, 0), im=(2, 3))}, seed=5)
    pts = [p for _, p in dom.sample(per_cell=64)]
    assert {p["n"] for p in pts} == {2, 3, 4} and {p["k"] for p in pts} == {-1, 0, 1}
    assert all(type(p["n"]) is int for p in pts)
    logs = [math.log10(p["s"]) for p in pts]
    assert -3 <= min(logs) < -1 and 1 < max(logs) <= 3          # spread over decades
    assert all(3 <= p["u"] <= 4 for p in pts)
    assert all(-1 <= p["z"].real <= 0 and 2 <= p["z"].imag <= 3 for p in pts)
    assert Domain({"z": (-1 - 1j, 1j)}).variables["z"].kind == "complex_box"


def test_the_working_precision_is_the_stated_one():
    seen = []
    Domain({"x": (0, 1)}).evaluate(printed=lambda x: seen.append(mp.mp.dps) or 0, dps=45, per_cell=2)
    assert seen == [45, 45]
    def off_by_1e25(x):
        return x / 3 + mp.mpf(10) ** -25, x / 3

    at30 = Domain({"x": (1, 2)}).evaluate(printed=off_by_1e25, dps=30, per_cell=2)
    at45 = Domain({"x": (1, 2)}).evaluate(printed=off_by_1e25, dps=45, per_cell=2)
    assert (at30.tol, at45.tol) == (1e-20, 1e-30)
    assert at30.printed_holds_everywhere() and not at45.printed_holds_everywhere()
    assert at45.cells()[0]["worst_residual"] == pytest.approx(1e-25, rel=1e-9)   # |x/3| < 1: absolute


@pytest.mark.parametrize("make, error", [
    (lambda: Domain({}), TypeError),
    (lambda: Domain({"x": "wide"}), TypeError),
    (lambda: uniform(2, 1), ValueError),
    (lambda: log_uniform(0, 1), ValueError),
    (lambda: integers(1.5, 3), ValueError),
    (lambda: sign(lambda x: x), ValueError),                       # a function needs a name
    (lambda: sign("x +"), ValueError),
    (lambda: choice("b", ()), ValueError),
    (lambda: choice("b", (1, 1)), ValueError),
    (lambda: XY.sample(sign("x"), sign("x")), ValueError),        # duplicate split
    (lambda: XY.sample(choice("x", (1,))), ValueError),           # a choice shadowing a variable
    (lambda: XY.sample(sign("z")), ValueError),                   # not a variable
    (lambda: XY.sample(per_cell=0), ValueError),
    (lambda: XY.sample("x"), TypeError),                          # a split is sign/choice/regime, not a name
    (lambda: XY.evaluate(printed=lambda x, w: 0), ValueError),    # asks for a variable the points lack
    (lambda: XY.evaluate(printed=lambda x: (1, 2, 3), per_cell=1), TypeError),
    (lambda: XY.evaluate(printed=lambda x: "zero", per_cell=1), TypeError),
    (lambda: XY.evaluate(regime("r", lambda x: "c", ("a", "b")), printed=lambda x: 0, per_cell=1), ValueError),
    (lambda: XY.evaluate(printed=lambda x: 0, dps=5), ValueError),
])
def test_bad_input_raises_a_typed_error(make, error):
    with pytest.raises(error):
        make()


def test_a_nan_residual_never_holds():
    table = Domain({"x": (0, 1)}).evaluate(printed=lambda x: mp.nan, per_cell=2)
    assert not table.printed_holds_everywhere()


def test_the_public_names_load_from_symbt():
    for name in ("Domain", "sign", "choice", "regime", "uniform", "log_uniform", "integers", "complex_box",
                 "UnfilledCellError", "CellTable", "judge", "solves_ode", "ode_residual"):
        assert name in dir(symbt) and getattr(symbt, name) is not None
    assert isinstance(XY.evaluate(printed=lambda x: 0, per_cell=1), CellTable)
