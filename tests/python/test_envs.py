"""gpfd's environments in Gymnasium: registration, keywords, check_env, seeding, Tetris, vectors."""

import subprocess
import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env
from gymnasium.vector import AutoresetMode, SyncVectorEnv

import gpfd
from conftest import gpfd_env
from gpfd import _core
from gpfd.envs import gym_id
from gpfd.user_env import is_builtin

VARIANTS = [
    ("gpfd/Acrobot-v0", {}),
    ("gpfd/Acrobot-v0", {"actions": "discrete", "integrator": "euler", "substeps": 4}),
    ("gpfd/CartPole-v0", {}),
    ("gpfd/CartPole-v0", {"actions": "discrete", "max_steps": 500}),
    ("gpfd/Swimmer-v0", {}),
    ("gpfd/Swimmer-v0", {"segments": 5}),
    ("gpfd/Tetris-v0", {}),
    ("gpfd/Tetris-v0", {"rows": 20, "cols": 10, "state": "bertsekas"}),
]


def test_every_gpfd_environment_is_registered():
    # Environments registered from Python (gpfd.user_env, by other tests too) get no gpfd/ id.
    for name in filter(is_builtin, _core.env_names()):
        assert gym_id(name) in gym.registry
    assert {gym_id(n) for n in ("acrobot", "cartpole", "swimmer", "tetris")} == {
        "gpfd/Acrobot-v0",
        "gpfd/CartPole-v0",
        "gpfd/Swimmer-v0",
        "gpfd/Tetris-v0",
    }


# The only warnings check_env may give: unbounded observations (the state variables have no
# bounds; Gymnasium's CartPole has the same) and, for the wrapped environment, the wrappers.
ACCEPTED = (
    "A Box observation space m",
    "For Box action spaces, we recommend",
    "is different from the unwrapped version",
)


@pytest.mark.parametrize("env_id,params", VARIANTS)
def test_check_env_passes(env_id, params):
    env = gym.make(env_id, **params)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
        check_env(env)  # Through Gymnasium's wrappers as well.
    unexpected = [str(w.message) for w in caught if not any(a in str(w.message) for a in ACCEPTED)]
    assert not unexpected


@pytest.mark.parametrize("name", ["acrobot", "cartpole", "swimmer", "tetris"])
def test_every_parameter_of_gpfd_envs_is_a_keyword(name):
    defaults = {p: default for p, default, _ in _core.env_params(name)}
    env = gym.make(gym_id(name), **defaults)
    # Every parameter, typed (test_env_options.py), as an environment made without keywords has.
    assert sorted(gpfd_env(env).params) == sorted(defaults)
    assert gpfd_env(env).params == gpfd_env(gym.make(gym_id(name))).params
    assert gpfd_env(env).gpfd_name == name


def test_keyword_values_reach_the_environment():
    env = gym.make("gpfd/Swimmer-v0", segments=np.int64(4), dt=0.05, max_torque=2)
    assert env.observation_space.shape == (10,)
    assert gpfd_env(env).params["dt"] == 0.05
    assert isinstance(env.action_space, gym.spaces.Box)
    assert env.action_space.high.tolist() == [2.0, 2.0, 2.0]
    assert gym.make("gpfd/CartPole-v0", actions="discrete").action_space == gym.spaces.Discrete(2)


def test_unknown_keywords_and_bad_values_are_refused():
    with pytest.raises(
        TypeError,
        match=r"gpfd/CartPole-v0 got unknown keyword 'lenght'; its parameters are: gravity",
    ):
        gym.make("gpfd/CartPole-v0", lenght=1.0)
    with pytest.raises(gpfd.InputError, match=r"\(swimmer.segments\)"):
        gym.make("gpfd/Swimmer-v0", segments=1)
    with pytest.raises(gpfd.InputError, match=r"tetris.state"):
        gym.make("gpfd/Tetris-v0", state="pixels")
    with pytest.raises(
        TypeError, match="parameter 'dt' must be a number, a bool or a string, not list"
    ):
        gym.make("gpfd/CartPole-v0", dt=[0.1])


def test_seeding_follows_gymnasiums_rules():
    env = gym.make("gpfd/Acrobot-v0")
    first, _ = env.reset(seed=42)
    second, _ = env.reset()
    assert not np.array_equal(first, second)  # reset() continues the stream.
    again, _ = env.reset(seed=42)
    assert np.array_equal(first, again)
    assert np.array_equal(env.reset()[0], second)
    other = gym.make("gpfd/Acrobot-v0")
    unseeded = [other.reset()[0] for _ in range(2)]
    assert not np.array_equal(unseeded[0], unseeded[1])
    fresh = gym.make("gpfd/Acrobot-v0").reset()[0]
    assert not np.array_equal(fresh, unseeded[0])  # Fresh entropy per environment.


@pytest.mark.parametrize("name", ["acrobot", "cartpole", "swimmer", "tetris"])
def test_a_seed_starts_where_gpfd_simulate_starts(cli, name):
    csv = subprocess.run(
        [cli, "simulate", name, "--seed", "7", "--policy", "random", "--steps", "1"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout.splitlines()
    header, row0 = csv[0].split(","), csv[1].split(",")
    env = gym.make(gym_id(name))
    obs, _ = env.reset(seed=7)
    names = gpfd_env(env).state_names
    expected = [float(row0[header.index(n)]) for n in names]
    assert obs.tolist() == expected


def test_state_can_be_read_and_set():
    env = gpfd_env(gym.make("gpfd/CartPole-v0"))
    env.reset(seed=1)
    env.set_state([0.1, 0.0, -0.05, 0.2])
    assert env.state.tolist() == [0.1, 0.0, -0.05, 0.2]
    obs, _ = env.reset(seed=3, options={"state": [0.0, 1.0, 0.0, 0.0]})
    assert obs.tolist() == [0.0, 1.0, 0.0, 0.0]
    with pytest.raises(ValueError, match="4 state variables"):
        env.set_state([1.0, 2.0])


def test_discrete_actions_out_of_range_are_refused():
    env = gym.make("gpfd/CartPole-v0", actions="discrete").unwrapped
    env.reset(seed=0)
    with pytest.raises(gpfd.InputError, match="integer in 0..1, got 2"):
        env.step(2)
    with pytest.raises(gpfd.InputError, match="an action has 2 components, got 3 values"):
        gym.make("gpfd/Swimmer-v0").unwrapped.step([0.0, 1.0, 2.0])


def test_tetris_maps_actions_to_legal_placements():
    env = gpfd_env(gym.make("gpfd/Tetris-v0"))
    _, info = env.reset(seed=3)
    mask = info["action_mask"]
    assert mask.shape == (4, 8) and mask.dtype == bool
    after = env.afterstates()
    legal = {tuple(a) for a in after["actions"]}
    assert legal == {(o, c) for o in range(4) for c in range(8) if mask[o, c]}
    assert after["features"].shape == (len(legal), 18)
    # Any action is accepted; an illegal one acts like the nearest legal placement.
    clone = gym.make("gpfd/Tetris-v0").unwrapped
    clone.reset(seed=3)
    obs, *_ = env.step(np.array([3, 7]))
    orientations = int(mask.any(axis=1).sum())
    o = 3 % orientations
    c = int(np.flatnonzero(mask[o]).max()) if np.flatnonzero(mask[o]).max() < 7 else 7
    assert np.array_equal(clone.step(np.array([o, c]))[0], obs)
    with pytest.raises(gpfd.InputError, match="orientation is a non-negative integer, got -1"):
        env.step(np.array([-1, 0]))


def sync_of(env_id, n, **params):
    return SyncVectorEnv([lambda: gym.make(env_id, **params) for _ in range(n)])


@pytest.mark.parametrize(
    "env_id,params",
    [
        ("gpfd/CartPole-v0", {"actions": "discrete", "max_steps": 60}),
        ("gpfd/Acrobot-v0", {"max_steps": 40}),
        ("gpfd/Tetris-v0", {"rows": 8, "cols": 6}),
    ],
)
def test_vector_environment_equals_gymnasiums_sync_vector_env(env_id, params):
    n = 8
    ours = gym.make_vec(env_id, num_envs=n, **params)
    assert type(ours.unwrapped).__name__ == "GpfdVectorEnv"
    theirs = sync_of(env_id, n, **params)
    assert ours.single_observation_space == theirs.single_observation_space
    assert ours.action_space == theirs.action_space
    a, _ = ours.reset(seed=11)
    b, _ = theirs.reset(seed=11)
    assert np.array_equal(a, b)
    theirs.action_space.seed(5)
    ended = 0
    for _ in range(150):
        action = theirs.action_space.sample()
        got = ours.step(action)
        want = theirs.step(action)
        for x, y in zip(got[:4], want[:4], strict=True):
            assert np.array_equal(x, y)
        ended += int(np.sum(got[2] | got[3]))
    assert ended > 0  # Autoresets happened.


def test_same_step_autoreset_reports_the_final_observation():
    ours = gym.make_vec(
        "gpfd/CartPole-v0",
        num_envs=4,
        actions="discrete",
        max_steps=5,
        autoreset_mode=AutoresetMode.SAME_STEP,
    )
    assert ours.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    ours.reset(seed=0)
    single = gym.make("gpfd/CartPole-v0", actions="discrete", max_steps=5)
    single.reset(seed=2)
    for _ in range(5):
        obs, _, _, truncated, info = ours.step(np.ones(4, dtype=np.int64))
        last, *_ = single.step(1)
    assert truncated.all() and info["_final_obs"].all()
    assert np.array_equal(info["final_obs"][2], last)
    assert np.array_equal(obs[2], single.reset()[0])  # Reset at once, continuing the stream.


def test_reset_mask_resets_only_the_masked_instances():
    ours = gym.make_vec("gpfd/Swimmer-v0", num_envs=3)
    start, _ = ours.reset(seed=1)
    moved, *_ = ours.step(np.ones((3, 2)))
    again, _ = ours.reset(seed=1, options={"reset_mask": np.array([True, False, True])})
    assert np.array_equal(again[0], start[0]) and np.array_equal(again[2], start[2])
    assert np.array_equal(again[1], moved[1])


def test_vector_actions_of_the_wrong_size_are_refused():
    ours = gym.make_vec("gpfd/CartPole-v0", num_envs=4, actions="discrete")
    ours.reset(seed=0)
    with pytest.raises(gpfd.InputError, match="expected 4 actions of 1 component"):
        ours.step(np.zeros(3))
    with pytest.raises(gpfd.InputError, match="action of environment 2"):
        ours.step(np.array([0, 1, 5, 0]))
    with pytest.raises(TypeError, match="unknown keyword 'segments'"):
        gym.make_vec("gpfd/CartPole-v0", num_envs=2, segments=3)
