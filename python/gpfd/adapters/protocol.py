"""What gpfd's C++ side looks up by name on the Python adapters: the protocol, written down once.

An environment stepped in Python is driven from C++ (python/src) through two adapters:

- ``AdapterProtocol``, one Gymnasium environment (gpfd.user_env.Adapter), driven by
  python/src/python_environment.cpp;
- ``VectorAdapterProtocol``, the vector form shared by a lockstep group's players
  (gpfd.adapters.vector_adapter.VectorAdapter), driven by python/src/vector_hub.cpp.

C++ reads every attribute as a property (it never sets one) and calls the methods with the GIL
held; it converts what they return as stated below and raises std::logic_error where a method
that must raise returns. mypy checks each adapter against its protocol (the ``_conforms``
functions of gpfd.user_env and gpfd.adapters.sources), and tests/python/test_protocol.py that
every name the C++ sources look up is a member here.

The module-level functions C++ calls are:

- ``gpfd.user_env.make_adapter(name) -> AdapterProtocol``: each new instance of a registered
  environment;
- ``gpfd.adapters.sources.native_single(name, adapter) -> (EnvBatch, bool) | None``: gpfd's own
  engine under a single adapter (stepped without Python), with whether actions round to float32;
- ``gpfd.adapters.sources.has_vector_form(name) -> bool``;
- ``gpfd.adapters.vector_adapter.make_vector_adapter(name, state_dim, choices, low, high)
  -> VectorAdapterProtocol``: each vector form made (one per lockstep group);
- ``gpfd.features.expectation(env, variables, params)``: what a features text is read against.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn, Protocol, runtime_checkable

import numpy as np

if TYPE_CHECKING:
    from gpfd._core import EnvBatch


@runtime_checkable
class AdapterProtocol(Protocol):
    """One Gymnasium environment as python/src/python_environment.cpp steps it."""

    @property
    def state_dim(self) -> int:
        """The number of state variables (x0 .. x{d-1}): the flattened observation's size."""

    @property
    def action_kind(self) -> str:
        """ "discrete" (one action of ``choices``) or "continuous" (a Box from ``low`` to
        ``high``, flattened)."""

    @property
    def choices(self) -> int:
        """A discrete action space's number of actions (read only where discrete)."""

    @property
    def low(self) -> Sequence[float]:
        """A continuous action space's lower bounds, finite, flattened (read only where
        continuous)."""

    @property
    def high(self) -> Sequence[float]:
        """A continuous action space's upper bounds, as ``low``."""

    @property
    def env(self) -> Any:
        """The Gymnasium environment; gpfd.adapters.sources.native_single unwraps it to find gpfd's
        own engine."""

    @property
    def action_dtype(self) -> np.dtype[Any] | None:
        """A continuous action space's dtype (float32 actions are rounded to it); None where
        discrete."""

    def reset(self, seed: int) -> np.ndarray:
        """Starts an episode with ``env.reset(seed=seed)`` (seed >= 0); returns the observation
        checked (check_observation): float64, C-contiguous, state_dim values. Raises
        gpfd.EnvError where the environment raises."""

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool]:
        """One step with `action` (float64, one value per action component; a discrete one holds
        the action's index from 0): (observation checked as reset's, reward, terminated,
        truncated). Raises gpfd.EnvError, naming the step of the episode (from 1), where the
        environment raises."""

    def check_observation(self, obs: Any, where: str) -> np.ndarray:
        """`obs` as float64 values, C-contiguous, flattened; gpfd.EnvError naming the call
        (`where`: "reset", "step 3") where it is not numeric, not state_dim values or not
        finite. C++ calls it with an observation of gpfd's own engine that is not finite, to
        raise that error."""

    def close(self) -> None:
        """gpfd is done with this instance (its C++ environment is destroyed): closes the
        environment, once. An error it raises is printed as unraisable, never thrown into C++."""


@runtime_checkable
class VectorAdapterProtocol(Protocol):
    """The vector form of an environment, as python/src/vector_hub.cpp steps it for a lockstep
    group's players. The attributes are read after each ``reset`` (which may make a new, larger
    vector environment) and hold until the next one."""

    @property
    def num_envs(self) -> int:
        """The sub-environments of the vector environment (at least the lanes reset asked for)."""

    @property
    def step_function(self) -> Callable[..., Any] | None:
        """The vector environment's ``step``, which C++ calls with ``actions``; its result is read
        in place where it holds arrays of the right shape and dtype, else through ``as_array``."""

    @property
    def actions(self) -> np.ndarray | None:
        """The action array C++ writes each step before calling ``step_function``: C-contiguous,
        one row per sub-environment, int64 (the action plus ``start``) for a discrete space,
        float32 or float64 (the space's dtype) for a continuous one."""

    @property
    def native_engine(self) -> EnvBatch | None:
        """gpfd's own engine (gpfd._core.EnvBatch) where the vector environment is gpfd's own
        made from its id, which C++ then steps without Python; None otherwise."""

    @property
    def start(self) -> int:
        """A Discrete action space's first action (added to each action index); 0 otherwise."""

    @property
    def resets_ended(self) -> bool:
        """Autoreset disabled: a sub-environment whose episode ended must be reset
        (``reset_ended``) before it is stepped again."""

    @property
    def elapsed_key(self) -> str:
        """The key of a step's info that counts each sub-environment's steps in its episode, which
        C++ checks against its own count; "" for none."""

    @property
    def steps_subsets(self) -> bool:
        """Whether ``step_subset`` steps only the sub-environments given (else every step steps
        all of them through ``step_function``)."""

    def reset(self, seeds: list[int | None]) -> np.ndarray:
        """Resets every sub-environment, lanes 0..len(seeds)-1 from their seeds (None: a
        sub-environment that starts no episode); returns every sub-environment's observation,
        float64 (num_envs, state_dim), C-contiguous, those of seeded lanes finite. Raises
        gpfd.EnvError naming the call."""

    def step_subset(self, sub_envs: Sequence[int]) -> Any:
        """Steps only the sub-environments `sub_envs` (sorted) with their rows of ``actions``;
        returns the vector environment's 5-tuple with their rows in that order."""

    def reset_ended(self, mask: list[bool], step: int) -> np.ndarray:
        """Autoreset disabled: resets the sub-environments in `mask` before vector step `step`;
        returns every sub-environment's observation as ``reset`` does."""

    def as_array(self, value: Any, what: str, step: int, rows: int | None = None) -> np.ndarray:
        """`what` ("observations", "rewards", "terminated", "truncated", "info['...']") of vector
        step `step` as the array C++ reads: observations float64 (rows, state_dim), flags bool and
        the rest float64 (rows,); `rows` defaults to num_envs. Raises gpfd.EnvError where it has
        another shape or is not numeric."""

    def final_observations(
        self, info: dict, step: int, sub_envs: Sequence[int] | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Same-step autoreset: (mask, observations) from ``info["_final_obs"]`` and
        ``info["final_obs"]``: bool (rows,) and float64 (rows, state_dim), a row set where the
        mask is; row i is sub-environment sub_envs[i] where a subset was stepped."""

    def step_raised(self, error: BaseException, step: int, lanes: list[int]) -> NoReturn:
        """Raises gpfd.EnvError for `error`, raised by step at vector step `step` while `lanes`
        played episodes."""

    def bad_result(self, result: Any, step: int) -> NoReturn:
        """Raises gpfd.EnvError: step returned `result`, not a 5-tuple."""

    def bad_observation(
        self, step: int, lane: int, episode_step: int, index: int, value: float
    ) -> NoReturn:
        """Raises gpfd.EnvError: sub-environment `lane`'s observation after step `episode_step`
        of its episode (from 1) holds the non-finite `value` at `index`."""

    def reset_on_its_own(self, step: int, lane: int, episode_step: int, how: str) -> NoReturn:
        """Raises gpfd.EnvError: sub-environment `lane` started an episode on its own (`how`) at
        step `episode_step` of its episode, which had not ended."""

    def close(self) -> None:
        """The group is over: the vector environment is closed or parked for the next group
        (gpfd.vector_cache). Called once, also after an error."""
