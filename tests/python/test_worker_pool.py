"""gpfd's worker pool (gpfd.workers.WorkerPool): an executor whose workers are fresh interpreters
that never run this ``__main__``; results in order; a worker's error comes back as itself; a
worker that dies is replaced and its task runs again, up to the task's attempts, after which the
task fails naming the worker and how it ended."""

import os
import signal
import subprocess
import sys
import threading
import time

import pytest

import gpfd
from gpfd.workers import RemoteTraceback, WorkerError, WorkerPool
from point_env import Point
from test_user_env_workers import SMALL

_SETUP: dict[str, int] = {}


def _setup(value: int) -> None:
    _SETUP["value"] = value


def _work(x: int) -> tuple[int, int, int]:
    return x * x, _SETUP.get("value", -1), os.getpid()


def _fail(x: int) -> int:
    raise ValueError(f"bad input {x}")


def _die(code: int) -> None:
    os._exit(code)


def test_results_in_order_setup_once_per_worker_and_workers_of_their_own():
    with WorkerPool(2, initializer=_setup, initargs=(7,)) as pool:
        results = list(pool.map(_work, range(20)))
        assert pool.workers == 2
    assert [r[0] for r in results] == [x * x for x in range(20)]
    assert {r[1] for r in results} == {7}  # Set up in each worker, kept there.
    assert os.getpid() not in {r[2] for r in results}
    # A function of this module travels by value (cloudpickle), a lambda too.
    with WorkerPool(1) as pool:
        assert pool.submit(lambda a, b: a + b, 2, 3).result() == 5


def test_an_error_in_a_task_comes_back_as_itself_and_the_pool_goes_on():
    with WorkerPool(1) as pool:
        with pytest.raises(ValueError, match="bad input 3") as error:
            pool.submit(_fail, 3).result()
        assert isinstance(error.value.__cause__, RemoteTraceback)
        assert "_fail" in str(error.value.__cause__)
        assert pool.submit(_work, 4).result()[0] == 16


def _die_once(flag: str, code: int) -> int:
    """Ends its worker the first time (`flag` made), returns the pid the second."""
    try:
        os.close(os.open(flag, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
    except FileExistsError:
        return os.getpid()
    os._exit(code)


def test_a_worker_that_dies_is_replaced_and_its_task_runs_again(tmp_path):
    with WorkerPool(2) as pool:
        pids = {pool.submit(_work, x).result(timeout=60)[2] for x in range(4)}
        flag = str(tmp_path / "died")
        again = pool.submit(_die_once, flag, 3).result(timeout=60)
        assert os.path.exists(flag) and again not in pids | {os.getpid()}  # A fresh worker.
        assert [r[0] for r in pool.map(_work, range(6))] == [x * x for x in range(6)]
        assert pool.workers == 2
    assert len(pool._workers) == 3 and all(w.process.returncode is not None for w in pool._workers)


def test_a_task_that_kills_each_worker_fails_after_its_attempts_naming_the_last():
    pool = WorkerPool(2, attempts=2)
    try:
        dead = pool.submit(_die, 3)
        with pytest.raises(
            WorkerError, match=r"gpfd worker \d \(pid \d+\) exited with code 3.*lost 2 workers"
        ):
            dead.result(timeout=60)
        assert pool.submit(_work, 1).result(timeout=60)[0] == 1  # The pool goes on.
    finally:
        pool.terminate()
    assert all(w.process.returncode is not None for w in pool._workers)


def test_a_worker_killed_by_a_signal_is_named_with_it():
    pool = WorkerPool(1, attempts=1)
    try:
        pid = pool.submit(_work, 1).result(timeout=60)[2]
        os.kill(pid, signal.SIGKILL)
        with pytest.raises(WorkerError, match="killed by SIGKILL.*lost 1 workers"):
            pool.submit(_work, 2).result(timeout=60)
        assert pool.submit(_work, 3).result(timeout=60)[2] != pid  # Replaced.
    finally:
        pool.terminate()


def test_a_setup_that_fails_fails_every_task():
    pool = WorkerPool(1, initializer=_fail, initargs=(5,))
    try:
        with pytest.raises(WorkerError, match="could not set up: ValueError: bad input 5"):
            pool.submit(_work, 1).result(timeout=60)
    finally:
        pool.terminate()


def test_workers_ignore_sigint():
    with WorkerPool(1) as pool:
        pid = pool.submit(_work, 1).result(timeout=60)[2]
        os.kill(pid, signal.SIGINT)  # Ignored: Ctrl-C is the parent's to handle.
        assert pool.submit(_work, 2).result(timeout=60)[2] == pid


def test_terminate_ends_running_tasks():
    pool = WorkerPool(1)
    try:
        sleeping = pool.submit(time.sleep, 300)
        while not sleeping.running():
            time.sleep(0.01)
    finally:
        pool.terminate()
    with pytest.raises(WorkerError, match="terminated"):
        sleeping.result(timeout=60)
    assert pool._workers[0].process.returncode == -signal.SIGTERM


class DiesInStep(Point):
    """Point whose step ends its process, as a crashing simulator would, but in the process of
    the test (which samples states with it)."""

    def step(self, action):
        if os.getpid() != int(os.environ["GPFD_TEST_PARENT"]):
            os._exit(7)
        return super().step(action)


def test_a_run_whose_every_worker_dies_stops_naming_one_and_keeps_nothing(tmp_path, monkeypatch):
    monkeypatch.setenv("GPFD_TEST_PARENT", str(os.getpid()))  # The workers inherit it.
    with pytest.raises(WorkerError, match=r"gpfd worker \d \(pid \d+\) exited with code 7"):
        gpfd.evolve(
            env=DiesInStep, population=4, generations=1, set=SMALL, threads=2, out=tmp_path / "r"
        )
    assert not (tmp_path / "r").exists()


def test_a_factory_that_does_not_pickle_is_a_clear_error_with_workers(tmp_path):
    lock = threading.Lock()  # Held by the factory: no pickle.

    def make():
        with lock:
            return Point()

    with pytest.raises(TypeError, match="cannot be sent to the worker processes.*threads=1"):
        gpfd.evolve(env=make, population=4, generations=1, threads=2, out=tmp_path / "r")
    assert not (tmp_path / "r").exists()


def _gone(pid: int) -> bool:
    """Whether process `pid` has ended (a zombie no init reaped counts as ended)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def _children(pid: int) -> list[int]:
    """The processes whose parent is `pid` (from /proc)."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        found.append(int(entry))
            except (FileNotFoundError, ProcessLookupError):
                continue
    return found


def _wait_until(condition, seconds: float = 120.0) -> bool:
    end = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > end:
            return False
        time.sleep(0.1)
    return True


HANGS_IN_STEP = """
import os, sys, time
import gpfd
from point_env import Point

class HangsInStep(Point):
    def step(self, action):
        if os.getpid() != PARENT:  # In a worker: note the pid, then hang in the step.
            with open(os.path.join(LOG, str(os.getpid())), "w"):
                pass
            time.sleep(3600)
        return super().step(action)

PARENT, LOG = os.getpid(), sys.argv[1]
gpfd.evolve(env=HangsInStep, seed=1, population=4, generations=1, threads=2,
            set={"learner.params.updates": 1, "fitness.trials": 1}, out=sys.argv[2],
            verbose=False)
"""


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="reads /proc")
def test_workers_die_with_their_parent_killed_in_the_middle_of_a_step(tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    here = os.path.dirname(os.path.abspath(__file__))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([here, *sys.path])}
    parent = subprocess.Popen(
        [sys.executable, "-c", HANGS_IN_STEP, str(log), str(tmp_path / "run")], env=env
    )
    try:
        # One worker in a step at least (the learner choice times its first training alone, so
        # the other may wait idle); every worker of the parent must go with it.
        assert _wait_until(lambda: len(list(log.iterdir())) >= 1), "no worker reached a step"
        workers = _children(parent.pid)
        assert {int(p.name) for p in log.iterdir()} <= set(workers)
        assert not any(_gone(pid) for pid in workers)
    finally:
        parent.kill()  # SIGKILL: the parent closes nothing.
        parent.wait()
    assert _wait_until(lambda: all(_gone(pid) for pid in workers)), "a worker outlived its parent"


def test_a_pool_made_in_a_thread_that_ended_keeps_its_workers():
    """A worker ends with the thread that started it: the pool's own threads start them, never
    the caller's (here one that has ended before the tasks come)."""
    pools: list[WorkerPool] = []

    def make() -> None:
        pools.append(WorkerPool(2, _setup, (3,)))
        list(pools[0].map(time.sleep, [0.5, 0.5]))  # Both workers up, each with a task.

    maker = threading.Thread(target=make)
    maker.start()
    maker.join()
    with pools[0] as pool:
        results = list(pool.map(_work, range(4)))
        assert [r[:2] for r in results] == [(0, 3), (1, 3), (4, 3), (9, 3)]
        assert pool._started == 2  # No worker died and was replaced.
