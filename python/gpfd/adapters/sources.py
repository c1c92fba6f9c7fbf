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
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn, cast

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.vector import AsyncVectorEnv, AutoresetMode, SyncVectorEnv, VectorEnv
from gymnasium.wrappers import OrderEnforcing, PassiveEnvChecker

from gpfd import _core, _deadline, registry, vector_cache
from gpfd.envs import GpfdEnv
from gpfd.errors import EnvError
from gpfd.planted import PlantedVectorEnv
from gpfd.vector import GpfdVectorEnv

if TYPE_CHECKING:
    from gpfd.protocol import AdapterProtocol, VectorAdapterProtocol

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


def make_vector_adapter(
    name: str, state_dim: int, choices: int, low: Sequence[float], high: Sequence[float]
) -> VectorAdapter:
    """Called by C++ for each batched form made: the adapter of `name`'s vector form, which must
    agree with the single environment's state size and action space (`choices` > 0: Discrete of
    so many; else a Box from `low` to `high`)."""
    source = registry.factory(name)
    assert isinstance(source, VectorSource), f"{name} has no vector form"
    return VectorAdapter(name, source, state_dim, choices, low, high)


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


def _mixed_seed(seeds: Sequence[int]) -> int:
    """One seed >= 0 from all lanes' seeds (for a vector environment seeded as a whole)."""
    state = np.random.SeedSequence([int(s) for s in seeds]).generate_state(1, np.uint64)
    return int(state[0]) >> 1


class VectorAdapter:
    """One vector environment driven by a lockstep group's players (python/src/vector_hub.cpp,
    gpfd.protocol.VectorAdapterProtocol): made on the first reset with as many sub-environments
    as lanes (again, larger, when a reset needs more), seeded, checked, and every failure raised
    as gpfd.EnvError naming the environment, the call, the step and the lane."""

    def __init__(
        self,
        name: str,
        source: VectorSource,
        state_dim: int,
        choices: int,
        low: Sequence[float],
        high: Sequence[float],
    ):
        self.name = name
        self.source = source
        self.state_dim = int(state_dim)
        self.choices = int(choices)
        self.low = np.asarray(low, dtype=np.float64)
        self.high = np.asarray(high, dtype=np.float64)
        self.envs: VectorEnv | None = None
        self.num_envs = 0
        self.start = 0  # A Discrete space's first action.
        self.resets_ended = False  # Autoreset disabled: ended sub-environments need a reset.
        self.elapsed_key = source.elapsed_key
        self.per_lane_seeds = False  # Its vector environment takes one seed per sub-environment.
        self.step_function: Callable[..., Any] | None = None
        self.steps_subsets = False  # step_subset steps only the sub-environments given.
        # gpfd's own vector environment: its C++ engine, which C++ steps without Python.
        self.native_engine: _core.EnvBatch | None = None
        self.actions: np.ndarray | None = None

    # -- what C++ calls ------------------------------------------------------------------------

    def reset(self, seeds: list[int | None]) -> np.ndarray:
        """Resets every sub-environment, those of lanes 0..len(seeds)-1 from their seeds (None:
        a sub-environment that plays no episode, in a lockstep group's layout); returns every
        sub-environment's observation as float64 (N, d)."""
        _deadline.current = self
        lanes = len(seeds)
        given = [int(s) for s in seeds if s is not None]
        if self.envs is None or self.num_envs < lanes:
            # Seeded at creation (EnvPool): from the first call's lanes; its sub-environments'
            # streams then go on from reset to reset.
            self._open(max(lanes, self.num_envs), _mixed_seed(given))
        assert self.envs is not None
        if self.source.seeded_at_creation:
            seed: Any = None
        elif self.per_lane_seeds:
            seed = [None if s is None else int(s) for s in seeds] + [None] * (self.num_envs - lanes)
        else:
            seed = _mixed_seed(given)
        try:
            result = self.envs.reset(seed=seed)
        except Exception as e:
            raise self._error(
                f"reset(seed=...) of its vector form raised {type(e).__name__}: {e} (lanes "
                f"0-{lanes - 1})"
            ) from e
        if not isinstance(result, tuple) or len(result) != 2:
            raise self._error(
                f"reset of its vector form returned {type(result).__name__}, not (obs, info)"
            )
        return self._observations(result[0], "reset", 0, lanes)

    def step_subset(self, sub_envs: Sequence[int]) -> Any:
        """One step of the sub-environments `sub_envs` only (sorted; a source that
        ``steps_subsets``): what step returns, with their rows in that order."""
        assert self.step_function is not None and self.actions is not None
        env_ids = np.asarray(sub_envs, dtype=np.int32)
        result = self.step_function(self.actions[env_ids], env_id=env_ids)
        if isinstance(result, tuple) and len(result) == 5 and isinstance(result[4], dict):
            returned = result[4].get("env_id")
            if returned is not None and not np.array_equal(np.asarray(returned), env_ids):
                raise self._error(
                    f"its vector form lies about its sub-environments: step(env_id=...) for "
                    f"{_ranges(env_ids.tolist())} returned rows for "
                    f"{_ranges(np.asarray(returned).tolist())}"
                )
        return result

    def reset_ended(self, mask: list[bool], step: int) -> np.ndarray:
        """Disabled autoreset: resets the sub-environments in `mask` (their episodes ended)."""
        assert self.envs is not None
        reset_mask = np.asarray(mask, dtype=bool)
        try:
            obs, _ = self.envs.reset(options={"reset_mask": reset_mask})
        except Exception as e:
            lanes = ", ".join(map(str, np.flatnonzero(reset_mask)))
            raise self._error(
                f"its vector form has autoreset disabled, and reset(options={{'reset_mask': "
                f"...}}) of the ended lanes {lanes} before vector step {step} raised "
                f"{type(e).__name__}: {e}"
            ) from e
        return self._observations(obs, f"reset of ended lanes before vector step {step}", step, 0)

    def step_raised(self, error: BaseException, step: int, lanes: list[int]) -> NoReturn:
        raise self._error(
            f"step of its vector form raised {type(error).__name__}: {error} (vector step {step}, "
            f"lanes {_ranges(lanes)} playing episodes)"
        ) from error

    def bad_result(self, result: Any, step: int) -> NoReturn:
        raise self._error(
            f"step of its vector form returned {type(result).__name__} at vector step {step}, "
            "not (obs, rewards, terminated, truncated, info)"
        )

    def as_array(self, value: Any, what: str, step: int, rows: int | None = None) -> np.ndarray:
        """`what` of a step as the array C++ reads: observations float64 (N, d), the rest (N,);
        N: `rows` (the sub-environments a step of a subset returned), else num_envs."""
        n = self.num_envs if rows is None else rows
        try:
            array = np.asarray(value, dtype=bool if what in ("terminated", "truncated") else float)
        except (TypeError, ValueError) as e:
            raise self._error(
                f"step of its vector form returned {what} that are not numeric at vector step "
                f"{step}: {e}"
            ) from e
        if what == "observations" or what.startswith("info['final_obs"):
            if array.shape[:1] != (n,) or math.prod(array.shape[1:]) != self.state_dim:
                raise self._error(
                    f"its vector form lies about its spaces: step returned {what} of shape "
                    f"{array.shape} at vector step {step}, for {n} sub-environments of "
                    f"{self.state_dim} values (single_observation_space)"
                )
            return np.ascontiguousarray(array.reshape(n, self.state_dim))
        if array.shape != (n,):
            raise self._error(
                f"step of its vector form returned {what} of shape {array.shape} at vector step "
                f"{step}, for {n} sub-environments"
            )
        return array

    def final_observations(
        self, info: dict, step: int, sub_envs: Sequence[int] | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """(mask, observations) of info["_final_obs"] and info["final_obs"] (same-step
        autoreset), observations float64 (N, d) with rows where the mask is set; row i is
        sub-environment sub_envs[i] where a step of a subset returned them."""
        rows = None if sub_envs is None else len(sub_envs)
        mask = self.as_array(info["_final_obs"], "info['_final_obs']", step, rows)
        obs = np.zeros((len(mask), self.state_dim))
        names: Sequence[int] = range(len(mask)) if sub_envs is None else sub_envs
        final = info.get("final_obs")
        for i in np.flatnonzero(mask):
            try:
                row = np.asarray(final[i], dtype=np.float64).reshape(-1)  # type: ignore[index]
            except (TypeError, ValueError, IndexError) as e:
                raise self._error(
                    f"info['final_obs'] of lane {names[int(i)]} after vector step {step} is not an "
                    f"observation: {e}"
                ) from e
            if row.size != self.state_dim:
                raise self._error(
                    f"its vector form lies about its spaces: info['final_obs'] of lane "
                    f"{names[int(i)]} after "
                    f"vector step {step} has {row.size} values, its single_observation_space "
                    f"{self.state_dim}"
                )
            obs[i] = row
        return mask, obs

    def bad_observation(
        self, step: int, lane: int, episode_step: int, index: int, value: float
    ) -> NoReturn:
        raise self._error(
            f"the observation of lane {lane} after step {episode_step} of its episode (vector "
            f"step {step}) holds {value} at index {index}; gpfd needs finite observations"
        )

    def reset_on_its_own(self, step: int, lane: int, episode_step: int, how: str) -> NoReturn:
        raise self._error(
            f"lane {lane} of its vector form reset on its own at vector step {step}, step "
            f"{episode_step} of its episode, which had not ended ({how}); gpfd starts every "
            "episode itself"
        )

    def close(self) -> None:
        """Parks the vector environment for the next adapter of the same environment, source and
        size (gpfd.vector_cache), or closes it. Parked only where every reset reseeds what the
        lanes play (not EnvPool, seeded at creation), so that reuse changes nothing."""
        if self.envs is not None:
            envs, self.envs = self.envs, None
            self.native_engine = None
            if self.source.seeded_at_creation or not vector_cache.park(
                self._key(self.num_envs), envs
            ):
                envs.close()

    # -- inside --------------------------------------------------------------------------------

    def _error(self, message: str) -> Exception:
        return EnvError(f"{self.name}: {message}")

    def where(self) -> str:
        """What a lockstep group was doing, as gpfd._deadline names it: C++ steps the vector
        form without a call here, so only the environment and its lanes are known."""
        return f"{self.name}: a reset or a step of its vector form ({self.num_envs} lanes)"

    def _key(self, num_envs: int) -> tuple[str, VectorSource, int]:
        return (self.name, self.source, num_envs)

    def _open(self, num_envs: int, seed: int) -> None:
        self.close()
        envs = None if self.source.seeded_at_creation else vector_cache.take(self._key(num_envs))
        if envs is None:
            try:
                envs = self.source.make_vector(num_envs, seed)
            except Exception as e:
                raise self._error(
                    f"making its vector form of {num_envs} lanes raised {type(e).__name__}: {e}"
                ) from e
            self._check_spaces(envs, num_envs)
        mode = AutoresetMode(envs.metadata.get("autoreset_mode", AutoresetMode.NEXT_STEP))
        self.envs = envs
        self.num_envs = num_envs
        self.per_lane_seeds = self.source.seeds_lanes(envs)
        self.resets_ended = mode == AutoresetMode.DISABLED
        self.step_function = envs.step
        self.steps_subsets = self.source.steps_subsets
        # Made from a gpfd id (not a VectorFactory, whose make_vec may be anything).
        native = type(envs) is GpfdVectorEnv and isinstance(self.source, GymnasiumSource)
        self.native_engine = cast(GpfdVectorEnv, envs).native_engine if native else None
        space = envs.single_action_space
        if isinstance(space, spaces.Discrete):
            self.start = int(space.start)
            self.actions = np.full(num_envs, self.start, dtype=np.int64)
        else:
            assert isinstance(space, spaces.Box)
            centre = (np.asarray(space.low, np.float64) + np.asarray(space.high, np.float64)) / 2
            dtype = np.float32 if space.dtype == np.float32 else np.float64
            self.actions = np.ascontiguousarray(
                np.broadcast_to(centre.reshape(space.shape), (num_envs, *space.shape)), dtype=dtype
            )

    def _check_spaces(self, envs: Any, num_envs: int) -> None:
        """The vector form must be what the single environment is: refuse a lie."""

        def lie(what: str) -> Exception:
            return self._error(f"its vector form lies about its spaces: {what}")

        if getattr(envs, "num_envs", None) != num_envs:
            raise lie(f"asked for {num_envs} lanes, it has num_envs={envs.num_envs!r}")
        obs = getattr(envs, "single_observation_space", None)
        if not isinstance(obs, spaces.Box) or math.prod(obs.shape) != self.state_dim:
            raise lie(
                f"its single_observation_space is {obs}, the single environment's a Box of "
                f"{self.state_dim} values"
            )
        act = getattr(envs, "single_action_space", None)
        if self.choices > 0:
            if not isinstance(act, spaces.Discrete) or int(act.n) != self.choices:
                raise lie(
                    f"its single_action_space is {act}, the single environment's "
                    f"Discrete({self.choices})"
                )
            return
        if not (
            isinstance(act, spaces.Box)
            and act.shape is not None
            and math.prod(act.shape) == self.low.size
            and np.array_equal(np.asarray(act.low, np.float64).ravel(), self.low)
            and np.array_equal(np.asarray(act.high, np.float64).ravel(), self.high)
            and act.dtype in (np.float32, np.float64)
        ):
            raise lie(
                f"its single_action_space is {act}, the single environment's a float Box from "
                f"{self.low.tolist()} to {self.high.tolist()}"
            )

    def _observations(self, obs: Any, call: str, step: int, lanes: int) -> np.ndarray:
        """Checked float64 (N, d) observations; lanes 0..lanes-1 must be finite."""
        values = self.as_array(obs, "observations", step)
        bad = np.argwhere(~np.isfinite(values[:lanes]))
        if bad.size:
            lane, index = bad[0]
            raise self._error(
                f"the observation of lane {lane} after {call} holds {values[lane, index]} at "
                f"index {index}; gpfd needs finite observations"
            )
        return np.ascontiguousarray(values, dtype=np.float64)


def _ranges(lanes: Sequence[int]) -> str:
    """Lane numbers as '0-3, 7'."""
    spans: list[list[int]] = []
    for lane in sorted(lanes):
        if spans and spans[-1][1] == lane - 1:
            spans[-1][1] = lane
        else:
            spans.append([lane, lane])
    return ", ".join(str(a) if a == b else f"{a}-{b}" for a, b in spans)


if TYPE_CHECKING:

    def _conforms(adapter: VectorAdapter) -> VectorAdapterProtocol:
        return adapter  # mypy: VectorAdapter is what C++ drives.
