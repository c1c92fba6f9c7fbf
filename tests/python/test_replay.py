"""A run sized by its time budget says so (printed, run.json's "sizes"), and gpfd.evolve(replay=)
/ gpfd evolve --replay reruns it with the sizes and learner settings it used: the same files,
byte for byte but timings, on another number of threads or workers; bad replays are refused."""

import json
import subprocess
import time
from pathlib import Path

import pytest

import gpfd
from conftest import script_module
from point_env import Point

# user-env's choice and trainings made small: a budgeted run of seconds.
SMALL = {
    "learner.params.updates": 3,
    "learner.params.episodes": 4,
    "learner.choose_seeds": 3,
    "learner.choose_random_sets": 2,
    "fitness.trials": 2,
    "fitness.state_sample": 16,
    "validation.candidates": 2,
    "validation.seeds": 4,
    "validation.confirm_seeds": 4,
    "validation.confirm_looks": 2,
    "validation.confirm_params.updates": 4,
}


def given_sizes_run(out, generations, **more):
    """A run of cartpole-quick of given sizes (nothing from the clock)."""
    return gpfd.evolve(
        seed=2,
        population=8,
        generations=generations,
        set={"learner.params.updates": 5},
        out=out,
        verbose=False,
        **more,
    )


def files_but_timings(directory: Path) -> dict[str, str]:
    """Every file of a run as scripts/compare-outputs compares them (timings out), run.json
    without the threads and the run it replays."""
    timeless = script_module("compare-outputs").output_compare.without_timings
    files = {}
    for path in sorted(directory.rglob("*")):
        name = str(path.relative_to(directory))
        if path.is_dir() or name == ".gpfd.lock":
            continue
        if name == "run.json":
            run = json.loads(path.read_text())
            run.pop("threads")
            run.pop("replay_of", None)
            run.pop("revision")
            files[name] = json.dumps(run, sort_keys=True)
        else:
            files[name] = timeless(path)
    return files


def assert_same_run(original: Path, replayed: Path) -> None:
    a, b = files_but_timings(original), files_but_timings(replayed)
    assert sorted(a) == sorted(b)
    differ = [name for name in a if a[name] != b[name]]
    assert not differ, differ
    assert json.loads((replayed / "run.json").read_text())["replay_of"] == str(original.resolve())


@pytest.mark.long
def test_a_budgeted_user_env_run_replays_on_one_thread(cli, tmp_path):
    """user-env on CartPole-v1 (its twin), sized by a 6 s budget on 2 threads, then replayed by
    the command line on 1."""
    sets = [f"--set={key}={value}" for key, value in SMALL.items()]
    args = ["evolve", "user-env", "--env", "CartPole-v1", "--seed", "3", "--threads", "2"]
    first = subprocess.run(
        [cli, *args, "--time-budget", "6", "--out", str(tmp_path / "run"), *sets],
        capture_output=True,
        text=True,
        check=True,
    )
    assert "These sizes come from the clock" in first.stdout
    run = json.loads((tmp_path / "run/run.json").read_text())
    assert run["sizes"]["from_clock"] is True
    config = (tmp_path / "run/config.toml").read_text()
    assert f"generations = {run['sizes']['generations']}\n" in config
    assert f"population = {run['sizes']['population']}\n" in config
    assert "choose" not in config  # The learner's settings as chosen.
    again = subprocess.run(
        [
            cli,
            "evolve",
            "--replay",
            str(tmp_path / "run"),
            "--threads",
            "1",
            "--out",
            str(tmp_path / "again"),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    assert "replaying" in again.stdout and "chosen by its time budget" in again.stdout
    assert_same_run(tmp_path / "run", tmp_path / "again")


@pytest.mark.long
def test_a_run_stopped_by_its_deadline_replays_on_other_workers(tmp_path):
    """A run stepped in Python on 2 worker processes whose deadline ends it before the
    generations its budget predicted (a callback that sleeps takes the time), replayed on 1."""

    def slow(stats):
        time.sleep(1.0)

    run = gpfd.evolve(
        env=Point,
        env_kwargs={"steps": 30},
        seed=4,
        threads=2,
        time_budget=20,
        set=SMALL,
        out=tmp_path / "run",
        callback=slow,
        verbose=False,
    )
    assert run.finished
    stored = json.loads((tmp_path / "run/run.json").read_text())
    assert stored["sizes"]["generations"] < stored["time_budget"]["chosen"]["generations"]
    replayed = gpfd.evolve(
        replay=tmp_path / "run",
        env=Point,
        env_kwargs={"steps": 30},
        threads=1,
        out=tmp_path / "again",
        verbose=False,
    )
    assert replayed.finished
    assert_same_run(tmp_path / "run", tmp_path / "again")


def test_an_unbudgeted_run_has_no_sizes_from_the_clock(tmp_path):
    given_sizes_run(tmp_path / "run", 2)
    assert "sizes" not in json.loads((tmp_path / "run/run.json").read_text())


def test_a_replay_of_no_finished_run_is_refused(cli, tmp_path):
    with pytest.raises(gpfd.InputError, match=r"no such results directory \(replay .*missing\)"):
        gpfd.evolve(replay=tmp_path / "missing")
    (tmp_path / "empty").mkdir()
    with pytest.raises(gpfd.InputError, match=r"not a run's results directory"):
        gpfd.evolve(replay=tmp_path / "empty")
    given_sizes_run(tmp_path / "stopped", 3, callback=lambda stats: True)
    with pytest.raises(
        gpfd.InputError, match=r"not a finished run \(generation 0 of 3\).*--resume"
    ):
        gpfd.evolve(replay=tmp_path / "stopped")
    assert not (tmp_path / "stopped-replay").exists()
    given_sizes_run(tmp_path / "set", 1, runs=2)
    with pytest.raises(gpfd.InputError, match=r"a set of runs: replay each of its runs"):
        gpfd.evolve(replay=tmp_path / "set")
    with pytest.raises(TypeError, match="replay runs the stored config"):
        gpfd.evolve(replay=tmp_path / "set/run-01", seed=3)
    refused = subprocess.run(
        [cli, "evolve", "--replay", str(tmp_path / "missing")],
        capture_output=True,
        text=True,
        check=False,
    )
    assert refused.returncode == 2
    assert refused.stderr.startswith("error: no such results directory (replay ")
    refused = subprocess.run(
        [cli, "evolve", "--replay", str(tmp_path / "set/run-01"), "--seed", "4"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert refused.returncode == 2 and "only the threads" in refused.stderr


def test_a_set_s_run_replays(tmp_path):
    """Each run of a set is a finished run of its own."""
    given_sizes_run(tmp_path / "set", 2, runs=2)
    gpfd.evolve(replay=tmp_path / "set/run-02", threads=1, out=tmp_path / "again", verbose=False)
    assert_same_run(tmp_path / "set/run-02", tmp_path / "again")
