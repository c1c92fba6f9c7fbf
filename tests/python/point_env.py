"""A point pushed along a line: the smallest Gymnasium environment with a continuous action, for
tests (test_user_env_workers.py) and benchmarks (bench/python_threads.py, python_no_vector.py)."""

import gymnasium as gym
import numpy as np


class Point(gym.Env):
    """Position and velocity; the action pushes (v' = 0.9 v + 0.1 a, a clipped to [-1, 1]);
    reward -|x| per step; truncated after `steps` steps."""

    observation_space = gym.spaces.Box(-10.0, 10.0, (2,), np.float64)
    action_space = gym.spaces.Box(-1.0, 1.0, (1,), np.float32)

    def __init__(self, steps: int = 50):
        self.limit = steps
        self.state = np.zeros(2)
        self.steps = 0

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.state = self.np_random.uniform(-1.0, 1.0, 2)
        self.steps = 0
        return self.state.copy(), {}

    def step(self, action):
        x, v = float(self.state[0]), float(self.state[1])
        v = 0.9 * v + 0.1 * float(np.clip(action[0], -1.0, 1.0))
        x = float(np.clip(x + v, -10.0, 10.0))
        self.state = np.array([x, v])
        self.steps += 1
        return self.state.copy(), -abs(x), False, self.steps >= self.limit, {}
