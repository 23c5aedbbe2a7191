"""``symbt figures --out DIR`` writes the two PNGs (skipped without matplotlib/scipy)."""
import pytest

pytest.importorskip("matplotlib")
pytest.importorskip("scipy")

from symbt import cli  # noqa: E402
from symbt.report.figures import paper_example_data  # noqa: E402


def test_cli_figures_writes_two_pngs(tmp_path):
    out = tmp_path / "figs"
    assert cli.main(["figures", "--out", str(out), "--iterates", "300", "--window", "12"]) == 0
    for name in ("fig1.png", "fig2.png"):
        f = out / name
        assert f.exists() and f.stat().st_size > 10_000
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_flow_and_iterates_agree():
    d = paper_example_data(5.0, 50)
    assert d["deviation"] < 1e-8
    assert [round(v, 4) for v in d["c"][:3]] == [-0.005, -0.0485, -0.5121]
