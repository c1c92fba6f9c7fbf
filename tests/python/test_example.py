"""examples/python/quickstart.py end to end (CI runs it here), on a small budget: its printed
summaries agree with its per-seed figures, and what it shows holds: on the discovered features its
REINFORCE learns on every seed, keeps what it learned (before, it reached up to 250 and then fell
to 9 on every seed), and ends above the raw observation."""

import re
import subprocess
import sys

import numpy as np
import pytest

SEED = re.compile(r"^  (.+), seed (\d+): first ([\d.]+) best ([\d.]+) last ([\d.]+)$", re.M)
SUMMARY = re.compile(
    r"^([^ ].+): last 20 episodes ([\d.]+) \+- ([\d.]+) \(mean \+- sd over seeds\); above its "
    r"first 20 on (\d+) of (\d+) seeds, within 10% of its best 20 on (\d+) of (\d+)$",
    re.M,
)
DIFFERENCE = re.compile(
    r"^discovered features minus (.+): ([-+][\d.]+) \+- ([\d.]+); higher on (\d+) of (\d+) seeds$",
    re.M,
)


def per_seed(printed: str) -> dict[str, np.ndarray]:
    """{observation: rows (first, best, last) by seed}."""
    rows: dict[str, list[tuple[float, ...]]] = {}
    for name, seed, *figures in SEED.findall(printed):
        assert int(seed) == len(rows.setdefault(name, []))
        rows[name].append(tuple(map(float, figures)))
    return {name: np.array(r) for name, r in rows.items()}


def check_summaries(printed: str, seeds: dict[str, np.ndarray]) -> None:
    """Each summary line is what the per-seed lines give (to their printed precision)."""
    summaries = SUMMARY.findall(printed)
    assert [s[0] for s in summaries] == list(seeds)
    for name, mean, sd, learned, n, kept, n2 in summaries:
        first, best, last = seeds[name].T
        assert int(n) == int(n2) == len(last)
        assert float(mean) == pytest.approx(last.mean(), abs=0.1)
        assert float(sd) == pytest.approx(last.std(ddof=1), abs=0.15)
        assert int(learned) == np.sum(last > first)
        assert int(kept) == np.sum(last >= 0.9 * best)
    differences = DIFFERENCE.findall(printed)
    assert [d[0] for d in differences] == ["raw observation", "raw, standardised"]
    for other, mean, sd, higher, n in differences:
        d = seeds["discovered features"][:, 2] - seeds[other][:, 2]
        assert float(mean) == pytest.approx(d.mean(), abs=0.1)
        assert float(sd) == pytest.approx(d.std(ddof=1), abs=0.15)
        assert (int(higher), int(n)) == (np.sum(d > 0), len(d))


def test_quickstart_learns_on_the_discovered_features(repo, tmp_path):
    result = subprocess.run(
        [sys.executable, str(repo / "examples/python/quickstart.py"), "--seeds", "2"]
        + ["--episodes", "100"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    printed = result.stdout
    assert "gen   5" in printed and "wrapped CartPole-v1" in printed
    assert (tmp_path / "results/cartpole-quick/best.features").is_file()
    seeds = per_seed(printed)
    assert list(seeds) == ["discovered features", "raw observation", "raw, standardised"]
    assert all(len(rows) == 2 for rows in seeds.values())
    check_summaries(printed, seeds)
    first, best, last = seeds["discovered features"].T
    assert np.all(last > first), printed  # It learns,
    assert np.all(last >= 0.5 * best), printed  # keeps it,
    assert np.all(last > seeds["raw observation"][:, 2]), printed  # and beats the raw observation.
