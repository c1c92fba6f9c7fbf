"""gpfd's CartPole and Acrobot against Gymnasium's CartPole-v1 and Acrobot-v1: the same
trajectories under the same actions from the same start state."""

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import gpfd  # noqa: F401  (registers gpfd/...)

CASES = [
    # gpfd id and the keywords that make it Gymnasium's task, Gymnasium's id, action count.
    ("gpfd/CartPole-v0", {"actions": "discrete", "max_steps": 500}, "CartPole-v1", 2),
    ("gpfd/Acrobot-v0", {"actions": "discrete", "max_steps": 500}, "Acrobot-v1", 3),
]


def policy(name, state, rng):
    """Random actions, with a balancing bias on CartPole so that some episodes reach the limit."""
    if name.startswith("gpfd/CartPole") and rng.random() < 0.8:
        return int(state[2] + 0.5 * state[3] > 0)
    return int(rng.integers(3 if "Acrobot" in name else 2))


@pytest.mark.parametrize("ours_id,params,theirs_id,actions", CASES)
def test_same_trajectories_as_gymnasium(ours_id, params, theirs_id, actions):
    ours = gym.make(ours_id, **params)
    theirs = gym.make(theirs_id)
    their_env: Any = theirs.unwrapped  # Gymnasium's CartPoleEnv or AcrobotEnv: its state.
    rng = np.random.default_rng(1)
    steps = truncations = terminations = 0
    worst = 0.0
    for episode in range(12):
        state, _ = ours.reset(seed=episode)
        theirs.reset(seed=episode)
        their_env.state = state.copy()  # The same start state.
        while True:
            action = policy(ours_id, state, rng)
            state, reward, terminated, truncated, _ = ours.step(action)
            _, their_reward, their_terminated, their_truncated, _ = theirs.step(action)
            their_state = np.asarray(their_env.state, dtype=np.float64)
            worst = max(worst, float(np.max(np.abs(state - their_state))))
            assert reward == their_reward
            assert terminated == their_terminated and truncated == their_truncated
            steps += 1
            if terminated or truncated:
                truncations += truncated
                terminations += terminated
                break
    # CartPole is bit-identical. Acrobot's RK4 rounds differently in the last bit (see the replay
    # test below) and the double pendulum is chaotic: over 500 steps that grows to about 6e-8.
    assert worst <= (0.0 if "CartPole" in ours_id else 1e-6), worst
    assert steps > 1000 and terminations > 0 and truncations > 0


@pytest.mark.parametrize("ours_id,params,theirs_id,actions", CASES)
def test_each_step_agrees_to_rounding(ours_id, params, theirs_id, actions):
    """Replayed from gpfd's state before every step, so that chaos cannot amplify rounding."""
    ours = gym.make(ours_id, **params)
    theirs: Any = gym.make(theirs_id).unwrapped
    theirs.reset(seed=0)
    rng = np.random.default_rng(2)
    state, _ = ours.reset(seed=3)
    worst = 0.0
    for _ in range(3000):
        theirs.state = state.copy()
        action = int(rng.integers(actions))
        state, _, terminated, truncated, _ = ours.step(action)
        _, _, their_terminated, _, _ = theirs.step(action)
        worst = max(worst, float(np.max(np.abs(state - np.asarray(theirs.state)))))
        assert terminated == their_terminated
        if terminated or truncated:
            state, _ = ours.reset()
            theirs.reset()
    assert worst <= 1e-15, worst
