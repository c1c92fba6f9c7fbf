"""Vector forms of the environments users bring: one vector step per time step for all lanes.

An environment stepped in Python (gpfd.user_env) has a vector form when it comes as

- a Gymnasium id whose spec has a ``vector_entry_point`` (gpfd's own ``gpfd/*`` ids, the planted
  tasks among them, Gymnasium's CartPole-v1):
  ``gymnasium.make_vec(id, num_envs, vectorization_mode="vector_entry_point")``;
- an EnvPool task, ``env="envpool/CartPole-v1"`` (any id of ``envpool.list_all_envs()`` after the
  slash; ``pip install gpfd[envpool]``);
- ``VectorFactory(make_vec)``, where ``make_vec(num_envs)`` returns a Gymnasium ``VectorEnv``.

Policy gradient's lockstep player (src/rl/lockstep_episodes.cpp) then plays the episodes of each
call in the lanes of one vector environment (python/src/vector_hub.cpp, driving VectorAdapter
here), shared by the players of a lockstep group (python/src/lockstep_group.hpp): one ``step``
for all their lanes per time step. The episodes of a call all start
with one ``reset``, each lane seeded from its episode's own stream where the vector environment
takes one seed per sub-environment (gpfd's ``GpfdVectorEnv`` and ``PlantedVectorEnv``,
``SyncVectorEnv``, ``AsyncVectorEnv``, or ``VectorFactory(..., per_lane_seeds=True)``): lane l
then gets the seed that the per-environment path gives ``reset(seed=...)``, and plays the same
episode. Otherwise the
vector environment gets one seed mixed from all lanes' seeds (EnvPool, whose seeds are fixed when
it is made: at its creation, once per lockstep group): the same seeds give the same episodes,
but not those of the per-environment path. Any autoreset mode works
(gymnasium.vector.AutoresetMode): an episode is booked up to the step that ends it and its lane
retired, before any autoreset.

Without a vector form, trials step one environment at a time in worker processes (user_env).
"""

from __future__ import annotations

import contextlib
import functools
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, cast

import gymnasium as gym
import numpy as np
from gymnasium.vector import AsyncVectorEnv, SyncVectorEnv, VectorEnv
from gymnasium.wrappers import OrderEnforcing, PassiveEnvChecker

from gpfd import _core
from gpfd.environments import registry
from gpfd.environments.gpfd_env import GpfdEnv
from gpfd.environments.gpfd_vector import GpfdVectorEnv
from gpfd.environments.planted import PlantedVectorEnv

if TYPE_CHECKING:
    from gpfd.adapters.protocol import AdapterProtocol

ENVPOOL_PREFIX = "envpool/"


class VectorSource:
    """Makes a single environment (called) and, where it has one, its vector form."""

    #: reset(seed=[s0, s1, ...]) seeds each sub-environment (else one seed for all).
    per_lane_seeds = False
    #: The seeds are fixed when the vector environment is made (EnvPool): ``make_vector`` gets one.
    seeded_at_creation = False
    #: The key of ``info`` that counts each sub-environment's steps in its episode, if any.
    elapsed_key = ""
    #: ``step(actions, env_id=ids)`` steps only the sub-environments ``ids`` and returns their
    #: rows in that order (EnvPool): gpfd then steps only those that play an episode.
    steps_subsets = False

    def __call__(self) -> gym.Env:
        raise NotImplementedError

    def has_vector(self) -> bool:
        return True

    def make_vector(self, num_envs: int, seed: int) -> VectorEnv:
        raise NotImplementedError

    def seeds_lanes(self, envs: VectorEnv) -> bool:
        """Whether ``envs`` (made by make_vector) takes one seed per sub-environment."""
        return self.per_lane_seeds


class GymnasiumSource(VectorSource):
    """A Gymnasium id: ``gymnasium.make`` for one environment, ``gymnasium.make_vec`` with its
    ``vector_entry_point`` for many."""

    def __init__(self, env_id: str, kwargs: dict[str, Any] | None = None):
        self.env_id = env_id
        self.kwargs = dict(kwargs or {})
        # The spec travels with the source to the worker processes, so that an id registered
        # where they never run it (under `if __name__ == "__main__":`) is made there too. None
        # for "module:Id", which gymnasium.make imports first.
        self.spec: gym.envs.registration.EnvSpec | None = None
        if ":" not in env_id:
            with contextlib.suppress(gym.error.Error):
                self.spec = gym.spec(env_id)

    def _id(self) -> str | gym.envs.registration.EnvSpec:
        return self.spec if self.spec is not None else self.env_id

    def __call__(self) -> gym.Env:
        return gym.make(self._id(), **self.kwargs)

    # Equal for the same id and keywords: idle vector environments serve the next call's source.
    def __eq__(self, other: object) -> bool:
        return type(other) is GymnasiumSource and self._identity() == other._identity()

    def __hash__(self) -> int:
        return hash(self._identity())

    def _identity(self) -> tuple[str, str]:
        return self.env_id, repr(sorted(self.kwargs.items()))

    def has_vector(self) -> bool:
        try:
            spec = self.spec if self.spec is not None else gym.spec(self.env_id)
        except gym.error.Error:
            return False
        return spec.vector_entry_point is not None

    def make_vector(self, num_envs: int, seed: int) -> VectorEnv:
        return gym.make_vec(
            self._id(), num_envs=num_envs, vectorization_mode="vector_entry_point", **self.kwargs
        )

    def seeds_lanes(self, envs: VectorEnv) -> bool:
        return isinstance(envs, (GpfdVectorEnv, PlantedVectorEnv, SyncVectorEnv, AsyncVectorEnv))


class EnvPoolSource(VectorSource):
    """An EnvPool task: ``envpool.make_gymnasium(task, num_envs=N, batch_size=N, seed=s,
    num_threads=1, **kwargs)``, synchronous; a single environment is a pool of one, made anew at
    each seeded reset. A pool is made once per lockstep group (again, larger, where a reset needs
    more sub-environments), seeded from the first call's lanes, and its streams go on from reset
    to reset."""

    seeded_at_creation = True
    elapsed_key = "elapsed_step"
    steps_subsets = True

    def __init__(self, task: str, kwargs: dict[str, Any] | None = None):
        self.task = task
        self.kwargs = dict(kwargs or {})

    def __call__(self) -> gym.Env:
        return OneLaneEnv(self)

    def make_vector(self, num_envs: int, seed: int) -> VectorEnv:
        import envpool

        # EnvPool takes a 32-bit seed and gives sub-environment i seed + i. One worker thread
        # unless told otherwise: gpfd spreads its work over processes (threads=).
        kwargs = {"num_threads": 1, **self.kwargs}
        envs: Any = envpool.make_gymnasium(
            self.task, num_envs=num_envs, batch_size=num_envs, seed=seed % 2**31, **kwargs
        )
        return envs


class VectorFactory(VectorSource):
    """Your own vector environment for gpfd: ``make_vec(num_envs)`` returns a Gymnasium
    ``VectorEnv`` (Box observations; Box or Discrete actions).

    per_lane_seeds: its ``reset(seed=[s0, s1, ...])`` seeds each sub-environment, as
    ``SyncVectorEnv`` does; then each lane's episode is seeded from gpfd's own stream for it.
    Otherwise ``reset(seed=s)`` gets one seed for all.

    make: where gpfd needs a single environment (the random walks that sample visited states),
    ``make()``; without it, lane 0 of ``make_vec(1)``.

    Pass it as ``env=`` to gpfd.evolve or gpfd.fitness.

    Example::

        factory = gpfd.VectorFactory(lambda n: MyVectorEnv(n), per_lane_seeds=True)
        run = gpfd.evolve(env=factory, threads=2)
    """

    def __init__(
        self,
        make_vec: Callable[[int], VectorEnv],
        *,
        per_lane_seeds: bool = False,
        make: Callable[[], gym.Env] | None = None,
    ) -> None:
        if not callable(make_vec):
            raise TypeError(f"make_vec must be callable, not {type(make_vec).__name__}")
        self.make_vec = make_vec
        self.per_lane_seeds = bool(per_lane_seeds)
        self.make = make
        # gpfd.user_env names the environment python:<this> (the factory's name).
        target = make_vec.func if isinstance(make_vec, functools.partial) else make_vec
        self.__qualname__ = getattr(target, "__qualname__", type(target).__name__)

    def __call__(self) -> gym.Env:
        return self.make() if self.make is not None else OneLaneEnv(self)

    def make_vector(self, num_envs: int, seed: int) -> VectorEnv:
        return self.make_vec(num_envs)


# The class names its public module, where it was defined before the package had layers: run.json's
# "env" names a VectorFactory by it (gpfd.discovery.runs._task_fingerprint, which a resume
# compares), and pickles find the class there (gpfd/__init__ imports it from there, so that module
# is loaded wherever the class is).
VectorFactory.__module__ = "gpfd.vector_source"


class OneLaneEnv(gym.Env):
    """Lane 0 of a source's vector form of one lane, as a single Gymnasium environment."""

    def __init__(self, source: VectorSource):
        self.source = source
        self.envs = source.make_vector(1, 0)
        self.observation_space = self.envs.single_observation_space
        self.action_space = self.envs.single_action_space

    def reset(self, *, seed: int | None = None, options: dict | None = None):
        if self.source.seeded_at_creation and seed is not None:
            self.envs.close()
            self.envs = self.source.make_vector(1, seed)
            seed = None
        elif seed is not None and self.source.seeds_lanes(self.envs):
            obs, _ = self.envs.reset(seed=cast(Any, [seed]), options=options)
            return obs[0], {}
        obs, _ = self.envs.reset(seed=seed, options=options)
        return obs[0], {}

    def step(self, action):
        obs, reward, terminated, truncated, info = self.envs.step(
            np.asarray([action], dtype=self.action_space.dtype)
        )
        if "_final_obs" in info and info["_final_obs"][0]:  # Same-step autoreset.
            obs = [info["final_obs"][0]]
        return obs[0], float(reward[0]), bool(terminated[0]), bool(truncated[0]), {}

    def close(self):
        self.envs.close()


def envpool_source(env: str, env_kwargs: dict[str, Any] | None) -> tuple[str, VectorSource]:
    """(name, source) for ``envpool/TASK``; InputError for ``envpool:TASK`` (Gymnasium's
    ``module:id`` syntax, which would import envpool and then make Gymnasium's own TASK)."""
    if env.startswith("envpool:"):
        raise _core.InputError(
            f"{env!r} would import envpool and then make Gymnasium's own "
            f"{env.split(':', 1)[1]!r}: write env={ENVPOOL_PREFIX + env.split(':', 1)[1]!r} for "
            "EnvPool's task"
        )
    task = env[len(ENVPOOL_PREFIX) :]
    try:
        import envpool
    except ImportError:
        raise _core.InputError(
            f"{env!r} needs EnvPool: pip install 'gpfd[envpool]' (or pip install envpool)"
        ) from None
    known = envpool.list_all_envs()
    if task not in known:
        raise _core.InputError(
            f"unknown EnvPool task {task!r} in {env!r}; EnvPool has: {', '.join(sorted(known))}"
        )
    return env, EnvPoolSource(task, env_kwargs)


def has_vector_form(name: str) -> bool:
    """Whether the environment registered as `name` has a vector form (asked by C++)."""
    source = registry.factory(name)
    return isinstance(source, VectorSource) and source.has_vector()


def native_single(name: str, adapter: AdapterProtocol) -> tuple[_core.EnvBatch, bool] | None:
    """(engine, float32 actions) where the environment registered as `name` is one of gpfd's own,
    made from its Gymnasium id by ``gymnasium.make`` with only the wrappers that adds by default
    (order enforcing, the passive checker, which change nothing): its C++ engine (EnvBatch), which
    C++ then resets and steps as GpfdEnv does, without Python. None for any other (asked by C++
    for each instance)."""
    if not isinstance(registry.factory(name), GymnasiumSource):
        return None
    env = adapter.env
    while type(env) in (OrderEnforcing, PassiveEnvChecker):
        env = env.env
    if type(env) is not GpfdEnv:
        return None
    return env.native_engine, adapter.action_dtype == np.float32
