"""Ctrl-C during gpfd.evolve on an environment stepped in Python, as at a terminal (SIGINT to the
script's process group), in each stage, with 1 and 2 workers, with and without a vector form: a
KeyboardInterrupt whose one line says how to continue, exit by SIGINT (130 in a
shell), no worker tracebacks; the printed line, run as printed, then gives the run that an
uninterrupted one gives.

The environment blocks (sleeps) once the script's instrumentation makes a flag file in the stage
under test, and says so with another: the run cannot end before the signal comes."""

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from test_user_env_workers import SMALL, run_files

TESTS = Path(__file__).resolve().parent

# The environments of every script, blocking where asked: Blocking (no vector form) and the id
# BlockingPoint-v0, whose vector_entry_point gives it one.
ENVS = """
import signal
import sys
import time
from pathlib import Path

signal.signal(signal.SIGINT, signal.default_int_handler)  # As an interactive Python has it.

import gymnasium as gym

import gpfd
from gpfd import evaluator
from point_env import Point

FLAGS = Path(sys.argv[1])


class Blocking(Point):
    def __init__(self):
        super().__init__(steps=10)

    def reset(self, *, seed=None, options=None):
        if (FLAGS / "block").exists():
            (FLAGS / "ready").touch()
            time.sleep(300)  # Until the run's process ends this one.
        return super().reset(seed=seed, options=options)


def blocking_vector(num_envs, **kwargs):
    return gym.vector.SyncVectorEnv([Blocking] * num_envs)


gym.register("BlockingPoint-v0", entry_point=Blocking, vector_entry_point=blocking_vector)
"""

# Makes the flag file "block" in the stage sys.argv[2], then runs; sys.argv[3]: the workers,
# sys.argv[4]: the results directory, sys.argv[5]: the environment (Blocking or its id).
RUN = (
    ENVS
    + """
STAGE, WORKERS, OUT = sys.argv[2], int(sys.argv[3]), sys.argv[4]
ENV = Blocking if sys.argv[5] == "Blocking" else sys.argv[5]


def block():
    (FLAGS / "block").touch()


GENERATIONS_DONE = False  # The learner's choice trains as the confirmation does, before GP.


def on_generation(stats):
    global GENERATIONS_DONE
    GENERATIONS_DONE = stats["generation"] == 2
    if STAGE == "generations" and stats["generation"] == 1:
        block()  # Generation 2 blocks.


calls, run_trials = evaluator.Evaluator.__call__, evaluator.Evaluator.run_trials


def evaluate(self, config_text, tasks):
    if STAGE == "generation 0":
        block()
    return calls(self, config_text, tasks)


def trials(self, config_text, budget, tasks):
    if GENERATIONS_DONE and (STAGE, budget) in (("validation", 1), ("confirmation", 2)):
        block()
    return run_trials(self, config_text, budget, tasks)


evaluator.Evaluator.__call__ = evaluate
evaluator.Evaluator.run_trials = trials
gpfd.evolve(env=ENV, seed=3, population=4, generations=3, threads=WORKERS, set=SETTINGS,
            out=OUT, callback=on_generation, verbose=False)
""".replace("SETTINGS", repr(SMALL))
)


def python(script: str, *args: str, **kwargs) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", script, *args],
        env={**os.environ, "PYTHONPATH": str(TESTS)},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **kwargs,
    )


def finish(process: subprocess.Popen, timeout: float = 300) -> tuple[int, str, str]:
    try:
        out, err = process.communicate(timeout=timeout)
    finally:  # A run that hangs must not outlive the test.
        process.kill()
    return process.returncode, out, err


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """The uninterrupted run on each environment, by name."""
    runs = {}
    for env in ("Blocking", "BlockingPoint-v0"):
        base = tmp_path_factory.mktemp("uninterrupted")
        code, _, err = finish(python(RUN, str(base), "none", "1", str(base / "run"), env))
        assert code == 0, err
        runs[env] = run_files(base / "run")
    return runs


def interrupt(tmp_path: Path, stage: str, workers: int, env: str) -> tuple[int, str]:
    """Runs the script, sends Ctrl-C once the stage blocks, returns (exit code, stderr)."""
    process = python(
        RUN,
        str(tmp_path),
        stage,
        str(workers),
        str(tmp_path / "run"),
        env,
        start_new_session=True,  # noqa: E131  Its own process group, as a terminal's job.
    )
    deadline = time.monotonic() + 300
    while not (tmp_path / "ready").exists():
        if process.poll() is not None or time.monotonic() > deadline:
            code, _, err = finish(process, 10)
            pytest.fail(f"the run ended ({code}) before its stage {stage!r} blocked:\n{err}")
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGINT)  # Ctrl-C at a terminal.
    code, _, err = finish(process, 60)
    return code, err


def check_interruption(code: int, err: str) -> str:
    """An exit by SIGINT with one traceback, gpfd.evolve's KeyboardInterrupt; its text."""
    assert code == -signal.SIGINT, err
    assert err.count("Traceback") == 1 and "Exception ignored" not in err, err
    last = err.strip().splitlines()[-1]
    assert last.startswith("KeyboardInterrupt: gpfd.evolve interrupted in "), err
    return last


CASES = [
    ("generations", "Blocking"),
    ("validation", "Blocking"),
    ("confirmation", "Blocking"),
    ("generations", "BlockingPoint-v0"),
    ("confirmation", "BlockingPoint-v0"),
]


@pytest.mark.parametrize("workers", [1, 2])
@pytest.mark.parametrize(("stage", "env"), CASES)
def test_ctrl_c_then_the_printed_line_gives_the_uninterrupted_run(
    tmp_path, uninterrupted, stage, env, workers
):
    code, err = interrupt(tmp_path, stage, workers, env)
    text = check_interruption(code, err)
    where = {"generations": "generation 2", "validation": "validation", "confirmation": "conf"}
    assert f"interrupted in {where[stage]}" in text
    line = re.search(r" with: (gpfd\.evolve\(.*\))$", text)
    assert line is not None, text
    (tmp_path / "block").unlink()
    resume = ENVS + f"run = {line.group(1)}\nassert run.finished\n"
    code, _, err = finish(python(resume, str(tmp_path)))
    assert code == 0, err
    assert run_files(tmp_path / "run") == uninterrupted[env]


@pytest.mark.parametrize("workers", [1, 2])
def test_ctrl_c_in_generation_0_keeps_nothing(tmp_path, workers):
    code, err = interrupt(tmp_path, "generation 0", workers, "Blocking")
    text = check_interruption(code, err)
    assert "interrupted in generation 0, before its first checkpoint: nothing is kept" in text
    assert not (tmp_path / "run").exists()
