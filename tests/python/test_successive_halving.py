"""Successive halving (fitness.promote) on a user's Python environment: each longer rung is a job
of its own config on the worker processes, and the run is the one threads=1 gives, with the
rungs' fitness in its checkpoint."""

import json
from pathlib import Path
from typing import Any

import gpfd
from point_env import Point
from test_user_env_workers import SMALL, run_files

HALVING: dict[str, Any] = {
    **SMALL,
    "fitness.promote": 0.4,
    "fitness.rung_params.updates": 3,
    "validation.confirm_params.updates": 4,
}


def evolve(out: Path, threads: int, options: dict[str, Any]) -> dict[str, str]:
    gpfd.evolve(
        env=lambda: Point(steps=30),
        seed=2,
        population=6,
        generations=2,
        set=options,
        threads=threads,
        out=out,
        verbose=False,
    )
    return run_files(out)


def rungs(out: Path) -> list[int]:
    checkpoint = json.loads((out / "checkpoint.json").read_text())
    return sorted(individual.get("rung", 0) for individual in checkpoint["population"])


def test_the_rungs_run_on_the_workers_and_give_the_threads_1_run(tmp_path):
    one = evolve(tmp_path / "one", 1, HALVING)
    two = evolve(tmp_path / "two", 2, HALVING)
    assert one == two
    # 6 individuals: ceil(0.4 x 6) = 3 at the middle rung, ceil(0.4 x 3) = 2 of them at the last.
    assert rungs(tmp_path / "one") == [0, 0, 0, 1, 2, 2]
    plain = evolve(tmp_path / "plain", 2, SMALL)
    assert plain["generations.csv"] != one["generations.csv"]
    assert rungs(tmp_path / "plain") == [0] * 6
