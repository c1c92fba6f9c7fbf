"""Config settings that make the shipped configs' runs small enough for CI's checks of installed
packages (tests/wheel): fewer and shorter learning trials, a small validation stage."""

from typing import Any

SMALL: dict[str, Any] = {
    "learner.params.updates": 3,
    "learner.params.episodes": 4,
    "fitness.trials": 2,
    "fitness.state_sample": 32,
    "validation.candidates": 2,
    "validation.seeds": 2,
    "validation.confirm_seeds": 3,
    "validation.confirm_looks": 1,
    "validation.confirm_params": {"updates": 3},
}
