"""gpfd.sb3: gpfd's vector environments as Stable-Baselines3 VecEnvs (scripts/sb3-example runs
these; the default test run has no SB3 and skips them)."""

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

sb3_vec_env = pytest.importorskip("stable_baselines3.common.vec_env")

import gpfd  # noqa: E402
import gpfd.sb3  # noqa: E402

TASK: dict[str, Any] = {"actions": "discrete", "max_steps": 30}
CONTINUOUS: dict[str, Any] = {"actions": "continuous", "max_steps": 30}


def features() -> gpfd.FeatureSet:
    return gpfd.FeatureSet.parse("dth + th\nx * dx", env="cartpole")


def run(venv, actions: list[np.ndarray]):
    """Every step's (obs, rewards, dones, terminal observations) after a reset."""
    out = [venv.reset().astype(np.float64)]
    for a in actions:
        obs, rewards, dones, infos = venv.step(a)
        terminal = [infos[i].get("terminal_observation") for i in range(venv.num_envs)]
        out.append((obs.astype(np.float64), rewards, dones, terminal))
    return out


def assert_steps_alike(got, want) -> int:
    """Two runs' steps are the same; how many episodes ended in them."""
    np.testing.assert_array_equal(got[0], want[0])
    ended = 0
    for (o1, r1, d1, t1), (o2, r2, d2, t2) in zip(got[1:], want[1:], strict=True):
        np.testing.assert_array_equal(o1, o2)
        np.testing.assert_array_equal(r1, r2)
        np.testing.assert_array_equal(d1, d2)
        for i in np.flatnonzero(d2):
            np.testing.assert_array_equal(t1[i], t2[i])
            ended += 1
    return ended


def test_the_adapter_steps_as_sb3s_own_dummy_vec_env():
    n, rng = 3, np.random.default_rng(0)
    actions = [rng.integers(0, 2, n) for _ in range(120)]
    ours = gpfd.sb3.make_vec_env("gpfd/CartPole-v0", n, seed=7, env_kwargs=TASK, float32=False)
    theirs = sb3_vec_env.DummyVecEnv([lambda: gym.make("gpfd/CartPole-v0", **TASK)] * n)
    theirs.seed(7)
    ended = assert_steps_alike(run(ours, actions), run(theirs, actions))
    assert ended >= n  # Every instance ended at least one episode (30 steps at most).


def test_observations_are_the_features_in_float32_by_default():
    fs = features()
    raw = gpfd.sb3.make_vec_env("gpfd/CartPole-v0", 4, seed=3, env_kwargs=TASK, float32=False)
    seen = gpfd.sb3.make_vec_env("gpfd/CartPole-v0", 4, seed=3, features=fs, env_kwargs=TASK)
    assert seen.observation_space.shape == (2,) and seen.observation_space.dtype == np.float32
    obs = seen.reset()
    assert obs.dtype == np.float32
    np.testing.assert_array_equal(obs, fs(raw.reset()).astype(np.float32))
    both = gpfd.sb3.make_vec_env(
        "gpfd/CartPole-v0", 4, seed=3, features=fs, with_original=True, env_kwargs=TASK
    )
    assert both.reset().shape == (4, 6)


def test_rescaled_actions_map_minus_one_and_one_onto_the_force_bounds():
    venv = gpfd.sb3.make_vec_env(
        "gpfd/CartPole-v0", 2, seed=1, env_kwargs=CONTINUOUS, rescale_actions=True
    )
    assert venv.action_space == gym.spaces.Box(-1.0, 1.0, (1,), np.float32)
    reference = gym.make_vec(
        "gpfd/CartPole-v0", 2, autoreset_mode=gym.vector.AutoresetMode.SAME_STEP, **CONTINUOUS
    )
    venv.reset()
    reference.reset(seed=[1, 2])  # type: ignore[arg-type]  # One seed per instance (gpfd's).
    for unit, force in ((1.0, 10.0), (-1.0, -10.0), (0.5, 5.0), (7.0, 10.0)):
        obs, *_ = venv.step(np.full((2, 1), unit, np.float32))
        expected, *_ = reference.step(np.full((2, 1), force))
        np.testing.assert_array_equal(obs, expected.astype(np.float32))


def test_a_vector_env_in_next_step_autoreset_is_refused():
    vector = gym.make_vec("gpfd/CartPole-v0", 2)
    with pytest.raises(ValueError, match="same-step autoreset"):
        gpfd.sb3.GpfdVecEnv(vector)


@pytest.mark.parametrize("n_envs", [0, -1, 2.0])
def test_a_bad_number_of_environments_is_an_input_error_naming_it(n_envs):
    with pytest.raises(gpfd.InputError, match=r"\(n_envs=\)"):
        gpfd.sb3.make_vec_env("CartPole-v1", n_envs)


def test_features_for_another_environment_are_refused():
    with pytest.raises(TypeError, match="features are for cartpole"):
        gpfd.sb3.make_vec_env("gpfd/Acrobot-v0", 2, features=features())


def test_ppo_learns_through_the_adapter():
    ppo = pytest.importorskip("stable_baselines3").PPO
    venv = gpfd.sb3.make_vec_env(
        "gpfd/CartPole-v0", 4, seed=0, features=features(), env_kwargs=TASK
    )
    model = ppo("MlpPolicy", venv, n_steps=64, batch_size=64, seed=0, device="cpu")
    model.learn(total_timesteps=512)
    actions, _ = model.predict(venv.reset(), deterministic=True)
    assert actions.shape == (4,)


@pytest.mark.parametrize("native", [False, True])
def test_a_gymnasium_id_whose_native_vector_form_is_next_step_is_stepped_in_sync(native):
    """Gymnasium's CartPole-v1 has a native vector form in next-step autoreset only: the adapter
    steps it as SB3's own DummyVecEnv of gym.make would (native=False), and so do gpfd's twins
    (native)."""
    n, rng = 2, np.random.default_rng(1)
    actions = [rng.integers(0, 2, n) for _ in range(80)]
    ours = gpfd.sb3.make_vec_env("CartPole-v1", n, seed=5, float32=False, native=native)
    theirs = sb3_vec_env.DummyVecEnv([lambda: gym.make("CartPole-v1")] * n)
    theirs.seed(5)
    ended = assert_steps_alike(run(ours, actions), run(theirs, actions))
    assert ended >= n  # Random actions end a CartPole-v1 episode within about 20-40 steps.
