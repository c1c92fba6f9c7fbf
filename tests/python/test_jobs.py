"""gpfd.discovery._jobs, the work shipped once: a worker without the job answers NeedJob and the
driver sends the task again with it; the job kept, its environment unpickled once and registered
only when it changes; the caches bounded; a round's results in order whatever the order of
completion."""

import threading
import time
from concurrent.futures import Executor, Future, ThreadPoolExecutor

import pytest

from gpfd.discovery import _jobs
from gpfd.environments import registry
from point_env import Point

UNPICKLED: list[str] = []


class Factory:
    """Makes Point; notes each unpickling in UNPICKLED (this process)."""

    def __init__(self, tag: str):
        self.tag = tag

    def __call__(self) -> Point:
        return Point()

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        UNPICKLED.append(self.tag)


def echo(config_text: str, value: int, delay: float = 0.0) -> tuple[str, int]:
    time.sleep(delay)
    return config_text, value


@pytest.fixture(autouse=True)
def fresh_worker():
    """This process as a worker that holds nothing yet."""
    for cache in (_jobs._jobs, _jobs._envs, _jobs._registered):
        cache.clear()
    UNPICKLED.clear()
    yield
    for cache in (_jobs._jobs, _jobs._envs, _jobs._registered):
        cache.clear()


def test_a_worker_without_the_job_asks_for_it_then_keeps_it():
    jobs = _jobs.Jobs("python:jobs-a", Factory("a"))
    key, payload = jobs.job("config A")
    answer = _jobs.run(key, None, echo, 1)
    assert isinstance(answer, _jobs.NeedJob) and answer.key == key
    assert _jobs.run(key, payload, echo, 2) == ("config A", 2)
    assert _jobs.run(key, None, echo, 3) == ("config A", 3)  # Kept.
    assert UNPICKLED == ["a"]
    assert isinstance(registry.factory("python:jobs-a"), Factory)


def test_one_environment_is_unpickled_once_for_all_its_jobs_and_registered_once():
    jobs = _jobs.Jobs("python:jobs-b", Factory("b"))
    for text in ("GP", "validation", "confirmation"):
        key, payload = jobs.job(text)
        assert _jobs.run(key, payload, echo, 0) == (text, 0)
    assert UNPICKLED == ["b"]
    registered = registry.factory("python:jobs-b")
    key, _ = jobs.job("GP")
    _jobs.run(key, None, echo, 0)
    assert registry.factory("python:jobs-b") is registered  # Not registered again.


def test_the_caches_keep_the_latest_jobs_and_environments():
    first = _jobs.Jobs("python:jobs-c", Factory("c"))
    key, _ = first.job("config 0")
    _jobs.run(key, first.job("config 0")[1], echo, 0)
    for i in range(1, _jobs.KEEP_JOBS + 1):
        _jobs.run(*first.job(f"config {i}"), echo, i)
    assert len(_jobs._jobs) == _jobs.KEEP_JOBS
    assert isinstance(_jobs.run(key, None, echo, 0), _jobs.NeedJob)  # The oldest went out.
    for i in range(_jobs.KEEP_ENVS + 1):
        other = _jobs.Jobs(f"python:jobs-d{i}", Factory(f"d{i}"))
        _jobs.run(*other.job("x"), echo, 0)
    assert len(_jobs._envs) == _jobs.KEEP_ENVS


def test_keys_differ_by_environment_and_config():
    a, b = _jobs.Jobs("python:jobs-e", Factory("e")), _jobs.Jobs("python:jobs-e", Factory("f"))
    assert a.job("x")[0] == a.job("x")[0]
    assert len({a.job("x")[0], a.job("y")[0], b.job("x")[0]}) == 3


class Forgetful(Executor):
    """Runs tasks on threads of this process; forgets every job before each task, as a worker
    that has just joined would. Forgetting and the task are one step: a task that forgot must not
    find the job another thread's task installed in between (tasks run one at a time in a
    worker anyway, under _jobs' lock)."""

    def __init__(self) -> None:
        self.pool = ThreadPoolExecutor(2)
        self.submitted = 0
        self.one_at_a_time = threading.Lock()

    def submit(self, fn, /, *args, **kwargs) -> Future:
        self.submitted += 1

        def forget_then_run():
            with self.one_at_a_time:
                _jobs._jobs.clear()
                return fn(*args, **kwargs)

        return self.pool.submit(forget_then_run)

    def shutdown(self, wait=True, *, cancel_futures=False) -> None:
        self.pool.shutdown(wait=wait, cancel_futures=cancel_futures)


def test_a_round_sends_the_job_again_to_whoever_lacks_it_and_keeps_the_order():
    jobs = _jobs.Jobs("python:jobs-g", Factory("g"))
    work = [(i, 0.02 * (5 - i)) for i in range(6)]  # The first finish last.
    with Forgetful() as executor:
        assert list(jobs.map(executor, echo, "text", work, copies=2)) == [
            ("text", i) for i in range(6)
        ]
        # Two carried the job from the start; the other four asked for it and got it.
        assert (executor.submitted, jobs.payloads_sent) == (10, 6)
    with ThreadPoolExecutor(2) as executor:  # A worker that keeps it: no job sent again.
        assert [v for _, v in jobs.map(executor, echo, "text", work, copies=2)] == list(range(6))
    assert jobs.payloads_sent == 6 and not jobs.pending


def test_a_task_error_is_raised_and_the_rest_cancelled():
    jobs = _jobs.Jobs("python:jobs-h", Factory("h"))

    def fails(config_text: str, value: int) -> int:
        if value == 1:
            raise ValueError("task 1")
        return value

    # Threads, and tasks all done before the first wait: task 0 comes out before task 1's error.
    for executor in (ThreadPoolExecutor(1), AtOnce()):
        with executor:
            results = jobs.map(executor, fails, "t", [(i,) for i in range(50)], copies=1)
            assert next(results) == 0
            with pytest.raises(ValueError, match="task 1"):
                next(results)
        assert not jobs.pending


class AtOnce(Executor):
    """Runs each task as it is submitted: its future is done before map first waits."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        future: Future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except Exception as e:
            future.set_exception(e)
        return future
