#!/usr/bin/env python3
"""A whole quick run from Python on a Gymnasium environment against the built-in one, side by
side in one process (docs/python.md, "Speed"): gpfd.evolve("cartpole-quick", threads=2) on the
built-in cart-pole and with env="CartPole-v1" (Gymnasium's, through its vector form), the two
alternating, wall seconds, median of the repetitions. Both results are printed, so that a run
that returns the original variables is seen.

Usage, with the package installed (scripts/test installs it in .venv):
  .venv/bin/python bench/python_whole_run.py [--repeats 3] [--env CartPole-v1] [--threads 2]
"""

import argparse
import os
import statistics
import tempfile
import time

import gpfd


def one_run(env, threads, out):
    start = time.perf_counter()
    run = gpfd.evolve("cartpole-quick", env=env, seed=1, threads=threads, out=out, verbose=False)
    seconds = time.perf_counter() - start
    features = run.best.show().count("\n") if run.best is not None else 0
    return seconds, features


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--env", default="CartPole-v1")
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    cases = {"cart-pole built in": None, args.env: args.env}
    times = {name: [] for name in cases}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(args.repeats):
            for name, env in cases.items():
                out = os.path.join(tmp, f"{r}-{len(times[name])}-{name.replace('/', '-')}")
                seconds, features = one_run(env, args.threads, out)
                times[name].append(seconds)
                print(f"  {name:<22} run {r + 1}: {seconds:7.1f} s wall, {features} features")
    base = statistics.median(times["cart-pole built in"])
    print(f"gpfd {gpfd.__version__}, threads={args.threads}, load average {os.getloadavg()[0]:.1f}")
    for name in cases:
        seconds = statistics.median(times[name])
        print(f"{name:<22} {seconds:8.1f} s  {seconds / base:6.1f}x")


if __name__ == "__main__":
    main()
