"""gpfd.wrappers: discovered features as a Gymnasium observation."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.envs.classic_control import PendulumEnv
from gymnasium.utils.env_checker import check_env

import gpfd
from conftest import gpfd_env
from gpfd.wrappers import FeatureObservation, VectorFeatureObservation

FEATURES = gpfd.FeatureSet.parse("th * dth\nsin(x) - dx / 2\nth\n", env="cartpole")


@pytest.mark.filterwarnings("ignore:.*different from the unwrapped version")
@pytest.mark.filterwarnings("ignore:.*For Box action spaces, we recommend")
def test_the_observation_is_the_features_of_the_state():
    env = FeatureObservation(gym.make("gpfd/CartPole-v0"), FEATURES)
    assert env.observation_space.shape == (3,) and env.observation_space.dtype == np.float64
    obs, _ = env.reset(seed=4)
    assert np.array_equal(obs, FEATURES(gpfd_env(env).state))
    obs, *_ = env.step(np.array([1.0]))
    assert np.array_equal(obs, FEATURES(gpfd_env(env).state))
    assert obs in env.observation_space
    check_env(env, skip_render_check=True)


def test_with_original_appends_the_state():
    env = FeatureObservation(gym.make("gpfd/CartPole-v0"), FEATURES, with_original=True)
    obs, _ = env.reset(seed=1)
    assert env.observation_space.shape == (7,)
    assert np.array_equal(obs[3:], gpfd_env(env).state)


def test_a_gymnasium_environment_with_float32_observations():
    fs = gpfd.FeatureSet.parse("x0 * x1\nx2\n", env=gym.make("Pendulum-v1"))
    env = FeatureObservation(gym.make("Pendulum-v1"), fs)
    obs, _ = env.reset(seed=0)
    pendulum = env.unwrapped
    assert isinstance(pendulum, PendulumEnv)
    raw = pendulum._get_obs().astype(np.float64)
    assert np.array_equal(obs, fs(raw))


def test_features_of_another_environment_are_refused():
    with pytest.raises(
        TypeError, match="the features are for cartpole, the environment is acrobot"
    ):
        FeatureObservation(gym.make("gpfd/Acrobot-v0"), FEATURES)
    with pytest.raises(TypeError, match="the features read 4 values"):
        FeatureObservation(gym.make("Pendulum-v1"), FEATURES)


def test_vector_wrapper_uses_one_batch_call():
    envs = VectorFeatureObservation(gym.make_vec("gpfd/CartPole-v0", num_envs=16), FEATURES)
    obs: np.ndarray  # Gymnasium's vector wrappers leave the observation type open.
    obs, _ = envs.reset(seed=0)
    assert obs.shape == (16, 3) and envs.single_observation_space.shape == (3,)
    assert np.array_equal(obs, FEATURES(envs.unwrapped.states))
    obs, *_ = envs.step(np.zeros((16, 1)))
    assert np.array_equal(obs, FEATURES(envs.unwrapped.states))
