"""gpfd's vector environment: N instances of one environment stepped by one C++ call per step.

``gymnasium.make_vec("gpfd/CartPole-v0", num_envs=64)`` makes one (the default vectorization mode
of gpfd's ids); every environment keyword of ``gymnasium.make`` works here too, with
``autoreset_mode`` (Gymnasium's AutoresetMode, or its value or name as a string: ``"NextStep"`` or
``"next_step"``, the default, same step, or disabled).
Cart-pole, Acrobot and the swimmer (up to 8 segments) step as lanes of gpfd's batched environment
(structure of arrays, AVX2); the others, and any with ``engine="loop"``, one scalar environment
after another. Both give the same numbers bit for bit.
Instance i behaves exactly like ``gymnasium.make`` of the same id reset with seed + i and
auto-reset by ``SyncVectorEnv``: the same observations, rewards and flags, and the same infos
(``action_mask`` with ``_action_mask`` where the legal actions depend on the state, as for Tetris;
``final_obs`` and ``final_info`` with their masks under same-step autoreset).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from gpfd import _core
from gpfd.environments import render
from gpfd.environments.gpfd_env import action_space, check_params, gym_id, observation_space, seed64

_MODES = {
    AutoresetMode.NEXT_STEP: "next_step",
    AutoresetMode.SAME_STEP: "same_step",
    AutoresetMode.DISABLED: "disabled",
}


def parse_autoreset_mode(mode: str | AutoresetMode) -> AutoresetMode:
    """Gymnasium's AutoresetMode from itself, its value ("SameStep") or its name in any case
    ("same_step", "SAME_STEP"); ValueError naming the accepted ones otherwise."""
    if isinstance(mode, AutoresetMode):
        return mode
    key = str(mode).replace("_", "").lower()
    for known in AutoresetMode:
        if key == known.value.lower():
            return known
    accepted = ", ".join(f"{m.value!r} ({m.name.lower()!r})" for m in AutoresetMode)
    raise ValueError(f"autoreset_mode {mode!r} is not one of {accepted}")


def with_mask(info: dict[str, Any], key: str, values: Any, present: np.ndarray) -> dict[str, Any]:
    """info with ``key`` and its presence array ``_key``, as Gymnasium's vector environments
    give a value that some instances report."""
    info[key] = values
    info[f"_{key}"] = present
    return info


def lane_seeds(seed: Any, num_envs: int) -> list[int | None]:
    """Each instance's seed as SyncVectorEnv takes them: None for all, an int (instance i gets
    seed + i) or one seed (or None) per instance; ValueError for a list of another length."""
    if seed is None:
        return [None] * num_envs
    if isinstance(seed, (int, np.integer)):
        return [int(seed) + i for i in range(num_envs)]
    seeds = list(seed)
    if len(seeds) != num_envs:
        raise ValueError(f"expected {num_envs} seeds, got {len(seeds)}")
    return seeds


class GpfdVectorEnv(VectorEnv):
    """N instances of the gpfd environment ``gpfd_env`` (see gpfd.envs.GpfdEnv).

    Example::

        envs = gymnasium.make_vec("gpfd/CartPole-v0", num_envs=64, actions="discrete")
        obs, info = envs.reset(seed=0)  # instance i seeded with 0 + i
        envs.unwrapped.engine  # "batched": one C++ call steps all 64
    """

    def __init__(
        self,
        gpfd_env: str,
        num_envs: int = 1,
        autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP,
        render_mode: str | None = None,
        engine: str = "auto",
        **params: Any,
    ):
        """engine: "auto" (batched where the environment has a batched form), "loop" (one scalar
        environment per instance: the reference) or "batched" (gpfd.InputError where there is
        none); ``self.engine`` says which one steps."""
        check_params(gpfd_env, params)
        render.check_mode(gym_id(gpfd_env), gpfd_env, render_mode)
        self.render_mode = render_mode
        mode = parse_autoreset_mode(autoreset_mode)
        self._core = _core.EnvBatch(gpfd_env, params, int(num_envs), _MODES[mode], engine)
        self.engine = self._core.engine
        self.gpfd_name = gpfd_env
        self.state_names = tuple(self._core.state_names)
        self.params = dict(self._core.params)
        self.num_envs = int(num_envs)
        self.metadata = {"autoreset_mode": mode, **render.metadata(self._core.params)}
        self.single_observation_space = observation_space(self._core)
        self.single_action_space = action_space(self._core)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._seeded = np.zeros(self.num_envs, dtype=bool)
        self._masked = self._core.state_dependent_actions

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        """seed: None, an int (instance i gets seed + i) or one seed (or None) per instance.
        options: ``{"reset_mask": bool array}`` resets only those instances."""
        super().reset(seed=seed if isinstance(seed, int) else None)
        seeds = lane_seeds(seed, self.num_envs)
        mask = None
        if options and "reset_mask" in options:
            mask = np.ascontiguousarray(options["reset_mask"], dtype=bool)
        for i, s in enumerate(seeds):
            if mask is not None and not mask[i]:
                continue
            if s is not None:
                self._core.seed(i, seed64(s))
            elif not self._seeded[i]:
                self._core.seed(i, int(self.np_random.integers(2**63)))
            self._seeded[i] = True
        obs = self._core.reset(mask)
        info: dict[str, Any] = {}
        if self._masked:  # The instances reset report their legal actions; the rows of the others
            present = np.ones(self.num_envs, dtype=bool) if mask is None else mask.copy()
            masks = self._core.action_masks()  # are False, as SyncVectorEnv leaves them.
            masks[~present] = False
            with_mask(info, "action_mask", masks, present)
        return obs, info

    def step(self, actions):
        obs, rewards, terminated, truncated, final_obs, final_mask, final_legal = self._core.step(
            np.ascontiguousarray(actions, dtype=np.float64)
        )
        info: dict[str, Any] = {}
        if final_mask is not None and final_mask.any():  # Same-step autoreset, as SyncVectorEnv.
            rows = np.full(self.num_envs, None, dtype=object)
            for i in np.flatnonzero(final_mask):
                rows[i] = final_obs[i]
            with_mask(info, "final_obs", rows, final_mask)
            final_info: dict[str, Any] = {}
            if final_legal is not None:
                final_legal[~final_mask] = False
                with_mask(final_info, "action_mask", final_legal, final_mask.copy())
            with_mask(info, "final_info", final_info, final_mask.copy())
        if self._masked:
            present = np.ones(self.num_envs, dtype=bool)
            with_mask(info, "action_mask", self._core.action_masks(), present)
        return obs, rewards, terminated, truncated, info

    def render(self) -> tuple[np.ndarray, ...] | None:
        """With render_mode="rgb_array": every instance drawn (gpfd.render), as Gymnasium's vector
        environments give them: a tuple of num_envs H x W x 3 uint8 frames."""
        if self.render_mode is None:
            gym.logger.warn(f"{gym_id(self.gpfd_name)} renders only with render_mode='rgb_array'")
            return None
        return tuple(render.frame(self._core, i) for i in range(self.num_envs))

    @property
    def native_engine(self) -> _core.EnvBatch:
        """The C++ engine that steps every instance (one call per step), which a lockstep group
        (python/src/vector_hub.cpp, through gpfd.adapters.vector_adapter.VectorAdapter) steps
        without Python."""
        return self._core

    @property
    def states(self) -> np.ndarray:
        """The state variables of every instance (N x d, a copy)."""
        return np.stack([self._core.state(i) for i in range(self.num_envs)])
