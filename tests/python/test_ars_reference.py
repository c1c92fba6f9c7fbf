"""gpfd's ARS against sb3-contrib's at a small scale (issue 52, point 1; scripts/ars-reference is
the full-scale benchmark): on CartPole-v1, the same steps, seeds and hyperparameters, gpfd's mean
greedy return lies within the spread of sb3-contrib's. Runs where sb3-contrib is installed
(the sb3 extra: scripts/sb3-example's .venv-sb3)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sb3_contrib")

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "ars-reference"


def test_gpfds_ars_is_within_the_spread_of_sb3_contribs(tmp_path):
    rows = tmp_path / "rows.json"
    env = dict(os.environ)
    subprocess.run(
        [
            sys.executable,
            str(SCRIPT),
            "--tasks",
            "CartPole-v1",
            "--seeds",
            "3",
            "--steps",
            "20000",
            "--json",
            str(rows),
        ],
        check=True,
        env=env,
        capture_output=True,
    )
    (row,) = json.loads(rows.read_text())
    assert len(row["gpfd"]) == 3 and len(row["sb3_contrib"]) == 3
    assert row["within"], row
