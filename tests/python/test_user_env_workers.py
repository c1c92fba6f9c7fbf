"""An environment stepped in Python: every stage on the worker processes (GP, validation,
confirmation, assessment), with the same results for any number of them; the config and the
results directory a run on it gets; an id registered under ``if __name__ == "__main__":``."""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import gpfd
from gpfd import user_env
from point_env import Point

# Short trials, validation and confirmation, few sampled states: each run takes seconds.
SMALL: dict[str, Any] = {
    "learner.params.updates": 2,
    "learner.params.episodes": 2,
    "fitness.trials": 2,
    "fitness.state_sample": 16,
    "validation.candidates": 2,
    "validation.seeds": 4,
    "validation.confirm_seeds": 4,
    "validation.confirm_looks": 2,
    "validation.confirm_params.updates": 2,
}


class CountedPoint(Point):
    """Point (30 steps) that notes each reset in `directory`, one line in a file named after the
    process."""

    def __init__(self, directory: str):
        super().__init__(steps=30)
        self.log = Path(directory, str(os.getpid()))

    def reset(self, *, seed=None, options=None):
        with self.log.open("a") as f:
            f.write("r\n")
        return super().reset(seed=seed, options=options)


def resets(directory: Path) -> dict[int, int]:
    return {int(p.name): len(p.read_text().splitlines()) for p in directory.iterdir()}


def run_files(directory: Path) -> dict[str, str]:
    """A run's results, but timings (generations.csv's last column, the checkpoint), the
    number of workers (run.json's threads) and the environment's keyword arguments (run.json's
    env.kwargs: the tests give each run a directory of its own)."""
    files = {}
    for path in sorted(directory.rglob("*")):
        name = str(path.relative_to(directory))
        if path.is_dir() or name in {"checkpoint.json", ".gpfd.lock"}:
            continue
        text = path.read_text()
        if name == "generations.csv":
            text = "\n".join(line.rsplit(",", 1)[0] for line in text.splitlines())
        if name == "run.json":
            info = {k: v for k, v in json.loads(text).items() if k != "threads"}
            if isinstance(info.get("env"), dict):
                info["env"] = {k: v for k, v in info["env"].items() if k != "kwargs"}
            text = json.dumps(info)
        files[name] = text
    return files


def test_validation_and_confirmation_run_on_the_workers_with_the_same_results(tmp_path):
    log = tmp_path / "resets"
    log.mkdir()
    after_gp: dict[int, int] = {}
    common: dict[str, Any] = {
        "env": CountedPoint,
        "env_kwargs": {"directory": str(log)},
        "seed": 2,
        "population": 6,
        "generations": 2,
        "set": SMALL,
    }

    def on_generation(stats):
        if stats["generation"] == 1:  # The GP is done; validation and confirmation follow.
            after_gp.update(resets(log))

    two = gpfd.evolve(**common, threads=2, out=tmp_path / "two", callback=on_generation)
    assert two.finished and after_gp
    later = resets(log)
    parent = os.getpid()
    in_parent = later.get(parent, 0) - after_gp.get(parent, 0)
    in_workers = sum(n - after_gp.get(pid, 0) for pid, n in later.items() if pid != parent)
    # Validation alone: at least 2 sets (the original variables and a candidate) x 4 seeds x 3
    # rows of 2 episodes. This process only samples states (16, for the validation's and the
    # confirmation's tasks).
    assert len((tmp_path / "two/validation.csv").read_text().splitlines()) >= 3
    assert in_workers >= 2 * 4 * 3 * 2
    assert in_parent <= 2 * 16

    one = gpfd.evolve(**common, threads=1, out=tmp_path / "one")
    assert run_files(tmp_path / "one") == run_files(tmp_path / "two")
    assert (one.info["threads"], two.info["threads"]) == (1, 2)  # The workers used.


def small_user_env_config(folder: Path) -> Path:
    """user-env's config with the learner's choice in 2 seeds of short trainings: gpfd.assess
    takes no --set, and the shipped choice trains 30 confirmation-length runs and 24 random sets
    (82,000 episodes here, minutes)."""
    text = (Path(__file__).parents[2] / "configs" / "user-env.toml").read_text()
    for old, new in [
        ("choose_seeds = 10", "choose_seeds = 2"),
        ("choose_random_sets = 8", "choose_random_sets = 0"),
        (
            "params = { updates = 15, episodes = 20, kl = 0.01 }",
            "params = { updates = 2, episodes = 2 }",
        ),
        ("confirm_params = { updates = 30 }", "confirm_params = { updates = 2 }"),
    ]:
        assert old in text, old  # The shipped config changed: update this copy.
        text = text.replace(old, new)
    path = folder / "user-env-small.toml"
    path.write_text(text)
    return path


def test_assess_runs_on_the_workers_with_the_same_table(tmp_path):
    log = tmp_path / "resets"
    log.mkdir()
    fs = gpfd.FeatureSet.parse("x0 * x1\nx1\n", variables=["x0", "x1"])
    common: dict[str, Any] = {
        "env": CountedPoint,
        "env_kwargs": {"directory": str(log)},
        "config": small_user_env_config(tmp_path),
        "runs": 3,
        "budget": 2,
        "as_frame": False,
    }
    two = gpfd.assess(fs, **common, threads=2)
    workers = {pid for pid in resets(log) if pid != os.getpid()}
    assert workers
    one = gpfd.assess(fs, **common, threads=1)
    assert list(one["set"]) == list(two["set"]) == ["original", "features", "no-learning"]
    for key in one.keys() - {"set"}:
        assert np.array_equal(one[key], two[key], equal_nan=True), key


def test_a_run_on_a_user_env_is_named_for_it_and_says_which_config(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    run = gpfd.evolve(
        env="MountainCarContinuous-v0",
        seed=1,
        population=4,
        generations=1,
        set={**SMALL, "learner.params.max_episode_steps": 20},
        threads=1,
    )
    assert run.dir == Path("results/MountainCarContinuous-v0")
    assert run.config["name"] == "user-env"
    assert run.best is not None and run.best.meta["experiment"] == "user-env"
    assert user_env.run_name("python:CountedPoint") == "CountedPoint"
    assert user_env.run_name("python:test.<locals>.make") == "make"
    assert user_env.run_name("python:<lambda>") == "user-env"
    assert user_env.run_name("ALE/Pong-v5") == "ALE-Pong-v5"
    assert user_env.run_name("envpool/CartPole-v1") == "envpool-CartPole-v1"
    assert user_env.run_name("my_module:Tiny-v0") == "Tiny-v0"
    assert user_env.run_name("python:..") == "user-env"


# A tiny Gymnasium environment as a script defines it (also tests/python/test_unguarded.py).
TINY_SOURCE = """
import gymnasium as gym
import numpy as np

import gpfd


class Tiny(gym.Env):
    observation_space = gym.spaces.Box(-1.0, 1.0, (2,), np.float64)
    action_space = gym.spaces.Discrete(2)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.t = 0
        return self.np_random.uniform(-1.0, 1.0, 2), {}

    def step(self, action):
        self.t += 1
        return np.full(2, 0.1 * action), float(action), False, self.t >= 10, {}

"""

SCRIPT = (
    "import sys\n"
    + TINY_SOURCE
    + """
if __name__ == "__main__":
    gym.register("GuardedTiny-v0", entry_point=Tiny)
    settings = {SETTINGS}
    run = gpfd.evolve(env="GuardedTiny-v0", seed=1, population=4, generations=1, threads=2,
                      set=settings, out=sys.argv[1])
    print("finished", run.finished)
"""
)


def test_an_id_registered_under_the_main_guard_reaches_the_workers(tmp_path):
    script = tmp_path / "guarded.py"
    script.write_text(textwrap.dedent(SCRIPT).replace("{SETTINGS}", repr(SMALL)))
    done = subprocess.run(
        [sys.executable, str(script), str(tmp_path / "run")],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    assert "finished True" in done.stdout


def test_a_run_on_a_user_env_resumes_with_the_env_as_stored_or_given(tmp_path):
    entry: Any = Point  # Gymnasium's EnvCreator type does not name a class.
    gym.register("gpfd-test/Point-v0", entry_point=entry, kwargs={"steps": 10})
    common: dict[str, Any] = {"seed": 2, "population": 4, "set": SMALL, "threads": 1}
    by_id = gpfd.evolve(env="gpfd-test/Point-v0", generations=1, out=tmp_path / "id", **common)
    assert by_id.finished and by_id.generations == 1
    # A Gymnasium id is found from the stored config; `env` may be given again.
    longer = gpfd.evolve(resume=tmp_path / "id", generations=2, threads=2)
    assert longer.finished and longer.generations == 2
    again = gpfd.evolve(resume=tmp_path / "id", env="gpfd-test/Point-v0", generations=3)
    assert again.generations == 3
    with pytest.raises(TypeError, match=r"is on gpfd-test/Point-v0, not CartPole-v1"):
        gpfd.evolve(resume=tmp_path / "id", env="CartPole-v1", generations=4)
    # A callable must be given again: nothing stored names it.
    gpfd.evolve(
        env=CountedPoint,
        env_kwargs={"directory": str(tmp_path)},
        generations=1,
        out=tmp_path / "callable",
        **common,
    )
    with pytest.raises(TypeError, match=r"is on CountedPoint, stepped in Python: give env="):
        gpfd.evolve(resume=tmp_path / "callable", generations=2)
    resumed = gpfd.evolve(
        resume=tmp_path / "callable",
        env=CountedPoint,
        env_kwargs={"directory": str(tmp_path)},
        generations=2,
    )
    assert resumed.finished and resumed.generations == 2
