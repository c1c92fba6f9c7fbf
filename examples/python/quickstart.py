"""gpfd from Python in three steps (about 15 seconds on 2 cores):

1. discover features for cart-pole with GP (gpfd's built-in environment, stepped in C++);
2. show them to an agent: wrap Gymnasium's own CartPole-v1 with FeatureObservation;
3. train a linear policy of our own (REINFORCE, plain NumPy) on the wrapped environment.

Run it with the package installed (scripts/test does): python examples/python/quickstart.py
"""

import gymnasium as gym
import numpy as np

import gpfd
from gpfd.wrappers import FeatureObservation


def discover() -> gpfd.FeatureSet:
    # configs/cartpole-quick.toml, made smaller so that the run takes seconds. The results go
    # to results/cartpole-quick (or -2, -3, ... when taken), as with `gpfd evolve`.
    run = gpfd.evolve(
        "cartpole-quick",
        seed=1,
        population=24,
        generations=6,
        set={"learner.params.updates": 15, "fitness.trials": 3},
        verbose=True,
    )
    assert run.best is not None  # A finished run has its best.features.
    print(f"\nbest features (fitness {run.history['best'][-1]:.1f}), in {run.dir}:")
    print(run.best.show())
    return run.best


def reinforce(env: gym.Env, episodes: int, rng: np.random.Generator) -> list[float]:
    """A softmax policy linear in the observation (plus a bias), trained by REINFORCE with a
    mean-return baseline: our own learner, which knows nothing of gpfd. Needs a Box observation
    and discrete actions."""
    assert isinstance(env.observation_space, gym.spaces.Box)
    assert isinstance(env.action_space, gym.spaces.Discrete)
    dim = env.observation_space.shape[0] + 1
    weights = np.zeros((env.action_space.n, dim))
    scale = np.ones(dim)  # Running scale of each input, so that one step size fits all features.
    returns: list[float] = []
    for _ in range(episodes):
        obs, _ = env.reset(seed=int(rng.integers(2**31)))
        inputs: list[np.ndarray] = []
        actions: list[int] = []
        rewards: list[float] = []
        done = False
        while not done:
            x = np.append(obs, 1.0)
            scale = np.maximum(scale, np.abs(x))
            x = x / scale
            logits = weights @ x
            p = np.exp(logits - logits.max())
            p /= p.sum()
            action = int(rng.choice(len(p), p=p))
            obs, reward, terminated, truncated, _ = env.step(action)
            inputs.append(x)
            actions.append(action)
            rewards.append(float(reward))
            done = terminated or truncated
        returns.append(sum(rewards))
        baseline = np.mean(returns[-20:])
        to_go = np.cumsum(rewards[::-1])[::-1]
        for x, a, g in zip(inputs, actions, to_go, strict=True):
            logits = weights @ x
            p = np.exp(logits - logits.max())
            p /= p.sum()
            grad = -np.outer(p, x)
            grad[a] += x
            weights += 0.05 * (g - baseline) / len(rewards) * grad
    return returns


def main() -> None:
    features = discover()
    # Gymnasium's CartPole-v1 observes (x, x_dot, theta, theta_dot): gpfd's x, dx, th, dth.
    env = FeatureObservation(gym.make("CartPole-v1"), features)
    print(f"wrapped CartPole-v1: observations {env.observation_space}")
    returns = reinforce(env, episodes=300, rng=np.random.default_rng(0))
    print(
        f"REINFORCE on the features: mean return {np.mean(returns[:20]):.1f} over the first 20 "
        f"episodes, {np.mean(returns[-20:]):.1f} over the last 20"
    )


if __name__ == "__main__":  # Needed: gpfd.evolve may start worker processes.
    main()
