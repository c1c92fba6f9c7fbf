"""Pickling and copying gpfd's environments mid-episode (EnvBatch.__getstate__ / __setstate__ over
Environment::snapshot): after pickle, copy.deepcopy or a trip to a spawned process, the copy
steps exactly as the original, bit for bit, random streams and step counts included."""

import copy
import multiprocessing
import pickle
from concurrent.futures import ProcessPoolExecutor
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import gpfd  # noqa: F401  (registers the gpfd/ ids)
from conftest import gpfd_env
from gpfd import _core
from gpfd.user_env import register

# Short time limits, so that the steps after the copy cross episode ends (resets draw from the
# environment's stream, the time limit reads the step count).
VARIANTS: list[tuple[str, dict[str, Any]]] = [
    ("gpfd/Acrobot-v0", {"max_steps": 40}),
    ("gpfd/CartPole-v0", {"max_steps": 30}),
    ("gpfd/CartPole-v0", {"actions": "discrete", "max_steps": 30}),
    ("gpfd/Swimmer-v0", {"horizon": 25}),
    ("gpfd/Swimmer-v0", {"segments": 12, "horizon": 25}),  # No batched form: the loop engine.
    ("gpfd/Tetris-v0", {"max_steps": 30}),
    ("gpfd/Tetris-v0", {"rows": 20, "cols": 10, "state": "bertsekas"}),
]


def bits(value) -> bytes:
    return b"" if value is None else np.ascontiguousarray(value).tobytes()


def trace(env: gym.Env, actions: list) -> list:
    """What the environment gives for `actions`, as bytes; reset() without a seed after an
    episode ends (the environment's own stream)."""
    out: list[tuple] = []
    for action in actions:
        obs, reward, terminated, truncated, info = env.step(action)
        out.append((bits(obs), bits(reward), terminated, truncated, bits(info.get("action_mask"))))
        if terminated or truncated:
            obs, info = env.reset()
            out.append((bits(obs), bits(info.get("action_mask"))))
    return out


def vector_trace(envs, actions: list) -> list:
    out = []
    for action in actions:
        obs, rewards, terminated, truncated, info = envs.step(action)
        rows = info.get("final_obs", [])  # An object array: an observation or None per instance.
        final = b"|".join(bits(row) for row in rows) + bits(info.get("action_mask"))
        out.append((bits(obs), bits(rewards), bits(terminated), bits(truncated), final))
    return out


def started(env_id: str, params: dict, steps: int = 17) -> tuple[gym.Env, list]:
    """An environment mid-episode (17 steps in, with ends on the way), and 80 actions to go on."""
    env = gym.make(env_id, **params)
    env.reset(seed=5)
    env.action_space.seed(5)
    trace(env, [env.action_space.sample() for _ in range(steps)])
    return env, [env.action_space.sample() for _ in range(80)]


def pickled(env):
    return pickle.loads(pickle.dumps(env))


@pytest.mark.parametrize("copier", [pickled, copy.deepcopy], ids=["pickle", "deepcopy"])
@pytest.mark.parametrize("env_id,params", VARIANTS)
def test_a_copy_steps_as_the_original(env_id, params, copier):
    env, actions = started(env_id, params)
    twin = copier(env)
    assert twin.unwrapped is not env.unwrapped
    base, twin_base = gpfd_env(env), gpfd_env(twin)
    assert twin_base.np_random.bit_generator.state == base.np_random.bit_generator.state
    assert bits(twin_base.state) == bits(base.state)
    expected = trace(env, actions)
    assert any(len(row) == 2 for row in expected), "no episode ended: resets were not tested"
    assert trace(twin, actions) == expected


@pytest.mark.parametrize("mode", list(AutoresetMode), ids=lambda mode: mode.value)
@pytest.mark.parametrize("engine", ["batched", "loop"])
def test_a_vector_copy_steps_as_the_original(engine, mode):
    envs = gym.make_vec(
        "gpfd/CartPole-v0",
        num_envs=5,
        engine=engine,
        autoreset_mode=mode,
        max_steps=12,
    )
    envs.reset(seed=3)
    envs.action_space.seed(3)
    # Up to a step where an episode has just ended: the copy must know to reset it next.
    for _ in range(100):
        _, _, terminated, truncated, _ = envs.step(envs.action_space.sample())
        if (terminated | truncated).any():
            break
    assert (terminated | truncated).any()
    actions = [envs.action_space.sample() for _ in range(40)]
    for twin in (pickled(envs), copy.deepcopy(envs)):
        assert twin.unwrapped.engine == engine
        assert bits(twin.unwrapped.states) == bits(envs.unwrapped.states)
    twins = [pickled(envs), copy.deepcopy(envs)]
    expected = vector_trace(envs, actions)
    for twin in twins:
        assert vector_trace(twin, actions) == expected


def test_a_vector_tetris_copy_steps_as_the_original():
    envs = gym.make_vec("gpfd/Tetris-v0", num_envs=3, max_steps=15)
    envs.reset(seed=2)
    envs.action_space.seed(2)
    vector_trace(envs, [envs.action_space.sample() for _ in range(9)])
    actions = [envs.action_space.sample() for _ in range(40)]
    twin = pickled(envs)
    assert vector_trace(twin, actions) == vector_trace(envs, actions)


def play_elsewhere(payload: bytes, actions: list) -> list:
    """In a spawned process: unpickle the environment, step it."""
    return trace(pickle.loads(payload), actions)


def test_environments_step_alike_in_a_spawned_process():
    """As SubprocVecEnv with the spawn start method: the environment travels pickled."""
    jobs = []
    for env_id, params in VARIANTS[::2]:
        env, actions = started(env_id, params)
        jobs.append((pickle.dumps(env), actions, env))
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=1, mp_context=context) as pool:
        futures = [pool.submit(play_elsewhere, payload, actions) for payload, actions, _ in jobs]
        for (_, actions, env), future in zip(jobs, futures, strict=True):
            assert future.result(timeout=120) == trace(env, actions)


def test_a_fresh_environment_pickles_too():
    env = gym.make("gpfd/Tetris-v0")
    twin = pickled(env)
    obs, _ = twin.reset(seed=8)
    assert bits(obs) == bits(env.reset(seed=8)[0])


def test_an_environment_without_snapshots_says_why_it_cannot_be_pickled():
    register("pickling-test-pendulum", lambda: gym.make("Pendulum-v1"))
    batch = _core.EnvBatch("pickling-test-pendulum", {}, 1, "disabled")
    with pytest.raises(TypeError, match="pickling-test-pendulum has no snapshots"):
        pickle.dumps(batch)
    with pytest.raises(TypeError, match="cannot pickle"):
        copy.deepcopy(batch)


def test_a_damaged_pickle_is_refused():
    batch = _core.EnvBatch("cartpole", {}, 2, "next_step")
    name, params, n, mode, engine, words = batch.__getstate__()
    acrobot = _core.EnvBatch("acrobot").__getstate__()[1]
    for state in [
        (name, params, n, mode, engine, words[:-8]),  # One word short
        (name, params, n, mode, engine, words[:-3]),  # Not whole words
        ("acrobot", acrobot, n, mode, engine, words),  # Another environment
        (name, params, 3, mode, engine, words),  # Another size
        (name, params, n, mode, "loop", words),  # Another engine
    ]:
        blank = _core.EnvBatch.__new__(_core.EnvBatch)  # As pickle makes it.
        with pytest.raises(gpfd.InputError, match="snapshot"):
            blank.__setstate__(state)
