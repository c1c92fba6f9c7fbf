"""scripts/compare-outputs, the check that a restructuring changes no output: it ignores timings
and revisions, and names every file whose content differs or that only one binary wrote."""

from pathlib import Path

import pytest

from conftest import script_module


@pytest.fixture(scope="module")
def compare_outputs():
    return script_module("compare-outputs")


def write(root: Path, files: dict[str, str]) -> Path:
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


def test_timings_and_revisions_are_ignored(compare_outputs, tmp_path):
    old = write(
        tmp_path / "old",
        {
            "run/generations.csv": "generation,best,seconds\n0,1.5,0.372\n",
            "run/run.json": '{"seed": 3, "revision": "442790eb0a9c", "seconds": 1.2}',
            "repro/section.json": '{"text": "Compute time: GP runs 18 s (gpfd 442790eb0a9c)"}',
            "cp.stdout": "gen   0  best 1.5  2s  ETA 4m05s\n"
            "results in 3.2 s (gpfd 0.1.0 442790eb0a9c)\n",
        },
    )
    new = write(
        tmp_path / "new",
        {
            "run/generations.csv": "generation,best,seconds\n0,1.5,0.989\n",
            "run/run.json": '{"seed": 3, "revision": "576aeb7c0d1e-dirty", "seconds": 0.8}',
            "repro/section.json": '{"text": "Compute time: GP runs 40 s (gpfd 576aeb7c0d1e)"}',
            "cp.stdout": "gen   0  best 1.5  1s  ETA 5m00s\n"
            "results in 2.9 s (gpfd 0.1.0 576aeb7c0d1e)\n",
        },
    )
    assert compare_outputs.output_compare.compare(old, new) == []


def test_content_and_missing_files_are_named(compare_outputs, tmp_path):
    old = write(
        tmp_path / "old",
        {
            "run/generations.csv": "generation,best,seconds\n0,1.5,0.372\n",
            "run/best.features": "x + 1\n",
        },
    )
    new = write(
        tmp_path / "new",
        {
            "run/generations.csv": "generation,best,seconds\n0,1.6,0.372\n",
            "run/front.csv": "size\n",
        },
    )
    assert compare_outputs.output_compare.compare(old, new) == [
        "only in old: run/best.features",
        "only in new: run/front.csv",
        "differs: run/generations.csv",
    ]
