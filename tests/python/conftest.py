"""Shared fixtures of the Python tests: the repository, the gpfd command line, small configs."""

import importlib.machinery
import importlib.util
import os
import shutil
from pathlib import Path
from types import ModuleType

import gymnasium as gym
import pytest

from gpfd.envs import GpfdEnv

REPO = Path(__file__).resolve().parents[2]

# GP settings that make a discovery run take a second: tiny population, short trials.
QUICK = {
    "learner.params.updates": 5,
    "fitness.trials": 2,
}


def script_module(name: str) -> ModuleType:
    """scripts/NAME (a Python script without the .py) loaded as a module."""
    loader = importlib.machinery.SourceFileLoader(
        name.replace("-", "_"), str(REPO / "scripts" / name)
    )
    spec = importlib.util.spec_from_loader(loader.name, loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


@pytest.fixture(scope="session")
def cli() -> str:
    """The gpfd command line: $GPFD_CLI (scripts/test sets it), else a build in the repository."""
    given = os.environ.get("GPFD_CLI")
    if given:
        assert Path(given).is_file(), f"GPFD_CLI={given} does not exist"
        return given
    for preset in ("release", "dev"):
        candidate = REPO / "build" / preset / "gpfd"
        if candidate.is_file():
            return str(candidate)
    found = shutil.which("gpfd")
    if found:
        return found
    pytest.skip("the gpfd command line is not built (set GPFD_CLI)")


def gpfd_env(env: gym.Env) -> GpfdEnv:
    """The gpfd environment under an environment's Gymnasium wrappers."""
    base = env.unwrapped
    assert isinstance(base, GpfdEnv), base
    return base


@pytest.fixture(scope="session")
def dask_client():
    """A Dask client of a local cluster of two worker processes, one thread each (skipped where
    distributed is not installed: the test extra installs it)."""
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()
