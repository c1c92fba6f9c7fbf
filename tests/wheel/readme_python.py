"""The README's Python lines, run against an installed gpfd (scripts/test-wheel runs this in each
venv that the wheel was installed into), each real call with a budget small enough for CI, then
a lockstep group: several feature sets evaluated together on Gymnasium's CartPole-v1 vector form.

    python tests/wheel/readme_python.py SCRATCH_DIR

Checks values, not only that nothing raised; exits non-zero on the first failure."""

import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
from small_budget import SMALL

import gpfd


def main() -> None:
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    scratch = Path(sys.argv[1])
    # run = gpfd.evolve("cartpole-quick", seed=1, threads=2)
    run = gpfd.evolve(
        "cartpole-quick",
        seed=1,
        threads=2,
        population=8,
        generations=2,
        set=SMALL,
        out=scratch / "cartpole-quick",
        verbose=False,
    )
    assert run.finished and run.generations == 2, (run.finished, run.generations)
    assert run.best is not None
    # print(run.best.show())
    shown = run.best.show()
    print(shown)
    assert shown.strip(), "run.best.show() is empty"
    # table = gpfd.assess(run.best, config="cartpole-quick")
    table = gpfd.assess(run.best, config="cartpole-quick", runs=2, budget=5, threads=2)
    # The original variables, run.best, then the no-learning reference.
    assert list(table["set"]) == ["original", "best", "no-learning"], table
    assert all(np.isfinite(v) for v in table["mean_final"]), table
    # env = gpfd.wrappers.FeatureObservation(gym.make("CartPole-v1"), run.best)
    env = gpfd.wrappers.FeatureObservation(gym.make("CartPole-v1"), run.best)
    obs, _ = env.reset(seed=1)
    assert obs.shape == env.observation_space.shape == (len(run.best),), obs.shape
    obs, *_ = env.step(env.action_space.sample())
    assert np.all(np.isfinite(obs)), obs
    env.close()
    # run = gpfd.evolve("cartpole-quick", env="MountainCarContinuous-v0", threads=2,
    #                   set={"learner.params.max_episode_steps": 999})
    run = gpfd.evolve(
        "cartpole-quick",
        env="MountainCarContinuous-v0",
        threads=2,
        population=4,
        generations=1,
        set=SMALL | {"learner.params.max_episode_steps": 50},
        out=scratch / "mountain-car",
        verbose=False,
    )
    assert run.finished and run.best is not None
    assert run.config["env"]["name"] == "MountainCarContinuous-v0", run.config["env"]

    # A lockstep group: three feature sets' evaluations in one vector environment (on every
    # CPython: Python runs on the thread's own stack, tests/python/test_thread_stack.py).
    raw = gpfd.FeatureSet.parse("x0\nx1\nx2\nx3\n", variables=["x0", "x1", "x2", "x3"])
    sets = [raw, gpfd.FeatureSet.parse("x2 + x3\nx3\n", variables=["x0", "x1", "x2", "x3"]), raw]
    values = gpfd.fitness_of_each(sets, env="CartPole-v1", seed=3, set=SMALL)
    assert len(values) == 3 and all(v > 0 for v in values), values
    print(f"readme_python: every line ran; lockstep group's fitness values {values}")


if __name__ == "__main__":
    main()
