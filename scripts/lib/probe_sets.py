"""Feature sets handed to a planted task's learner, for the probes (scripts/planted-*-probe)."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

import gpfd
from gpfd.planted import TASKS


def scaled(text: str, values: np.ndarray) -> str:
    """`text` centred and scaled by its mean and sd on `values`, as fitness.normalise does."""
    return f"(({text}) - {float(values.mean())!r}) / {float(values.std())!r}"


def write_set(directory: Path, task: str, label: str, expressions: list[str]) -> Path:
    """A features file `label`.features for the planted task `task` (its name: "Energy")."""
    names = [f"x{i}" for i in range(TASKS[task].variables)]
    path = directory / f"{label}.features"
    gpfd.FeatureSet.parse("".join(e + "\n" for e in expressions), variables=names).save(str(path))
    return path


def scores(out: Path, column: str) -> dict[str, np.ndarray]:
    """Per set of a gpfd.assess directory `out`, its runs' `column` of finals.csv."""
    by_set: dict[str, list[float]] = {}
    with (out / "finals.csv").open(newline="") as f:
        for row in csv.DictReader(f):
            by_set.setdefault(row["set"], []).append(float(row[column]))
    return {k: np.array(v) for k, v in by_set.items()}
