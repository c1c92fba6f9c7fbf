"""The reach of a linear policy on a feature set, whatever trains it (README.md beside this file):
the cross-entropy method searches the weights and bias of a linear policy on
the set's features (each standardised by its mean and sd on states of random-action episodes;
two searches, the first weights drawn with sd 1 and with sd 10: fine control and bang-bang),
selecting on 10 episodes (seeds 1000000 + e, zoo-check's evaluation seeds) and reporting the
selected policy on 20 other episodes (seeds 2000000 + e), so the reported mean is not the one it
was chosen on. A search finds a lower bound on the reach, not the reach.

The policy is sb3-contrib's LinearPolicy's form: continuous actions clipped to the action space,
discrete ones the arg-max of one linear score per action. Gymnasium's own environments stepped in
Python. Usage, from the repository root (the package installed, .venv):

    .venv/bin/python docs/results/zoo/physics/reach.py TASK [SET] [--sets DIR] [--seed 1]

TASK: one of scripts/zoo-check's tasks. SET: a run number of DIR/runs.csv's rows for TASK
(default DIR: this study's sets, read as zoo-check reads a study's rows), or "raw". Appends a row
to docs/results/zoo/physics/reach.csv and prints it."""

import argparse
import csv
import importlib.machinery
import importlib.util
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

HERE = Path(__file__).resolve().parent
ZOO_CHECK = HERE.parents[3] / "scripts" / "zoo-check"
SELECT_SEED, REPORT_SEED = 1_000_000, 2_000_000
POPULATION, ELITE, ITERATIONS = 24, 6, 25
# The first weights' sd, on standardised features: fine control (1) and bang-bang (10).
FIRST_SPREADS = (1.0, 10.0)


def zoo_check():
    """scripts/zoo-check as a module: its tasks and its reading of a study's sets."""
    loader = importlib.machinery.SourceFileLoader("zoo_check", str(ZOO_CHECK))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    return module


def feature_set(zoo, task, run, sets_dir, parser):
    """(text, function of one observation) of the raw observation or a run's set."""
    if run == "raw":
        return "the observation", lambda obs: np.asarray(obs, dtype=float)
    sets = dict(zoo.committed_sets(sets_dir, task))
    if not run.isdigit() or int(run) not in sets:
        parser.error(f'SET {run!r}: not "raw" nor a run of {task} in {sets_dir}/runs.csv')
    features = sets[int(run)]
    text = " ; ".join(zoo.expressions(features))
    return text, lambda obs: np.asarray(features(np.asarray(obs, dtype=float)), dtype=float)


def standardiser(env, features, seed):
    """Each feature's mean and sd over 20 random-action episodes' states."""
    env.action_space.seed(seed)
    values = []
    for e in range(20):
        obs, _ = env.reset(seed=seed + e)
        done = False
        while not done:
            values.append(features(obs))
            obs, _, terminated, truncated, _ = env.step(env.action_space.sample())
            done = terminated or truncated
    values = np.array(values)
    return values.mean(axis=0), np.maximum(values.std(axis=0), 1e-8)


def episodes_mean(env, act, first_seed, count):
    returns = []
    for e in range(count):
        obs, _ = env.reset(seed=first_seed + e)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(act(obs))
            total += float(reward)
            done = terminated or truncated
        returns.append(total)
    return float(np.mean(returns)), float(np.std(returns, ddof=1))


def policy(env, features, mean, sd, weights):
    """The linear policy of weights (actions x features + 1, the last column the bias)."""
    space = env.action_space

    def scores(obs):
        return weights @ np.append((features(obs) - mean) / sd, 1.0)

    if isinstance(space, gym.spaces.Discrete):
        return lambda obs: int(np.argmax(scores(obs)))
    return lambda obs: np.clip(scores(obs), space.low, space.high).astype(space.dtype)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("task")
    parser.add_argument("set", nargs="?", default="raw")
    parser.add_argument("--sets", default=str(HERE / "sets"))
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    zoo = zoo_check()
    zoo.check_task(args.task, parser)
    start = time.monotonic()
    env = gym.make(args.task)
    text, features = feature_set(zoo, args.task, args.set, args.sets, parser)
    mean, sd = standardiser(env, features, 3_000_000)
    space = env.action_space
    actions = space.n if isinstance(space, gym.spaces.Discrete) else space.shape[0]
    shape = (actions, len(mean) + 1)
    rng = np.random.default_rng(args.seed)
    best = (-np.inf, None)
    for first_spread in FIRST_SPREADS:
        centre, spread = np.zeros(shape), np.full(shape, first_spread)
        for _ in range(ITERATIONS):
            samples = centre + spread * rng.standard_normal((POPULATION, *shape))
            scores = [
                episodes_mean(env, policy(env, features, mean, sd, w), SELECT_SEED, 10)[0]
                for w in samples
            ]
            order = np.argsort(scores)[::-1][:ELITE]
            if scores[order[0]] > best[0]:
                best = (scores[order[0]], samples[order[0]])
            centre = samples[order].mean(axis=0)
            spread = samples[order].std(axis=0) + 0.05
    chosen = policy(env, features, mean, sd, best[1])
    report, report_sd = episodes_mean(env, chosen, REPORT_SEED, 20)
    row = {
        "task": args.task,
        "set": args.set,
        "features": text,
        "selected_on_10": round(best[0], 2),
        "reported_on_20": round(report, 2),
        "reported_sd": round(report_sd, 2),
        "evaluations": POPULATION * ITERATIONS * len(FIRST_SPREADS),
        "search_seed": args.seed,
        "seconds": round(time.monotonic() - start, 1),
    }
    out = HERE / "reach.csv"
    new = not out.exists()
    with open(out, "a", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(row))
        if new:
            writer.writeheader()
        writer.writerow(row)
    print(row)


if __name__ == "__main__":
    main()
