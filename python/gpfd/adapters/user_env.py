"""Your own Gymnasium environment in gpfd's discovery: stepped in Python, in worker processes.

``gpfd.evolve(env=...)`` takes a Gymnasium id (``"MountainCarContinuous-v0"``) or a callable that
returns a Gymnasium environment. The environment needs a Box observation space (its observation,
flattened, is the state: variables x0, x1, ...) and a Box (finite bounds) or Discrete action space.
Every episode starts with ``reset(seed=s)``, s drawn from the trial's own stream, so a run is
reproducible when the environment is deterministic given its seed. Every stage runs in worker
processes (one per thread asked for), since Python steps one environment at a time per process:
the GP's fitness evaluations, and the learning runs of validation, confirmation and assessment
(gpfd.evaluator, on gpfd.workers' pool). Each worker makes its own environments.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from gpfd import _core
from gpfd.adapters import sources, vector_cache
from gpfd.environments import registry
from gpfd.environments.registry import is_builtin  # Also gpfd.user_env.is_builtin, as before.
from gpfd.errors import EnvError  # Also gpfd.user_env.EnvError, as before.
from gpfd.execution import _deadline

if TYPE_CHECKING:
    from gpfd.adapters.protocol import AdapterProtocol

#: The shipped config (configs/user-env.toml) of gpfd.evolve and gpfd.assess on an environment
#: stepped in Python, when no config is given.
DEFAULT_CONFIG = "user-env"


def state_names(space: spaces.Space) -> list[str]:
    """x0 .. x{d-1} for a Box observation space of d values; TypeError for any other space."""
    if not isinstance(space, spaces.Box):
        raise TypeError(
            f"gpfd needs a Box observation space (a vector of numbers), not {space}; wrap the "
            "environment (e.g. gymnasium.wrappers.FlattenObservation) to give it one"
        )
    return [f"x{i}" for i in range(math.prod(space.shape))]


def resolve(
    env: str | Callable[..., gym.Env], env_kwargs: dict[str, Any] | None
) -> tuple[str, Callable[[], gym.Env]]:
    """(registry name, factory) for a Gymnasium id, an EnvPool task ("envpool/TASK") or a
    callable returning an environment; the factory of an id is a sources.VectorSource."""
    if isinstance(env, str):
        if env.startswith((sources.ENVPOOL_PREFIX, "envpool:")):
            return sources.envpool_source(env, env_kwargs)
        if ":" not in env:  # "module:Id" imports the module first: gymnasium.make checks it.
            try:
                gym.spec(env)
            except gym.error.Error as e:
                builtin = ", ".join(filter(is_builtin, _core.env_names()))
                raise _core.InputError(
                    f"unknown environment {env!r}: neither gpfd's ({builtin}) nor a Gymnasium "
                    f"id ({e})"
                ) from None
        return env, sources.GymnasiumSource(env, env_kwargs)
    if not callable(env):
        raise TypeError(
            f"env must be a name, a Gymnasium id or a callable, not {type(env).__name__}"
        )
    if env_kwargs and isinstance(env, sources.VectorFactory):
        raise TypeError("env_kwargs with a VectorFactory: give them to its make_vec")
    if env_kwargs:
        env = functools.partial(env, **env_kwargs)
    target = env.func if isinstance(env, functools.partial) else env
    return "python:" + getattr(target, "__qualname__", type(target).__name__), env


def run_name(name: str) -> str:
    """The results directory's default name for the registered environment `name` (resolve):
    a Gymnasium id or EnvPool task as a plain name ("ALE/Pong-v5" -> "ALE-Pong-v5"), a callable's
    name, or "user-env" where nothing usable is left (a lambda).

    Example::

        from gpfd.adapters.user_env import run_name

        run_name("ALE/Pong-v5"), run_name("python:make_env")  # "ALE-Pong-v5", "make_env"
    """
    if name.startswith("python:"):  # A callable's qualified name: "f.<locals>.make" -> "make".
        base = name.removeprefix("python:").rsplit(".", 1)[-1]
        base = "" if base.startswith("<") else base  # "<lambda>" names nothing.
    else:  # "module:Id" -> "Id".
        base = name.rsplit(":", 1)[-1]
    plain = re.sub(r"[^A-Za-z0-9._-]+", "-", base).strip("-.")
    return plain or "user-env"


def register(name: str, factory: Callable[[], gym.Env]) -> None:
    """Makes `name` a gpfd environment whose instances `factory` makes (in this process); the
    idle vector environments of an earlier registration of the name are closed."""
    vector_cache.close(name)
    registry.add(name, factory)


def make_adapter(name: str) -> Adapter:
    """Called by gpfd's registry (C++) for each new instance."""
    factory = registry.factory(name)
    if factory is None:
        raise EnvError(f"{name} is not registered in this process (gpfd.user_env.register)")
    try:
        env = factory()
    except Exception as e:
        raise EnvError(f"{name}: making the environment raised {type(e).__name__}: {e}") from e
    return Adapter(name, env)


class Adapter:
    """Drives one Gymnasium environment for gpfd (gpfd.adapters.protocol.AdapterProtocol): checks
    its spaces once and every observation, converts actions, and turns its exceptions into EnvError
    naming the call."""

    def __init__(self, name: str, env: gym.Env):
        self.name = name
        self.env = env
        self.state_dim = len(state_names(env.observation_space))
        self.choices = 0
        self.low: list[float] = []
        self.high: list[float] = []
        self.action_dtype: np.dtype[Any] | None = None
        space = env.action_space
        if isinstance(space, spaces.Discrete):
            self.action_kind = "discrete"
            self.choices = int(space.n)
            self._start = int(space.start)
        elif isinstance(space, spaces.Box):
            low = np.asarray(space.low, dtype=np.float64).ravel()
            high = np.asarray(space.high, dtype=np.float64).ravel()
            if not (np.isfinite(low).all() and np.isfinite(high).all()):
                raise TypeError(f"{name}: gpfd's learners need finite action bounds, got {space}")
            self.action_kind = "continuous"
            self.low, self.high = low.tolist(), high.tolist()
            self._shape, self.action_dtype = space.shape, np.dtype(space.dtype)
        else:
            raise TypeError(f"{name}: gpfd drives Box or Discrete action spaces, not {space}")
        self._steps = 0  # The steps of the episode so far.
        self._closed = False

    def close(self) -> None:
        """Closes the environment (``env.close()``), once: gpfd is done with this instance (its
        C++ environment's destructor calls it). EnvError where the environment's close raises."""
        if self._closed:
            return
        self._closed = True
        try:
            self.env.close()
        except Exception as e:
            raise EnvError(f"{self.name}: close() raised {type(e).__name__}: {e}") from e

    def where(self) -> str:
        """The call under way or last made, as an error names it (gpfd.execution._deadline)."""
        call = "reset" if self._steps == 0 else f"step {self._steps} of its episode, counted from 1"
        return f"{self.name}: {call}"

    def reset(self, seed: int) -> np.ndarray:
        self._steps = 0
        _deadline.current = self
        try:
            obs, _ = self.env.reset(seed=seed)
        except Exception as e:
            raise EnvError(f"{self.name}: reset(seed={seed}) raised {type(e).__name__}: {e}") from e
        return self.check_observation(obs, f"reset(seed={seed})")

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool]:
        """Step n of the episode (counted from 1 after each reset: the environment's n-th step
        call), as its errors name it."""
        if self.action_kind == "discrete":
            act: Any = int(action[0]) + self._start
        else:
            act = action.reshape(self._shape).astype(self.action_dtype)
        self._steps += 1
        _deadline.current = self
        try:
            obs, reward, terminated, truncated, _ = self.env.step(act)
        except Exception as e:
            raise EnvError(
                f"{self.name}: step({act!r}) raised {type(e).__name__}: {e} (step {self._steps} "
                "of its episode, counted from 1)"
            ) from e
        return (
            self.check_observation(obs, f"step {self._steps}"),
            float(reward),
            bool(terminated),
            bool(truncated),
        )

    def check_observation(self, obs: Any, where: str) -> np.ndarray:
        """`obs` as float64 values (C-contiguous, flattened), or EnvError naming `where` (the
        call after which it came) where it is not numeric, of another size or not finite."""
        try:
            values = np.ascontiguousarray(obs, dtype=np.float64).reshape(-1)
        except (TypeError, ValueError) as e:
            raise EnvError(f"{self.name}: the observation after {where} is not numeric: {e}") from e
        if values.size != self.state_dim:
            raise EnvError(
                f"{self.name}: the observation after {where} has {values.size} values, its space "
                f"{self.state_dim}"
            )
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise EnvError(
                f"{self.name}: the observation after {where} holds {values[bad[0]]} at index "
                f"{bad[0]}; gpfd needs finite observations"
            )
        return values


if TYPE_CHECKING:

    def _conforms(adapter: Adapter) -> AdapterProtocol:
        return adapter  # mypy: Adapter is what C++ drives.
