"""Shared fixtures of the Python tests: the repository, the gpfd command line, small configs."""

import os
import shutil
from pathlib import Path

import gymnasium as gym
import pytest

from gpfd.envs import GpfdEnv

REPO = Path(__file__).resolve().parents[2]

# GP settings that make a discovery run take a second: tiny population, short trials.
QUICK = {
    "learner.params.updates": 5,
    "fitness.trials": 2,
}


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
