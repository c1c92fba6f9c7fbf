"""One GP run of this study (README.md): ARS in the loop on a MuJoCo task stepped in Python, at
the smoke scale the README gives. Usage, from the repository root with the mujoco extra:

    .venv/bin/python docs/results/gymnasium/ars-in-the-loop-mujoco/run.py TASK SEED WORK

The run's directory is WORK/TASK/run-SEED (a new one: gpfd refuses one that holds files); the
last line printed is "TASK,SEED,SECONDS" (the run's wall seconds; runs.csv's rows were written
from the run's verdict and best.features)."""

import argparse
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

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("task", choices=("Swimmer-v5", "Hopper-v5"))
parser.add_argument("seed", type=int)
parser.add_argument("work", type=Path)
args = parser.parse_args()
if args.seed < 0:
    parser.error(f"seed {args.seed}: must be at least 0")
start = time.monotonic()
gpfd.evolve(
    config="user-env-ars",
    env=args.task,
    seed=args.seed,
    population=6,
    generations=2,
    threads=1,
    set=SETTINGS,
    out=str(args.work / args.task / f"run-{args.seed}"),
    verbose=True,
)
print(f"{args.task},{args.seed},{time.monotonic() - start:.1f}")
