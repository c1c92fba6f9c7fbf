"""One GP run of this study (README.md): ARS in the loop on a MuJoCo task stepped in Python, at
the smoke scale the README gives. Usage, from the repository root with the mujoco extra:

    .venv/bin/python docs/results/gymnasium/ars-in-the-loop-mujoco/run.py TASK SEED WORK

The run's directory is WORK/TASK/run-SEED; the last line printed is "TASK,SEED,SECONDS" (the
run's wall seconds; runs.csv's rows were written from the run's verdict and best.features)."""

import sys
import time
from pathlib import Path

import gpfd

SETTINGS = {
    "learner.params.updates": 6,
    "learner.params.n_delta": 4,
    "learner.params.n_top": 2,
    "learner.params.max_episode_steps": 100,
    "learner.params.normalise": True,
    "fitness.trials": 2,
    "fitness.max_trials": 0,
    "validation.candidates": 2,
    "validation.seeds": 4,
    "validation.confirm_seeds": 4,
    "validation.confirm_looks": 1,
    "validation.confirm_params": {"updates": 12},
}

task, seed, work = sys.argv[1], int(sys.argv[2]), Path(sys.argv[3])
start = time.monotonic()
run = gpfd.evolve(
    config="configs/user-env-ars.toml",
    env=task,
    seed=seed,
    population=6,
    generations=2,
    threads=1,
    set=SETTINGS,
    out=str(work / task / f"run-{seed}"),
    force=True,
    verbose=True,
)
print(f"{task},{seed},{time.monotonic() - start:.1f}")
