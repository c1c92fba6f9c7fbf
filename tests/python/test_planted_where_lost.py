"""scripts/planted-where-lost: where a planted task's answer is lost. It reproduces the committed
where-lost.csv of docs/results/planted/energy-selection, ranks a run's scored genomes in the
hall-of-fame order (mean minus the size penalty per node) with a test of values, and refuses a
directory without runs."""

import csv
import json
import shutil
import subprocess
import sys

COMMITTED = "docs/results/planted/energy-selection/crn-s1/Energy"


def run_script(repo, *args):
    return subprocess.run(
        [sys.executable, str(repo / "scripts" / "planted-where-lost"), *args],
        cwd=repo,
        capture_output=True,
        text=True,
    )


def test_reproduces_the_committed_counts(repo, tmp_path):
    done = run_script(repo, COMMITTED, "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    written = (tmp_path / "where-lost.csv").read_text()
    assert written == (repo / COMMITTED / "where-lost.csv").read_text()
    # The README's row: the answer among validation's candidates in 7 runs, returned in 4.
    assert "among validation's candidates in 7, returned in 4" in done.stdout


def test_ranks_the_scored_genomes_in_the_hall_of_fame_order(repo, tmp_path):
    # One run copied from the committed ones, with a made-up fitness cache: the energy third
    # once the size penalty (0.01 per node) has put it behind a set it led by its mean, and
    # its parts, as two features, last.
    run = tmp_path / "Energy" / "run-01"
    shutil.copytree(repo / COMMITTED / "run-01", run)
    energy = "(- (* (* x[1] x[1]) 0.5) (cos x[0]))"  # 8 nodes
    cache = [
        ["(+ (cos x[0]) (cos x[1]))", -5.0, 3],  # 5 nodes: -5.05 (R^2 0.97: a near miss)
        [energy, -5.02, 6],  # -5.10
        ["(+ (cos x[0]) (sqrt (cos x[1])))", -5.03, 3],  # 6 nodes: -5.09 (R^2 0.79)
        ["(- (cos x[0]) (* x[1] x[1]))", -5.1, 3],  # twice the x1 term: R^2 0.80, -5.16
        ["(* x[1] x[1]) ; (cos x[0])", -5.2, 3],  # the parts: carries, 5 nodes: -5.25
        ["(sin x[0])", float("nan"), 3],  # not finite: left out
    ]
    (run / "checkpoint.json").write_text(json.dumps({"cache": cache}))
    done = run_script(repo, str(run.parent))
    assert done.returncode == 0, done.stderr
    (row,) = csv.DictReader((run.parent / "where-lost.csv").open())
    assert row["evaluated"] == "5"
    assert row["carrying"] == "2"
    assert row["best_carrier_rank"] == "3"
    assert "scored in 1 of the 1 with a checkpoint" in done.stdout


def test_a_directory_without_runs_is_an_error(repo, tmp_path):
    done = run_script(repo, str(tmp_path))
    assert done.returncode != 0
    assert str(tmp_path) in done.stderr
