"""gpfd.evolve(time_budget=...) as gpfd evolve --time-budget: the sizes chosen are written into
config.toml (no budget left in it) and run.json; bad values are gpfd.InputError."""

import json
import re

import pytest

import gpfd
from conftest import QUICK


def test_a_budget_writes_the_sizes_it_chose(tmp_path):
    settings = {**QUICK, "validation.candidates": 3, "validation.seeds": 6}
    settings["validation.confirm_seeds"] = 6
    run = gpfd.evolve("cartpole-quick", time_budget="3s", set=settings, out=tmp_path / "run")
    config = (tmp_path / "run/config.toml").read_text()
    assert "time_budget" not in config
    chosen = json.loads((tmp_path / "run/run.json").read_text())["time_budget"]
    assert chosen["seconds"] == 3.0
    population = re.search(r"^population = (\d+)$", config, re.MULTILINE)
    assert population is not None
    assert int(population.group(1)) == chosen["chosen"]["population"]
    assert re.search(r"^generations = [1-9]", config, re.MULTILINE)
    assert run.dir == tmp_path / "run"


@pytest.mark.parametrize("budget", ["ten minutes", "0s", -5])
def test_a_bad_budget_is_an_input_error(tmp_path, budget):
    with pytest.raises(gpfd.InputError, match="time_budget"):
        gpfd.evolve("cartpole-quick", time_budget=budget, out=tmp_path / "run")


@pytest.mark.parametrize("budget", [float("nan"), float("inf"), b"10", [60], True])
def test_a_budget_of_no_number_names_the_argument(tmp_path, budget):
    """Not a finite number nor text: named as the argument given, not as a config value."""
    with pytest.raises(gpfd.InputError, match=r"^time_budget must be .*\(time_budget=\)$") as e:
        gpfd.evolve("cartpole-quick", time_budget=budget, out=tmp_path / "run")
    assert "config" not in str(e.value)


@pytest.mark.parametrize("budget", ["abc", 0.01])
def test_a_budget_error_names_the_argument_not_the_command_line(tmp_path, budget):
    """A bad budget, and one too short for the runs asked for, name time_budget=, the argument the
    caller gave, where the command line's error names its option."""
    with pytest.raises(gpfd.InputError, match=r"\(time_budget=\)$") as refused:
        gpfd.evolve("cartpole-quick", time_budget=budget, runs=2, out=tmp_path / "run")
    assert "--" not in str(refused.value)
