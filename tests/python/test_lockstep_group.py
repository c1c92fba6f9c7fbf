"""Lockstep groups (python/src/lockstep_group.hpp): the fitness evaluations of several genomes
played in one vector environment, one vector step for all their lanes. Where the vector form
seeds each lane, a group gives every genome the fitness it gets alone, in every autoreset mode;
a vector form seeded as a whole gives the same run for any number of workers; and a failure in
one member's lanes stops the group with the EnvError that names it, without a hang."""

import functools
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import gpfd
from gpfd import _core, evaluator
from test_vector_source import MODES, TINY, Toy, ToyVector, toy_vector


class SubsetToy(ToyVector):
    """ToyVector whose step(actions, env_id=ids) steps only the lanes `ids` and returns their rows
    in that order, with info["env_id"], as EnvPool does."""

    def step(self, actions, env_id=None):
        if env_id is None:
            return super().step(actions)
        ids = np.asarray(env_id)
        kept = (self.t.copy(), self.length.copy(), self.done.copy(), list(self.rngs))
        full = np.zeros(self.num_envs, dtype=np.int64)
        full[ids] = actions
        obs, reward, terminated, truncated, _ = super().step(full)
        others = np.setdiff1d(np.arange(self.num_envs), ids)
        for array, before in zip((self.t, self.length, self.done), kept[:3], strict=True):
            array[others] = before[others]
        for i in others:
            self.rngs[i] = kept[3][i]
        info = {"env_id": ids}
        return obs[ids], reward[ids], terminated[ids], truncated[ids], info


class SubsetFactory(gpfd.VectorFactory):
    steps_subsets = True


SMALL_VALIDATION: dict[str, Any] = {
    "validation.candidates": 2,
    "validation.seeds": 2,
    "validation.confirm_seeds": 3,
    "validation.confirm_looks": 1,
    "validation.confirm_params": {"updates": 3},
}


def recorded_tasks(env, monkeypatch, tmp_path, **kwargs) -> tuple[str, list[tuple[bytes, int]]]:
    """The config text and (genome, seed) tasks of the first generation of a small run."""
    calls: list[tuple[str, list]] = []
    original = evaluator.Evaluator.__call__

    def record(self, config_text, tasks):
        calls.append((config_text, list(tasks)))
        return original(self, config_text, tasks)

    monkeypatch.setattr(evaluator.Evaluator, "__call__", record)
    gpfd.evolve(
        env=env,
        seed=5,
        population=6,
        generations=1,
        threads=1,
        set=TINY | SMALL_VALIDATION,
        out=tmp_path / "run",
        **kwargs,
    )
    return calls[0]


@pytest.mark.parametrize(
    "env",
    [
        pytest.param("gpfd/CartPole-v0", id="gpfd-native"),
        pytest.param(
            gpfd.VectorFactory(
                lambda n: gym.make_vec("gpfd/CartPole-v0", n, vectorization_mode="sync"),
                per_lane_seeds=True,
            ),
            id="sync-vector-env",
        ),
    ]
    + [
        pytest.param(
            gpfd.VectorFactory(functools.partial(toy_vector, mode=mode), per_lane_seeds=True),
            id=f"toy-{mode.value}",
        )
        for mode in MODES
    ]
    + [
        pytest.param(
            SubsetFactory(lambda n: SubsetToy(n), per_lane_seeds=True), id="toy-steps-subsets"
        )
    ],
)
def test_a_group_gives_each_genome_its_fitness_alone(env, monkeypatch, tmp_path):
    config_text, tasks = recorded_tasks(env, monkeypatch, tmp_path)
    assert len(tasks) >= 4
    alone = [_core.trial_fitness_group(config_text, [task])[0] for task in tasks]
    assert all(np.isfinite(alone))
    assert _core.trial_fitness_group(config_text, tasks) == alone
    # Any split into groups, the members in another order too.
    assert _core.trial_fitness_group(config_text, tasks[::-1]) == alone[::-1]
    assert _core.trial_fitness_group(config_text, tasks[:1]) == alone[:1]


def test_a_vector_form_that_steps_subsets_plays_the_per_environment_path():
    subsets = SubsetFactory(lambda n: SubsetToy(n), per_lane_seeds=True)
    raw = gpfd.FeatureSet.parse("x0\nx1\n", variables=["x0", "x1"])
    assert gpfd.fitness(raw, env=subsets, set=TINY, seed=3) == gpfd.fitness(
        raw, env=Toy, set=TINY, seed=3
    )
    assert (
        gpfd.fitness_of_each([raw] * 3, env=subsets, set=TINY, seed=3)
        == [gpfd.fitness(raw, env=Toy, set=TINY, seed=3)] * 3
    )


def test_fitness_of_each_takes_a_list():
    raw = gpfd.FeatureSet.parse("x0\nx1\n", variables=["x0", "x1"])
    with pytest.raises(TypeError, match="list of feature sets"):
        gpfd.fitness_of_each(raw, env=Toy, set=TINY)  # type: ignore[arg-type]


def test_a_vector_form_seeded_as_a_whole_gives_one_run_for_any_number_of_workers(tmp_path):
    common: dict[str, Any] = {
        "env": "CartPole-v1",
        "native": False,  # Gymnasium's own, whose vector form is the subject.
        "seed": 2,
        "population": 20,
        "generations": 1,
        "set": TINY | SMALL_VALIDATION,
    }
    one = gpfd.evolve(**common, threads=1, out=tmp_path / "one")
    two = gpfd.evolve(**common, threads=2, out=tmp_path / "two")
    assert one.best is not None and two.best is not None
    assert one.best.to_text() == two.best.to_text()
    assert list(one.history["best"]) == list(two.history["best"])
    assert list(one.history["mean"]) == list(two.history["mean"])


@pytest.mark.parametrize(
    "fault, message",
    [
        (
            "raises",
            r"step of its vector form raised RuntimeError: the simulator crashed \(vector step "
            r"3, lanes [0-9, -]+ playing episodes\)",
        ),
        (
            "nan",
            r"the observation of lane 1 after step 3 of its episode \(vector step 3\) holds nan",
        ),
        (
            "shape",
            r"its vector form lies about its spaces: step returned observations of shape "
            r"\(\d+, 3\) at vector step 1, for \d+ sub-environments",
        ),
        (
            "resets itself",
            r"lane \d+ of its vector form reset on its own at vector step 3",
        ),
    ],
    ids=["raises", "nan", "shape", "resets-itself"],
)
@pytest.mark.parametrize("threads", [1, 2])
def test_a_misbehaving_vector_form_stops_a_group_with_the_error_that_names_it(
    fault, message, threads, tmp_path
):
    faulty = gpfd.VectorFactory(functools.partial(toy_vector, fault=fault, at=3))
    with pytest.raises(gpfd.EnvError, match="python:toy_vector: " + message):
        gpfd.evolve(
            env=faulty,
            seed=5,
            population=6,
            generations=1,
            threads=threads,
            set=TINY | SMALL_VALIDATION,
            out=tmp_path / "run",
        )
    assert not (tmp_path / "run" / "best.features").exists()


def test_two_lambdas_one_after_the_other_are_two_environments(tmp_path):
    # Both are "python:<lambda>": the worker's cached tasks must not keep the first one.
    small: dict[str, Any] = {"seed": 1, "population": 4, "generations": 1, "threads": 1}
    small["set"] = TINY | SMALL_VALIDATION
    first = gpfd.evolve(env=lambda: Toy(), out=tmp_path / "toy", **small)
    second = gpfd.evolve(
        env=lambda: gym.make("gpfd/CartPole-v0", actions="discrete"), out=tmp_path / "cp", **small
    )
    assert first.best is not None and second.best is not None
    assert "x3" in second.best.to_text() or "x2" in second.best.to_text()


@pytest.mark.parametrize(
    "call, error, message",
    [
        (
            lambda: gpfd.fitness_of_each([42], env=Toy),  # type: ignore[list-item]
            TypeError,
            r"features\[0\] must be a",
        ),
        (lambda: gpfd.assess(env=Toy, runs=-1), ValueError, "runs must be at least 1, got -1"),
        (
            lambda: gpfd.assess(env=Toy, threads="x"),  # type: ignore[arg-type]
            TypeError,
            "threads must be an integer",
        ),
        (lambda: gpfd.assess(env=Toy, budget=0), ValueError, "budget must be at least 1"),
        (
            lambda: gpfd.evolve(env=Toy, population=2.5),  # type: ignore[arg-type]
            TypeError,
            "population must be an",
        ),
        (lambda: gpfd.evolve(env=Toy, runs=0), ValueError, "runs must be at least 1, got 0"),
        (lambda: gpfd.evolve(env=Toy, generations=-1), ValueError, "generations must be at"),
        (
            lambda: gpfd.evolve(env=Toy, verbose="yes"),  # type: ignore[arg-type]
            TypeError,
            r"verbose must be None, True or False, not str \('yes'\)",
        ),
    ],
)
def test_bad_python_arguments_are_errors_that_name_them(call, error, message):
    with pytest.raises(error, match=message):
        call()
