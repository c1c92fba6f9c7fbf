#!/usr/bin/env python3
"""An environment without a vector form: one fitness evaluation stepped one environment at a time
(gpfd's per-environment path, what gpfd does) against Gymnasium's SyncVectorEnv and
AsyncVectorEnv over the same environment as its vector form (gpfd.VectorFactory), side by side in
one run (docs/python.md, "Vector forms").

Usage, with the package installed (scripts/test installs it in .venv):
  .venv/bin/python bench/python_no_vector.py [--evaluations K]

Environments: the tiny one of bench/python_threads.py (a point pushed along a line, 50 steps) and
Gymnasium's CartPole-v1 through gymnasium.make. cartpole-quick's learner, 3 trials x 11 batches of
10 episodes (30 lanes), the original variables. The cases alternate within each repetition; a
figure is the median of 3 of the mean over K evaluations: CPU seconds of this process and its
children (AsyncVectorEnv's workers), and wall seconds.
"""

import argparse
import functools
import resource
import statistics
import time
import warnings

import gymnasium as gym
from python_threads import Point

import gpfd

REPEATS = 3


def cpu_seconds() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def sync_vector(num_envs, make):
    return gym.vector.SyncVectorEnv([make] * num_envs)


def async_vector(num_envs, make):
    return gym.vector.AsyncVectorEnv([make] * num_envs, context="forkserver")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--evaluations", type=int, default=3)
    args = parser.parse_args()
    warnings.filterwarnings("ignore")
    settings = {"learner.params.updates": 10, "learner.params.episodes": 10, "fitness.trials": 3}
    print(f"gpfd {gpfd.__version__}, Gymnasium {gym.__version__}; median of {REPEATS}")
    print(f"{'environment':<12} {'how':<28} {'CPU s / eval':>13} {'wall s / eval':>14}")
    for label, make in [
        ("Point", Point),
        ("CartPole-v1", functools.partial(gym.make, "CartPole-v1")),
    ]:
        dim = make().observation_space.shape[0]
        names = [f"x{i}" for i in range(dim)]
        raw = gpfd.FeatureSet.parse("".join(n + "\n" for n in names), variables=names)
        cases = {
            "one environment at a time": make,
            "SyncVectorEnv (VectorFactory)": gpfd.VectorFactory(
                functools.partial(sync_vector, make=make), per_lane_seeds=True, make=make
            ),
            "AsyncVectorEnv (VectorFactory)": gpfd.VectorFactory(
                functools.partial(async_vector, make=make), per_lane_seeds=True, make=make
            ),
        }
        results = {}
        for case, env in cases.items():  # The same seeds: the same fitness, checked.
            results[case] = gpfd.fitness(raw, env=env, set=settings, seed=1)
        assert len(set(results.values())) == 1, results
        times = {case: [] for case in cases}
        for _ in range(REPEATS):
            for case, env in cases.items():
                cpu, wall = cpu_seconds(), time.perf_counter()
                for seed in range(2, 2 + args.evaluations):
                    gpfd.fitness(raw, env=env, set=settings, seed=seed)
                times[case].append(
                    (
                        (cpu_seconds() - cpu) / args.evaluations,
                        (time.perf_counter() - wall) / args.evaluations,
                    )
                )
        for case in cases:
            cpu = statistics.median(t[0] for t in times[case])
            wall = statistics.median(t[1] for t in times[case])
            print(f"{label:<12} {case:<28} {cpu:>13.3f} {wall:>14.3f}")


if __name__ == "__main__":
    main()
