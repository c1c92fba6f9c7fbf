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
and Ray runs it again (``max_retries``); a task whose worker died on its last try fails with
gpfd.WorkerError, naming where its last try was when its deadline passed (the worker leaves that
text in Ray's key-value store, namespace ``gpfd``, under this executor's id; ``shutdown`` deletes
what is left).
"""

from __future__ import annotations

import contextlib
import threading
import uuid
from collections.abc import Callable
from concurrent import futures
from typing import Any

from gpfd.execution import _deadline
from gpfd.execution.workers import WorkerError

NAMESPACE = "gpfd"  # Of Ray's key-value store: where a worker says where its task expired.


def _call(fn: Callable[..., Any], args: tuple, kwargs: dict, owner: str) -> Any:
    """What a Ray task runs: `fn`, a task past its deadline (gpfd.execution._deadline) saying
    where it was under the key ``OWNER:TASK-ID`` (_expired_key) before its worker process
    ends."""
    import ray

    key = _expired_key(owner, ray.get_runtime_context().get_task_id() or "")

    def report(text: str) -> None:
        _deadline._print(text)
        from ray.experimental import internal_kv

        internal_kv._internal_kv_put(key, text, namespace=NAMESPACE)

    _deadline.report = report
    return fn(*args, **kwargs)


def _expired_key(owner: str, task_id: str) -> str:
    return f"{owner}:{task_id}"


class Executor(futures.Executor):
    """Submits each call as a Ray task; ``max_retries``: how many times Ray runs a task again
    after its worker died; ``cancel_force``: ``shutdown(cancel_futures=True)`` ends the worker
    processes of running tasks (``ray.cancel(force=True)``; a task hung in native code ignores
    the interruption otherwise, and so do the workers of a Ray started from a process that
    ignores SIGINT, as a script run with ``nohup`` or ``&`` does); ``options``: more of Ray's
    task options (``resources``, ...)."""

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
        self._id = uuid.uuid4().hex  # The owner of its tasks' keys in the key-value store.

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
            ref = self._remote.remote(fn, args, kwargs, self._id)
            future = _TaskFuture(self._ray, ref, self._cancel_force)
            self._pending.add(future)
        future.add_done_callback(self._forget)
        ref.future().add_done_callback(lambda done: self._settle(future, ref, done))
        return future

    def _settle(self, future: futures.Future, ref: Any, done: futures.Future) -> None:
        """Gives `future` the outcome of `done` (Ray's own future of the task `ref`), unless
        cancelled; a task whose worker died on its last try fails with WorkerError, naming where
        it was where its deadline ended it."""
        with contextlib.suppress(futures.InvalidStateError):  # Cancelled meanwhile.
            error = done.exception()
            if error is None:
                future.set_result(done.result())
                return
            crashed = getattr(getattr(self._ray, "exceptions", None), "WorkerCrashedError", ())
            if isinstance(error, crashed):
                error = self._lost(ref, error)
            future.set_exception(error)

    def _lost(self, ref: Any, error: BaseException) -> WorkerError:
        tries = self._options["max_retries"] + 1
        text = (
            f"the worker of a Ray task died on its last try (of {tries}: max_retries={tries - 1})"
        )
        with contextlib.suppress(Exception):  # Nothing said: the worker died another way.
            from ray.experimental import internal_kv

            key = _expired_key(self._id, ref.task_id().hex())
            expired = internal_kv._internal_kv_get(key, namespace=NAMESPACE)
            if expired:
                internal_kv._internal_kv_del(key, namespace=NAMESPACE)
                text += f": {expired.decode()}"
        failure = WorkerError(text)
        failure.__cause__ = error
        return failure

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
        if self._remote is not None:
            with contextlib.suppress(Exception):  # What expired tasks said, where any did.
                from ray.experimental import internal_kv

                prefix = _expired_key(self._id, "")
                internal_kv._internal_kv_del(prefix, del_by_prefix=True, namespace=NAMESPACE)


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
