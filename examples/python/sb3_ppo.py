"""PPO from Stable-Baselines3 on discovered features, against PPO on the raw observation.

1. discover features for Gymnasium's CartPole-v1 as a user does: ``gpfd.evolve(env="CartPole-v1",
   time_budget=60)``, the defaults for a user's environment within a time budget (validation,
   confirmation, the one-standard-error rule), once per GP seed;
2. train PPO (SB3's MlpPolicy) on CartPole-v1 seen through each returned set alone,
   through the set beside the raw observation (``with_original=True``: nothing the observation
   holds is lost, so a set fitted to gpfd's linear learner cannot hide a variable PPO needs),
   on the raw observation, and on the raw observation standardised by SB3's VecNormalize
   (running mean and sd, what SB3 users do for scale; gpfd's features carry their own scaling),
   over several PPO seeds (gpfd.sb3.make_vec_env);
3. evaluate every trained policy (deterministic actions) on 20 fresh episodes and compare.

Needs the optional extra (PyTorch comes with SB3): scripts/sb3-example installs it and runs this.
    python examples/python/sb3_ppo.py                  # docs/results/sb3/README.md's figures
    python examples/python/sb3_ppo.py --gp-runs 1 --gp-budget 20 --seeds 1 --timesteps 2000  # smoke
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.vec_env import VecEnv, VecMonitor, VecNormalize

import gpfd
import gpfd.sb3

ENV_ID = "CartPole-v1"
N_ENVS = 8
# PPO's hyperparameters for CartPole-v1 from the RL Baselines3 Zoo (hyperparams/ppo.yml), with
# constant rates instead of its linear schedules.
PPO_PARAMS = {
    "n_steps": 32,
    "batch_size": 256,
    "gae_lambda": 0.8,
    "gamma": 0.98,
    "n_epochs": 20,
    "ent_coef": 0.0,
    "learning_rate": 1e-3,
    "clip_range": 0.2,
}


def discover(seed: int, budget: float) -> gpfd.FeatureSet:
    """One GP run on CartPole-v1 with the defaults for a user's environment, sized by gpfd to end
    within `budget` seconds; its returned (confirmed) set, or the original variables. A finished
    run of the same settings in results/sb3-example is read back instead."""
    out = Path(f"results/sb3-example/gp{seed}-budget{budget:g}s")
    if (out / "best.features").is_file():
        best = gpfd.load_run(out).best
    else:
        best = gpfd.evolve(
            env=ENV_ID, seed=seed, time_budget=budget, threads=2, verbose=False, out=out
        ).best
    assert best is not None  # A finished run has its best.features.
    return best


def train_and_evaluate(
    features: gpfd.FeatureSet | None,
    seed: int,
    timesteps: int,
    episodes: int,
    normalise: bool,
    with_original: bool = False,
) -> float:
    """PPO trained for `timesteps` steps; the mean return of `episodes` evaluation episodes."""

    def make(env_seed: int) -> VecEnv:
        return gpfd.sb3.make_vec_env(
            ENV_ID, N_ENVS, seed=env_seed, features=features, with_original=with_original
        )

    venv: VecEnv = VecMonitor(make(seed))
    if normalise:
        venv = VecNormalize(venv, norm_reward=False)
    model = PPO("MlpPolicy", venv, seed=seed, device="cpu", verbose=0, **PPO_PARAMS)
    model.learn(total_timesteps=timesteps)
    evaluation: VecEnv = make(10_000 + seed)
    if isinstance(venv, VecNormalize):  # The statistics learnt in training, frozen.
        evaluation = VecNormalize(evaluation, training=False, norm_reward=False)
        evaluation.obs_rms = venv.obs_rms
    returns: list[float] = []
    totals = np.zeros(N_ENVS)
    obs = evaluation.reset()
    while len(returns) < episodes:
        actions, _ = model.predict(obs, deterministic=True)
        obs, rewards, dones, _ = evaluation.step(actions)
        totals += rewards
        for i in np.flatnonzero(dones):
            returns.append(float(totals[i]))
            totals[i] = 0.0
    score = statistics.fmean(returns[:episodes])
    print(f"  PPO seed {seed}: {score:.1f}", flush=True)
    return score


def summary(values: list[float]) -> str:
    spread = statistics.stdev(values) if len(values) > 1 else 0.0
    return f"{statistics.fmean(values):7.1f} ± {spread:5.1f}"


def positive(text: str) -> int:
    """An argument that counts something: a whole number of at least 1."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number of at least 1, not {text!r}")
    return int(text)


def seconds(text: str) -> float:
    """A GP run's time budget: seconds above 0 (gpfd sizes the run to it)."""
    try:
        value = float(text)
    except ValueError:
        value = 0.0
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be seconds above 0, not {text!r}")
    return value


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--gp-runs", type=positive, default=3, help="independent GP runs (seeds 1..)"
    )
    parser.add_argument("--seeds", type=positive, default=10, help="PPO seeds per observation")
    # 20,000 steps: below the 500 ceiling on the raw observation, so that faster learning shows
    # (at 50,000 PPO solves the task on every seed from the raw observation).
    parser.add_argument("--timesteps", type=positive, default=20_000, help="PPO steps per training")
    parser.add_argument("--episodes", type=positive, default=20, help="evaluation episodes")
    parser.add_argument(
        "--gp-budget", type=seconds, default=60.0, help="seconds for each GP run (time_budget)"
    )
    options = parser.parse_args()
    torch.set_num_threads(1)  # Small networks: one thread is faster than several contending.
    start = time.monotonic()
    seeds = range(options.seeds)
    rows: list[tuple[str, list[float]]] = []
    for normalise, name in ((False, "raw observation"), (True, "raw observation, VecNormalize")):
        print(name, flush=True)
        scores = [
            train_and_evaluate(None, s, options.timesteps, options.episodes, normalise)
            for s in seeds
        ]
        rows.append((name, scores))
    for gp_seed in range(1, options.gp_runs + 1):
        features = discover(gp_seed, options.gp_budget)
        print(f"GP run {gp_seed}'s features:\n{features.show()}", flush=True)
        for beside in (False, True):
            scores = [
                train_and_evaluate(features, s, options.timesteps, options.episodes, False, beside)
                for s in seeds
            ]
            where = "beside the observation" if beside else "alone"
            rows.append((f"GP run {gp_seed}'s {features.n_features} features, {where}", scores))
    print(
        f"\nPPO, {options.timesteps} steps, {N_ENVS} environments, seeds 0-{options.seeds - 1}; "
        f"mean return of {options.episodes} deterministic episodes (max 500), mean ± sd over "
        "seeds; p: Wilcoxon signed-rank test against the raw observation, seed by seed:"
    )
    raw = rows[0][1]
    for name, scores in rows:
        each = ", ".join(f"{v:.1f}" for v in scores)
        p = gpfd.signed_rank_test(np.subtract(scores, raw)).p
        print(f"  {name:46s} {summary(scores)}  p {p:.3g}   ({each})")
    print(f"took {time.monotonic() - start:.0f} s")


if __name__ == "__main__":
    main()
