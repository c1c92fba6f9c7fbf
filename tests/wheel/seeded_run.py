"""Writes what a small seeded run gives, so that CI can compare it byte for byte across Pythons
and dependency versions (scripts/test-pythons): the same seed must give the same run on each.

    python tests/wheel/seeded_run.py OUT_FILE

Three parts, each a real call with a small budget: a discovery run on gpfd's own cart-pole
(2 worker threads), one on Gymnasium's CartPole-v1 stepped in Python (NumPy and Gymnasium in the
loop; its vector form plays each generation as a lockstep group), and the fitness of three
feature sets played together on that vector form. Each part writes the returned features and
every fitness value, floats as repr() writes them (every bit)."""

import csv
import sys
import tempfile
from pathlib import Path

import small_budget

import gpfd

SMALL = small_budget.SMALL | {"learner.params.max_episode_steps": 60}
# The columns of generations.csv that depend on the machine, not on the seed.
TIMING = {"seconds"}


def run_lines(title: str, run: gpfd.Run) -> list[str]:
    """The run's returned features and its generations' statistics, timing left out."""
    assert run.best is not None, f"{title}: the run returned no features"
    lines = [f"## {title}", "best:", run.best.show()]
    with (run.dir / "generations.csv").open(newline="") as f:
        for row in csv.DictReader(f):
            lines.append(" ".join(f"{k}={v}" for k, v in row.items() if k not in TIMING))
    return lines


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    lines: list[str] = []
    with tempfile.TemporaryDirectory() as scratch:
        # (title, config, env, threads): gpfd's own cart-pole, then Gymnasium's stepped in Python.
        runs = [
            ("gpfd cartpole-quick, seed 7", "cartpole-quick", None, 2),
            ("Gymnasium CartPole-v1, seed 7", None, "CartPole-v1", 1),
        ]
        for i, (title, config, env, threads) in enumerate(runs):
            run = gpfd.evolve(
                config,
                env=env,
                seed=7,
                population=12,
                generations=3,
                threads=threads,
                set=SMALL,
                out=Path(scratch, f"run-{i}"),
                verbose=False,
            )
            lines += run_lines(title, run)
        assert run.best is not None  # the run stepped in Python: its features, fitness on the group
        sets = [run.best, run.best_of(0), run.best_of(1)]
        values = gpfd.fitness_of_each(sets, env="CartPole-v1", seed=11, set=SMALL)
        lines += ["## fitness_of_each on CartPole-v1, seed 11"] + [repr(v) for v in values]
    Path(sys.argv[1]).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
