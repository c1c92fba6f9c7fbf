"""Discovery on Gymnasium environments stepped in Python, in worker processes."""

import os
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium import spaces

import gpfd

# Trials short enough for tests: 2 updates of 2 episodes of at most 50 steps; the learner's
# choice in 2 seeds without random sets (it trains confirmation-length runs).
TINY: dict[str, Any] = {
    "learner.params.updates": 2,
    "learner.params.episodes": 2,
    "learner.params.max_episode_steps": 50,
    "fitness.trials": 2,
    "learner.choose_seeds": 2,
    "learner.choose_random_sets": 0,
}

# One generation of six.
SHORT: dict[str, Any] = {"seed": 1, "population": 6, "generations": 1, "set": TINY}


def without_seconds(path):
    return [line.rsplit(",", 1)[0] for line in Path(path).read_text().splitlines()]


def test_a_gymnasium_id_evolves_for_two_generations_in_worker_processes(tmp_path):
    seen: list[dict[str, Any]] = []
    common: dict[str, Any] = {
        "env": "MountainCarContinuous-v0",
        "native": False,  # Gymnasium's own, stepped in worker processes.
        "seed": 3,
        "population": 6,
        "generations": 2,
    }
    run = gpfd.evolve(**common, set=TINY, threads=2, out=tmp_path / "two", callback=seen.append)
    assert run.finished and [s["generation"] for s in seen] == [0, 1]
    assert run.best is not None
    assert run.best.env == "gymnasium:MountainCarContinuous-v0"
    assert run.best.variables == ["x0", "x1"]
    assert np.isfinite(run.history["best"]).all()
    # The same run on one process: the same result (each trial's resets are seeded).
    one = gpfd.evolve(**common, set=TINY, threads=1, out=tmp_path / "one")
    assert one.best is not None and one.best.to_text() == run.best.to_text()
    assert without_seconds(tmp_path / "one/generations.csv") == without_seconds(
        tmp_path / "two/generations.csv"
    )


class PidRecorder(gym.Wrapper):
    """Pendulum that notes which process made it. In a worker, the first instance waits (5 s at
    most) until a second worker has made one too, so that the test does not depend on how fast
    the workers start: one worker alone could otherwise take every task of a short generation.
    Once per process: a run's phases of one task (the learner choice's first, timed, training)
    would otherwise wait the whole time at every instance; that first phase's one task waits
    the whole 5 s, while the other worker starts."""

    waited = False

    def __init__(self, directory, parent):
        super().__init__(gym.make("Pendulum-v1"))
        Path(directory, str(os.getpid())).touch()
        deadline = time.monotonic() + (0 if PidRecorder.waited else 5)
        PidRecorder.waited = True
        while os.getpid() != parent and time.monotonic() < deadline:
            if len({p.name for p in Path(directory).iterdir()} - {str(parent)}) >= 2:
                break
            time.sleep(0.01)


def test_a_callable_runs_in_worker_processes(tmp_path):
    pids = tmp_path / "pids"
    pids.mkdir()
    kwargs: dict[str, Any] = {"directory": str(pids), "parent": os.getpid()}
    run = gpfd.evolve(env=PidRecorder, env_kwargs=kwargs, **SHORT, threads=2, out=tmp_path / "r")
    assert run.config["env"]["name"] == "python:PidRecorder"
    workers = {int(p.name) for p in pids.iterdir()} - {os.getpid()}
    assert len(workers) == 2


def test_a_discrete_action_space_works(tmp_path):
    run = gpfd.evolve(env="CartPole-v1", native=False, **SHORT, threads=1, out=tmp_path / "run")
    assert run.best is not None and run.best.variables == ["x0", "x1", "x2", "x3"]


def test_independent_runs_on_a_python_environment(tmp_path):
    # runs=2, as gpfd evolve --runs 2: run 1 is the single run, and runs.csv gives the verdict.
    small = {**SHORT, "set": TINY | {"validation.candidates": 2, "validation.seeds": 2}}
    gymnasiums: dict[str, Any] = {"env": "CartPole-v1", "native": False, **small}
    sets = gpfd.evolve(**gymnasiums, runs=2, threads=1, out=tmp_path / "runs")
    single = gpfd.evolve(**gymnasiums, threads=1, out=tmp_path / "single")
    assert (sets.dir / "runs.csv").is_file()
    assert single.best is not None
    first = gpfd.FeatureSet.load(str(tmp_path / "runs" / "run-01" / "best.features"))
    assert first.to_text() == single.best.to_text()
    assert (tmp_path / "runs" / "run-02" / "best.features").is_file()


def test_fitness_on_a_python_environment():
    fs = gpfd.FeatureSet.parse("x0 * x1\nx1\n", variables=["x0", "x1"])
    mcc: dict[str, Any] = {"env": "MountainCarContinuous-v0", "native": False}
    value = gpfd.fitness(fs, **mcc, set=TINY, seed=2)
    assert np.isfinite(value)
    assert gpfd.fitness(fs, **mcc, set=TINY, seed=2) == value


class NaNAfterThreeSteps(gym.Env):
    observation_space: spaces.Space[Any] = spaces.Box(-1.0, 1.0, (2,), np.float64)
    action_space = spaces.Discrete(2)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.t = 0
        return np.zeros(2), {}

    def step(self, action):
        self.t += 1
        obs = np.full(2, np.nan if self.t == 3 else 0.1)
        return obs, 1.0, False, False, {}


class RaisesInStep(NaNAfterThreeSteps):
    def step(self, action):
        raise RuntimeError("the simulator crashed")


class TextObservations(NaNAfterThreeSteps):
    observation_space = spaces.Discrete(4)


# What a misbehaving environment stops the run with, in this process and in a worker.
BAD_ENVS = [
    (
        NaNAfterThreeSteps,
        r"python:NaNAfterThreeSteps: the observation after step 3 holds nan at index 0; gpfd "
        r"needs finite",
    ),
    (
        RaisesInStep,
        r"python:RaisesInStep: step\(.*\) raised RuntimeError: the simulator crashed \(step 1 of "
        r"its episode, counted from 1\)",
    ),
]


@pytest.mark.parametrize("threads", [1, 2])
@pytest.mark.parametrize("env,message", BAD_ENVS)
def test_a_misbehaving_environment_is_a_clear_error(tmp_path, threads, env, message):
    with pytest.raises(gpfd.EnvError, match=message):
        gpfd.evolve(env=env, **SHORT, threads=threads, out=tmp_path / "r")
    assert not (tmp_path / "r").exists()  # Failed in generation 0: nothing to keep.


def test_non_box_observations_are_refused(tmp_path):
    with pytest.raises(
        TypeError, match=r"gpfd needs a Box observation space .*, not Discrete\(4\)"
    ):
        gpfd.evolve(env=TextObservations, out=tmp_path / "a")
    with pytest.raises(TypeError, match="Box observation space"):
        gpfd.evolve(env="FrozenLake-v1", out=tmp_path / "b")
    with pytest.raises(TypeError, match="env must be a name, a Gymnasium id or a callable"):
        gpfd.evolve(env=3, out=tmp_path / "c")  # type: ignore[arg-type]
