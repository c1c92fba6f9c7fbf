"""Lockstep trials on vector forms (gpfd.adapters.sources): one vector step per time step for all
lanes, under every autoreset mode, equal to the per-environment path where lanes are seeded alike,
and every misbehaviour of a vector environment an EnvError naming the environment, the call, the
step and the lane."""

import functools
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces
from gymnasium.vector import AutoresetMode, VectorEnv

import gpfd
from gpfd import vector_source

# Short trials: 3 updates of 4 episodes, 2 trials: 8 lanes per call.
TINY: dict[str, Any] = {
    "learner.params.updates": 3,
    "learner.params.episodes": 4,
    "learner.params.max_episode_steps": 50,
    "fitness.trials": 2,
    "fitness.state_sample": 16,
}
RAW2 = gpfd.FeatureSet.parse("x0\nx1\n", variables=["x0", "x1"])
RAW4 = gpfd.FeatureSet.parse("x0\nx1\nx2\nx3\n", variables=["x0", "x1", "x2", "x3"])
MODES = [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP, AutoresetMode.DISABLED]


def toy_length(rng: np.random.Generator, extra: int) -> int:
    return 2 + int(rng.integers(6)) + extra


class Toy(gym.Env):
    """Episodes of a known length L = 2..7 (drawn from the reset seed): observation (t, L),
    reward t at step t, terminated at t = L; the action changes nothing, so the returns are
    L (L + 1) / 2 whatever the policy does."""

    observation_space = spaces.Box(-np.inf, np.inf, (2,), np.float64)
    action_space = spaces.Discrete(2)

    def __init__(self, extra: int = 0):
        self.extra = extra

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.t, self.length = 0, toy_length(self.np_random, self.extra)
        return np.array([0.0, self.length]), {}

    def step(self, action):
        self.t += 1
        return (
            np.array([self.t, self.length], float),
            float(self.t),
            self.t >= self.length,
            False,
            {},
        )


class ToyVector(VectorEnv):
    """N Toy lanes under one of Gymnasium's autoreset modes, implemented as Gymnasium defines
    them: next-step (the step after the end resets, reward 0), same-step (the end's observation
    in info["final_obs"], the new episode's returned) or disabled (stepping an ended lane without
    reset(options={"reset_mask": ...}) is an error here). reset(seed=[...]) seeds each lane as
    Toy.reset does; reset(seed=s) gives lane i s + i. `fault` makes it misbehave for the error
    tests, with more than one lane (the lockstep player's, not the single environment's)."""

    def __init__(self, num_envs, mode=AutoresetMode.NEXT_STEP, extra=0, fault=None, at=3):
        self.num_envs = num_envs
        self.metadata = {"autoreset_mode": mode}
        self.mode, self.extra, self.at = mode, extra, at
        self.fault = fault if num_envs > 1 else None
        self.single_observation_space = Toy.observation_space
        self.single_action_space = Toy.action_space
        self.observation_space = gym.vector.utils.batch_space(Toy.observation_space, num_envs)
        self.action_space = gym.vector.utils.batch_space(Toy.action_space, num_envs)
        self.rngs = [np.random.default_rng(i) for i in range(num_envs)]
        self.t = np.zeros(num_envs, int)
        self.length = np.ones(num_envs, int)
        self.done = np.zeros(num_envs, bool)
        self.steps = 0

    def _start(self, i):
        self.t[i], self.length[i], self.done[i] = 0, toy_length(self.rngs[i], self.extra), False

    def _obs(self):
        return np.stack([self.t, self.length], axis=1).astype(np.float64)

    def reset(self, *, seed=None, options=None):
        mask = np.ones(self.num_envs, bool)
        if options and "reset_mask" in options:
            mask = np.asarray(options["reset_mask"], bool)
            if self.fault == "mask ignored":
                mask[:] = True
        seeds = [seed + i for i in range(self.num_envs)] if isinstance(seed, int) else seed
        for i in np.flatnonzero(mask):
            if seeds is not None and seeds[i] is not None:
                self.rngs[i] = np.random.default_rng(seeds[i])
            self._start(i)
        self.steps = 0
        return self._obs(), {}

    def step(self, actions):
        assert self.action_space.contains(np.asarray(actions)), actions
        self.steps += 1
        if self.fault == "raises" and self.steps == self.at:
            raise RuntimeError("the simulator crashed")
        reward = np.zeros(self.num_envs)
        terminated = np.zeros(self.num_envs, bool)
        final = np.zeros(self.num_envs, bool)
        final_obs = np.zeros((self.num_envs, 2))
        for i in range(self.num_envs):
            if self.done[i] and self.mode == AutoresetMode.NEXT_STEP:
                self._start(i)
                continue
            if self.done[i] and self.mode == AutoresetMode.DISABLED:
                raise RuntimeError(f"lane {i} stepped after its end without a reset")
            self.t[i] += 1
            reward[i] = self.t[i]
            terminated[i] = self.t[i] >= self.length[i]
            self.done[i] = terminated[i]
            if terminated[i] and self.mode == AutoresetMode.SAME_STEP:
                final[i], final_obs[i] = True, (self.t[i], self.length[i])
                self._start(i)
        obs = self._obs()
        info: dict[str, Any] = {}
        if final.any():
            info = {"final_obs": final_obs, "_final_obs": final}
        if self.fault == "nan" and self.steps == self.at:
            obs[1, 0] = np.nan
        if self.fault == "shape":
            obs = np.zeros((self.num_envs, 3))
        if self.fault == "resets itself" and self.steps == self.at:
            lane = int(np.flatnonzero(~terminated)[0])
            self._start(lane)
            info = {"final_obs": final_obs, "_final_obs": np.eye(self.num_envs, dtype=bool)[lane]}
        return obs, reward, terminated, np.zeros(self.num_envs, bool), info


def toy_vector(num_envs, **kwargs):
    return ToyVector(num_envs, **kwargs)


def fitness(env, seed=3, features=RAW2, **kwargs):
    return gpfd.fitness(features, env=env, set=TINY, seed=seed, **kwargs)


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.value)
def test_every_autoreset_mode_books_the_episodes_the_per_environment_path_plays(mode):
    single = fitness(Toy)
    vector = gpfd.VectorFactory(functools.partial(toy_vector, mode=mode), per_lane_seeds=True)
    assert fitness(vector) == single
    # One step more per episode changes the fitness, so an off-by-one would show.
    longer = gpfd.VectorFactory(
        functools.partial(toy_vector, mode=mode, extra=1), per_lane_seeds=True
    )
    assert fitness(longer) != single
    assert fitness(functools.partial(Toy, extra=1)) == fitness(longer)


def test_a_vector_form_seeded_as_a_whole_gives_the_same_episodes_in_every_mode():
    results = {
        fitness(gpfd.VectorFactory(functools.partial(toy_vector, mode=mode))) for mode in MODES
    }
    assert len(results) == 1
    (value,) = results
    assert fitness(gpfd.VectorFactory(toy_vector), seed=3) == value
    assert fitness(gpfd.VectorFactory(toy_vector), seed=4) != value


@pytest.mark.parametrize(
    "kwargs",
    [
        {"actions": "discrete", "max_steps": 500},
        {},  # Continuous force: a float64 Box.
    ],
    ids=["discrete", "continuous"],
)
def test_gpfd_cartpole_through_its_vector_form_equals_the_per_environment_path(
    kwargs: dict[str, Any],
):
    per_env = functools.partial(gym.make, "gpfd/CartPole-v0", **kwargs)
    for seed in (1, 2):
        expected = fitness(per_env, seed=seed, features=RAW4)
        assert np.isfinite(expected)
        got = fitness("gpfd/CartPole-v0", seed=seed, features=RAW4, env_kwargs=kwargs)
        assert got == expected


def test_gpfd_acrobot_through_its_vector_form_equals_the_per_environment_path():
    kwargs: dict[str, Any] = {"actions": "discrete"}
    raw = gpfd.FeatureSet.parse(
        "\n".join(f"x{i}" for i in range(4)) + "\n", variables=[f"x{i}" for i in range(4)]
    )
    per_env = functools.partial(gym.make, "gpfd/Acrobot-v0", **kwargs)
    assert fitness("gpfd/Acrobot-v0", features=raw, env_kwargs=kwargs) == fitness(
        per_env, features=raw
    )


def test_a_gymnasium_id_with_a_vector_entry_point_has_a_vector_form():
    assert vector_source.GymnasiumSource("CartPole-v1").has_vector()
    assert vector_source.GymnasiumSource("gpfd/CartPole-v0").has_vector()
    assert not vector_source.GymnasiumSource("Pendulum-v1").has_vector()
    a = fitness("CartPole-v1", features=RAW4)
    assert np.isfinite(a) and fitness("CartPole-v1", features=RAW4) == a


def test_the_same_seed_gives_the_same_run_on_one_or_two_workers(tmp_path):
    common: dict[str, Any] = {"env": "gpfd/CartPole-v0", "seed": 2, "population": 6}
    small_validation = {
        "validation.candidates": 2,
        "validation.seeds": 2,
        "validation.confirm_seeds": 3,
        "validation.confirm_looks": 1,
        "validation.confirm_params": {"updates": 3},
    }
    common |= {"generations": 1, "set": TINY | small_validation}
    common["env_kwargs"] = {"actions": "discrete"}
    one = gpfd.evolve(**common, threads=1, out=tmp_path / "one")
    two = gpfd.evolve(**common, threads=2, out=tmp_path / "two")
    assert one.best is not None and two.best is not None
    assert one.best.to_text() == two.best.to_text()
    assert list(one.history["best"]) == list(two.history["best"])


def test_envpool_colon_is_refused_naming_the_right_spelling():
    with pytest.raises(gpfd.InputError, match="envpool/CartPole-v1"):
        fitness("envpool:CartPole-v1", features=RAW4)


# -- errors: gpfd.EnvError naming the environment, the call, the step and the lane -------------


def faulty(fault, **kwargs):
    return gpfd.VectorFactory(functools.partial(toy_vector, fault=fault, **kwargs))


@pytest.mark.parametrize(
    "fault, at, message",
    [
        (  # Raises mid-step.
            "raises",
            1,
            r"step of its vector form raised RuntimeError: the simulator crashed \(vector step 1, "
            r"lanes 0-7",
        ),
        (  # Returns NaN.
            "nan",
            2,
            r"the observation of lane 1 after step 2 of its episode \(vector step 2\) holds nan "
            r"at index 0",
        ),
        (  # Lies about its observation space.
            "shape",
            1,
            r"its vector form lies about its spaces: step returned observations of shape \(8, 3\) "
            r"at vector step 1",
        ),
    ],
    ids=["raises", "nan", "shape"],
)
def test_a_misbehaving_vector_form_is_an_env_error_naming_call_step_and_lane(fault, at, message):
    with pytest.raises(gpfd.EnvError, match="python:toy_vector: " + message):
        fitness(faulty(fault, at=at))


def test_a_vector_entry_point_whose_spaces_differ_from_the_single_environment():
    gym.register(
        "gpfd-test/Lying-v0",
        entry_point=Toy,  # type: ignore[arg-type]
        vector_entry_point=LyingVector,  # type: ignore[arg-type]
    )
    try:
        with pytest.raises(
            gpfd.EnvError,
            match=r"gpfd-test/Lying-v0: its vector form lies about "
            r"its spaces: its single_observation_space is Box.*\(3,\)",
        ):
            fitness("gpfd-test/Lying-v0")
    finally:
        del gym.registry["gpfd-test/Lying-v0"]


class LyingVector(ToyVector):
    def __init__(self, num_envs, **kwargs):
        super().__init__(num_envs, **kwargs)
        self.single_observation_space = spaces.Box(-np.inf, np.inf, (3,), np.float64)


def test_a_vector_form_that_resets_a_lane_on_its_own():
    with pytest.raises(
        gpfd.EnvError,
        match=r"python:toy_vector: lane 0 of its vector form reset "
        r"on its own at vector step 1, step 1 of its episode",
    ):
        fitness(faulty("resets itself", at=1, mode=AutoresetMode.SAME_STEP))


def test_a_vector_form_whose_masked_reset_resets_every_lane():
    with pytest.raises(
        gpfd.EnvError,
        match=r"python:toy_vector: lane \d+ of its vector form reset "
        r"on its own .*reset\(options=\{'reset_mask'",
    ):
        fitness(faulty("mask ignored", mode=AutoresetMode.DISABLED))


class ElapsedToy(ToyVector):
    """Counts each lane's steps in info["elapsed_step"], as EnvPool does; `fault="elapsed"` makes
    lane 2 restart its count at vector step `at`, as a lane that reset on its own would."""

    def step(self, actions):
        obs, reward, terminated, truncated, info = super().step(actions)
        elapsed = self.t.copy()
        if self.fault == "elapsed" and self.steps == self.at:
            elapsed[2] = 0
        return obs, reward, terminated, truncated, {**info, "elapsed_step": elapsed}


class CountingFactory(gpfd.VectorFactory):
    elapsed_key = "elapsed_step"


def test_a_step_count_off_gpfd_s_is_a_lane_that_reset_on_its_own():
    assert fitness(CountingFactory(ElapsedToy)) == fitness(gpfd.VectorFactory(toy_vector))
    with pytest.raises(
        gpfd.EnvError,
        match=r"lane 2 of its vector form reset on its own at vector "
        r"step 2, step 2 of its episode.*info\['elapsed_step'\] says 0",
    ):
        fitness(CountingFactory(functools.partial(ElapsedToy, fault="elapsed", at=2)))


def test_an_envpool_task_is_a_vector_form():
    pytest.importorskip("envpool")
    a = fitness("envpool/CartPole-v1", features=RAW4)
    assert np.isfinite(a) and fitness("envpool/CartPole-v1", features=RAW4) == a
    assert fitness("envpool/CartPole-v1", features=RAW4, seed=4) != a
    with pytest.raises(gpfd.InputError, match="unknown EnvPool task 'CartPole-v9'"):
        fitness("envpool/CartPole-v9", features=RAW4)
