"""scripts/zoo-check at a tiny scale (issue 52, point 2; docs/results/zoo/ is the real run):
sb3-contrib's ARS with the Zoo's CartPole-v1 settings on the raw observation and on one returned
set of docs/results/gymnasium/native-defaults, 2 seeds, 1,500 steps; the rows and the table are
well formed, and each row's mean, p and counts are those of the per-seed scores it was made from.
Runs where sb3-contrib is installed (the sb3 extra: scripts/sb3-example's .venv-sb3)."""

import csv
import statistics
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader
from pathlib import Path

import pytest

pytest.importorskip("sb3_contrib")

ROOT = Path(__file__).resolve().parents[2]
STUDY = ROOT / "docs" / "results" / "gymnasium" / "native-defaults"


def load_script():
    loader = SourceFileLoader("zoo_check", str(ROOT / "scripts" / "zoo-check"))
    spec = spec_from_loader("zoo_check", loader)
    assert spec is not None
    module = module_from_spec(spec)
    loader.exec_module(module)
    return module


zoo = load_script()


def test_the_paired_test_and_counts_by_hand():
    # 5 differences all positive: the exact two-sided p is 2 / 2^5.
    p, above, below = zoo.paired([2, 3, 4, 5, 6], [1, 1, 1, 1, 1])
    assert p == pytest.approx(2 / 32) and (above, below) == (5, 0)
    # 10 all negative: 2 / 2^10.
    p, above, below = zoo.paired([0] * 10, list(range(1, 11)))
    assert p == pytest.approx(2 / 1024) and (above, below) == (0, 10)
    # Differences -1, +2, +3, +4: W+ = 9 of 10, P(W+ >= 9) = 2/16, two-sided 0.25.
    p, above, below = zoo.paired([0, 2, 3, 4], [1, 0, 0, 0])
    assert p == pytest.approx(0.25) and (above, below) == (3, 1)
    # Identical scores: nothing to test.
    assert zoo.paired([5.0, 6.0], [5.0, 6.0]) == (1.0, 0, 0)
    with pytest.raises(ValueError):
        zoo.paired([1.0], [1.0, 2.0])


def test_the_original_variables_alone_are_the_raw_observation():

    identity = dict(zoo.committed_sets(STUDY, "MountainCar-v0"))[1]  # The original variables.
    assert zoo.observation_key(identity, False) == "raw"
    assert zoo.observation_key(identity, True) != "raw"
    discovered = dict(zoo.committed_sets(STUDY, "CartPole-v1"))[1]
    keys = {zoo.observation_key(discovered, w) for w in (False, True)}
    assert len(keys) == 2 and "raw" not in keys


def test_a_tiny_run_on_cartpole(tmp_path):
    tiny = ["--sets", str(STUDY), "--tasks", "CartPole-v1", "--seeds", "2", "--fraction", "0.0075"]
    tiny += ["--max-sets", "1", "--out", str(tmp_path)]
    rows = zoo.main(tiny)
    assert [r["configuration"] for r in rows] == ["raw", "set 1 alone", "set 1 beside"]
    with open(tmp_path / "scores.csv", newline="") as f:
        scores = list(csv.DictReader(f))
    assert len(scores) == 6 and {int(s["steps"]) for s in scores} == {1500}
    by = {(s["observation"], int(s["seed"])): float(s["final_return"]) for s in scores}
    assert all(1 <= v <= 500 for v in by.values())  # CartPole-v1's returns
    raw = [by[("raw", s)] for s in (1, 2)]
    for r in rows:
        values = [by[(r["observation"], s)] for s in (1, 2)]
        assert r["mean"] == pytest.approx(statistics.mean(values))
        assert r["sd"] == pytest.approx(statistics.stdev(values))
        assert r["seeds"] == 2 and r["steps"] == 1500 and r["zoo_steps"] == 200_000
        if r["configuration"] != "raw":
            p, above, below = zoo.paired(values, raw)
            assert (r["wilcoxon_p"], r["above_raw"], r["below_raw"]) == (p, above, below)
            assert 0 < r["wilcoxon_p"] <= 1
    with open(tmp_path / "summary.csv", newline="") as f:
        summary = list(csv.DictReader(f))
    assert [s["configuration"] for s in summary] == ["raw", "set 1 alone", "set 1 beside"]
    assert summary[0]["gp_seconds"] == "180.7"  # native-defaults' summary.csv, CartPole-v1
    table = (tmp_path / "README-table.md").read_text()
    assert "| CartPole-v1 | 1500 (200000) | 180.7 | 500 +- 0 (0.05M)" in table
    assert "| set 1 beside | set 1 + the observation |" in table
    assert "| set 1 alone | (x2 - 0.001465) * 9.975 ; " in table  # The set's first expression.
    # A rerun reuses the scores: no training, the same rows.
    again = zoo.main(tiny)
    assert again == rows
    assert len((tmp_path / "scores.csv").read_text().splitlines()) == 7


def test_fresh_seeds_start_at_the_first_seed(tmp_path):
    fresh = ["--sets", str(STUDY), "--tasks", "CartPole-v1", "--seeds", "2", "--first-seed", "3"]
    fresh += ["--fraction", "0.0075", "--max-sets", "1", "--alone-only", "--out", str(tmp_path)]
    rows = zoo.main(fresh)
    assert [r["configuration"] for r in rows] == ["raw", "set 1 alone"]
    with open(tmp_path / "scores.csv", newline="") as f:
        assert sorted({int(s["seed"]) for s in csv.DictReader(f)}) == [3, 4]
    assert "2 training seeds (3 to 4);" in (tmp_path / "README-table.md").read_text()
