"""Your own Gymnasium environment in gpfd's discovery: stepped in Python, in worker processes.

``gpfd.evolve(env=...)`` takes a Gymnasium id (``"MountainCarContinuous-v0"``) or a callable that
returns a Gymnasium environment. The environment needs a Box observation space (its observation,
flattened, is the state: variables x0, x1, ...) and a Box (finite bounds) or Discrete action space.
Every episode starts with ``reset(seed=s)``, s drawn from the trial's own stream, so a run is
reproducible when the environment is deterministic given its seed. Every stage runs in worker
processes (one per thread asked for), since Python steps one environment at a time per process:
the GP's fitness evaluations, and the learning runs of validation, confirmation and assessment.
Each worker makes its own environments.
"""

from __future__ import annotations

import functools
import math
import multiprocessing
import os
import re
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

import cloudpickle
import gymnasium as gym
import numpy as np
from gymnasium import spaces

from gpfd import _core, registry, vector_cache, vector_source
from gpfd.errors import EnvError  # Also gpfd.user_env.EnvError, as before.
from gpfd.registry import is_builtin  # Also gpfd.user_env.is_builtin, as before.

if TYPE_CHECKING:
    from multiprocessing.pool import Pool

    from gpfd.protocol import AdapterProtocol

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
    callable returning an environment; the factory of an id is a vector_source.VectorSource."""
    if isinstance(env, str):
        if env.startswith((vector_source.ENVPOOL_PREFIX, "envpool:")):
            return vector_source.envpool_source(env, env_kwargs)
        if ":" not in env:  # "module:Id" imports the module first: gymnasium.make checks it.
            try:
                gym.spec(env)
            except gym.error.Error as e:
                builtin = ", ".join(filter(is_builtin, _core.env_names()))
                raise _core.InputError(
                    f"unknown environment {env!r}: neither gpfd's ({builtin}) nor a Gymnasium "
                    f"id ({e})"
                ) from None
        return env, vector_source.GymnasiumSource(env, env_kwargs)
    if not callable(env):
        raise TypeError(
            f"env must be a name, a Gymnasium id or a callable, not {type(env).__name__}"
        )
    if env_kwargs and isinstance(env, vector_source.VectorFactory):
        raise TypeError("env_kwargs with a VectorFactory: give them to its make_vec")
    if env_kwargs:
        env = functools.partial(env, **env_kwargs)
    target = env.func if isinstance(env, functools.partial) else env
    return "python:" + getattr(target, "__qualname__", type(target).__name__), env


def run_name(name: str) -> str:
    """The results directory's default name for the registered environment `name` (resolve):
    a Gymnasium id or EnvPool task as a plain name ("ALE/Pong-v5" -> "ALE-Pong-v5"), a callable's
    name, or "user-env" where nothing usable is left (a lambda)."""
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
    """Drives one Gymnasium environment for gpfd (gpfd.protocol.AdapterProtocol): checks its
    spaces once and every observation, converts actions, and turns its exceptions into EnvError
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

    def reset(self, seed: int) -> np.ndarray:
        self._steps = 0
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


def _init_worker(name: str, payload: bytes) -> None:
    register(name, cloudpickle.loads(payload))


def _fitness_group_task(task: tuple[str, list[tuple[bytes, int]]]) -> list[float]:
    return _core.trial_fitness_group(*task)


def _runs_group_task(task: tuple[str, int, list[tuple[tuple, list[int]]]]) -> list[list]:
    return _core.train_runs_group(*task)


# Fitness evaluations played together in one vector environment (a lockstep group) where the
# environment has a vector form: 30 lanes each for cartpole-quick's 3 trials of 10 episodes.
LOCKSTEP_GROUP = 16


def _lockstep_groups(tasks: list) -> list[list]:
    """Consecutive groups of at most LOCKSTEP_GROUP tasks, as equal as may be, an even number of
    them (two workers share them evenly; 21 evaluations: 11 and 10, not 16 and 5). Their number
    follows from the tasks alone, never from the workers, so that a vector form seeded as a whole
    (one seed mixed from a group's lanes) gives the same run for any number of workers."""
    n = len(tasks)
    count = -(-n // LOCKSTEP_GROUP)
    if count % 2 == 1 and n > 1:
        count += 1
    groups, start = [], 0
    for i in range(count):
        size = n // count + (1 if i < n % count else 0)
        groups.append(tasks[start : start + size])
        start += size
    return groups


class Evaluator:
    """evaluate(config_text, [(genome, seed), ...]) for gpfd's discovery: run::trialFitness of
    each genome; and run_trials for the learning runs of validation, confirmation and assessment.
    In this process (workers == 1) or in a pool of worker processes. A fitness depends on its
    genome and seed only, a curve on its features, budget and seed, so any number of workers
    gives the same run."""

    def __init__(self, name: str, factory: Callable[[], gym.Env], workers: int):
        self.name = name
        self.factory = factory
        self.workers = workers if workers > 0 else (os.cpu_count() or 1)
        self._pool: Pool | None = None

    def __call__(self, config_text: str, tasks: list[tuple[bytes, int]]) -> list[float]:
        groups = [(config_text, group) for group in self._groups(tasks)]
        return [fitness for done in self._map(_fitness_group_task, groups) for fitness in done]

    @property
    def lockstep(self) -> bool:
        """Whether the environment has a vector form, whose calls go in lockstep groups
        (_lockstep_groups), each group's episodes in one vector environment
        (python/src/lockstep_group.hpp)."""
        from gpfd.vector_source import has_vector_form

        return has_vector_form(self.name)

    def _groups(self, tasks: list) -> list[list]:
        """Lockstep groups where the environment has a vector form, else one task each."""
        return _lockstep_groups(tasks) if self.lockstep else [[task] for task in tasks]

    def run_trials(
        self, config_text: str, budget: int, tasks: list[tuple[tuple, list[int]]]
    ) -> Iterator[list]:
        """The curves of each task (a feature set and the seeds of its runs) under the config
        and budget (run::LearningTask::Budget), in task order, as each is done
        (python/src/trial_runner.cpp)."""
        groups = [(config_text, budget, group) for group in self._groups(tasks)]
        return (curves for done in self._map(_runs_group_task, groups) for curves in done)

    def _map(self, function: Callable[[Any], Any], work: list) -> Iterator:
        """function over work, in order, as each is done: here, or on the workers."""
        if self.workers == 1:
            return map(function, work)
        return self._started().imap(function, work, chunksize=1)

    def _started(self) -> Pool:
        if self._pool is None:
            # forkserver: workers do not inherit this process' threads (oneTBB's) or state.
            method = (
                "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
            )
            context = multiprocessing.get_context(method)
            self._pool = context.Pool(
                self.workers, _init_worker, (self.name, cloudpickle.dumps(self.factory))
            )
        return self._pool

    def close(self) -> None:
        if self._pool is not None:
            self._pool.close()
            self._pool.join()
            self._pool = None
