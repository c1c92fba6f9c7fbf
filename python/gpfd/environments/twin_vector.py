"""The twins' vector form: ``gymnasium.make_vec("gpfd/CartPole-v1", num_envs=64)`` steps 64 twins
by one C++ call per step (gpfd._core.TwinVector), in any of Gymnasium's autoreset modes
(``autoreset_mode``: next step, the default, same step or disabled).

Instance i behaves exactly as instance i of ``SyncVectorEnv`` over ``gymnasium.make(id)`` with the
same autoreset mode: reset with seed + i (or its own seed from a list), the same observations,
rewards and flags bit for bit, and under same-step autoreset the same ``final_obs`` and
``final_info`` with their masks (tests/python/test_twins.py). The time limit is the spec's, or
``max_episode_steps``.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from gpfd import _core
from gpfd.environments.gpfd_vector import lane_seeds, parse_autoreset_mode, with_mask
from gpfd.environments.twins import TWINS, reference, seed_words, twin_params

_MODES = {
    AutoresetMode.NEXT_STEP: "next_step",
    AutoresetMode.SAME_STEP: "same_step",
    AutoresetMode.DISABLED: "disabled",
}


class TwinVectorEnv(VectorEnv):
    """``num_envs`` twins of Gymnasium's ``task`` (a key of gpfd.twins.TWINS).

    Example::

        envs = gymnasium.make_vec("gpfd/CartPole-v1", num_envs=64, autoreset_mode="SameStep")
        obs, info = envs.reset(seed=0)  # instance i as gymnasium.make("CartPole-v1") seeded i
    """

    def __init__(
        self,
        task: str,
        num_envs: int = 1,
        autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP,
        render_mode: str | None = None,
        max_episode_steps: int | None = None,
        **kwargs: Any,
    ):
        if task not in TWINS:
            raise ValueError(f"no twin of {task!r}; the twins: {', '.join(TWINS)}")
        if render_mode is not None:
            raise ValueError(f"gpfd/{task} does not render: use Gymnasium's {task} to render")
        mode = parse_autoreset_mode(autoreset_mode)
        steps = gym.spec(task).max_episode_steps if max_episode_steps is None else max_episode_steps
        params = {**twin_params(task, kwargs), "max_episode_steps": str(int(steps or 0))}
        single = reference(task, kwargs)
        self.task = task
        self.num_envs = int(num_envs)
        self.metadata = {"autoreset_mode": mode}
        self.single_observation_space = single.observation_space
        self.single_action_space = single.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._mode = mode
        self._discrete = isinstance(self.single_action_space, gym.spaces.Discrete)
        self._core = _core.TwinVector(task, params, self.num_envs, _MODES[mode])
        self._ended = np.zeros(self.num_envs, dtype=bool)

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        """seed: None, an int (instance i gets seed + i) or one seed (or None) per instance.
        options: ``{"reset_mask": bool array}`` resets only those instances."""
        super().reset(seed=seed if isinstance(seed, int) else None)
        seeds = lane_seeds(seed, self.num_envs)
        mask: list[bool] = []
        if options and "reset_mask" in options:
            mask = [bool(m) for m in np.asarray(options["reset_mask"], dtype=bool)]
        words = [None if s is None else seed_words(_checked_seed(s)) for s in seeds]
        obs = self._core.reset(words, mask)
        if mask:
            self._ended[np.asarray(mask)] = False
        else:
            self._ended[:] = False
        return obs, {}

    def step(self, actions: Any):
        if self._mode == AutoresetMode.DISABLED and self._ended.any():
            raise AssertionError(f"self._autoreset_envs={self._ended}")  # As SyncVectorEnv.
        values, kind = self._actions(actions)
        obs, rewards, terminated, truncated, final_obs, final_mask = self._core.step(values, kind)
        self._ended = terminated | truncated
        info: dict[str, Any] = {}
        if final_mask is not None and final_mask.any():
            rows = np.full(self.num_envs, None, dtype=object)
            for i in np.flatnonzero(final_mask):
                rows[i] = final_obs[i]
            with_mask(info, "final_obs", rows, final_mask)
            with_mask(info, "final_info", {}, final_mask.copy())
        return obs, rewards, terminated, truncated, info

    def _actions(self, actions: Any) -> tuple[np.ndarray, str]:
        """The actions as doubles, one row per instance, and their NumPy type."""
        array = np.asarray(actions)
        if self._discrete:
            if array.shape != (self.num_envs,) or not np.issubdtype(array.dtype, np.integer):
                raise ValueError(
                    f"gpfd/{self.task}: one whole-number action per instance ({self.num_envs}), "
                    f"got {array.dtype} of shape {array.shape}"
                )
            if self.task == "Acrobot-v1":
                if ((array < -3) | (array > 2)).any():
                    raise IndexError(f"Acrobot-v1's actions are 0, 1 or 2, got {array}")
                array = array % 3
            elif not self.single_action_space.contains(array.min()) or not (
                self.single_action_space.contains(array.max())
            ):
                raise AssertionError(f"{actions!r} ({type(actions)}) invalid")
            return np.ascontiguousarray(array, dtype=np.float64), "python"
        if array.dtype not in (np.float32, np.float64) or array.shape != (self.num_envs, 1):
            raise ValueError(
                f"gpfd/{self.task}: actions of shape ({self.num_envs}, 1), float32 or float64, "
                f"got {array.dtype} of shape {array.shape}"
            )
        return np.ascontiguousarray(array, dtype=np.float64), str(array.dtype)


def _checked_seed(seed: Any) -> int:
    """Gymnasium's rule for a seed: an int >= 0."""
    if not isinstance(seed, (int, np.integer)) or seed < 0:
        raise gym.error.Error(f"Seed must be a python integer >= 0, actual: {seed!r}")
    return int(seed)
