#!/usr/bin/env python3
"""gpfd.evolve(executor=) on Dask across W worker hosts made of network namespaces
(scripts/multihost's Network): evaluations per second of a Python-stepped environment, for each W,
beside a model. Root only (namespaces).

Usage, with the package installed with the extra executors (scripts/test installs it in .venv):
  .venv/bin/python bench/dask_scaling.py [--workers 1,2,3] [--sleep-ms 1] [--population 24]
                                         [--generations 4] [--repeats 2]

Host 0 holds the Dask scheduler and the calling process; hosts 1..W one worker each (a nanny and
one single-threaded worker process); every message crosses the bridge. The environment is a point
pushed along a line whose step sleeps SLEEP ms, so that sleeping workers stand for cores on a
machine that has two (as docs/mpi.md's scaling does for gpfd evolve under MPI). The rate is the
evaluations of generations 1 to G-1 over their seconds (generations.csv); generation 0 also
ships the environment to the workers.

The model: a generation of E evaluations on W workers takes ceil(E / W) (t + o), where t is one
evaluation's time in this process (seconds per evaluation of a threads=1 run, the GP's own work
included) and o what Dask adds to each task, fitted to the runs on one worker alone (o = 1 / rate
on one worker - t); the rates on more workers are predictions. Results in docs/cluster.md.
"""

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import gpfd

ROOT = Path(__file__).resolve().parents[1]
SUBNET = "10.79.0"
SETTINGS = {
    "learner.params.updates": 2,
    "learner.params.episodes": 2,
    "fitness.trials": 2,
    "fitness.state_sample": 16,
    "validation.candidates": 2,
    "validation.seeds": 2,
    "validation.confirm_seeds": 2,
    "validation.confirm_looks": 1,
    "validation.confirm_params.updates": 1,
}

ENV = '''
import time
import gymnasium as gym
import numpy as np


class SleepyPoint(gym.Env):
    """A point pushed along a line (tests/python/point_env.py), 30 steps, each sleeping."""

    observation_space = gym.spaces.Box(-10.0, 10.0, (2,), np.float64)
    action_space = gym.spaces.Box(-1.0, 1.0, (1,), np.float32)

    def __init__(self, sleep: float):
        self.sleep, self.state, self.steps = sleep, np.zeros(2), 0

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.state, self.steps = self.np_random.uniform(-1.0, 1.0, 2), 0
        return self.state.copy(), {}

    def step(self, action):
        time.sleep(self.sleep)
        x, v = float(self.state[0]), float(self.state[1])
        v = 0.9 * v + 0.1 * float(np.clip(action[0], -1.0, 1.0))
        x = float(np.clip(x + v, -10.0, 10.0))
        self.state, self.steps = np.array([x, v]), self.steps + 1
        return self.state.copy(), -abs(x), False, self.steps >= 30, {}
'''

DRIVER = """
import json, sys
from distributed import Client
import gpfd
from sleepy_point import SleepyPoint

address, out, options = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
client = Client(address, timeout=60)
client.wait_for_workers(options.pop("workers"), timeout=60)
gpfd.evolve(env=SleepyPoint, **options, executor=client.get_executor(), out=out, verbose=False)
client.close()
"""


def rate(run: Path) -> tuple[float, list[int]]:
    """Evaluations per second over generations 1..G-1, and each generation's evaluations."""
    history = gpfd.load_run(run, as_frame=False).history
    evaluations = [int(e) for e in history["evaluations"]][1:]
    return sum(evaluations) / float(sum(history["seconds"][1:])), evaluations


def on_dask(workers: int, directory: Path, options: dict, multihost) -> Path:
    """One run on a scheduler and `workers` worker hosts; its results directory."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(directory), *sys.path])}
    address = f"tcp://{SUBNET}.1:8786"
    python = [sys.executable, "-m"]
    out = directory / f"w{workers}-{time.monotonic_ns()}"
    own = out.with_name(out.name + "-net")  # The network's files (launcher, /etc/hosts).
    own.mkdir()
    processes = []
    with (directory / "dask.log").open("a") as log, multihost.Network(
        workers + 1, SUBNET, own
    ) as net:
        try:
            scheduler = ["distributed.cli.dask_scheduler", "--host", f"{SUBNET}.1"]
            processes.append(
                subprocess.Popen(
                    [*net.enter(0), *python, *scheduler, "--port", "8786", "--no-dashboard"],
                    env=env,
                    stdout=log,
                    stderr=log,
                )
            )
            for host in range(1, workers + 1):
                worker = ["distributed.cli.dask_worker", address, "--nthreads", "1"]
                worker += ["--host", f"{SUBNET}.{host + 1}", "--no-dashboard"]
                processes.append(
                    subprocess.Popen(
                        [*net.enter(host), *python, *worker], env=env, stdout=log, stderr=log
                    )
                )
            driver = [sys.executable, str(directory / "driver.py"), address, str(out)]
            arguments = json.dumps({**options, "workers": workers})
            subprocess.run([*net.enter(0), *driver, arguments], env=env, check=True, timeout=900)
        finally:
            for process in processes:
                process.kill()
                process.wait()
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", default="1,2,3")
    parser.add_argument("--sleep-ms", type=float, default=1.0)
    parser.add_argument("--population", type=int, default=24)
    parser.add_argument("--generations", type=int, default=4)
    parser.add_argument("--repeats", type=int, default=2)
    args = parser.parse_args()
    sys.path.insert(0, str(ROOT / "tests" / "python"))
    from conftest import script_module

    multihost = script_module("multihost")
    why = multihost.usable()
    if why:
        print(f"dask_scaling: skipped: {why}", file=sys.stderr)
        return 77
    counts = [int(w) for w in args.workers.split(",")]
    options = {
        "env_kwargs": {"sleep": args.sleep_ms / 1000},
        "seed": 1,
        "population": args.population,
        "generations": args.generations,
        "set": SETTINGS,
    }
    with tempfile.TemporaryDirectory(prefix="dask-scaling-") as tmp:
        directory = Path(tmp)
        (directory / "sleepy_point.py").write_text(ENV)
        (directory / "driver.py").write_text(DRIVER)
        sys.path.insert(0, tmp)
        from sleepy_point import SleepyPoint

        here = gpfd.evolve(env=SleepyPoint, **options, threads=1, out=directory / "one",
                           verbose=False)  # fmt: skip
        one, _ = rate(here.dir)
        t = 1 / one
        rates: dict[int, list[float]] = {w: [] for w in counts}
        sizes: list[int] = []
        for _ in range(args.repeats):  # Interleaved: the machine's load varies.
            for w in counts:
                got, sizes = rate(on_dask(w, directory, options, multihost))
                rates[w].append(got)
    base = statistics.median(rates[counts[0]]) if counts[0] == 1 else None
    o = (1 / base - t) if base else 0.0
    print(f"one evaluation in this process (threads=1): t = {t * 1000:.1f} ms; "
          f"Dask's cost per task beyond it (1 worker): o = {o * 1000:.1f} ms; "
          f"evaluations per generation {sizes}")  # fmt: skip
    print("| workers | evaluations/s | median | model |")
    print("|---|---|---|---|")
    for w in counts:
        seconds = sum(math.ceil(e / w) * (t + o) for e in sizes)
        model = sum(sizes) / seconds
        runs = ", ".join(f"{r:.2f}" for r in rates[w])
        print(f"| {w} | {runs} | {statistics.median(rates[w]):.2f} | {model:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
