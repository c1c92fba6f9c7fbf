"""The vector adapter: one vector environment (a vector form of gpfd.adapters.sources) as a
lockstep group's players drive it from C++ (python/src/vector_hub.cpp,
gpfd.adapters.protocol.VectorAdapterProtocol): made, seeded, stepped and checked, each failure
an EnvError naming the environment, the call, the step and the lane.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn, cast

import numpy as np
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

from gpfd import _core
from gpfd.adapters import vector_cache
from gpfd.adapters.sources import GymnasiumSource, VectorSource
from gpfd.environments import registry
from gpfd.environments.gpfd_vector import GpfdVectorEnv
from gpfd.errors import EnvError
from gpfd.execution import _deadline

if TYPE_CHECKING:
    from gpfd.adapters.protocol import VectorAdapterProtocol


def make_vector_adapter(
    name: str, state_dim: int, choices: int, low: Sequence[float], high: Sequence[float]
) -> VectorAdapter:
    """Called by C++ for each batched form made: the adapter of `name`'s vector form, which must
    agree with the single environment's state size and action space (`choices` > 0: Discrete of
    so many; else a Box from `low` to `high`)."""
    source = registry.factory(name)
    assert isinstance(source, VectorSource), f"{name} has no vector form"
    return VectorAdapter(name, source, state_dim, choices, low, high)


def _mixed_seed(seeds: Sequence[int]) -> int:
    """One seed >= 0 from all lanes' seeds (for a vector environment seeded as a whole)."""
    state = np.random.SeedSequence([int(s) for s in seeds]).generate_state(1, np.uint64)
    return int(state[0]) >> 1


class VectorAdapter:
    """One vector environment driven by a lockstep group's players (python/src/vector_hub.cpp,
    gpfd.adapters.protocol.VectorAdapterProtocol): made on the first reset with as many
    sub-environments as lanes (again, larger, when a reset needs more), seeded, checked, and every
    failure raised as gpfd.EnvError naming the environment, the call, the step and the lane."""

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
        """What a lockstep group was doing, as gpfd.execution._deadline names it: C++ steps the
        vector form without a call here, so only the environment and its lanes are known."""
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
