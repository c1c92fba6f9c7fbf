"""gpfd's environments as Gymnasium environments, registered under the ``gpfd/`` namespace.

Every parameter that ``gpfd envs`` lists is a keyword of ``gymnasium.make``::

    env = gymnasium.make("gpfd/Swimmer-v0", segments=5)
    env = gymnasium.make("gpfd/CartPole-v0", actions="discrete", max_steps=500)

Observations are the state variables as float64 (``env.unwrapped.state_names``); the dynamics,
rewards and time limits are gpfd's own (docs/environments.md). Seeding follows Gymnasium:
``reset(seed=s)`` starts the environment's stream from ``s`` (the same start state as
``gpfd simulate ENV --seed s``), ``reset()`` continues it, and the first reset without a seed
draws one from fresh entropy.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from gpfd import _core
from gpfd.environments import render
from gpfd.environments.registry import is_builtin
from gpfd.environments.twins import TWINS

# Gymnasium ids of the built-in environments; any other registered gpfd environment gets
# gpfd/<Name>-v0.
_IDS = {
    "acrobot": "gpfd/Acrobot-v0",
    "cartpole": "gpfd/CartPole-v0",
    "swimmer": "gpfd/Swimmer-v0",
    "tetris": "gpfd/Tetris-v0",
}


# Gymnasium's tasks that a gpfd environment reproduces with some keywords, under ids of their own:
# id -> (gpfd environment, keywords, Gymnasium's reward threshold). gpfd/GymnasiumCartPole-v1 is
# Gymnasium's CartPole-v1 (two pushes, 500 steps; the same trajectories bit for bit), where
# gpfd/CartPole-v0 is gpfd's default task (a continuous force, 1000 steps).
TASKS: dict[str, tuple[str, dict[str, Any], float]] = {
    "gpfd/GymnasiumCartPole-v1": ("cartpole", {"actions": "discrete", "max_steps": 500}, 475.0),
}


def gym_id(name: str) -> str:
    """The Gymnasium id of a gpfd environment (gpfd/<Gymnasium id> for a twin, gpfd.twins)."""
    if name in TWINS:
        return f"gpfd/{name}"
    return _IDS.get(name) or f"gpfd/{name[:1].upper()}{name[1:]}-v0"


def check_params(name: str, params: dict[str, Any]) -> None:
    """TypeError for a keyword that is not one of the environment's parameters."""
    known = [p[0] for p in _core.env_params(name)]
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise TypeError(
            f"{gym_id(name)} got unknown keyword{'s' if len(unknown) > 1 else ''} "
            f"{', '.join(map(repr, unknown))}; its parameters are: {', '.join(known)}"
        )


def seed64(seed: int) -> int:
    """A Gymnasium seed (any int >= 0) as the 64-bit seed of gpfd's generator."""
    return int(seed) & 0xFFFFFFFFFFFFFFFF


def observation_space(core: _core.EnvBatch) -> spaces.Box:
    dim = len(core.state_names)
    return spaces.Box(-np.inf, np.inf, shape=(dim,), dtype=np.float64)


def action_space(core: _core.EnvBatch) -> spaces.Space:
    """From the environment's action space alone: a float64 Box for continuous actions,
    Discrete(n) for a discrete action of one component, MultiDiscrete(choices) for one of several
    (Tetris: (orientation, column))."""
    choices = list(core.action_choices)
    if not choices:
        low = np.asarray(core.action_low, dtype=np.float64)
        high = np.asarray(core.action_high, dtype=np.float64)
        return spaces.Box(low, high, dtype=np.float64)
    if len(choices) == 1:
        return spaces.Discrete(choices[0])
    return spaces.MultiDiscrete(choices)


class GpfdEnv(gym.Env):
    """One of gpfd's environments (``gpfd_env``: its name in ``gpfd envs``), stepped in C++.

    Where the legal actions depend on the state (Tetris: an action is (orientation, column)), an
    action that is not legal now is mapped to the nearest legal one (Tetris: orientation modulo the
    piece's orientations, column clipped), and ``info["action_mask"]`` (bool, the shape of the
    action space's choices: 4 x cols for Tetris) marks the legal ones; Tetris'
    :meth:`afterstates` lists every placement with the state it leads to.

    Example::

        env = gymnasium.make("gpfd/Swimmer-v0", segments=5)
        obs, info = env.reset(seed=0)
        env.unwrapped.params["segments"], env.unwrapped.state_names  # 5, ("dGx", "dGy", ...)
    """

    metadata: dict[str, Any] = {"render_modes": list(render.MODES), "render_fps": 50}

    def __init__(self, gpfd_env: str, render_mode: str | None = None, **params: Any):
        check_params(gpfd_env, params)
        render.check_mode(gym_id(gpfd_env), gpfd_env, render_mode)
        self.render_mode = render_mode
        self._core = _core.EnvBatch(gpfd_env, params, 1, "disabled")
        self.metadata = render.metadata(self._core.params)
        self.gpfd_name = gpfd_env
        self.state_names = tuple(self._core.state_names)
        self.params = dict(self._core.params)
        self.observation_space = observation_space(self._core)
        self.action_space = action_space(self._core)
        self._masked = self._core.state_dependent_actions
        self._seeded = False

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        """Starts an episode. ``options={"state": values}`` then sets the state exactly."""
        super().reset(seed=seed)
        if seed is not None:
            self._core.seed(0, seed64(seed))
        elif not self._seeded:
            self._core.seed(0, int(self.np_random.integers(2**63)))
        self._seeded = True
        obs = self._core.reset_one()
        if options and "state" in options:
            self.set_state(options["state"])
            obs = self._core.state(0)
        return obs, self._info()

    def step(self, action):
        obs, reward, terminated, truncated = self._core.step_one(action)
        return obs, reward, terminated, truncated, self._info()

    @property
    def native_engine(self) -> _core.EnvBatch:
        """The C++ engine that steps this environment (one instance), which gpfd's own drivers
        (gpfd.adapters.sources.native_single) step without Python."""
        return self._core

    @property
    def state(self) -> np.ndarray:
        """The state variables (a copy)."""
        return self._core.state(0)

    def set_state(self, values) -> None:
        """Sets the state variables exactly (gpfd.InputError when the environment cannot take
        them)."""
        values = np.ascontiguousarray(values, dtype=np.float64).ravel()
        if values.shape != self.observation_space.shape:
            raise ValueError(
                f"{gym_id(self.gpfd_name)} has {len(self.state_names)} state variables "
                f"({', '.join(self.state_names)}), got {values.size} values"
            )
        self._core.set_state(0, values)

    def render(self) -> np.ndarray | None:
        """With render_mode="rgb_array": the current state drawn (gpfd.render), H x W x 3 uint8."""
        if self.render_mode is None:
            gym.logger.warn(f"{gym_id(self.gpfd_name)} renders only with render_mode='rgb_array'")
            return None
        return render.frame(self._core)

    def afterstates(self) -> dict[str, np.ndarray]:
        """Tetris: every legal placement: ``actions`` (K x 2), ``features`` (the state after it,
        K x d), ``rewards`` (rows removed) and ``game_over``."""
        return self._core.afterstates(0)

    def _info(self) -> dict[str, Any]:
        return {"action_mask": self._core.action_mask(0)} if self._masked else {}


def register_all() -> None:
    """Registers every gpfd environment with Gymnasium (idempotent)."""
    for name in filter(is_builtin, _core.env_names()):
        if name in TWINS:
            continue  # Registered by gpfd.twins, with Gymnasium's spaces and time limits.
        env_id = gym_id(name)
        if env_id in gym.registry:
            continue
        gym.register(
            id=env_id,
            entry_point="gpfd.envs:GpfdEnv",
            vector_entry_point="gpfd.vector:GpfdVectorEnv",
            kwargs={"gpfd_env": name},
        )
    for env_id, (name, params, threshold) in TASKS.items():
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point="gpfd.envs:GpfdEnv",
                vector_entry_point="gpfd.vector:GpfdVectorEnv",
                reward_threshold=threshold,
                kwargs={"gpfd_env": name, **params},
            )
