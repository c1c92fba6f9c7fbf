"""Planted-feature tasks: small Gymnasium environments whose answer is known (issue 34, point 1).

Each task plants one function of its observation that a linear policy needs and the raw
variables cannot give (by a symmetry: a linear fit of it on them explains nothing), so a
discovery run on it can be checked against that answer (gpfd.planted_check). Registered on
``import gpfd`` as ``gpfd/Planted<Name>-v0``, each with a vector form
(``gymnasium.make_vec(id, num_envs)``), so that gpfd's lockstep players step many lanes per call.

Four tasks are tracking tasks: the state moves on its own (the action never changes it) and the
reward of a step is ``-(a - f(s))**2`` for the observed state s, so the best policy is a = f(s) and
the best linear policy on features phi is the least-squares fit of f on phi and a constant: it is
optimal exactly when f lies in their span. One is a control task with discrete actions.

- ``PlantedProduct``: x0 = c, a context drawn per episode from U(-1, 1), x1 = x, drawn each step
  from U(-1, 1); f = x0 * x1 (a gain that the context sets).
- ``PlantedRatio``: x0 ~ U(-1, 1), x1 = +-U(0.5, 2) (either sign), both drawn each step;
  f = 0.5 * x0 / x1 (within [-1, 1]).
- ``PlantedEnergy``: a frictionless pendulum (x0 = angle, x1 = angular velocity, g / l = 1,
  semi-implicit Euler with dt = 0.1), started at an angle from U(-pi, pi) and a velocity from
  U(-1, 1); f = (E - 1.25) / 1.25 with E = x1**2 / 2 + 1 - cos(x0), its energy (E in [0, 2.5]).
- ``PlantedDistractor``: x0, x1, x2 ~ U(-1, 1), each step; f = x0 * x1, and x2 is a distractor
  that features must leave out.
- ``PlantedSwitch`` (two actions): x0 = x, started in U(-1, 1), x1 = s, +1 or -1 per episode;
  action 1 moves x by 0.1 s, action 0 by -0.1 s (x kept in [-2, 2]), reward -x**2 after the move,
  30 steps. The best policy moves x towards 0: action 1 exactly when s x < 0, so a softmax policy
  linear in s x = x0 * x1 approaches it (a policy linear in x0 and x1 cannot tell the signs apart).
  Only the sign of s x decides, so any set on which a linear function has that sign carries it
  (``sqrt(x1 - x0)`` does, with its threshold at 1).

Every episode's randomness comes from the generator that ``reset(seed=s)`` makes
(``gymnasium.utils.seeding.np_random(s)``, as ``gym.Env.reset`` does), drawn at the reset, so an
episode is a function of its seed and actions. Lane i of the vector form reset with seed s plays
exactly what the single environment reset with seed s plays; both step the same code (_Lanes).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from gpfd._core import InputError

Array = np.ndarray


@dataclass(frozen=True)
class Task:
    """One planted task: its variables, length, action kind, dynamics and known answer.

    start(rng) -> (first state (d,), the episode's exogenous draws (steps, m));
    step(states (k, d), actions (k,), draws (k, m)) -> (next states (k, d), rewards (k,)).
    needed: the features a best linear policy needs, as (name, function of states (N, d) -> (N,)).
    left_out: the variables that a returned feature must not depend on.
    by_sign: only the needed features' signs matter (the best action of a discrete task is where
    one is below 0), so a set carries them when a linear function of it has their sign.

    Example::

        t = gpfd.planted.task("Product")
        t.gym_id, t.variables, [name for name, f in t.needed]  # ..., 2, ["x0 * x1"]
    """

    name: str
    variables: int
    steps: int
    discrete: bool
    start: Callable[[np.random.Generator], tuple[Array, Array]]
    step: Callable[[Array, Array, Array], tuple[Array, Array]]
    needed: tuple[tuple[str, Callable[[Array], Array]], ...]
    left_out: tuple[int, ...] = ()
    by_sign: bool = False

    @property
    def gym_id(self) -> str:
        return f"gpfd/Planted{self.name}-v0"


def _tracking(target: Callable[[Array], Array], advance: Callable[[Array, Array], Array]):
    """A tracking task's step: reward -(a - target(s))**2, then the state advances on its own."""

    def step(states: Array, actions: Array, draws: Array) -> tuple[Array, Array]:
        actions = np.clip(actions, -1.0, 1.0)
        return advance(states, draws), -((actions - target(states)) ** 2)

    return step


def _product(states: Array) -> Array:
    return states[:, 0] * states[:, 1]


def _ratio(states: Array) -> Array:
    return 0.5 * states[:, 0] / states[:, 1]


def _energy(states: Array) -> Array:
    return (0.5 * states[:, 1] ** 2 + 1.0 - np.cos(states[:, 0]) - 1.25) / 1.25


def _start_product(rng: np.random.Generator) -> tuple[Array, Array]:
    values = rng.uniform(-1.0, 1.0, 22)  # c, x, then the next 20 x's.
    return values[:2], values[2:].reshape(20, 1)


def _advance_product(states: Array, draws: Array) -> Array:
    return np.column_stack([states[:, 0], draws[:, 0]])


def _signed_scale(rng: np.random.Generator, size: int) -> Array:
    """Values of U(0.5, 2) with a random sign: a ratio's denominator away from 0."""
    return rng.uniform(0.5, 2.0, size) * np.where(rng.random(size) < 0.5, -1.0, 1.0)


def _start_ratio(rng: np.random.Generator) -> tuple[Array, Array]:
    x = rng.uniform(-1.0, 1.0, 21)
    y = _signed_scale(rng, 21)
    return np.array([x[0], y[0]]), np.column_stack([x[1:], y[1:]])


def _start_energy(rng: np.random.Generator) -> tuple[Array, Array]:
    angle, velocity = rng.uniform(-math.pi, math.pi), rng.uniform(-1.0, 1.0)
    return np.array([angle, velocity]), np.zeros((20, 0))


def _advance_pendulum(states: Array, draws: Array) -> Array:
    velocity = states[:, 1] - 0.1 * np.sin(states[:, 0])
    angle = np.mod(states[:, 0] + 0.1 * velocity + math.pi, 2 * math.pi) - math.pi
    return np.column_stack([angle, velocity])


def _start_distractor(rng: np.random.Generator) -> tuple[Array, Array]:
    values = rng.uniform(-1.0, 1.0, (21, 3))
    return values[0], values[1:]


def _start_switch(rng: np.random.Generator) -> tuple[Array, Array]:
    x = rng.uniform(-1.0, 1.0)
    s = 1.0 if rng.random() < 0.5 else -1.0
    return np.array([x, s]), np.zeros((30, 0))


def _step_switch(states: Array, actions: Array, draws: Array) -> tuple[Array, Array]:
    push = np.where(np.asarray(actions) > 0, 0.1, -0.1) * states[:, 1]
    x = np.clip(states[:, 0] + push, -2.0, 2.0)
    return np.column_stack([x, states[:, 1]]), -(x**2)


TASKS: dict[str, Task] = {
    t.name: t
    for t in (
        Task(
            "Product",
            2,
            20,
            False,
            _start_product,
            _tracking(_product, _advance_product),
            (("x0 * x1", _product),),
        ),
        Task(
            "Ratio",
            2,
            20,
            False,
            _start_ratio,
            _tracking(_ratio, lambda states, draws: draws),
            (("x0 / x1", _ratio),),
        ),
        Task(
            "Energy",
            2,
            20,
            False,
            _start_energy,
            _tracking(_energy, _advance_pendulum),
            (("x1 * x1 / 2 - cos(x0)", _energy),),
        ),
        Task(
            "Distractor",
            3,
            20,
            False,
            _start_distractor,
            _tracking(_product, lambda states, draws: draws),
            (("x0 * x1", _product),),
            left_out=(2,),
        ),
        Task(
            "Switch",
            2,
            30,
            True,
            _start_switch,
            _step_switch,
            (("x0 * x1", _product),),
            by_sign=True,
        ),
    )
}


def task(name: str) -> Task:
    """The task `name` ("Product") or its Gymnasium id; gpfd.InputError naming the tasks
    otherwise.

    Example::

        env = gymnasium.make(gpfd.planted.task("Product").gym_id)  # gpfd/PlantedProduct-v0
    """
    for t in TASKS.values():
        if name in (t.name, t.gym_id):
            return t
    raise InputError(f"no planted task {name!r}; the tasks: {', '.join(TASKS)}")


def _spaces(t: Task) -> tuple[spaces.Box, spaces.Space]:
    obs = spaces.Box(-np.inf, np.inf, shape=(t.variables,), dtype=np.float64)
    act: spaces.Space = (
        spaces.Discrete(2) if t.discrete else spaces.Box(-1.0, 1.0, shape=(1,), dtype=np.float64)
    )
    return obs, act


class _Lanes:
    """The episodes of n lanes of one task: states, step counts and exogenous draws."""

    def __init__(self, t: Task, n: int):
        self.task = t
        self.states = np.zeros((n, t.variables))
        self.draws: list[Array] = [np.zeros((t.steps, 0))] * n
        self.t = np.zeros(n, dtype=np.int64)

    def start(self, lane: int, rng: np.random.Generator) -> None:
        self.states[lane], self.draws[lane] = self.task.start(rng)
        self.t[lane] = 0

    def step(self, lanes: Array, actions: Array) -> tuple[Array, Array, Array]:
        """Steps `lanes` (indices) with `actions` (one per lane): (rewards, terminated,
        truncated) of those lanes; their states move."""
        if len(lanes) == 0:
            return np.zeros(0), np.zeros(0, dtype=bool), np.zeros(0, dtype=bool)
        draws = np.stack([self.draws[i][self.t[i]] for i in lanes])
        self.states[lanes], rewards = self.task.step(self.states[lanes], actions, draws)
        self.t[lanes] += 1
        return rewards, np.zeros(len(lanes), dtype=bool), self.t[lanes] >= self.task.steps


def _actions(t: Task, actions: Any, n: int) -> Array:
    """Actions as one value per lane: ints for a discrete task, floats for a continuous one."""
    values = np.asarray(actions).reshape(n, -1)[:, 0]
    return values.astype(np.int64) if t.discrete else values.astype(np.float64)


class PlantedEnv(gym.Env):
    """One planted task (gpfd.planted.TASKS) as a Gymnasium environment."""

    metadata: dict[str, Any] = {"render_modes": []}

    def __init__(self, task_name: str):
        self.task = task(task_name)
        self.observation_space, self.action_space = _spaces(self.task)
        self._lanes = _Lanes(self.task, 1)
        self._seeded = False

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)  # A seed makes self.np_random anew; else its stream goes on.
        self._lanes.start(0, self.np_random)
        return self._lanes.states[0].copy(), {}

    def step(self, action):
        rewards, terminated, truncated = self._lanes.step(
            np.array([0]), _actions(self.task, action, 1)
        )
        obs = self._lanes.states[0].copy()
        return obs, float(rewards[0]), bool(terminated[0]), bool(truncated[0]), {}


class PlantedVectorEnv(VectorEnv):
    """num_envs lanes of one planted task, autoreset as Gymnasium's vector environments do
    (next step by default; same step; disabled, with ``options={"reset_mask": ...}``).

    ``reset(seed=s)`` seeds lane i with s + i; ``reset(seed=[s0, s1, ...])`` lane i with si (None:
    its stream goes on, or fresh entropy where it has none yet)."""

    def __init__(
        self,
        task_name: str,
        num_envs: int = 1,
        autoreset_mode: str | AutoresetMode = AutoresetMode.NEXT_STEP,
    ):
        self.task = task(task_name)
        self.num_envs = int(num_envs)
        if self.num_envs < 1:
            raise InputError(f"{self.task.gym_id}: num_envs must be at least 1, got {num_envs}")
        mode = AutoresetMode(autoreset_mode)
        self.metadata = {"autoreset_mode": mode}
        self.single_observation_space, self.single_action_space = _spaces(self.task)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self._lanes = _Lanes(self.task, self.num_envs)
        self._rngs: list[np.random.Generator | None] = [None] * self.num_envs
        self._ended = np.zeros(self.num_envs, dtype=bool)

    def reset(self, *, seed: int | list[int | None] | None = None, options: dict | None = None):
        if seed is None or isinstance(seed, (int, np.integer)):
            seeds: list[int | None] = [
                None if seed is None else int(seed) + i for i in range(self.num_envs)
            ]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f"expected {self.num_envs} seeds, got {len(seeds)}")
        mask = np.ones(self.num_envs, dtype=bool)
        if options and "reset_mask" in options:
            mask = np.asarray(options["reset_mask"], dtype=bool)
        for i in np.flatnonzero(mask):
            self._start(int(i), seeds[i])
        return self._lanes.states.copy(), {}

    def step(self, actions):
        actions = _actions(self.task, actions, self.num_envs)
        mode = self.metadata["autoreset_mode"]
        rewards = np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, dtype=bool)
        truncated = np.zeros(self.num_envs, dtype=bool)
        restart = (
            self._ended.copy() if mode == AutoresetMode.NEXT_STEP else np.zeros_like(self._ended)
        )
        for i in np.flatnonzero(restart):
            self._start(int(i), None)
        lanes = np.flatnonzero(~restart)
        rewards[lanes], terminated[lanes], truncated[lanes] = self._lanes.step(
            lanes, actions[lanes]
        )
        self._ended = terminated | truncated
        info: dict[str, Any] = {}
        if mode == AutoresetMode.SAME_STEP and self._ended.any():
            final = np.full(self.num_envs, None, dtype=object)
            for i in np.flatnonzero(self._ended):
                final[i] = self._lanes.states[i].copy()
                self._start(int(i), None)
            info = {
                "final_obs": final,
                "_final_obs": self._ended.copy(),
                "final_info": {},
                "_final_info": self._ended.copy(),
            }
            self._ended = np.zeros(self.num_envs, dtype=bool)
        return self._lanes.states.copy(), rewards, terminated, truncated, info

    def _start(self, lane: int, seed: int | None) -> None:
        rng = self._rngs[lane]
        if seed is not None or rng is None:
            rng, _ = seeding.np_random(seed)
            self._rngs[lane] = rng
        self._lanes.start(lane, rng)
        self._ended[lane] = False


def register_all() -> None:
    """Registers every planted task with Gymnasium, with its vector form (idempotent)."""
    for t in TASKS.values():
        if t.gym_id not in gym.registry:
            gym.register(
                id=t.gym_id,
                entry_point="gpfd.planted:PlantedEnv",
                vector_entry_point="gpfd.planted:PlantedVectorEnv",
                kwargs={"task_name": t.name},
            )
