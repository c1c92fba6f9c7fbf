#!/usr/bin/env python3
"""Discovery on an environment stepped in Python, with 1 and with 2 worker processes, side by side
in one run: wall time and CPU time (this process and its workers) of a whole `gpfd.evolve`.

Usage, with the package installed (scripts/test installs it in .venv):
  .venv/bin/python bench/python_threads.py [--mountain-car] [--config NAME]

The environments: a tiny one of the user's own (a point pushed along a line: 2 variables, one
continuous action, 50 steps) and, with --mountain-car, Gymnasium's MountainCarContinuous-v0.
Each run: population 10, generations 2, seed 1, the config given (default cartpole-quick, the
budgets of the first measurements; a user environment's own default is user-env), results in a
fresh temporary directory. The results of 1 and 2 workers must be identical, and the script
checks it. The load average before each run is printed beside it (other work on the machine
slows a run), and the CPU seconds of the calling process apart from the workers': on an idle
machine with 2 cores, the wall time of threads=2 is about that plus half the workers'.
"""

import argparse
import os
import resource
import sys
import tempfile
import time
from pathlib import Path

import gpfd

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
from point_env import Point  # noqa: E402  (the tests' tiny environment)


def live_children_seconds() -> float:
    """CPU seconds of this process' live children and of the children they reaped (gpfd's
    workers are reaped when a run ends, into RUSAGE_CHILDREN; a process of children of its own,
    such as a forkserver, is counted here while it lives)."""
    total = 0
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == os.getpid():  # fields[0] is the state, [1] the parent.
            total += sum(int(f) for f in fields[11:15])  # utime stime cutime cstime
    return total / os.sysconf("SC_CLK_TCK")


def cpu_seconds() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    reaped = children.ru_utime + children.ru_stime
    return own.ru_utime + own.ru_stime + reaped + live_children_seconds()


def own_seconds() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    return own.ru_utime + own.ru_stime


def measure(env, threads: int, config: str = "cartpole-quick") -> tuple[float, float, float, str]:
    """Wall seconds, CPU seconds (with the workers), CPU seconds of this process, best features."""
    with tempfile.TemporaryDirectory() as tmp:
        wall, cpu, own = time.perf_counter(), cpu_seconds(), own_seconds()
        run = gpfd.evolve(
            config,
            env=env,
            seed=1,
            population=10,
            generations=2,
            threads=threads,
            out=Path(tmp) / "run",
        )
        wall = time.perf_counter() - wall
        time.sleep(1.0)  # Any child's own children are reaped meanwhile.
        cpu, own = cpu_seconds() - cpu, own_seconds() - own
        return wall, cpu, own, run.best.to_text()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mountain-car", action="store_true")
    parser.add_argument("--config", default="cartpole-quick")
    args = parser.parse_args()
    envs = [("tiny environment (Point)", Point)]
    if args.mountain_car:
        envs.append(("MountainCarContinuous-v0", "MountainCarContinuous-v0"))
    print(
        "| environment | threads | wall s | CPU s (with workers) | CPU s of the calling process "
        "| load average before |"
    )
    print("|---|---|---|---|---|---|")
    for name, env in envs:
        results = {}
        for threads in (1, 2):
            load = os.getloadavg()[0]
            wall, cpu, own, best = measure(env, threads, args.config)
            results[threads] = best
            print(
                f"| {name} | {threads} | {wall:.1f} | {cpu:.1f} | {own:.1f} | {load:.2f} |",
                flush=True,
            )
        assert results[1] == results[2], f"{name}: 1 and 2 workers returned different features"


if __name__ == "__main__":
    main()
