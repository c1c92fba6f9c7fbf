"""Twins of Gymnasium's classic-control tasks, stepped in C++, episode for episode the same.

``gymnasium.make("gpfd/Pendulum-v1")`` plays what ``gymnasium.make("Pendulum-v1")`` plays: for any
seed and any actions, the same observations, rewards, ``terminated`` and ``truncated``, bit for
bit (tests/python/test_twins.py steps both side by side). The twins are
``gpfd/CartPole-v1``, ``gpfd/Acrobot-v1``, ``gpfd/Pendulum-v1``, ``gpfd/MountainCar-v0`` and
``gpfd/MountainCarContinuous-v0``, with Gymnasium's spaces, time limits and reward thresholds,
and gpfd's C++ registry knows them by Gymnasium's ids (``gpfd evolve user-env --env
Pendulum-v1``).

How: ``reset(seed=s)`` draws the start state from NumPy's SeedSequence and PCG64 as Gymnasium's
``np_random`` does, and ``reset()`` continues that stream; the dynamics follow Gymnasium's Python
operation by operation, in the NumPy types it computes with (NEP 50's promotion under NumPy 2,
the legacy rules under NumPy 1.x: the twin follows the NumPy installed), with the C library's
``sin``, ``cos`` and ``pow``, as NumPy and Python call them on the same machine.

What differs: ``info`` is always empty (Gymnasium's is too, but for Gymnasium's warnings);
``render`` is not supported; reset ``options`` are refused (use Gymnasium's own for them);
keywords other than each task's own (``TWINS``) are refused. An invalid action gets what
Gymnasium gives (CartPole-v1 and MountainCar-v0: the same AssertionError), or a clear error where
Gymnasium's would fail deep inside (an action of the wrong shape or type).
"""

from __future__ import annotations

import operator
from typing import Any

import gymnasium as gym
import numpy as np

from gpfd import _core

#: Gymnasium id -> (Gymnasium's class, the keywords of gymnasium.make that the twin accepts).
TWINS: dict[str, tuple[str, tuple[str, ...]]] = {
    "CartPole-v1": (
        "gymnasium.envs.classic_control.cartpole:CartPoleEnv",
        ("sutton_barto_reward",),
    ),
    "Acrobot-v1": ("gymnasium.envs.classic_control.acrobot:AcrobotEnv", ()),
    "Pendulum-v1": ("gymnasium.envs.classic_control.pendulum:PendulumEnv", ("g",)),
    "MountainCar-v0": (
        "gymnasium.envs.classic_control.mountain_car:MountainCarEnv",
        ("goal_velocity",),
    ),
    "MountainCarContinuous-v0": (
        "gymnasium.envs.classic_control.continuous_mountain_car:Continuous_MountainCarEnv",
        ("goal_velocity",),
    ),
}


def numpy_rule() -> str:
    """The twins' ``numpy`` parameter for the NumPy installed: "2" (NEP 50) or "1" (legacy)."""
    return "2" if int(np.__version__.split(".")[0]) >= 2 else "1"


def twin_params(task: str, kwargs: dict[str, Any]) -> dict[str, str]:
    """The C++ twin's parameters for gymnasium.make(task, **kwargs): its keywords (and
    ``max_episode_steps``) as text, with the NumPy rule installed; TypeError naming a keyword the
    twin does not take."""
    accepted = (*TWINS[task][1], "max_episode_steps")
    unknown = sorted(set(kwargs) - set(accepted))
    if unknown:
        raise TypeError(
            f"gpfd's twin of {task} takes {', '.join(accepted)}, not {', '.join(unknown)}: give "
            f"native=False (gpfd.evolve) or use Gymnasium's {task}"
        )
    params = {"numpy": numpy_rule()}
    for key, value in kwargs.items():
        if isinstance(value, bool):
            params[key] = str(value).lower()
        elif key == "max_episode_steps":
            params[key] = str(int(value))
        else:
            params[key] = repr(float(value))
    return params


def seed_words(seed: int) -> list[int]:
    """A seed (an int >= 0) as NumPy's SeedSequence splits it: 32-bit words, least significant
    first."""
    words = []
    while seed > 0:
        words.append(seed & 0xFFFFFFFF)
        seed >>= 32
    return words or [0]


def reference(task: str, kwargs: dict[str, Any]) -> gym.Env:
    """Gymnasium's own environment of `task`, whose spaces the twin takes."""
    module, name = TWINS[task][0].split(":")
    return getattr(__import__(module, fromlist=[name]), name)(**kwargs)


class TwinEnv(gym.Env):
    """The twin of Gymnasium's ``task`` (a key of ``TWINS``), one environment.

    Example::

        env = gymnasium.make("gpfd/CartPole-v1")  # Gymnasium's CartPole-v1, stepped in C++
        obs, info = env.reset(seed=0)  # as gymnasium.make("CartPole-v1") starts, bit for bit
    """

    metadata: dict[str, Any] = {"render_modes": []}

    def __init__(self, task: str, render_mode: str | None = None, **kwargs: Any):
        if task not in TWINS:
            raise ValueError(f"no twin of {task!r}; the twins: {', '.join(TWINS)}")
        if render_mode is not None:
            raise ValueError(f"gpfd/{task} does not render: use Gymnasium's {task} to render")
        params = {**twin_params(task, kwargs), "max_episode_steps": "0"}  # gymnasium.make's.
        reference_env = reference(task, kwargs)
        self.task = task
        self.observation_space = reference_env.observation_space
        self.action_space = reference_env.action_space
        self._discrete = isinstance(self.action_space, gym.spaces.Discrete)
        self._core = _core.Twin(task, params)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)  # Gymnasium's checks of the seed, and its np_random.
        if options:
            raise ValueError(
                f"gpfd/{self.task} takes no reset options; Gymnasium's {self.task} does"
            )
        obs = self._core.reset(None if seed is None else seed_words(seed))
        return obs, {}

    def step(self, action: Any):
        values, kind = self._action(action)
        obs, reward, terminated, truncated = self._core.step(values, kind)
        return obs, reward, terminated, truncated, {}

    def _action(self, action: Any) -> tuple[list[float], str]:
        """The action as the C++ twin takes it: its values and their NumPy type."""
        if self._discrete:
            if self.task == "Acrobot-v1":  # AVAIL_TORQUE[a]: Python's indexing of a 3-list.
                try:
                    index = operator.index(action)
                except TypeError:
                    raise TypeError(
                        f"Acrobot-v1's action is an integer 0, 1 or 2, got {action!r}"
                    ) from None
                if not -3 <= index <= 2:
                    raise IndexError(f"Acrobot-v1's action is 0, 1 or 2, got {index}")
                return [float(index % 3)], "python"
            assert self.action_space.contains(action), f"{action!r} ({type(action)}) invalid"
            return [float(action)], "python"
        if isinstance(action, (list, tuple)) and self.task == "MountainCarContinuous-v0":
            if not action:
                raise ValueError("MountainCarContinuous-v0's action is a force, got []")
            return [float(action[0])], "python"  # action[0] is a Python number.
        array = np.asarray(action)
        if array.ndim != 1 or array.size == 0:
            raise ValueError(f"{self.task}'s action has shape (1,), got {array.shape}")
        if array.dtype == np.float32:
            return [float(array[0])], "float32"
        if array.dtype == np.float64 or np.issubdtype(array.dtype, np.integer):
            return [float(array[0])], "float64"
        raise TypeError(f"{self.task}'s action is float32 or float64, got {array.dtype}")


def register_all() -> None:
    """Registers gpfd/<Gymnasium id> for each twin, with the spec's time limit and threshold."""
    for task in TWINS:
        env_id = f"gpfd/{task}"
        if env_id in gym.registry:
            continue
        spec = gym.spec(task)
        gym.register(
            id=env_id,
            entry_point="gpfd.twins:TwinEnv",
            vector_entry_point="gpfd.twin_vector:TwinVectorEnv",
            max_episode_steps=spec.max_episode_steps,
            reward_threshold=spec.reward_threshold,
            kwargs={"task": task},
        )
