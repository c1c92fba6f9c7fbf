"""gpfd's vector environment on its batched engine (one call of env/batch.hpp per step) against its
loop engine (one scalar environment per instance, the reference): the same observations, rewards,
flags, final observations and states, bit for bit, in every autoreset mode, over episodes that end
by termination and by the time limit, with states set in the middle of episodes."""

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode, SyncVectorEnv

import gpfd
from conftest import gpfd_env
from gpfd.vector import GpfdVectorEnv

MODES = [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP, AutoresetMode.DISABLED]


def near_terminal(name, rng, dim):
    """A state from which a few steps end the episode: cart-pole at the edge of the track, Acrobot
    with its tip near the goal height; the swimmer (which never terminates) anywhere."""
    if name == "cartpole":
        return np.array([rng.choice([-2.39, 2.39]), rng.normal(), rng.uniform(-0.2, 0.2), 0.0])
    if name == "acrobot":
        return np.array([np.pi + rng.uniform(-1.1, 1.1), rng.uniform(-0.4, 0.4), 0.0, 0.0])
    return rng.uniform(-2.0, 2.0, size=dim)


def random_actions(env, rng, n):
    """Random legal discrete choices; continuous ones beyond the bounds (clipped)."""
    space = env.single_action_space
    if isinstance(space, gym.spaces.Discrete):
        return rng.integers(0, space.n, size=n)
    return rng.uniform(-1.5, 1.5, size=(n, *space.shape)) * space.high


def assert_same(got, want, what):
    assert got.dtype == want.dtype, what
    assert np.array_equal(got, want, equal_nan=True), what
    # Bit for bit: the same doubles, -0.0 and the NaN payloads included.
    assert got.tobytes() == want.tobytes(), what


CASES = [
    ("cartpole", {"max_steps": 40}),
    ("cartpole", {"actions": "discrete", "max_steps": 30, "integrator": "rk4"}),
    ("acrobot", {"max_steps": 25}),
    ("acrobot", {"actions": "discrete", "max_steps": 30, "dynamics": "nips"}),
    ("swimmer", {"segments": 3, "horizon": 20}),
    ("swimmer", {"segments": 5, "horizon": 15}),
]


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.value)
@pytest.mark.parametrize("name,params", CASES, ids=lambda c: str(c))
def test_batched_engine_equals_the_loop_engine(name, params, mode):
    n, steps = 7, 240  # 7: a partial group of AVX2 lanes.
    batched = GpfdVectorEnv(name, num_envs=n, autoreset_mode=mode, engine="batched", **params)
    loop = GpfdVectorEnv(name, num_envs=n, autoreset_mode=mode, engine="loop", **params)
    assert (batched.engine, loop.engine) == ("batched", "loop")
    dim = len(batched.state_names)
    rng = np.random.default_rng(17)
    a, _ = batched.reset(seed=5)
    b, _ = loop.reset(seed=5)
    assert_same(a, b, "reset")
    terminated = truncated = 0
    for t in range(steps):
        actions = random_actions(batched, rng, n)
        got = batched.step(actions)
        want = loop.step(actions)
        for i, what in enumerate(("obs", "rewards", "terminated", "truncated")):
            assert_same(got[i], want[i], f"{what} at step {t}")
        assert_same_info(got[4], want[4], f"info at step {t}")  # final_obs under same-step.
        terminated += int(got[2].sum())
        truncated += int(got[3].sum())
        ended = got[2] | got[3]
        if mode == AutoresetMode.DISABLED and ended.any():
            a, _ = batched.reset(options={"reset_mask": ended})
            b, _ = loop.reset(options={"reset_mask": ended})
            assert_same(a, b, f"reset_mask at step {t}")
        if t % 9 == 4:  # A state set mid-episode restarts the time limit's step count too.
            i = int(rng.integers(n))
            state = near_terminal(name, rng, dim)
            batched._core.set_state(i, state)
            loop._core.set_state(i, state)
        assert_same(batched.states, loop.states, f"states at step {t}")
    assert truncated > 0
    if name != "swimmer":
        assert terminated > 0


def assert_same_info(got, want, what):
    """Infos as SyncVectorEnv gives them: the same keys, each value's presence array, stacked
    arrays bit for bit, final_obs an object array (None where no episode ended), nested dicts
    (final_info) alike."""
    assert sorted(got) == sorted(want), what
    for key, value in want.items():
        mine = got[key]
        if isinstance(value, dict):
            assert_same_info(mine, value, f"{what}: {key}")
        elif value.dtype == object:
            assert mine.dtype == object, f"{what}: {key}"
            for i, row in enumerate(value):
                assert (row is None) == (mine[i] is None), f"{what}: {key}[{i}]"
                if row is not None:
                    assert_same(mine[i], row, f"{what}: {key}[{i}]")
        else:
            assert_same(mine, value, f"{what}: {key}")


def assert_equals_sync_vector_env(env_id, n, params, mode, steps, seed):
    """gpfd's vector environment against N of gpfd's single Gymnasium environments, as Gymnasium
    itself vectorises them, under the same random actions: observations, rewards, flags and infos;
    returns gpfd's vector environment."""
    ours = gym.make_vec(env_id, num_envs=n, autoreset_mode=mode, **params)
    theirs = SyncVectorEnv(
        [lambda: gym.make(env_id, **params) for _ in range(n)], autoreset_mode=mode
    )
    got_reset = ours.reset(seed=seed)
    want_reset: tuple[Any, ...] = theirs.reset(seed=seed)
    assert_same(got_reset[0], want_reset[0], "reset")
    assert_same_info(got_reset[1], want_reset[1], "reset info")
    theirs.action_space.seed(seed)
    ended = 0
    for t in range(steps):
        action = theirs.action_space.sample()
        got = ours.step(action)
        want: tuple[Any, ...] = theirs.step(action)  # SyncVectorEnv leaves its types open.
        for i in range(4):
            assert_same(np.asarray(got[i]), np.asarray(want[i]), f"output {i} at step {t}")
        assert_same_info(got[4], want[4], f"info at step {t}")
        done = got[2] | got[3]
        ended += int(done.sum())
        if mode == AutoresetMode.DISABLED and done.any():
            got_reset = ours.reset(options={"reset_mask": done})
            want_reset = theirs.reset(options={"reset_mask": done})
            assert_same_info(got_reset[1], want_reset[1], f"reset info at step {t}")
    assert ended > 0
    return ours.unwrapped


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.value)
def test_batched_engine_equals_single_environments_under_sync_vector_env(mode):
    params = {"actions": "discrete", "max_steps": 25}
    ours = assert_equals_sync_vector_env("gpfd/CartPole-v0", 5, params, mode, 150, 3)
    assert ours.engine == "batched"


def test_time_limit_counts_from_reset_and_from_set_state():
    env = GpfdVectorEnv("swimmer", num_envs=3, engine="batched", horizon=4)
    env.reset(seed=0)
    for _ in range(2):
        env.step(np.zeros((3, 2)))
    env._core.set_state(1, np.zeros(8))
    flags = [env.step(np.zeros((3, 2)))[3].tolist() for _ in range(4)]
    assert flags == [
        [False, False, False],
        [True, False, True],
        [False, False, False],  # 0 and 2 start again (next-step autoreset).
        [False, True, False],
    ]


def test_the_batched_engine_serves_what_has_a_batched_form():
    def engine(name, **params):
        return GpfdVectorEnv(name, num_envs=2, **params).engine

    assert engine("cartpole") == engine("acrobot") == "batched"
    assert engine("swimmer", segments=3) == engine("swimmer", segments=8) == "batched"
    assert engine("swimmer", segments=9) == "loop"  # Beyond the fixed-size kernel.
    assert engine("tetris") == "loop"
    assert gym.make_vec("gpfd/Swimmer-v0", num_envs=2, engine="loop").unwrapped.engine == "loop"
    with pytest.raises(gpfd.InputError, match="tetris has no batched form"):
        GpfdVectorEnv("tetris", num_envs=2, engine="batched")
    with pytest.raises(gpfd.InputError, match="unknown engine 'fast'"):
        GpfdVectorEnv("cartpole", num_envs=2, engine="fast")


def test_set_state_and_errors_on_the_batched_engine():
    env = GpfdVectorEnv("cartpole", num_envs=6, engine="batched", actions="discrete")
    env.reset(seed=1)
    env._core.set_state(4, np.array([0.1, 0.2, 0.3, 0.4]))
    assert env._core.state(4).tolist() == [0.1, 0.2, 0.3, 0.4]
    assert env.states[4].tolist() == [0.1, 0.2, 0.3, 0.4]
    with pytest.raises(gpfd.InputError, match="cartpole state must be finite"):
        env._core.set_state(2, np.array([0.0, np.nan, 0.0, 0.0]))
    with pytest.raises(gpfd.InputError, match="cartpole takes 4 state variables, got 2"):
        env._core.set_state(2, np.array([0.0, 0.0]))
    with pytest.raises(IndexError):
        env._core.state(6)
    with pytest.raises(IndexError):
        env._core.set_state(6, np.zeros(4))
    before = env.states
    with pytest.raises(gpfd.InputError, match="action of environment 3"):
        env.step(np.array([0, 1, 0, 2, 0, 1]))
    assert np.array_equal(env.states, before)  # Nothing moved.
    with pytest.raises(gpfd.InputError, match="afterstates exist for Tetris only"):
        env._core.afterstates(0)
    assert env._core.action_mask(0).tolist() == [True, True]  # Not state-dependent: all legal.


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.value)
def test_tetris_steps_on_the_loop_engine(mode):
    params: dict[str, Any] = {"rows": 8, "cols": 6}
    ours = assert_equals_sync_vector_env("gpfd/Tetris-v0", 4, params, mode, 120, 2)
    assert ours.engine == "loop"
    single = gpfd_env(gym.make("gpfd/Tetris-v0", **params))
    single.reset(seed=1)
    assert len(single.afterstates()["actions"]) > 0


def test_tetris_vector_info_has_the_action_mask():
    """Issue 27.6: the vector environment's reset gave {}."""
    envs = gym.make_vec("gpfd/Tetris-v0", num_envs=2)
    _, info = envs.reset(seed=0)
    assert info["action_mask"].shape == (2, 4, 8) and info["action_mask"].dtype == bool
    assert info["_action_mask"].tolist() == [True, True]
    single = gym.make("gpfd/Tetris-v0")
    assert np.array_equal(info["action_mask"][1], single.reset(seed=1)[1]["action_mask"])
    _, info = envs.reset(options={"reset_mask": np.array([False, True])})
    assert info["_action_mask"].tolist() == [False, True]
    assert not info["action_mask"][0].any()  # As SyncVectorEnv leaves an instance not reset.
