"""gpfd.evolve, gpfd.fitness, gpfd.assess and gpfd.load_run against the command line."""

import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import gpfd
from conftest import QUICK

# Settings per config that make a run of 8 x 3 take about a second.
SETTINGS = {
    "cartpole-quick": QUICK,
    "tetris-quick": {
        "learner.params.iterations": 2,
        "learner.params.games": 3,
        "fitness.trials": 2,
    },
}


def run_cli(cli, *args, cwd=None):
    return subprocess.run(
        [cli, *map(str, args)], check=True, capture_output=True, text=True, cwd=cwd
    )


def without_seconds(text):
    return [line.rsplit(",", 1)[0] for line in text.splitlines()]


@pytest.mark.parametrize(
    "config,env,threads",
    [("cartpole-quick", None, 2), ("cartpole-quick", "acrobot", 1), ("tetris-quick", None, 2)],
)
def test_evolve_equals_gpfd_evolve(cli, tmp_path, config, env, threads):
    settings = SETTINGS[config]
    cli_args = [
        "evolve",
        config,
        "--seed",
        5,
        "--out",
        tmp_path / "cli",
        "--quiet",
        "--population",
        8,
        "--generations",
        3,
    ]
    cli_args += [f"--set={k}={v}" for k, v in settings.items()]
    if env:
        cli_args += ["--env", env]
    run_cli(cli, *cli_args)
    run = gpfd.evolve(
        config,
        env=env,
        seed=5,
        population=8,
        generations=3,
        threads=threads,
        set=settings,
        out=tmp_path / "py",
    )
    for name in ["best.features", "config.toml", "best/generation-0002.features"]:
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text(), name
    assert without_seconds((tmp_path / "py/generations.csv").read_text()) == without_seconds(
        (tmp_path / "cli/generations.csv").read_text()
    )
    assert run.finished and run.generations == 3 and run.info["seed"] == 5
    assert run.best is not None
    assert run.best.to_text() == (tmp_path / "cli/best.features").read_text()


def test_callback_sees_each_generation_and_can_stop_the_run(tmp_path):
    seen = []

    def callback(stats):
        seen.append(stats)
        return stats["generation"] == 1

    run = gpfd.evolve(
        seed=2, population=8, generations=5, set=QUICK, out=tmp_path / "run", callback=callback
    )
    assert [s["generation"] for s in seen] == [0, 1]
    assert set(seen[0]) == {
        "generation",
        "best",
        "mean",
        "median",
        "mean_size",
        "mean_features",
        "evaluations",
        "cache_hits",
        "seconds",
        "best_features",
        "generations",
    }
    assert seen[0]["generations"] == 5  # The run's, as the config (or a deadline) sets them.
    assert isinstance(seen[1]["best_features"], gpfd.FeatureSet)
    assert (
        seen[1]["best_features"].to_text().splitlines()[-1]
        == run.best_of(1).to_text().splitlines()[-1]
    )
    assert not run.finished and run.generations == 2
    # The stopped run continues exactly: same as an uninterrupted one.
    resumed = gpfd.evolve(resume=tmp_path / "run")
    whole = gpfd.evolve(seed=2, population=8, generations=5, set=QUICK, out=tmp_path / "whole")
    assert resumed.best is not None and whole.best is not None
    assert resumed.finished and resumed.best.to_text() == whole.best.to_text()


def test_a_callback_that_raises_stops_the_run_with_its_exception(tmp_path):
    def callback(stats):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        gpfd.evolve(
            seed=2, population=8, generations=3, set=QUICK, out=tmp_path / "run", callback=callback
        )
    assert gpfd.load_run(tmp_path / "run").generations == 1  # Its checkpoint was written.


def test_bad_settings_are_clear_errors(tmp_path):
    with pytest.raises(gpfd.InputError, match="gp.populaton"):
        gpfd.evolve(set={"gp.populaton": 10}, out=tmp_path / "a")
    with pytest.raises(gpfd.InputError, match="unknown environment 'cartpol ': neither gpfd's"):
        gpfd.evolve(env="cartpol ", out=tmp_path / "b")
    with pytest.raises(gpfd.InputError, match="no-such-config"):
        gpfd.evolve("no-such-config", out=tmp_path / "c")
    with pytest.raises(TypeError, match="resume continues with the stored config"):
        gpfd.evolve(resume=tmp_path / "c", seed=3)
    assert not (tmp_path / "a").exists()


def test_fitness_is_the_fitness_gp_computed(tmp_path):
    run = gpfd.evolve(seed=4, population=8, generations=2, set=QUICK, out=tmp_path / "run")
    best = run.best_of(1)
    # The recorded fitness includes the size penalty (cartpole-quick: 0.05 per node).
    value = gpfd.fitness(best, "cartpole-quick", set=QUICK, seed=1)
    assert np.isfinite(value) and value > 0
    assert gpfd.fitness(best, "cartpole-quick", set=QUICK, seed=1) == value
    with pytest.raises(gpfd.InputError, match="the features are for cartpole, not acrobot"):
        gpfd.fitness(best, "acrobot-quick")


def test_assess_returns_the_statistics_table(cli, tmp_path):
    features = tmp_path / "f.features"
    features.write_text("# env: cartpole\n# variables: x, dx, th, dth\nth + dth\nth * 2\n")
    table = gpfd.assess(
        str(features), env="cartpole", runs=4, budget=5, seed=3, out=tmp_path / "py", as_frame=False
    )
    assert list(table["set"]) == ["original", "f", "no-learning"]  # The reference last.
    assert all(isinstance(v, np.ndarray) and len(v) == 3 for v in table.values())
    run_cli(
        cli,
        "assess",
        "cartpole",
        "--features",
        features,
        "--runs",
        4,
        "--budget",
        5,
        "--seed",
        3,
        "--out",
        tmp_path / "cli",
        "--quiet",
    )
    assert (tmp_path / "py/summary.csv").read_text() == (tmp_path / "cli/summary.csv").read_text()
    header, *rows = (tmp_path / "cli/summary.csv").read_text().splitlines()
    for i, row in enumerate(rows):
        for key, cell in zip(header.split(","), row.split(","), strict=True):
            if key != "set":
                assert float(table[key][i]) == float(cell), key
    fs = gpfd.FeatureSet.load(str(features))
    again = gpfd.assess([fs], env="cartpole", runs=4, budget=5, seed=3, as_frame=False)
    assert np.array_equal(again["mean_final"], table["mean_final"])
    with pytest.raises(gpfd.InputError, match="nothing to assess"):
        gpfd.assess(env="cartpole")


def test_load_run_reads_a_results_directory(repo):
    run = gpfd.load_run(repo / "tests/data/results/acrobot-quick-run", as_frame=False)
    assert run.finished and run.generations == 15
    assert run.config["env"]["name"] == "acrobot"
    assert run.history["generation"].tolist() == list(range(15))
    assert run.best is not None
    assert run.best.env == "acrobot" and run.best_of(14).n_features >= 1
    with pytest.raises(FileNotFoundError, match="holds no gpfd run"):
        gpfd.load_run(repo / "docs")


def test_pandas_tables_when_pandas_is_installed(repo):
    pandas = pytest.importorskip("pandas")
    run = gpfd.load_run(repo / "tests/data/results/acrobot-quick-run")
    assert isinstance(run.history, pandas.DataFrame)


def test_ctrl_c_stops_after_a_checkpoint(tmp_path):
    # Generations enough that the run cannot end before the signal comes, however late: 500 of
    # this converged population took 3.6 s, so a loaded machine could finish them first.
    # The child takes Ctrl-C as an interactive Python does, even where this test runs with SIGINT
    # ignored (a background job of a non-interactive shell), which the child would inherit.
    script = (
        "import signal\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "import gpfd\n"
        f"gpfd.evolve(seed=2, population=8, generations=1000000, set={QUICK!r}, threads=1, "
        f"out={str(tmp_path / 'run')!r})\n"
    )
    process = subprocess.Popen([sys.executable, "-c", script], stderr=subprocess.PIPE, text=True)
    history = tmp_path / "run/generations.csv"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and (
        not history.is_file() or len(history.read_text().splitlines()) < 3
    ):
        time.sleep(0.05)
    process.send_signal(signal.SIGINT)
    try:
        _, stderr = process.communicate(timeout=120)
    finally:  # A run that ignored the signal must not outlive the test.
        process.kill()
    assert process.returncode != 0 and "KeyboardInterrupt" in stderr
    run = gpfd.load_run(tmp_path / "run")
    assert 2 <= run.generations < 1000000 and not run.finished
    resumed = gpfd.evolve(resume=tmp_path / "run", generations=run.generations + 1)
    assert resumed.finished and resumed.generations == run.generations + 1


def _hold_lock(directory):
    """A process that holds `directory`'s lock as another gpfd would (flock on .gpfd.lock)."""
    directory.mkdir(parents=True, exist_ok=True)
    script = (
        "import fcntl, sys, time\n"
        "f = open(sys.argv[1], 'w')\n"
        "fcntl.flock(f, fcntl.LOCK_EX)\n"
        "f.write('4242\\n'); f.flush()\n"
        "print('locked', flush=True)\n"
        "time.sleep(120)\n"
    )
    holder = subprocess.Popen(
        [sys.executable, "-c", script, str(directory / ".gpfd.lock")],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert holder.stdout is not None
    assert holder.stdout.readline().strip() == "locked"
    return holder


def test_evolve_and_assess_take_the_directory_lock(tmp_path):
    """One writer per results directory, from Python as from the command line."""
    holder = _hold_lock(tmp_path / "run")
    try:
        with pytest.raises(gpfd.InputError, match="another gpfd process"):
            gpfd.evolve(seed=2, population=8, generations=1, set=QUICK, out=tmp_path / "run")
        with pytest.raises(gpfd.InputError, match="another gpfd process"):
            gpfd.assess(env="cartpole", raw=True, runs=2, budget=2, out=tmp_path / "run")
        assert sorted(p.name for p in (tmp_path / "run").iterdir()) == [".gpfd.lock"]
    finally:
        holder.kill()
        holder.wait()


def test_a_directory_holding_files_needs_force(tmp_path):
    out = tmp_path / "busy"
    out.mkdir()
    (out / "notes.txt").write_text("mine\n")
    with pytest.raises(gpfd.InputError, match="force=True"):
        gpfd.evolve(seed=2, population=8, generations=1, set=QUICK, out=out)
    with pytest.raises(gpfd.InputError, match="empty directory name"):
        gpfd.evolve(seed=2, population=8, generations=1, set=QUICK, out="")
    run = gpfd.evolve(seed=2, population=8, generations=1, set=QUICK, out=out, force=True)
    assert run.finished and (out / "notes.txt").read_text() == "mine\n"
    # A run is resumed, never started over, even with force.
    with pytest.raises(gpfd.InputError, match="resume"):
        gpfd.evolve(seed=2, population=8, generations=1, set=QUICK, out=out, force=True)


def test_verbose_prints_what_the_command_prints(tmp_path, capsys):
    gpfd.evolve(seed=2, population=8, generations=2, set=QUICK, out=tmp_path / "run", verbose=True)
    printed = capsys.readouterr().out
    assert "gpfd evolve: cartpole-quick (pg on cartpole), population 8, generations 2" in printed
    assert "gen   1  best " in printed and "ETA" in printed
    assert "best.features" in printed.splitlines()[-1]
