#!/usr/bin/env python3
"""gpfd's twins of Gymnasium's classic control beside their peers, side by side in one run
(docs/performance.md, "The twins of Gymnasium's tasks"):

1. steps per CPU second of this process (one core: every peer runs on one thread), for one
   environment and a batch of 64: the twin (``gymnasium.make("gpfd/ID")``, ``make_vec``),
   Gymnasium's own (``gymnasium.make(ID)``; its native vector form where it has one, else
   ``SyncVectorEnv``) and EnvPool's (``envpool.make_gymnasium(ID, num_envs=N, batch_size=N,
   num_threads=1)``, where envpool is installed: ``pip install envpool``);
2. one fitness evaluation of a group of 16 feature sets (``gpfd.fitness_of_each``, user-env's
   trial, its learner's updates cut to --updates on both sides) on the twin and with
   ``native=False``, wall seconds and CPU seconds of the process (every thread's: the cost,
   whatever the load and the threads);
3. a whole ``gpfd.evolve("cartpole-quick", ...)`` run on gpfd's own cart-pole (as configured,
   and set to CartPole-v1's task: discrete actions, 500 steps), on ``env="CartPole-v1"`` (the
   twin) and with ``native=False``, wall seconds, and the GP generations' work (their evaluations
   times the mean return, proportional to the steps played) and seconds per unit of it: runs
   that learn differently play different numbers of steps.

The peers alternate within each repetition; each figure is the median over the repetitions.

Usage, with the package installed (scripts/test installs it in .venv):
  .venv/bin/python bench/twins.py [--repeats 3] [--steps 20000] [--updates 3] [--sections 1,2,3]
      [--no-python-run]
"""

import argparse
import contextlib
import csv
import io
import os
import statistics
import tempfile
import time

import gymnasium as gym
import numpy as np

import gpfd

TASKS = ["CartPole-v1", "Acrobot-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0"]

try:
    import envpool
except ImportError:
    envpool = None


def single_rate(env, actions):
    """Steps per CPU second of one environment, reset when an episode ends."""
    env.reset(seed=0)
    start = time.process_time()
    for a in actions:
        _, _, terminated, truncated, _ = env.step(a)
        if terminated or truncated:
            env.reset()
    return len(actions) / (time.process_time() - start)


def batch_rate(env, actions, n):
    """Instance-steps per CPU second of a vector environment (its own autoreset)."""
    env.reset(seed=0)
    start = time.process_time()
    for a in actions:
        env.step(a)
    return len(actions) * n / (time.process_time() - start)


def for_envpool(actions):
    """EnvPool's action dtypes: int32 choices, float32 forces."""
    if np.issubdtype(actions.dtype, np.integer):
        return actions.astype(np.int32)
    return actions.astype(np.float32)


def draw_actions(space, count, seed):
    space.seed(seed)
    return [space.sample() for _ in range(count)]


def steps_table(steps, repeats):
    print(
        f"1. steps per CPU second (one core), {steps} steps (single) or {steps // 16} vector steps"
    )
    header = "| task | N | gpfd twin | Gymnasium | EnvPool | twin / Gymnasium | twin / EnvPool |"
    print(header)
    print("|---|---|---|---|---|---|---|")
    for task in TASKS:
        for n in (1, 64):
            makers = {}
            if n == 1:
                makers["twin"] = lambda t=task: gym.make(f"gpfd/{t}")
                makers["gymnasium"] = lambda t=task: gym.make(t)
                if envpool is not None:
                    makers["envpool"] = lambda t=task: envpool.make_gymnasium(
                        t, num_envs=1, batch_size=1, num_threads=1
                    )
            else:
                makers["twin"] = lambda t=task: gym.make_vec(f"gpfd/{t}", n)
                mode = "vector_entry_point" if gym.spec(task).vector_entry_point else "sync"
                makers["gymnasium"] = lambda t=task, m=mode: gym.make_vec(
                    t, n, vectorization_mode=m
                )
                if envpool is not None:
                    makers["envpool"] = lambda t=task: envpool.make_gymnasium(
                        t, num_envs=n, batch_size=n, num_threads=1
                    )
            rates = {name: [] for name in makers}
            single = gym.make(task).action_space
            batched = gym.vector.utils.batch_space(single, n)
            for r in range(repeats):
                for name, make in makers.items():
                    env = make()
                    if n == 1:
                        actions = draw_actions(single, steps, r)
                        if name == "envpool":  # EnvPool takes a batch of one.
                            actions = [for_envpool(np.asarray([a])) for a in actions]
                            rates[name].append(batch_rate(env, actions, 1))
                        else:
                            rates[name].append(single_rate(env, actions))
                    else:
                        actions = draw_actions(batched, steps // 16, r)
                        if name == "envpool":
                            actions = [for_envpool(a) for a in actions]
                        rates[name].append(batch_rate(env, actions, n))
                    env.close()
            m = {name: statistics.median(v) for name, v in rates.items()}
            pool = m.get("envpool")
            print(
                f"| {task} | {n} | {m['twin']:,.0f} | {m['gymnasium']:,.0f} | "
                + (f"{pool:,.0f}" if pool else "-")
                + f" | {m['twin'] / m['gymnasium']:.1f}x | "
                + (f"{m['twin'] / pool:.1f}x |" if pool else "- |")
            )


def sixteen_sets(dim):
    """16 feature sets over x0 .. x{dim-1}: one variable, and a product of two others."""
    sets = []
    for k in range(16):
        a, b, c = k % dim, (k + 1) % dim, (k + 2) % dim
        text = f"# variables: {' '.join(f'x{i}' for i in range(dim))}\nx{a}\nx{b} * x{c}\n"
        sets.append(gpfd.FeatureSet.parse(text))
    return sets


def fitness_table(repeats, updates):
    print(
        f"\n2. a fitness evaluation of 16 sets (user-env's trial with updates = {updates}), "
        "wall seconds and CPU seconds of this process (all its threads)"
    )
    print("| task | twin wall | native=False wall | ratio | twin CPU | native=False CPU | ratio |")
    print("|---|---|---|---|---|---|---|")
    settings = {"learner.params.updates": updates, "learner.params.step": "rprop"}
    for task in TASKS:
        dim = gym.make(task).observation_space.shape[0]
        sets = sixteen_sets(dim)
        wall = {True: [], False: []}
        cpu = {True: [], False: []}
        for _ in range(repeats):
            for native in (True, False):
                start, start_cpu = time.perf_counter(), time.process_time()
                with contextlib.redirect_stderr(io.StringIO()):
                    gpfd.fitness_of_each(sets, env=task, set=settings, seed=1, native=native)
                wall[native].append(time.perf_counter() - start)
                cpu[native].append(time.process_time() - start_cpu)
        w = {k: statistics.median(v) for k, v in wall.items()}
        c = {k: statistics.median(v) for k, v in cpu.items()}
        print(
            f"| {task} | {w[True]:.3f} | {w[False]:.2f} | {w[False] / w[True]:,.0f}x "
            f"| {c[True]:.3f} | {c[False]:.2f} | {c[False] / c[True]:,.0f}x |"
        )


def gp_work(out):
    """The GP generations' seconds and work: the evaluations (and re-evaluations) times the mean
    fitness, which on a cart-pole task (1 per step, measure "mean") is proportional to the steps
    the trials played."""
    with open(os.path.join(out, "generations.csv")) as f:
        rows = list(csv.DictReader(f))
    work = sum((int(r["evaluations"]) + int(r["reevaluations"])) * float(r["mean"]) for r in rows)
    return sum(float(r["seconds"]) for r in rows), work


def run_table(repeats, threads, python_run):
    print(f"\n3. a whole gpfd.evolve('cartpole-quick', seed=1, threads={threads}), wall seconds")
    cases = {
        "gpfd's own cart-pole": {},
        "gpfd's own cart-pole as CartPole-v1's task": {
            "set": {"env.params.actions": "discrete", "env.params.max_steps": 500}
        },
        "CartPole-v1, the twin": {"env": "CartPole-v1"},
        "CartPole-v1, native=False": {"env": "CartPole-v1", "native": False},
    }
    if not python_run:
        del cases["CartPole-v1, native=False"]
    times = {name: [] for name in cases}
    work = {}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(repeats):
            for name, kwargs in cases.items():
                out = os.path.join(tmp, f"{r}-{list(cases).index(name)}")
                start = time.perf_counter()
                with contextlib.redirect_stderr(io.StringIO()):
                    gpfd.evolve(
                        "cartpole-quick", seed=1, threads=threads, out=out, verbose=False, **kwargs
                    )
                times[name].append(time.perf_counter() - start)
                work[name] = gp_work(out)
    base = statistics.median(times["gpfd's own cart-pole"])
    print(
        "| run | seconds | against gpfd's own cart-pole | GP work (evaluations x mean return) "
        "| GP us per unit of work |"
    )
    print("|---|---|---|---|---|")
    for name in cases:
        seconds = statistics.median(times[name])
        gp_seconds, units = work[name]
        print(
            f"| {name} | {seconds:.1f} | {seconds / base:.2f}x | {units:,.0f} "
            f"| {gp_seconds / units * 1e6:.1f} |"
        )


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=20000)
    parser.add_argument("--updates", type=int, default=3)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--sections", default="1,2,3", help="which of the three to measure")
    parser.add_argument(
        "--no-python-run",
        action="store_true",
        help="section 3 without the run stepped in Python (about 13 minutes)",
    )
    args = parser.parse_args()
    print(
        f"gpfd {gpfd.__version__}, Gymnasium {gym.__version__}, NumPy {np.__version__}, "
        f"EnvPool {getattr(envpool, '__version__', 'not installed')}, "
        f"load average {os.getloadavg()[0]:.1f}\n"
    )
    sections = {int(x) for x in args.sections.split(",")}
    if 1 in sections:
        steps_table(args.steps, args.repeats)
    if 2 in sections:
        fitness_table(args.repeats, args.updates)
    if 3 in sections:
        run_table(args.repeats, args.threads, not args.no_python_run)


if __name__ == "__main__":
    main()
