"""The wheel's command line: `pip install .` installs the tool `gpfd` beside the interpreter."""

import importlib.metadata
import os
import subprocess
import sysconfig
from pathlib import Path

import pytest

import gpfd
from conftest import REPO


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
    for name in gpfd._core.env_names():
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
