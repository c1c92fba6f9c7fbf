"""What a Gymnasium user passes to gpfd's environments and reads back: the autoreset mode as an enum
or a string, typed parameters, NaN actions refused, the action space derived from gpfd's own, and
the CartPole-v1 task under its own id."""

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import gpfd
from conftest import gpfd_env
from gpfd import _core


@pytest.mark.parametrize(
    "given,mode",
    [
        (AutoresetMode.SAME_STEP, AutoresetMode.SAME_STEP),
        ("SameStep", AutoresetMode.SAME_STEP),
        ("same_step", AutoresetMode.SAME_STEP),
        ("SAME_STEP", AutoresetMode.SAME_STEP),
        ("next_step", AutoresetMode.NEXT_STEP),
        ("Disabled", AutoresetMode.DISABLED),
    ],
)
def test_autoreset_mode_is_the_enum_its_value_or_its_name(given, mode):
    env = gym.make_vec("gpfd/CartPole-v0", num_envs=2, autoreset_mode=given)
    assert env.metadata["autoreset_mode"] == mode


def test_an_unknown_autoreset_mode_names_the_accepted_ones():
    with pytest.raises(ValueError, match="autoreset_mode 'sometimes' is not one of 'NextStep'"):
        gym.make_vec("gpfd/CartPole-v0", num_envs=2, autoreset_mode="sometimes")


def test_params_are_typed_as_declared():
    params = gpfd_env(gym.make("gpfd/CartPole-v0", max_steps=500)).params
    assert params["max_steps"] == 500 and type(params["max_steps"]) is int
    assert params["dt"] == 0.02 and type(params["dt"]) is float
    assert params["actions"] == "continuous"
    vector = gym.make_vec("gpfd/Tetris-v0", num_envs=2, rows=10).unwrapped
    assert vector.params["rows"] == 10 and type(vector.params["rows"]) is int
    # They round-trip through gym.make.
    again = gpfd_env(gym.make("gpfd/CartPole-v0", **params))
    assert again.params == params


def test_a_flag_parameter_is_a_bool():
    flags = {
        (name, param)
        for name in ("acrobot", "cartpole", "swimmer", "tetris")
        for param, default, _ in _core.env_params(name)
        if default in ("true", "false")
    }
    for name, param in flags:
        value = gpfd_env(gym.make(gpfd.envs.gym_id(name))).params[param]
        assert type(value) is bool, (name, param)


@pytest.mark.parametrize("env_id", ["gpfd/CartPole-v0", "gpfd/Swimmer-v0"])
def test_a_nan_action_is_refused(env_id):
    env = gym.make(env_id)
    env.reset(seed=0)
    state = gpfd_env(env).state
    nan = np.full(gpfd_env(env).action_space.sample().shape, np.nan)
    with pytest.raises(ValueError, match="is NaN; an action is a number"):
        env.step(nan)
    assert np.array_equal(gpfd_env(env).state, state)  # Nothing moved.
    vector = gym.make_vec(env_id, num_envs=3)
    vector.reset(seed=0)
    actions = np.zeros_like(vector.action_space.sample())
    actions[1] = np.nan
    with pytest.raises(ValueError, match="action of environment 1"):
        vector.step(actions)


def test_a_nan_discrete_action_is_refused():
    env = gym.make("gpfd/CartPole-v0", actions="discrete")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="is a non-negative integer, got nan"):
        env.step(np.nan)


@pytest.mark.parametrize(
    "env_id,params,choices,space",
    [
        ("gpfd/CartPole-v0", {"actions": "discrete"}, [2], gym.spaces.Discrete(2)),
        ("gpfd/Acrobot-v0", {"actions": "discrete"}, [3], gym.spaces.Discrete(3)),
        ("gpfd/Tetris-v0", {"cols": 6}, [4, 6], gym.spaces.MultiDiscrete([4, 6])),
    ],
)
def test_the_action_space_comes_from_the_environments_own(env_id, params, choices, space):
    env = gym.make(env_id, **params)
    core = gpfd_env(env)._core
    assert list(core.action_choices) == choices
    assert env.action_space == space
    assert not hasattr(core, "action_kind") and not hasattr(core, "tetris_columns")
    _, info = env.reset(seed=1)
    assert core.state_dependent_actions == ("action_mask" in info)
    # Every discrete space has a mask: all legal where the legal actions do not depend on the state.
    mask = core.action_mask(0)
    assert mask.shape == tuple(core.action_choices) and mask.dtype == bool
    assert mask.all() != core.state_dependent_actions


def test_a_continuous_space_has_no_mask():
    core = gpfd_env(gym.make("gpfd/CartPole-v0"))._core
    assert list(core.action_choices) == [] and not core.state_dependent_actions
    with pytest.raises(gpfd.InputError, match="cartpole has continuous actions"):
        core.action_mask(0)


def test_gymnasium_cartpole_v1_is_the_discrete_500_step_task():
    env = gym.make("gpfd/GymnasiumCartPole-v1")
    assert env.spec is not None and env.spec.reward_threshold == 475.0
    theirs = gym.spec("CartPole-v1")
    assert env.spec.reward_threshold == theirs.reward_threshold
    params = gpfd_env(env).params
    assert params["actions"] == "discrete" and params["max_steps"] == 500
    assert env.action_space == gym.spaces.Discrete(2)
    # The same trajectory as gpfd/CartPole-v0 with those keywords, up to the time limit.
    same = gym.make("gpfd/CartPole-v0", actions="discrete", max_steps=500)
    a, _ = env.reset(seed=4)
    b, _ = same.reset(seed=4)
    steps = 0
    while True:
        action = int(a[2] + 0.5 * a[3] > 0)
        a, ra, ta, ua, _ = env.step(action)
        b, rb, tb, ub, _ = same.step(action)
        assert np.array_equal(a, b) and (ra, ta, ua) == (rb, tb, ub)
        steps += 1
        if ta or ua:
            break
    assert steps == 500 and ua  # A balancing policy reaches CartPole-v1's limit.
    vector = gym.make_vec("gpfd/GymnasiumCartPole-v1", num_envs=2)
    assert vector.unwrapped.params["max_steps"] == 500
