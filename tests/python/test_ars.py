"""The ars learner (Augmented Random Search) from Python: gpfd.evolve with `[learner] name = "ars"`
gives what `gpfd evolve` gives, and on an environment stepped in Python the same run on one and two
workers."""

import subprocess
from pathlib import Path

import gpfd

CONFIG = """name = "ars-py"
seed = 2
[env]
name = "cartpole"
params = { actions = "discrete", max_steps = 200 }
[learner]
name = "ars"
params = { updates = 4, n_delta = 4, n_top = 3, normalise = true }
[fitness]
trials = 3
[genome]
max_features = 3
max_depth = 3
max_size = 9
[gp]
population = 6
generations = 2
[validation]
candidates = 2
seeds = 4
confirm_seeds = 6
confirm_params = { updates = 6 }
"""


def without_seconds(text: str) -> list[str]:
    return [line.rsplit(",", 1)[0] for line in text.splitlines()]


def outcome(directory: Path) -> tuple[str, list[str], str]:
    return (
        (directory / "best.features").read_text(),
        without_seconds((directory / "generations.csv").read_text()),
        (directory / "validation.csv").read_text(),
    )


def test_evolve_with_ars_equals_gpfd_evolve(cli, tmp_path):
    config = tmp_path / "ars.toml"
    config.write_text(CONFIG)
    subprocess.run(
        [cli, "evolve", str(config), "--quiet", "--threads", "2", "--out", str(tmp_path / "cli")],
        check=True,
        capture_output=True,
    )
    run = gpfd.evolve(str(config), threads=1, out=tmp_path / "py", verbose=False)
    assert run.finished and run.best is not None
    assert outcome(tmp_path / "py") == outcome(tmp_path / "cli")


def test_ars_on_a_python_environment_is_the_same_on_one_and_two_workers(tmp_path):
    config = tmp_path / "ars.toml"
    config.write_text(CONFIG)
    for workers in (1, 2):
        gpfd.evolve(
            str(config),
            env="CartPole-v1",
            native=False,  # Gymnasium's own, stepped in Python by the workers.
            set={"learner.params.max_episode_steps": 200},
            threads=workers,
            out=tmp_path / f"workers-{workers}",
            verbose=False,
        )
    assert outcome(tmp_path / "workers-1") == outcome(tmp_path / "workers-2")
    assert "# env: gymnasium:CartPole-v1" in (tmp_path / "workers-1/best.features").read_text()
