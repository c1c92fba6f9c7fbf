"""Ray tasks as a ``concurrent.futures.Executor``, for ``gpfd.evolve(executor=gpfd.ray.Executor())``
(the extra ``ray``).

Each ``submit(fn, *args)`` is one Ray task of one CPU, its result a ``concurrent.futures.Future``
(``ObjectRef.future()``). Ray runs a task again when its worker dies (``max_retries``, 3 by
default), so a lost worker loses no evaluation; gpfd's jobs (gpfd._jobs) ship the environment once
to each Ray worker process. The executor uses the Ray cluster this process is connected to
(``ray.init(...)`` first; without it, the first submit starts a local one, as Ray does), and
``shutdown`` leaves the cluster as it is.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent import futures
from typing import Any


def _call(fn: Callable[..., Any], args: tuple, kwargs: dict) -> Any:
    """What a Ray task runs."""
    return fn(*args, **kwargs)


class Executor(futures.Executor):
    """Submits each call as a Ray task; ``max_retries``: how many times Ray runs a task again
    after its worker died; ``options``: more of Ray's task options (``resources``, ...)."""

    def __init__(self, *, max_retries: int = 3, **options: Any) -> None:
        try:
            import ray
        except ImportError as e:
            raise ImportError("gpfd.ray needs Ray: pip install 'gpfd[ray]' (or ray itself)") from e
        self._ray = ray
        self._options = {"num_cpus": 1, "max_retries": max_retries, **options}
        self._remote: Any = None
        self._lock = threading.Lock()
        self._shut = False

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
        return self._remote.remote(fn, args, kwargs).future()

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """No more submits; the tasks under way go on, and so does the Ray cluster."""
        with self._lock:
            self._shut = True
