"""Python never runs on a lockstep group's fiber (python/src/python_call.hpp): every call gpfd
makes into an environment (making it, reset, step, close) runs on the thread's own stack, as
CPython 3.14 and later require, in a group of several members and in a group of one."""

import gymnasium as gym
import numpy as np

import gpfd
from gpfd import _core
from test_vector_source import RAW2, TINY, Toy, ToyVector

# One entry per call gpfd made into the environments: whether it ran on the thread's own stack.
calls: dict[str, list[bool]] = {}


def record(what: str) -> None:
    calls.setdefault(what, []).append(_core.on_thread_stack())


class RecordingToy(Toy):
    def __init__(self):
        record("make")
        super().__init__()

    def reset(self, *, seed=None, options=None):
        record("reset")
        return super().reset(seed=seed, options=options)

    def step(self, action):
        record("step")
        return super().step(action)


class RecordingToyVector(ToyVector):
    def __init__(self, num_envs):
        record("make_vec")
        super().__init__(num_envs)

    def reset(self, *, seed=None, options=None):
        record("reset")
        return super().reset(seed=seed, options=options)

    def step(self, actions):
        record("step")
        return super().step(actions)

    def close(self, **kwargs):
        record("close")
        return super().close(**kwargs)


def test_the_check_is_true_on_the_main_threads_stack():
    # Its other side, false on a fiber's stack: tests/fibers/scheduler_test.cpp.
    assert _core.on_thread_stack()


def test_a_group_calls_its_vector_environment_on_the_threads_own_stack():
    calls.clear()
    env = gpfd.VectorFactory(lambda n: RecordingToyVector(n), per_lane_seeds=True)
    values = gpfd.fitness_of_each([RAW2] * 3, env=env, set=TINY, seed=2)
    assert all(np.isfinite(values))
    for what in ("make_vec", "reset", "step"):  # close: the adapter may keep it for reuse.
        assert calls.get(what), f"no call of {what} recorded"
    assert {what: all(on) for what, on in calls.items()} == dict.fromkeys(calls, True)


def test_an_environment_without_a_vector_form_is_called_on_the_threads_own_stack():
    calls.clear()
    assert np.isfinite(gpfd.fitness(RAW2, env=RecordingToy, set=TINY, seed=2))
    for what in ("make", "reset", "step"):
        assert calls.get(what), f"no call of {what} recorded"
    assert {what: all(on) for what, on in calls.items()} == dict.fromkeys(calls, True)


def test_gymnasiums_own_vector_form_plays_a_group_too():
    # CartPole-v1's vector_entry_point: the group plays as on every CPython (no fallback).
    values = gpfd.fitness_of_each(
        [gpfd.FeatureSet.parse("x2\nx3\n", variables=["x0", "x1", "x2", "x3"])] * 2,
        env="CartPole-v1",
        set=TINY,
        seed=1,
        native=False,  # Gymnasium's own vector form, not gpfd's twin.
    )
    assert all(np.isfinite(values))
    assert gym.spec("CartPole-v1").vector_entry_point is not None
