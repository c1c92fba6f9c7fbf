"""The scripts that summarise committed reproductions (scripts/discovery-cost,
scripts/winners-curse) reproduce the figures docs/experiments.md quotes from docs/results, and
refuse a directory without GP runs."""

import subprocess
import sys

import pytest


def run_script(repo, name, *args):
    return subprocess.run(
        [sys.executable, str(repo / "scripts" / name), *args],
        cwd=repo,
        capture_output=True,
        text=True,
    )


def table_rows(output):
    """{first cell: cells} of a Markdown table, header and rule left out."""
    rows = {}
    for line in output.splitlines()[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows[cells[0]] = cells
    return rows


def test_discovery_cost_gives_the_documented_shares(repo):
    done = run_script(repo, "discovery-cost", "docs/results/paper-runs")
    assert done.returncode == 0, done.stderr
    rows = table_rows(done.stdout)
    assert len(rows) == 5
    # docs/experiments.md, "Cost of the added evaluation": re-evaluation share, validation share,
    # added compute and early confirmations of the paper-scale runs.
    expected = {
        "cartpole": ("6.4%", "12%"),
        "acrobot": ("7.3%", "13%"),
        "swimmer3": ("8.6%", "17%"),
        "swimmer5": ("7.1%", "23%"),
        "tetris": ("10.2%", "20%"),
    }
    for name, (reevaluated, added) in expected.items():
        cells = rows[f"{name} (docs/results/paper-runs)"]
        assert cells[1] == "5"
        assert (cells[2], cells[4]) == (reevaluated, added), cells


def test_discovery_cost_sets_the_default_validation_against_the_gp(repo):
    # docs/experiments.md, "Cost of the added evaluation": gpfd's default validation (330 short
    # trials per run) against the short trials of the quick GP runs.
    done = run_script(repo, "discovery-cost", "docs/results/robust-quick/new")
    assert done.returncode == 0, done.stderr
    shares = {cells[0].split()[0]: cells[-1] for cells in table_rows(done.stdout).values()}
    assert shares == {
        "cartpole-quick": "30%",
        "acrobot-quick": "16%",
        "swimmer3-quick": "22%",
        "swimmer5-quick": "45%",
        "tetris-quick": "73%",
    }


def test_winners_curse_gives_the_documented_agreement(repo):
    done = run_script(repo, "winners-curse", "docs/results/paper-runs")
    assert done.returncode == 0, done.stderr
    rows = table_rows(done.stdout).values()
    within = {cells[0]: cells[-2] for cells in rows}
    assert within == {
        "cartpole": "5 of 5",
        "acrobot": "5 of 5",
        "swimmer3": "4 of 5",
        "swimmer5": "5 of 5",
        "tetris": "5 of 5",
    }
    pooled = {cells[0]: cells[-1] for cells in rows}
    assert pooled == {
        "cartpole": "+0.69",
        "acrobot": "-0.88",
        "swimmer3": "+0.28",
        "swimmer5": "+0.79",
        "tetris": "+1.75",
    }


def test_winners_curse_pools_the_runs_of_each_benchmark(repo):
    # docs/experiments.md, section 6: pooled over the 8 quick runs, only Acrobot's validated
    # means lie more than 2 standard errors above their re-measurement.
    done = run_script(repo, "winners-curse", "docs/results/robust-quick/new")
    assert done.returncode == 0, done.stderr
    pooled = {cells[0]: float(cells[-1]) for cells in table_rows(done.stdout).values()}
    assert {name for name, z in pooled.items() if abs(z) > 2} == {"acrobot-quick"}
    assert pooled["acrobot-quick"] == pytest.approx(2.68, abs=0.005)


@pytest.mark.parametrize("name", ["discovery-cost", "winners-curse"])
def test_a_directory_without_gp_runs_is_an_error(repo, tmp_path, name):
    done = run_script(repo, name, str(tmp_path))
    assert done.returncode != 0
    assert str(tmp_path) in done.stderr
    assert done.stdout == ""
