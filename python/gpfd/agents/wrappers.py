"""Gymnasium wrappers that show an agent discovered features instead of (or beside) the state."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector import VectorEnv, VectorObservationWrapper
from gymnasium.vector.utils import batch_space

from gpfd._core import FeatureSet

_MAX = np.finfo(np.float64).max


def _feature_space(features: FeatureSet, with_original: bool, source: spaces.Space) -> spaces.Box:
    """Every feature value is finite (gpfd's protected semantics), so the box is [-max, max]."""
    count = features.n_features + (features.input_dim if with_original else 0)
    if with_original and not isinstance(source, spaces.Box):
        raise TypeError(f"with_original needs a Box observation space, not {source}")
    return spaces.Box(-_MAX, _MAX, shape=(count,), dtype=np.float64)


def check_features(env, features: FeatureSet, space: spaces.Space) -> None:
    """TypeError unless the features read this environment's observation (`space`, one
    instance's): gpfd's environments by name and variables, others by size."""
    base = env.unwrapped
    if hasattr(base, "gpfd_name"):
        if features.env and features.env != base.gpfd_name:
            raise TypeError(
                f"the features are for {features.env}, the environment is {base.gpfd_name}"
            )
        if list(base.state_names) != list(features.variables):
            raise TypeError(
                f"the features read {', '.join(features.variables)}; the environment's "
                f"observation is {', '.join(base.state_names)}"
            )
        return
    if not isinstance(space, spaces.Box):
        raise TypeError(f"gpfd needs a Box observation space, not {space}")
    if int(np.prod(space.shape)) != features.input_dim:
        raise TypeError(
            f"the features read {features.input_dim} values ({', '.join(features.variables)}); "
            f"the observation has {int(np.prod(space.shape))}"
        )


class FeatureObservation(gym.ObservationWrapper, gym.utils.RecordConstructorArgs):
    """Observations become ``features(obs)`` (float64), followed by the original observation when
    ``with_original``: what gpfd's learners see in discovery.

    Example::

        env = FeatureObservation(gymnasium.make("CartPole-v1"), run.best, with_original=True)
        obs, info = env.reset(seed=0)  # the features, then the 4 state variables
    """

    def __init__(self, env: gym.Env, features: FeatureSet, with_original: bool = False):
        gym.utils.RecordConstructorArgs.__init__(
            self, features=features, with_original=with_original
        )
        gym.ObservationWrapper.__init__(self, env)
        check_features(env, features, env.observation_space)
        self.features = features
        self.with_original = with_original
        self.observation_space = _feature_space(features, with_original, env.observation_space)

    def observation(self, observation):
        state = np.ascontiguousarray(observation, dtype=np.float64).reshape(-1)
        phi = self.features(state)
        return np.concatenate([phi, state]) if self.with_original else phi


class VectorFeatureObservation(VectorObservationWrapper):
    """FeatureObservation for a vector environment: one batch-kernel call per step.

    Example::

        envs = VectorFeatureObservation(gymnasium.make_vec("gpfd/CartPole-v0", 64), run.best)
        obs, info = envs.reset(seed=0)  # 64 rows of features
    """

    def __init__(self, env: VectorEnv, features: FeatureSet, with_original: bool = False):
        super().__init__(env)
        single = env.single_observation_space
        check_features(env, features, single)
        self.features = features
        self.with_original = with_original
        self.single_observation_space = _feature_space(features, with_original, single)
        self.observation_space = batch_space(self.single_observation_space, env.num_envs)

    def observations(self, observations):
        states = np.ascontiguousarray(observations, dtype=np.float64).reshape(self.num_envs, -1)
        phi = self.features(states)
        return np.concatenate([phi, states], axis=1) if self.with_original else phi
