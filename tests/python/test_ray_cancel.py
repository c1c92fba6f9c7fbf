"""gpfd.ray.Executor cancels its Ray tasks (``ray.cancel``) when their futures are cancelled and
on ``shutdown(cancel_futures=True)``, so that a failed or interrupted run leaves no work on the
cluster; checked against a stand-in for the ``ray`` module that records what is asked of it
(test_executor_ray.py runs the executor on a real local cluster)."""

import sys
import types
from concurrent.futures import Future
from typing import Any

import pytest

import gpfd.ray
from gpfd.discovery import _jobs
from point_env import Point


class TaskCancelledError(Exception):
    pass


class Ref:
    """An ObjectRef: its outcome comes through future(), set by the test or by cancel."""

    def __init__(self, call: tuple) -> None:
        self.call = call
        self.outcome: Future = Future()

    def future(self) -> Future:
        return self.outcome


class FakeRay(types.ModuleType):
    def __init__(self) -> None:
        super().__init__("ray")
        self.refs: list[Ref] = []
        self.cancelled: list[tuple[Ref, bool]] = []
        self.options: dict[str, Any] = {}
        self.fails: Any = None  # A task whose last argument is this fails at once.

    def remote(self, function):
        fake = self

        class Remote:
            def options(self, **options):
                fake.options = options
                return self

            def remote(self, *call):
                fake.refs.append(Ref(call))
                if fake.fails is not None and call[1][-1] == fake.fails:
                    fake.refs[-1].outcome.set_exception(ValueError("the environment raised"))
                return fake.refs[-1]

        return Remote()

    def cancel(self, ref: Ref, force: bool = False) -> None:
        self.cancelled.append((ref, force))
        if not ref.outcome.done():
            ref.outcome.set_exception(TaskCancelledError())

    def is_initialized(self) -> bool:
        return True

    def cluster_resources(self) -> dict[str, float]:
        return {"CPU": 2.0}


@pytest.fixture
def ray(monkeypatch) -> FakeRay:
    fake = FakeRay()
    monkeypatch.setitem(sys.modules, "ray", fake)
    return fake


def test_results_and_errors_come_through(ray):
    executor = gpfd.ray.Executor()
    ok, bad = executor.submit(abs, -1), executor.submit(abs, "x")
    ray.refs[0].outcome.set_result(1)
    ray.refs[1].outcome.set_exception(TypeError("bad operand"))
    assert ok.result(timeout=5) == 1
    with pytest.raises(TypeError, match="bad operand"):
        bad.result(timeout=5)
    assert ray.options["max_retries"] == 3 and not ray.cancelled


def test_shutdown_cancelling_futures_cancels_the_tasks_not_done(ray):
    executor = gpfd.ray.Executor(cancel_force=True)
    futures = [executor.submit(abs, -i) for i in range(3)]
    ray.refs[0].outcome.set_result(0)
    executor.shutdown(cancel_futures=True)
    assert {(id(ref), force) for ref, force in ray.cancelled} == {
        (id(ray.refs[1]), True),
        (id(ray.refs[2]), True),
    }
    assert futures[0].result() == 0 and futures[1].cancelled() and futures[2].cancelled()


def test_shutdown_without_cancelling_leaves_the_tasks(ray):
    executor = gpfd.ray.Executor()
    future = executor.submit(abs, -1)
    executor.shutdown()
    assert not ray.cancelled and not future.done()
    ray.refs[0].outcome.set_result(1)
    assert future.result(timeout=5) == 1


def test_a_cancelled_future_cancels_its_task_once(ray):
    executor = gpfd.ray.Executor()
    future = executor.submit(abs, -1)
    assert future.cancel() and future.cancel()
    assert ray.cancelled == [(ray.refs[0], False)]


def test_a_failed_round_cancels_its_other_tasks_on_the_cluster(ray):
    """A task's error stops gpfd's round (gpfd.discovery._jobs.Jobs.map), which cancels the others:
    Ray cancels each."""
    executor = gpfd.ray.Executor()
    jobs = _jobs.Jobs("python:ray-cancel", Point)  # Never made: the stand-in runs nothing.
    ray.fails = 1
    results = jobs.map(executor, _jobs.fitness_group, "config", [(i,) for i in range(4)], 2)
    with pytest.raises(ValueError, match="the environment raised"):
        next(results)
    assert len(ray.refs) == 4
    assert {id(ref) for ref, _ in ray.cancelled} == {id(ray.refs[i]) for i in (0, 2, 3)}
