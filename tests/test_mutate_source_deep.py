"""``symbt mutate --source --deep``: the deep claims and variants reach the line map and every mutant's run."""
from __future__ import annotations

from symbt.engine import mutate_source, source_tree


def test_deep_is_passed_to_verify(monkeypatch, tmp_path):
    seen = []

    def fake(argv, cwd, timeout, env):
        seen.append(list(argv))
        return source_tree.Run(0, "", "", 0.0)
    monkeypatch.setattr(source_tree, "run_command", fake)
    source_tree.run_verify(tmp_path, ["paths.qd.n2"], 10.0, deep=True)
    source_tree.run_verify(tmp_path, ["paths.qd.n2"], 10.0)
    assert "--deep" in seen[0] and "--deep" not in seen[1]


def test_deep_has_its_own_cached_map(tmp_path):
    (tmp_path / "a.py").write_text("x = 1\n")
    assert mutate_source._digest(tmp_path, [], [], True) != mutate_source._digest(tmp_path, [], [])


def test_the_flag_is_parsed():
    assert mutate_source.build_parser().parse_args(["--source", "numeric", "--deep"]).deep
    assert not mutate_source.build_parser().parse_args(["--source", "numeric"]).deep

