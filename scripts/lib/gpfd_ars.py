"""gpfd's own `ars` learner trained and scored from a script: `gpfd train ID --learner ars`
(native, on gpfd's twin of a Gymnasium task), its final policy's greedy mean return over
`gpfd train --eval` episodes. Used by scripts/ars-reference and scripts/zoo-check --learner gpfd."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path


def gpfd_cli() -> str:
    """$GPFD_CLI, or the `gpfd` beside this Python (the package's console script)."""
    return os.environ.get("GPFD_CLI") or str(Path(sys.executable).with_name("gpfd"))


def train_and_score(
    task: str,
    seed: int,
    params: dict[str, object],
    features: str | None = None,
    with_original: bool = False,
    episodes: int = 20,
) -> float:
    """The greedy mean return over `episodes` of ARS trained with `params` (gpfd learners' ars
    names) on the raw observation, or on the features file `features` (beside the observation
    where `with_original`). A missing command line, a failed training or one that diverged (no
    evaluation) ends the script with a message naming it, not a number."""
    with tempfile.TemporaryDirectory() as out:
        command = [gpfd_cli(), "train", task, "--learner", "ars", "--seed", str(seed)]
        if features is not None:
            command += ["--features", features] + (["--add-raw"] if with_original else [])
        for key, value in params.items():
            command += ["--param", f"{key}={value}"]
        command += ["--eval", str(episodes), "--out", out, "--force", "--quiet"]
        try:
            subprocess.run(command, check=True, capture_output=True, text=True)
        except FileNotFoundError:
            raise SystemExit(
                f"{command[0]}: gpfd's command line is not there; set GPFD_CLI or install the "
                "package (scripts/install-python)"
            ) from None
        except subprocess.CalledProcessError as failed:
            message = f"gpfd train {task} seed {seed} failed: {failed.stderr.strip()}"
            raise SystemExit(message) from None
        weights = json.loads((Path(out) / "weights.json").read_text())
    evaluation = weights.get("greedy_evaluation")
    if evaluation is None:
        raise SystemExit(f"gpfd train {task} seed {seed}: no greedy evaluation (diverged?)")
    return float(evaluation["mean_return"])
