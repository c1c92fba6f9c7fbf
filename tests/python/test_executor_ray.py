"""gpfd.evolve(executor=gpfd.ray.Executor()) on a local Ray cluster of 2 CPUs: the same run as
threads=1, and with a worker killed mid-generation (Ray runs its task again); a task past its
task_timeout runs again on a new worker, and one past it on every try stops the run with a
WorkerError naming the environment and the step; shutdown(cancel_futures=True) leaves no task
running. Skipped where Ray is not installed (the extra executors installs it)."""

import os
import signal
import sys
import time
from pathlib import Path

import pytest

import gpfd
from gpfd.workers import WorkerError
from test_executor_faults import evolve
from test_task_timeout import COMMON as HANG_COMMON
from test_task_timeout import TIMEOUT, reference_files, resumed_mended
from test_task_timeout import evolve as evolve_hangs
from test_user_env_workers import run_files

ray = pytest.importorskip("ray")
import gpfd.ray  # noqa: E402  (after the skip: it needs Ray)


@pytest.fixture
def ray_cluster():
    """A local Ray cluster whose workers import this directory's modules as this process does,
    one per test: a test's runs that failed on purpose may leave tasks queued on it (a hung task
    retried), which would take the CPUs another test counts."""
    path = os.pathsep.join(sys.path)
    # Ray's workers inherit the driver's SIGINT; one ignored (a script started in the background
    # by a non-interactive shell, as `cmd &`) never gets the KeyboardInterrupt of a cancel
    # without force: started as an interactive session starts them.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        runtime_env={"env_vars": {"PYTHONPATH": path}},
    )
    signal.signal(signal.SIGINT, previous)
    yield
    ray.shutdown()


def test_ray_gives_threads_one_and_survives_a_killed_worker(tmp_path, ray_cluster):
    reference = run_files(evolve(tmp_path, "one", threads=1).dir)
    executor = gpfd.ray.Executor()
    assert executor.workers == 2
    run = evolve(tmp_path, "ray", executor=executor)
    assert (tmp_path / "ray-flags/died").exists()  # A Ray worker died mid-generation.
    assert run.info["threads"] == 2
    assert run_files(run.dir) == reference


def test_ray_executor_after_shutdown_refuses_work():
    executor = gpfd.ray.Executor()
    executor.shutdown()
    with pytest.raises(RuntimeError, match="shut down"):
        executor.submit(abs, -1)


@pytest.fixture(scope="module")
def hung_reference(tmp_path_factory) -> dict[str, str]:
    return reference_files(tmp_path_factory.mktemp("ref"))


def test_a_task_hung_once_runs_again_on_a_new_ray_worker(tmp_path, ray_cluster, hung_reference):
    executor = gpfd.ray.Executor()
    run = evolve_hangs(
        tmp_path, "ray", once=True, arm=True, **HANG_COMMON, executor=executor, task_timeout=TIMEOUT
    )
    assert (tmp_path / "ray-flags/hung").exists()
    assert run.finished and run_files(run.dir) == hung_reference


def test_a_task_hung_on_every_ray_worker_stops_naming_the_step_and_resumes(
    tmp_path,
    ray_cluster,
    hung_reference,
):
    # One retry, and a deadline of 3 s: a few seconds in all (a task of these runs takes
    # milliseconds; one slowed past it on a loaded machine is run again, to the same result).
    executor = gpfd.ray.Executor(max_retries=1)
    with pytest.raises(WorkerError) as caught:
        evolve_hangs(
            tmp_path, "run", once=False, arm=True, **HANG_COMMON, executor=executor, task_timeout=3
        )
    text = str(caught.value)
    assert "task_timeout=3 s in python:Hangs: step " in text and "of its episode" in text, text
    assert "resume= continues" in text, text
    assert resumed_mended(tmp_path / "run") == hung_reference


def spin(directory: str, i: int) -> None:
    """A task that never ends by itself: it marks its start, then sleeps in short turns."""
    (Path(directory) / f"started-{i}").touch()
    while True:
        time.sleep(0.05)


@pytest.mark.isolated  # Failed after the whole suite's collection, not alone.
@pytest.mark.parametrize("force", [False, True])
def test_shutdown_cancelling_futures_leaves_no_task_running(tmp_path, ray_cluster, force):
    """Four endless tasks on 2 CPUs (two running, two queued): shutdown(cancel_futures=True)
    cancels them all; the cluster's CPUs come back free (no task holds one), and a task queued
    then never starts."""
    executor = gpfd.ray.Executor(cancel_force=force)
    futures = [executor.submit(spin, str(tmp_path), i) for i in range(4)]
    deadline = time.monotonic() + 120
    while len(list(tmp_path.glob("started-*"))) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    assert len(list(tmp_path.glob("started-*"))) >= 2  # Two are running.
    executor.shutdown(cancel_futures=True)
    assert all(future.cancelled() for future in futures)
    while ray.available_resources().get("CPU", 0) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    assert ray.available_resources().get("CPU", 0) == 2  # No task of them holds a CPU.
    started = set(tmp_path.glob("started-*"))
    time.sleep(1.0)  # A queued task left on the cluster would take a free CPU and start.
    assert set(tmp_path.glob("started-*")) == started
    assert ray.available_resources().get("CPU", 0) == 2
