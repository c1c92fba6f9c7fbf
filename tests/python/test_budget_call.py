"""A time budget is the whole call (issue 53, point 2): a budget too short is refused within 10%
of it, naming one that works when followed; the call given that budget ends within it + 10%,
having said each stage as it began. On user-env's CartPole-v1 (its twin, stepped in C++), whose
learner choice alone takes seconds."""

import json
import re
import subprocess
import time

import pytest


def evolve(cli, out, budget):
    """5 runs of user-env on CartPole-v1 in `budget` seconds; the process and its wall time."""
    start = time.monotonic()
    done = subprocess.run(
        [
            cli,
            "evolve",
            "user-env",
            "--env",
            "CartPole-v1",
            "--seed",
            "2",
            "--threads",
            "2",
            "--time-budget",
            str(budget),
            "--runs",
            "5",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    return done, time.monotonic() - start


@pytest.mark.long
def test_a_refusal_names_a_budget_that_holds(cli, tmp_path):
    refused, wall = evolve(cli, tmp_path / "short", 1)  # 5 of the smallest runs do not fit.
    assert refused.returncode == 2, refused.stdout + refused.stderr
    assert wall <= 1.1 * 1 + 1.0  # The process's start and exit beside the call.
    assert "choosing the learner's settings" in refused.stdout  # Said as it began.
    found = re.search(r"give at least (\d+) s", refused.stderr)
    assert found, refused.stderr
    budget = int(found.group(1))
    done, wall = evolve(cli, tmp_path / "run", budget)
    assert done.returncode == 0, done.stdout + done.stderr
    assert wall <= 1.1 * budget + 1.0, (wall, budget)
    lines = done.stdout.splitlines()
    assert lines[0].startswith("gpfd evolve: choosing the learner's settings")
    assert any(line.startswith("gpfd evolve: measuring") for line in lines)
    run = json.loads((tmp_path / "run/run-01/run.json").read_text())
    assert run["sizes"]["from_clock"] is True
    assert (tmp_path / "run/runs.csv").read_text().count("\n") == 6  # A header and 5 runs.
