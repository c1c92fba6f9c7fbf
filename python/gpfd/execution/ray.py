"""Ray tasks as a ``concurrent.futures.Executor``, for ``gpfd.evolve(executor=gpfd.ray.Executor())``
(the extra ``ray``).

Each ``submit(fn, *args)`` is one Ray task of one CPU, its result a ``concurrent.futures.Future``
(``ObjectRef.future()``). Ray runs a task again when its worker dies (``max_retries``, 3 by
default), so a lost worker loses no evaluation; gpfd's jobs (gpfd.discovery._jobs) ship the
environment once to each Ray worker process. The executor uses the Ray cluster this process is
connected to (``ray.init(...)`` first; without it, the first submit starts a local one, as Ray
does), and ``shutdown`` leaves the cluster as it is; ``shutdown(cancel_futures=True)`` (what gpfd
calls when a run fails or is interrupted) cancels, with ``ray.cancel``, every task of this executor
not yet done, so that no work of the run goes on on the cluster. With the config key
``task_timeout`` a task that runs past it ends its Ray worker process (gpfd.execution._deadline),
and Ray runs it again (``max_retries``), then fails it.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable
from concurrent import futures
from typing import Any


def _call(fn: Callable[..., Any], args: tuple, kwargs: dict) -> Any:
    """What a Ray task runs."""
    return fn(*args, **kwargs)


class Executor(futures.Executor):
    """Submits each call as a Ray task; ``max_retries``: how many times Ray runs a task again
    after its worker died; ``cancel_force``: ``shutdown(cancel_futures=True)`` ends the worker
    processes of running tasks (``ray.cancel(force=True)``; a task hung in native code ignores
    the interruption otherwise); ``options``: more of Ray's task options (``resources``, ...)."""

    def __init__(self, *, max_retries: int = 3, cancel_force: bool = False, **options: Any) -> None:
        try:
            import ray
        except ImportError as e:
            raise ImportError("gpfd.ray needs Ray: pip install 'gpfd[ray]' (or ray itself)") from e
        self._ray = ray
        self._cancel_force = bool(cancel_force)
        self._options = {"num_cpus": 1, "max_retries": max_retries, **options}
        self._remote: Any = None
        self._lock = threading.Lock()
        self._shut = False
        self._pending: set[futures.Future] = set()  # The futures of the tasks not yet done.

    @property
    def workers(self) -> int:
        """The CPUs of the Ray cluster: how many tasks run at once (0 before it is started)."""
        if not self._ray.is_initialized():
            return 0
        return int(self._ray.cluster_resources().get("CPU", 0))

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> futures.Future:
        with self._lock:
            if self._shut:
                raise RuntimeError("cannot submit to a gpfd.ray.Executor that is shut down")
            if self._remote is None:
                self._remote = self._ray.remote(_call).options(**self._options)
            ref = self._remote.remote(fn, args, kwargs)
            future = _TaskFuture(self._ray, ref, self._cancel_force)
            self._pending.add(future)
        future.add_done_callback(self._forget)
        ref.future().add_done_callback(lambda done: _settle(future, done))
        return future

    def _forget(self, future: futures.Future) -> None:
        with self._lock:
            self._pending.discard(future)

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """No more submits. The tasks under way go on, and so does the Ray cluster; with
        `cancel_futures`, every task of this executor not yet done is cancelled (``ray.cancel``),
        as a cancelled future of it is: gpfd cancels its round's tasks when a run fails or is
        interrupted, so that none goes on on the cluster."""
        with self._lock:
            self._shut = True
            pending = list(self._pending) if cancel_futures else []
        for future in pending:
            future.cancel()


class _TaskFuture(futures.Future):
    """The future of one Ray task (its ObjectRef `ref`): cancelling it cancels the task,
    ``ray.cancel(ref)``; a queued task then never runs, a running one is interrupted (its
    worker process ended where `force`)."""

    def __init__(self, ray: Any, ref: Any, force: bool) -> None:
        super().__init__()
        self._ray, self._ref, self._force = ray, ref, force

    def cancel(self) -> bool:
        if self.cancelled():
            return True
        if not super().cancel():
            return False
        with contextlib.suppress(Exception):  # The task ended on the cluster meanwhile.
            self._ray.cancel(self._ref, force=self._force)
        return True


def _settle(future: futures.Future, done: futures.Future) -> None:
    """Gives `future` the outcome of `done` (Ray's own future of the task), unless cancelled."""
    with contextlib.suppress(futures.InvalidStateError):  # Cancelled meanwhile.
        error = done.exception()
        if error is None:
            future.set_result(done.result())
        else:
            future.set_exception(error)
