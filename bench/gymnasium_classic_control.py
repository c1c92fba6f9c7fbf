#!/usr/bin/env python3
"""Gymnasium's Acrobot-v1 and CartPole-v1 beside gpfd's: agreement and steps per second.

Usage (Gymnasium's source is not part of gpfd; put its `gymnasium` package folder on PYTHONPATH,
with Debian's python3-numpy installed):
  PYTHONPATH=/path/to/Gymnasium /usr/bin/python3 bench/gymnasium_classic_control.py build/release/gpfd

1. Agreement: runs `gpfd simulate ENV --param actions=discrete --policy random`, then replays each
   step in Gymnasium from gpfd's state before it (so chaos cannot amplify differences) and prints
   the largest absolute difference of the state after the step, and whether the terminal flags agree.
2. Speed: steps per second of the bare Gymnasium environment (no wrappers) on random discrete
   actions, resetting at termination. Compare with bench_env_step's BM_AcrobotDiscrete and
   BM_CartPoleDiscrete items_per_second, measured on the same machine.
"""
import subprocess
import sys
import time

import numpy as np
from gymnasium.envs.classic_control.acrobot import AcrobotEnv
from gymnasium.envs.classic_control.cartpole import CartPoleEnv


def agreement(gpfd, name, make, steps=2000, seed=1):
    csv = subprocess.run([gpfd, "simulate", name, "--param", "actions=discrete", "--policy",
                          "random", "--steps", str(steps), "--seed", str(seed), "--no-stop"],
                         check=True, capture_output=True, text=True).stdout.splitlines()
    rows = [line.split(",") for line in csv[1:]]
    env = make()
    env.reset(seed=0)
    worst, flags = 0.0, 0
    for prev, row in zip(rows, rows[1:]):
        env.state = np.array([float(v) for v in prev[2:6]])
        _, _, terminated, _, _ = env.step(int(float(row[1])))
        ours = np.array([float(v) for v in row[2:6]])
        worst = max(worst, float(np.max(np.abs(np.asarray(env.state, dtype=float) - ours))))
        flags += int(terminated != (row[7] == "1"))
    print(f"{name}: {len(rows) - 1} steps replayed, max |state difference| = {worst:.3g}, "
          f"terminal flags differing: {flags}")


def speed(name, make, actions, steps=200000):
    env = make()
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    picks = rng.integers(0, actions, size=steps)
    start, cpu = time.perf_counter(), time.process_time()
    for a in picks:
        _, _, terminated, _, _ = env.step(int(a))
        if terminated:
            env.reset()
    elapsed, cpu = time.perf_counter() - start, time.process_time() - cpu
    print(f"{name}: Gymnasium {steps / elapsed:,.0f} steps/s wall, {steps / cpu:,.0f} steps/s CPU")


if __name__ == "__main__":
    import warnings
    warnings.filterwarnings("ignore")
    gpfd = sys.argv[1] if len(sys.argv) > 1 else "build/release/gpfd"
    agreement(gpfd, "acrobot", AcrobotEnv)
    agreement(gpfd, "cartpole", CartPoleEnv)
    speed("acrobot", AcrobotEnv, 3, 50000)
    speed("cartpole", CartPoleEnv, 2, 200000)
