"""gpfd.evolve and gpfd.assess on any concurrent.futures.Executor (executor=): the same run as
threads=1 on ProcessPoolExecutor, gpfd's own WorkerPool, loky and Dask; the environment shipped
once per worker (gpfd.discovery._jobs); the caller's executor left running; bad input named."""

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import gpfd
from gpfd.workers import WorkerPool
from point_env import Point
from test_lockstep_group import SMALL_VALIDATION, TINY
from test_user_env_workers import SMALL, run_files

COMMON: dict[str, Any] = {"seed": 4, "population": 6, "generations": 2, "set": SMALL}


class LoggedFactory:
    """Makes Point; notes in `directory` each unpickling of itself, one line in a file named
    after the process: how many times a worker received the environment."""

    def __init__(self, directory: str):
        self.directory = directory

    def __call__(self) -> Point:
        return Point(steps=30)

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        with Path(self.directory, str(os.getpid())).open("a") as f:
            f.write("unpickled\n")


def process_pool(workers: int) -> ProcessPoolExecutor:
    """A ProcessPoolExecutor whose workers do not fork this process (gpfd refuses those)."""
    return ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("forkserver"))


def received(directory: Path) -> dict[int, int]:
    return {int(p.name): len(p.read_text().splitlines()) for p in directory.iterdir()}


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> dict[str, str]:
    """The files of the run on threads=1."""
    out = tmp_path_factory.mktemp("one") / "run"
    gpfd.evolve(env=LoggedFactory(str(out.parent)), **COMMON, threads=1, out=out, verbose=False)
    return run_files(out)


def evolve_on(executor: Any, tmp_path: Path, threads: int = 0) -> tuple[gpfd.Run, dict[int, int]]:
    log = tmp_path / "received"
    log.mkdir()
    run = gpfd.evolve(
        env=LoggedFactory(str(log)),
        **COMMON,
        threads=threads,
        executor=executor,
        out=tmp_path / "run",
        verbose=False,
    )
    return run, received(log)


def test_process_pool_gives_threads_one_and_gets_the_env_once_per_worker(tmp_path, reference):
    with process_pool(2) as executor:
        run, got = evolve_on(executor, tmp_path)
        assert executor.submit(int, "7").result() == 7  # The caller's executor goes on.
    assert run_files(run.dir) == reference
    assert run.info["threads"] == 2  # The executor's workers.
    # GP, validation and confirmation: three jobs (config texts), one environment sent once.
    assert got and set(got.values()) == {1} and os.getpid() not in got


def test_gpfd_worker_pool_given_as_executor_gives_threads_one(tmp_path, reference):
    with WorkerPool(2) as executor:
        run, got = evolve_on(executor, tmp_path, threads=3)
        assert executor.submit(abs, -2).result() == 2
    assert run_files(run.dir) == reference
    assert run.info["threads"] == 3  # Sized as told.
    assert len(got) == 2 and set(got.values()) == {1}


def test_threads_two_runs_on_gpfd_pool_through_the_same_jobs(tmp_path, reference):
    run, got = evolve_on(None, tmp_path, threads=2)
    assert run_files(run.dir) == reference
    assert len(got) == 2 and set(got.values()) == {1}


def test_a_thread_pool_runs_in_this_process_with_the_same_run(tmp_path, reference):
    with ThreadPoolExecutor(2) as executor:
        run, _ = evolve_on(executor, tmp_path)
    assert run_files(run.dir) == reference


def test_loky_gives_threads_one(tmp_path, reference):
    loky = pytest.importorskip("loky")
    executor = loky.get_reusable_executor(max_workers=2)
    try:
        run, got = evolve_on(executor, tmp_path)
    finally:
        executor.shutdown(wait=True)
    assert run_files(run.dir) == reference
    assert got and set(got.values()) == {1}


def test_dask_gives_threads_one(tmp_path, reference, dask_client):
    run, got = evolve_on(dask_client.get_executor(), tmp_path)
    assert run_files(run.dir) == reference
    assert run.info["threads"] == 2
    assert got and set(got.values()) == {1}


def test_a_vector_form_in_lockstep_groups_on_dask_gives_threads_one(tmp_path, dask_client):
    common: dict[str, Any] = {
        "env": "CartPole-v1",
        "native": False,  # Gymnasium's own, stepped in Python: its vector form on Dask.
        "seed": 2,
        "population": 20,  # Two lockstep groups of 10 evaluations.
        "generations": 1,
        "set": TINY | SMALL_VALIDATION,
        "verbose": False,
    }
    one = gpfd.evolve(**common, threads=1, out=tmp_path / "one")
    dask = gpfd.evolve(**common, executor=dask_client.get_executor(), out=tmp_path / "dask")
    assert run_files(one.dir) == run_files(dask.dir)


def test_assess_on_an_executor_gives_the_same_table():
    fs = gpfd.FeatureSet.parse("x0 * x1\nx1\n", variables=["x0", "x1"])
    # The learner pinned: choosing it on the task trains ~100 runs on each side, and is tested on
    # workers by test_user_env_workers.py.
    common: dict[str, Any] = {"env": Point, "runs": 3, "budget": 2, "as_frame": False}
    common["params"] = {"step": "rprop", "rprop": "large"}
    one = gpfd.assess(fs, **common, threads=1)
    with process_pool(2) as executor:
        two = gpfd.assess(fs, **common, executor=executor)
    for key in one.keys() - {"set"}:
        assert np.array_equal(one[key], two[key], equal_nan=True), key


def test_executor_must_be_an_executor(tmp_path):
    with pytest.raises(gpfd.InputError, match="executor must be a concurrent.futures.Executor"):
        gpfd.evolve(env=Point, executor=4, out=tmp_path / "r")  # type: ignore[arg-type]
    with pytest.raises(gpfd.InputError, match="executor must be"):
        gpfd.assess([], env=Point, executor="dask")  # type: ignore[arg-type]


def test_a_process_pool_that_forks_is_an_input_error(tmp_path):
    forking = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"))
    with forking, pytest.raises(gpfd.InputError, match="executor: a ProcessPoolExecutor.*fork"):
        gpfd.evolve(env=Point, executor=forking, out=tmp_path / "r")
    assert not (tmp_path / "r").exists()


def test_executor_with_gpfd_own_environment_is_an_input_error(tmp_path):
    with process_pool(1) as executor:
        with pytest.raises(gpfd.InputError, match="executor=.*cartpole is gpfd's own"):
            gpfd.evolve(env="cartpole", executor=executor, out=tmp_path / "r")
        with pytest.raises(gpfd.InputError, match="executor=.*without env="):
            gpfd.evolve("cartpole-quick", executor=executor, out=tmp_path / "r")
        with pytest.raises(gpfd.InputError, match="executor=.*stepped in C\\+\\+"):
            gpfd.assess([], env="cartpole", executor=executor)
    assert not (tmp_path / "r").exists()
