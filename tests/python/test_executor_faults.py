"""A worker lost mid-generation (gpfd.evolve(executor=...)): on gpfd's own pool and on Dask its
task runs again elsewhere and the run ends as on threads=1; ProcessPoolExecutor breaks as a whole,
and gpfd stops with a clear error and a directory that resume= continues to the same run, as it
does when a Dask scheduler goes away."""

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import gpfd
from gpfd.workers import WorkerError, WorkerPool
from point_env import Point
from test_executors import process_pool
from test_user_env_workers import SMALL, run_files

COMMON: dict[str, Any] = {"seed": 5, "population": 6, "generations": 3, "set": SMALL}


class DiesOnce(Point):
    """Point whose step, in a process other than `parent` and once `directory`/armed exists,
    ends its process: once in all (whoever makes `directory`/died first)."""

    def __init__(self, directory: str, parent: int):
        super().__init__(steps=30)
        self.directory, self.parent = Path(directory), parent

    def step(self, action):
        if os.getpid() != self.parent and (self.directory / "armed").exists():
            try:
                os.close(os.open(self.directory / "died", os.O_CREAT | os.O_EXCL | os.O_WRONLY))
            except FileExistsError:
                pass
            else:
                os._exit(9)
        return super().step(action)


def arm_after_generation_0(directory: Path):
    def callback(stats: dict) -> None:
        if stats["generation"] == 0:
            (directory / "armed").touch()

    return callback


def evolve(tmp_path: Path, name: str, **options: Any) -> gpfd.Run:
    directory = tmp_path / f"{name}-flags"
    directory.mkdir()
    return gpfd.evolve(
        env=DiesOnce,
        env_kwargs={"directory": str(directory), "parent": os.getpid()},
        **COMMON,
        **options,
        callback=arm_after_generation_0(directory),
        out=tmp_path / name,
        verbose=False,
    )


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> dict[str, str]:
    return run_files(evolve(tmp_path_factory.mktemp("ref"), "one", threads=1).dir)


def test_gpfd_pool_loses_no_evaluation_when_a_worker_dies(tmp_path, reference):
    run = evolve(tmp_path, "pool", threads=2)
    assert (tmp_path / "pool-flags/died").exists()
    assert run.finished and run_files(run.dir) == reference


def test_gpfd_pool_given_as_executor_loses_no_evaluation(tmp_path, reference):
    with WorkerPool(2) as executor:
        run = evolve(tmp_path, "given", executor=executor)
    assert (tmp_path / "given-flags/died").exists()
    assert run_files(run.dir) == reference


def test_dask_loses_no_evaluation_when_a_worker_dies(tmp_path, reference, dask_client):
    run = evolve(tmp_path, "dask", executor=dask_client.get_executor())
    assert (tmp_path / "dask-flags/died").exists()
    assert run_files(run.dir) == reference


def test_a_broken_process_pool_stops_the_run_and_resume_continues_it(tmp_path, reference):
    broken = pytest.raises(WorkerError, match="executor broke.*resume= continues")
    with process_pool(2) as executor, broken:
        evolve(tmp_path, "broken", executor=executor)
    assert (tmp_path / "broken-flags/died").exists()
    with process_pool(2) as executor:
        run = gpfd.evolve(
            resume=tmp_path / "broken",
            env=DiesOnce,
            env_kwargs={"directory": str(tmp_path / "broken-flags"), "parent": os.getpid()},
            executor=executor,
            verbose=False,
        )
    assert run.finished and run_files(run.dir) == reference


def test_a_dask_scheduler_that_goes_away_stops_the_run_and_resume_continues_it(
    tmp_path, reference, dask_client
):
    """A scheduler and two workers of their own (dask's command line), the scheduler killed
    after generation 0; the run resumed on another cluster."""
    distributed = pytest.importorskip("distributed")
    dask = [sys.executable, "-m", "distributed.cli.dask_scheduler"]
    address = str(tmp_path / "scheduler.json")
    path = os.pathsep.join(sys.path)  # The workers import this module (DiesOnce) as this does.
    quiet: dict[str, Any] = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    quiet["env"] = {**os.environ, "PYTHONPATH": path}
    scheduler = subprocess.Popen(
        [*dask, "--port", "0", "--no-dashboard", "--scheduler-file", address], **quiet
    )
    worker = [sys.executable, "-m", "distributed.cli.dask_worker", "--nthreads", "1"]
    workers = [
        subprocess.Popen([*worker, "--no-dashboard", "--scheduler-file", address], **quiet)
        for _ in range(2)
    ]
    try:
        client = distributed.Client(scheduler_file=address, timeout=60)
        client.wait_for_workers(2, timeout=60)
        flags = tmp_path / "lost-flags"
        flags.mkdir()
        (flags / "died").touch()  # No worker dies here: the scheduler goes.

        def kill_scheduler(stats: dict) -> None:
            if stats["generation"] == 0:
                scheduler.kill()

        with pytest.raises(WorkerError, match="cancelled a task.*scheduler goes away"):
            gpfd.evolve(
                env=DiesOnce,
                env_kwargs={"directory": str(flags), "parent": os.getpid()},
                **COMMON,
                executor=client.get_executor(),
                callback=kill_scheduler,
                out=tmp_path / "lost",
                verbose=False,
            )
        client.close(timeout=5)
    finally:
        for process in (scheduler, *workers):
            process.kill()
            process.wait()
    run = gpfd.evolve(
        resume=tmp_path / "lost",
        env=DiesOnce,
        env_kwargs={"directory": str(flags), "parent": os.getpid()},
        executor=dask_client.get_executor(),
        verbose=False,
    )
    assert run.finished and run_files(run.dir) == reference
