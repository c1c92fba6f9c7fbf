"""A Gymnasium vector environment (gpfd's own, or any in same-step autoreset) as a
Stable-Baselines3 ``VecEnv``, optionally seen through discovered features.

Needs the optional extra: ``pip install "gpfd[sb3]"`` (Stable-Baselines3, and with it PyTorch)::

    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor
    import gpfd.sb3

    venv = VecMonitor(gpfd.sb3.make_vec_env("gpfd/CartPole-v0", n_envs=8, features=run.best,
                                            env_kwargs={"actions": "discrete", "max_steps": 500}))
    PPO("MlpPolicy", venv, seed=0).learn(50_000)

SB3 resets an environment in the step that ends its episode and hands the last observation over
in ``infos[i]["terminal_observation"]``: Gymnasium's same-step autoreset, which ``make_vec_env``
asks for. Observations are float32 by default (what SB3's policies compute in; feature values are
clipped to float32's finite range), and ``rescale_actions`` presents a Box action space as
[-1, 1]^d, mapped linearly onto the environment's bounds: the two adjustments SB3's ``check_env``
recommends.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from typing import Any, cast

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

try:
    from stable_baselines3.common.vec_env import VecEnv as _SB3VecEnv
except ImportError as e:  # The optional extra.
    raise ImportError(
        "gpfd.sb3 needs Stable-Baselines3: pip install 'gpfd[sb3]' (or stable-baselines3)"
    ) from e

from gpfd._core import FeatureSet, InputError
from gpfd.agents.wrappers import check_features
from gpfd.environments import twins

_F32_MAX = float(np.finfo(np.float32).max)


def make_vec_env(
    env_id: str,
    n_envs: int = 1,
    *,
    seed: int | None = None,
    features: FeatureSet | None = None,
    with_original: bool = False,
    env_kwargs: dict[str, Any] | None = None,
    float32: bool = True,
    rescale_actions: bool = False,
    native: bool = True,
) -> GpfdVecEnv:
    """``gymnasium.make_vec(env_id, n_envs, **env_kwargs)`` in same-step autoreset, as an SB3
    VecEnv. gpfd's ids step all instances in one C++ call; other ids use their native vector form
    where Gymnasium has one in same-step autoreset, else ``SyncVectorEnv`` (Gymnasium's own
    CartPole-v1 has a native one in next-step autoreset only). seed: instance i starts from
    seed + i at the first reset (SB3's own convention). A Gymnasium id with a twin in gpfd
    (gpfd.twins: CartPole-v1, Acrobot-v1, Pendulum-v1, MountainCar-v0, MountainCarContinuous-v0)
    steps the twins, the same episodes as Gymnasium's bit for bit, unless ``native=False`` or
    ``env_kwargs`` holds a keyword the twin does not take; one line on stderr says so.

    Example::

        venv = gpfd.sb3.make_vec_env("CartPole-v1", n_envs=8, seed=0, features=run.best,
                                     with_original=True)
        stable_baselines3.PPO("MlpPolicy", venv, seed=0).learn(20_000)
    """
    if isinstance(n_envs, bool) or not isinstance(n_envs, int) or n_envs < 1:
        raise InputError(f"must be a whole number of at least 1, not {n_envs!r} (n_envs=)")
    kwargs = dict(env_kwargs or {})
    if (
        native
        and env_id in twins.TWINS
        and set(kwargs) <= {*twins.TWINS[env_id][1], "max_episode_steps"}
    ):
        print(
            f"gpfd: {env_id} stepped in C++ by gpfd's twins (native=False: Gymnasium's own)",
            file=sys.stderr,
        )
        env_id = "gpfd/" + env_id
    if env_id.startswith("gpfd/"):
        vector = gym.make_vec(env_id, n_envs, autoreset_mode=AutoresetMode.SAME_STEP, **kwargs)
    else:
        vector = _same_step_vector(env_id, n_envs, kwargs)
    venv = GpfdVecEnv(
        vector,
        features=features,
        with_original=with_original,
        float32=float32,
        rescale_actions=rescale_actions,
    )
    if seed is not None:
        venv.seed(seed)
    return venv


def _same_step_vector(env_id: str, n_envs: int, kwargs: dict[str, Any]) -> VectorEnv:
    """A Gymnasium id's vector form in same-step autoreset: its native one where that is the mode
    it steps in (a native vector environment takes no ``vector_kwargs``), else SyncVectorEnv."""
    if gym.spec(env_id).vector_entry_point is not None:
        native = gym.make_vec(env_id, n_envs, **kwargs)
        if native.metadata.get("autoreset_mode") == AutoresetMode.SAME_STEP:
            return native
        native.close()
    return gym.make_vec(
        env_id,
        n_envs,
        vectorization_mode="sync",
        vector_kwargs={"autoreset_mode": AutoresetMode.SAME_STEP},
        **kwargs,
    )


class GpfdVecEnv(_SB3VecEnv):
    """``vector`` (a Gymnasium VectorEnv in same-step autoreset) as an SB3 VecEnv. features: what
    the agent sees instead of the observation (followed by it when ``with_original``), computed
    for all instances in one call of the compiled feature set.

    Example::

        vector = gymnasium.make_vec("gpfd/CartPole-v0", 8, autoreset_mode="SameStep")
        venv = GpfdVecEnv(vector, features=run.best, rescale_actions=True)
    """

    def __init__(
        self,
        vector: VectorEnv,
        *,
        features: FeatureSet | None = None,
        with_original: bool = False,
        float32: bool = True,
        rescale_actions: bool = False,
    ):
        mode = vector.metadata.get("autoreset_mode")
        if mode != AutoresetMode.SAME_STEP:
            raise ValueError(
                "SB3 needs the vector environment in same-step autoreset "
                f"(autoreset_mode=AutoresetMode.SAME_STEP); this one is in {mode}"
            )
        if with_original and features is None:
            raise ValueError("with_original needs features")
        if features is not None:
            check_features(vector, features, vector.single_observation_space)
        self.vector = vector
        self.features = features
        self.with_original = with_original
        self.dtype = np.float32 if float32 else np.float64
        single_action = vector.single_action_space
        self._bounds: tuple[np.ndarray, np.ndarray] | None = None
        if rescale_actions:
            if not isinstance(single_action, spaces.Box):
                raise ValueError(f"rescale_actions needs a Box action space, not {single_action}")
            if not (np.isfinite(single_action.low).all() and np.isfinite(single_action.high).all()):
                raise ValueError("rescale_actions needs finite action bounds")
            self._bounds = (
                single_action.low.astype(np.float64),
                single_action.high.astype(np.float64),
            )
            single_action = spaces.Box(-1.0, 1.0, shape=single_action.shape, dtype=np.float32)
        elif float32 and isinstance(single_action, spaces.Box):
            single_action = spaces.Box(
                single_action.low.astype(np.float32),
                single_action.high.astype(np.float32),
                dtype=np.float32,
            )
        self.render_mode = vector.render_mode
        super().__init__(vector.num_envs, self._observation_space(), single_action)
        self._actions: np.ndarray | None = None

    def _observation_space(self) -> spaces.Box:
        single = self.vector.single_observation_space
        if not isinstance(single, spaces.Box):
            raise ValueError(f"gpfd.sb3 needs a Box observation space, not {single}")
        width = int(np.prod(single.shape))
        if self.features is not None:
            width = self.features.n_features + (width if self.with_original else 0)
        limit = _F32_MAX if self.dtype == np.float32 else np.inf
        return spaces.Box(-limit, limit, shape=(width,), dtype=self.dtype)

    def _seen(self, observations: np.ndarray) -> np.ndarray:
        """What the agent sees of a batch of observations (n x d)."""
        states = np.ascontiguousarray(observations, dtype=np.float64).reshape(len(observations), -1)
        seen = states
        if self.features is not None:
            phi = self.features(states)
            seen = np.concatenate([phi, states], axis=1) if self.with_original else phi
        if self.dtype == np.float32:
            seen = np.clip(seen, -_F32_MAX, _F32_MAX)
        return seen.astype(self.dtype, copy=False)

    def reset(self) -> np.ndarray:
        """Every instance reset; with the seeds of ``seed()`` (then forgotten) where given."""
        seeds = None if all(s is None for s in self._seeds) else list(self._seeds)
        options = self._options[0] if self._options and self._options[0] else None
        # Gymnasium's vector environments take one seed per instance (SyncVectorEnv, gpfd's),
        # although VectorEnv.reset's annotation says int.
        observations, info = self.vector.reset(seed=seeds, options=options)  # type: ignore[arg-type]
        self.reset_infos = [_instance(info, i) for i in range(self.num_envs)]
        self._reset_seeds()
        self._reset_options()
        return self._seen(observations)

    def step_async(self, actions: np.ndarray) -> None:
        actions = np.asarray(actions)
        if self._bounds is not None:
            low, high = self._bounds
            unit = np.clip(actions.astype(np.float64), -1.0, 1.0)
            actions = low + (unit + 1.0) * 0.5 * (high - low)
        self._actions = actions

    def step_wait(self):
        if self._actions is None:
            raise RuntimeError("step_wait() without step_async()")
        observations, rewards, terminated, truncated, info = self.vector.step(self._actions)
        self._actions = None
        dones = np.logical_or(terminated, truncated)
        infos = [_instance(info, i) for i in range(self.num_envs)]
        final = info.get("_final_obs")
        for i in np.flatnonzero(dones):
            if final is None or not final[i]:
                raise RuntimeError(
                    f"instance {i} ended its episode but the vector environment gave no final_obs"
                )
            infos[i]["terminal_observation"] = self._seen(
                np.asarray(info["final_obs"][i])[None, :]
            )[0]
            infos[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
        return self._seen(observations), np.asarray(rewards, dtype=np.float32), dones, infos

    def close(self) -> None:
        self.vector.close()

    def get_images(self) -> Sequence[np.ndarray | None]:
        frames = cast("Sequence[np.ndarray] | None", self.vector.render())
        return list(frames) if frames is not None else [None] * self.num_envs

    def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
        """The vector environment's attribute, once per instance asked for (they share it)."""
        return [getattr(self.vector, attr_name)] * len(self._get_indices(indices))

    def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
        if len(self._get_indices(indices)) != self.num_envs:
            raise ValueError("gpfd.sb3 sets an attribute of every instance at once, not of some")
        setattr(self.vector, attr_name, value)

    def env_method(
        self, method_name: str, *method_args: Any, indices: Any = None, **method_kwargs: Any
    ) -> list[Any]:
        raise AttributeError(
            f"gpfd.sb3 steps its instances as one vector environment and cannot call "
            f"{method_name}() on one of them"
        )

    def env_is_wrapped(self, wrapper_class: type[gym.Wrapper], indices: Any = None) -> list[bool]:
        return [False] * len(self._get_indices(indices))


def _instance(info: dict[str, Any], i: int) -> dict[str, Any]:
    """Instance i's part of a Gymnasium vector info (keys with a `_key` presence mask), without
    the autoreset's own keys."""
    out: dict[str, Any] = {}
    for key, value in info.items():
        if key.startswith("_") or key in ("final_obs", "final_info"):
            continue
        mask = info.get("_" + key)
        if mask is None or mask[i]:
            out[key] = value[i]
    return out
