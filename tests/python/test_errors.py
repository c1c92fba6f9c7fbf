"""gpfd's errors are named as documented, gpfd.InputError and gpfd.EnvError: in a traceback, in
their repr, and through pickling (as a worker process sends them)."""

import pickle
import subprocess
import sys
import textwrap

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

import gpfd
from gpfd import errors, user_env


def test_the_classes_are_the_packages():
    assert gpfd.InputError is errors.InputError is gpfd._core.InputError
    assert gpfd.EnvError is errors.EnvError is user_env.EnvError
    for cls in (gpfd.InputError, gpfd.EnvError):
        assert f"{cls.__module__}.{cls.__qualname__}" == f"gpfd.{cls.__name__}"
        assert pickle.loads(pickle.dumps(cls("what (where)"))).args == ("what (where)",)
        assert type(pickle.loads(pickle.dumps(cls("x")))) is cls


@pytest.mark.parametrize(
    "code, line",
    [
        (
            'gym.make("gpfd/Swimmer-v0", segments=1)',
            "gpfd.InputError: segments must lie in [2, 100], got 1 (swimmer.segments)",
        ),
        (
            'user_env.Adapter("python:Broken", Broken()).reset(seed=3)',
            "gpfd.EnvError: python:Broken: reset(seed=3) raised RuntimeError: no simulator",
        ),
    ],
)
def test_an_uncaught_error_names_its_class_in_gpfd(code, line):
    script = textwrap.dedent(
        f"""
        import gymnasium as gym
        import numpy as np
        from gymnasium import spaces
        from gpfd import user_env

        class Broken(gym.Env):
            observation_space = spaces.Box(-1.0, 1.0, (2,), np.float64)
            action_space = spaces.Discrete(2)

            def reset(self, *, seed=None, options=None):
                raise RuntimeError("no simulator")

        {code}
        """
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last == line, done.stderr
    assert "gpfd._core" not in done.stderr and "gpfd.errors" not in done.stderr


class Counted(gym.Env):
    """Raises in its 50th step of an episode."""

    observation_space = spaces.Box(-1.0, 1.0, (2,), np.float64)
    action_space = spaces.Discrete(2)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.calls = 0
        return np.zeros(2), {}

    def step(self, action):
        self.calls += 1
        if self.calls == 50:
            raise RuntimeError(f"call {self.calls}")
        return np.zeros(2), 0.0, False, False, {}


def test_a_step_is_named_by_its_call_counted_from_one():
    adapter = user_env.Adapter("python:Counted", Counted())
    for _ in range(2):  # A reset starts the count again.
        adapter.reset(seed=1)
        for _ in range(49):
            adapter.step(np.zeros(1))
        with pytest.raises(gpfd.EnvError) as raised:
            adapter.step(np.zeros(1))
        assert str(raised.value) == (
            "python:Counted: step(0) raised RuntimeError: call 50 (step 50 of its episode, "
            "counted from 1)"
        )
