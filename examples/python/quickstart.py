"""gpfd from Python in three steps:

1. discover features for cart-pole with GP (gpfd's built-in environment, stepped in C++);
2. show them to an agent: wrap Gymnasium's own CartPole-v1 with FeatureObservation;
3. train a linear policy of our own (REINFORCE, plain NumPy) on the wrapped environment, and the
   same learner on the raw observation, over several seeds, and compare.

Run it with the package installed (scripts/test does):
    python examples/python/quickstart.py            # docs/python.md's figures (45 s of CPU)
    python examples/python/quickstart.py --seeds 2 --episodes 100   # tests/python/test_example.py
"""

import argparse

import gymnasium as gym
import numpy as np

import gpfd
from gpfd.wrappers import FeatureObservation


def discover(population: int, generations: int) -> gpfd.FeatureSet:
    # configs/cartpole-quick.toml, made smaller so that the run takes seconds. The results go
    # to results/cartpole-quick (or -2, -3, ... when taken), as with `gpfd evolve`.
    run = gpfd.evolve(
        "cartpole-quick",
        seed=1,
        population=population,
        generations=generations,
        set={"learner.params.updates": 15, "fitness.trials": 3},
        verbose=True,
    )
    assert run.best is not None  # A finished run has its best.features.
    print(f"\nbest features (fitness {run.history['best'][-1]:.1f}), in {run.dir}:")
    print(run.best.show())
    return run.best


def softmax(logits: np.ndarray) -> np.ndarray:
    p = np.exp(logits - logits.max(axis=-1, keepdims=True))
    return p / p.sum(axis=-1, keepdims=True)


def reinforce(
    env: gym.Env, episodes: int, rng: np.random.Generator, batch: int = 10, lr: float = 0.05
) -> list[float]:
    """A softmax policy linear in the observation (plus a bias), trained by REINFORCE: our own
    learner, which knows nothing of gpfd. Each update plays `batch` episodes and weights each
    step's log-probability gradient by its discounted return-to-go (gamma 0.99), standardised over
    the batch (the baseline and the scale), then takes an Adam step (Kingma & Ba 2015: each
    weight moves by about `lr` per update whatever the scale of its input; a discovered feature
    such as a ratio can reach hundreds near its pole). Needs a Box observation and discrete
    actions; returns each episode's return."""
    assert isinstance(env.observation_space, gym.spaces.Box)
    assert isinstance(env.action_space, gym.spaces.Discrete)
    n = int(env.action_space.n)
    weights = np.zeros((n, env.observation_space.shape[0] + 1))
    moment, second = np.zeros_like(weights), np.zeros_like(weights)
    returns: list[float] = []
    for update in range(1, episodes // batch + 1):
        inputs: list[np.ndarray] = []
        actions: list[int] = []
        advantages: list[float] = []
        for _ in range(batch):
            obs, _ = env.reset(seed=int(rng.integers(2**31)))
            rewards: list[float] = []
            done = False
            while not done:
                x = np.append(obs, 1.0)
                p = softmax(weights @ x)
                action = min(int(np.searchsorted(np.cumsum(p), rng.random())), n - 1)
                obs, reward, terminated, truncated, _ = env.step(action)
                inputs.append(x)
                actions.append(action)
                rewards.append(float(reward))
                done = terminated or truncated
            returns.append(sum(rewards))
            to_go, acc = [], 0.0
            for r in reversed(rewards):
                acc = r + 0.99 * acc
                to_go.append(acc)
            advantages.extend(reversed(to_go))
        x = np.array(inputs)
        adv = np.array(advantages)
        adv = (adv - adv.mean()) / (adv.std() + 1e-8)
        grad = ((np.eye(n)[actions] - softmax(x @ weights.T)) * adv[:, None]).T @ x / len(x)
        moment = 0.9 * moment + 0.1 * grad
        second = 0.999 * second + 0.001 * grad**2
        step = (moment / (1 - 0.9**update)) / (np.sqrt(second / (1 - 0.999**update)) + 1e-8)
        weights += lr * step
    return returns


def standardised(env: gym.Env, rng: np.random.Generator, states: int = 512) -> gym.Env:
    """`env` observed in standard units: each variable less its mean, over its sd, on states that
    random actions visit, as gpfd scales each discovered feature (fitness.normalise)."""
    assert isinstance(env.action_space, gym.spaces.Discrete)
    actions = int(env.action_space.n)
    seen: list[np.ndarray] = []
    while len(seen) < states:
        obs, _ = env.reset(seed=int(rng.integers(2**31)))
        done = False
        while not done and len(seen) < states:
            seen.append(obs)
            obs, _, terminated, truncated, _ = env.step(int(rng.integers(actions)))
            done = terminated or truncated
    mean, sd = np.mean(seen, axis=0), np.std(seen, axis=0)
    space = gym.spaces.Box(-np.inf, np.inf, mean.shape, np.float64)
    return gym.wrappers.TransformObservation(env, lambda o: (o - mean) / sd, space)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5, help="trainings per observation")
    parser.add_argument("--episodes", type=int, default=300, help="episodes per training")
    parser.add_argument("--population", type=int, default=24, help="GP population")
    parser.add_argument("--generations", type=int, default=6, help="GP generations")
    args = parser.parse_args()
    if args.seeds < 2 or args.episodes < 20:
        parser.error("--seeds must be at least 2 (for an sd) and --episodes at least 20")

    features = discover(args.population, args.generations)
    # Gymnasium's CartPole-v1 observes (x, x_dot, theta, theta_dot): gpfd's x, dx, th, dth.
    inputs = {
        "discovered features": lambda: FeatureObservation(gym.make("CartPole-v1"), features),
        "raw observation": lambda: gym.make("CartPole-v1"),
        "raw, standardised": lambda: standardised(
            gym.make("CartPole-v1"), np.random.default_rng(1234)
        ),
    }
    print(
        f"\nwrapped CartPole-v1: observations {inputs['discovered features']().observation_space}"
    )
    print(
        f"REINFORCE on CartPole-v1 (ceiling 500), {args.episodes} episodes per training, seeds "
        f"0..{args.seeds - 1}; mean return of the first, the best and the last 20 episodes:"
    )
    last: dict[str, np.ndarray] = {}
    for name, make in inputs.items():
        rows = []
        for seed in range(args.seeds):
            r = np.array(reinforce(make(), args.episodes, np.random.default_rng(seed)))
            blocks = r[: len(r) // 20 * 20].reshape(-1, 20).mean(axis=1)
            rows.append((blocks[0], blocks.max(), blocks[-1]))
            print(
                f"  {name}, seed {seed}: first {blocks[0]:.1f} best {blocks.max():.1f} "
                f"last {blocks[-1]:.1f}"
            )
        last[name] = np.array([final for _, _, final in rows])
        learned = sum(final > first for first, _, final in rows)
        kept = sum(final >= 0.9 * best for _, best, final in rows)
        print(
            f"{name}: last 20 episodes {last[name].mean():.1f} +- {last[name].std(ddof=1):.1f} "
            f"(mean +- sd over seeds); above its first 20 on {learned} of {args.seeds} seeds, "
            f"within 10% of its best 20 on {kept} of {args.seeds}"
        )
    for other in ("raw observation", "raw, standardised"):
        difference = last["discovered features"] - last[other]
        print(
            f"discovered features minus {other}: {difference.mean():+.1f} +- "
            f"{difference.std(ddof=1):.1f}; higher on {int(np.sum(difference > 0))} of "
            f"{args.seeds} seeds"
        )


if __name__ == "__main__":  # Needed: gpfd.evolve may start worker processes.
    main()
