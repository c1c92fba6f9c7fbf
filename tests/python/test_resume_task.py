"""A resumed run continues only the task it was started on (issue 53.6): gpfd.evolve records in
run.json ("env") the callable's qualified name, its keyword arguments and a fingerprint of its
spaces, and refuses a resume with another callable, other keywords or other spaces, naming the
difference."""

import json
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import gpfd
from point_env import Point

SMALL: dict[str, Any] = {
    "learner.params.updates": 2,
    "learner.params.episodes": 2,
    "fitness.trials": 1,
    "fitness.state_sample": 16,
    "validation.candidates": 2,
    "validation.seeds": 2,
    "validation.confirm_seeds": 2,
    "validation.confirm_looks": 1,
    "validation.confirm_params.updates": 2,
}

BOUND = {"high": 10.0}  # The observation bound of bounded_point, changed by a test.


class OtherPoint(Point):
    """The same dynamics under another name."""


def bounded_point(steps: int = 20) -> gym.Env:
    env = Point(steps)
    env.observation_space = gym.spaces.Box(-BOUND["high"], BOUND["high"], (2,), np.float64)
    return env


def start(tmp_path, env: Any, env_kwargs: dict | None = None) -> Any:
    return gpfd.evolve(
        "cartpole-quick",
        env=env,
        env_kwargs=env_kwargs,
        seed=1,
        population=4,
        generations=1,
        threads=1,
        set=SMALL,
        out=tmp_path / "run",
        verbose=False,
    )


def resume(tmp_path, env: Any, env_kwargs: dict | None = None) -> Any:
    return gpfd.evolve(
        resume=tmp_path / "run",
        env=env,
        env_kwargs=env_kwargs,
        generations=2,
        threads=1,
        verbose=False,
    )


def test_run_json_records_the_task(tmp_path):
    start(tmp_path, Point, {"steps": 20})
    task = json.loads((tmp_path / "run/run.json").read_text())["env"]
    assert task["callable"] == "point_env.Point"
    assert task["kwargs"] == {"steps": 20}
    assert task["observation_space"] == str(Point.observation_space)
    assert task["spaces"].startswith("sha256:") and len(task["spaces"]) == 7 + 64
    again = resume(tmp_path, Point, {"steps": 20})  # The same task resumes.
    assert again.finished and again.generations == 2


def test_another_callable_is_refused_naming_both(tmp_path):
    start(tmp_path, Point, {"steps": 20})
    with pytest.raises(gpfd.InputError, match=r"the environment is .*OtherPoint, not point_env\."):
        resume(tmp_path, OtherPoint, {"steps": 20})
    assert gpfd.load_run(tmp_path / "run").generations == 1  # Nothing was run.


def test_other_keywords_are_refused_naming_both(tmp_path):
    start(tmp_path, Point, {"steps": 20})
    with pytest.raises(
        gpfd.InputError, match=r"env_kwargs are \{'steps': 30\}, not \{'steps': 20\}"
    ):
        resume(tmp_path, Point, {"steps": 30})
    with pytest.raises(gpfd.InputError, match=r"env_kwargs are \{\}, not \{'steps': 20\}"):
        resume(tmp_path, Point)


def test_other_spaces_are_refused_naming_the_space(tmp_path, monkeypatch):
    start(tmp_path, bounded_point)
    monkeypatch.setitem(BOUND, "high", 5.0)
    with pytest.raises(gpfd.InputError, match=r"its observation_space is Box\(-5\.0, 5\.0,") as e:
        resume(tmp_path, bounded_point)
    assert "run.json" in str(e.value) and "action_space" not in str(e.value)
    monkeypatch.setitem(BOUND, "high", 10.0)
    assert resume(tmp_path, bounded_point).generations == 2


def test_a_gymnasium_id_resumes_only_with_its_keywords(tmp_path):
    """The id is found from the stored config; its keywords are not in it: run.json's say which
    were given, and a resume without them (or with others) is refused."""
    entry: Any = Point
    gym.register("gpfd-test/ResumedPoint-v0", entry_point=entry)
    start(tmp_path, "gpfd-test/ResumedPoint-v0", {"steps": 20})
    with pytest.raises(gpfd.InputError, match=r"env_kwargs are \{\}, not \{'steps': 20\}"):
        resume(tmp_path, None)
    assert resume(tmp_path, None, {"steps": 20}).generations == 2
