"""Where the original variables, the random feature sets and no learning score alike with every
learner setting user-env lists (MountainCar-v0 under policy gradient: -200 on every episode),
user-env tries its fallback, ARS, and goes on with it where it learns; where nothing learns (the
fallback taken away here), the run stops before GP spends its budget, saying that the learner does
not learn the task and what to change."""

import json
import subprocess
import sys

import pytest

import gpfd

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

NO_FALLBACK: dict[str, list[str]] = {"learner.choose_fallback": []}


def test_mountain_car_falls_back_to_ars_which_learns(tmp_path):
    out = tmp_path / "run"
    gpfd.evolve(
        env="MountainCar-v0", population=4, generations=1, threads=2, out=out, verbose=False
    )
    choice = json.loads((out / "run.json").read_text())["learner_choice"]
    assert choice["nothing_learns"] is False
    assert choice["fallback_from"] == 3 and choice["learner"] == "ars"
    for tried in choice["tried"][:3]:  # pg's three: no learning's -200.
        assert tried["mean"] == tried["no_learning"] == -200
    ars = choice["tried"][3]
    assert max(ars["mean"], ars["random_sets_best"]) > ars["no_learning"]
    written = tomllib.loads((out / "config.toml").read_text())
    assert written["learner"]["name"] == "ars" and "choose" not in written["learner"]


def test_mountain_car_is_refused_before_the_gp(tmp_path):
    with pytest.raises(gpfd.InputError, match=r"^nothing learns here") as refused:
        gpfd.evolve(env="MountainCar-v0", out=tmp_path / "run", set=NO_FALLBACK, verbose=False)
    text = str(refused.value)
    assert "the original variables (-200)" in text
    assert "random feature sets (-200)" in text and "no learning does" in text
    assert "learner.params" in text and "reward" in text  # What to change.
    assert not (tmp_path / "run").exists()  # Nothing written, no budget spent on GP.


def test_a_task_that_learns_goes_on_and_records_no_learning(cli, tmp_path):
    out = tmp_path / "run"
    settings = ["--set=learner.choose_seeds=3", "--set=learner.choose_random_sets=2"]
    subprocess.run(
        [
            cli,
            "evolve",
            "user-env",
            "--env",
            "CartPole-v1",
            "--population",
            "8",
            "--generations",
            "1",
            "--set=learner.params.updates=3",
            "--threads",
            "2",
            "--out",
            str(out),
            *settings,
        ],
        check=True,
        capture_output=True,
        text=True,
    )
    choice = json.loads((out / "run.json").read_text())["learner_choice"]
    assert choice["nothing_learns"] is False
    for tried in choice["tried"]:
        assert tried["no_learning"] < max(tried["mean"], tried["random_sets_best"])


def test_the_command_line_refuses_with_exit_code_2(cli, tmp_path):
    refused = subprocess.run(
        [
            cli,
            "evolve",
            "user-env",
            "--env",
            "MountainCar-v0",
            "--set=learner.choose_fallback=[]",
            "--out",
            str(tmp_path / "run"),
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert refused.returncode == 2
    assert refused.stderr.startswith("error: nothing learns here")
    assert refused.stderr.rstrip().endswith("(learner.choose (MountainCar-v0))")
