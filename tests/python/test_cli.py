"""The wheel's command line: `pip install .` installs the tool `gpfd` beside the interpreter."""

import csv
import importlib.metadata
import os
import subprocess
import sysconfig
from pathlib import Path

import pytest

import gpfd
from conftest import REPO
from point_env import Point


def installed_cli() -> Path:
    """The `gpfd` that pip installed with this package (its scripts directory)."""
    try:
        dist = importlib.metadata.distribution("gpfd")
    except importlib.metadata.PackageNotFoundError:
        pytest.skip("gpfd is not installed with pip")
    scripts = [f for f in dist.files or [] if f.name == "gpfd" and f.parent.name == "bin"]
    assert scripts, "the installed package has no gpfd command"
    path = Path(str(dist.locate_file(scripts[0]))).resolve()
    assert path == (Path(sysconfig.get_path("scripts")) / "gpfd").resolve()
    assert os.access(path, os.X_OK), path
    return path


def run(*args: str | Path) -> str:
    result = subprocess.run(
        [str(installed_cli()), *map(str, args)], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_the_command_is_the_modules_build():
    assert run("--version").strip() == f"gpfd {gpfd.__version__} ({gpfd._core.revision})"


def test_the_command_lists_the_environments():
    listed = run("envs")
    # The C++ ones: those registered from Python by tests run before are this process's only.
    for name in filter(gpfd.environments.registry.is_builtin, gpfd._core.env_names()):
        assert f"\n{name}: " in "\n" + listed


def test_the_command_evolves_like_the_cpp_build(tmp_path, cli):
    """The same seed gives the same features from the wheel's tool as from the C++ build."""
    options = ["--seed", "1", "--population", "20", "--generations", "2", "--threads", "2"]
    run("evolve-toy", *options, "--quiet", "--out", tmp_path / "wheel")
    subprocess.run(
        [cli, "evolve-toy", *options, "--quiet", "--out", str(tmp_path / "cpp")],
        check=True,
        capture_output=True,
    )
    written = (tmp_path / "wheel/best.features").read_text()
    assert "# env: toy" in written
    assert written == (tmp_path / "cpp/best.features").read_text()


def test_the_command_loads_plugins():
    """The tool exports its symbols (ENABLE_EXPORTS) for the plug-ins it loads: the test plug-in
    of a C++ build ($GPFD_TEST_PLUGIN, else build/release) registers its environment."""
    plugin = os.environ.get("GPFD_TEST_PLUGIN") or str(
        REPO / "build/release/tests/libgpfd_test_plugin.so"
    )
    if not Path(plugin).is_file():
        pytest.skip("the test plug-in is not built (set GPFD_TEST_PLUGIN)")
    if os.environ.get("GPFD_DEBIAN_LIBS_HIDDEN"):
        pytest.skip("the test plug-in links Debian's libraries, hidden here (scripts/test-wheel)")
    assert "walk: a point on a line" in run("--plugin", plugin, "envs")


@pytest.mark.parametrize("env", ["callable", "gymnasium"])
def test_the_front_of_a_run_on_an_environment_stepped_in_python(tmp_path, env):
    """`gpfd features show DIR --front` on a run of gpfd.evolve whose environment the command
    cannot make (a callable's python:NAME, Gymnasium's own as gymnasium:ID): the validated front
    as the run left it, its variables named as the run's features files name them."""
    small = {
        "learner.params.updates": 2,
        "learner.params.episodes": 2,
        "learner.params.max_episode_steps": 20,
        "fitness.trials": 1,
        "fitness.state_sample": 16,
        "validation.candidates": 2,
        "validation.seeds": 2,
        "validation.confirm_seeds": 2,
        "validation.confirm_looks": 1,
        "validation.confirm_params.updates": 2,
    }
    gpfd.evolve(
        "cartpole-quick",
        env=Point if env == "callable" else "CartPole-v1",
        native=False,
        seed=1,
        population=4,
        generations=1,
        threads=1,
        set=small,
        out=tmp_path / "run",
        verbose=False,
    )
    shown = run("features", "show", tmp_path / "run", "--front")
    with (tmp_path / "run/front.csv").open(newline="") as f:
        front = list(csv.DictReader(f))
    assert shown.startswith("nodes  features  selection"), shown
    assert len(shown.splitlines()) == len(front) + 1, (shown, front)
    for row in front:  # Each set's first expression, as front.csv has it.
        assert row["expressions"].split(" ; ")[0] in shown, (row, shown)
