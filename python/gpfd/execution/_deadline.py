"""The deadline of a task in a worker process (the config key ``task_timeout``, seconds): a task
that runs past it ends its process, so that the executor takes the worker as lost, replaces it
and runs the task again (gpfd.workers.WorkerPool, Dask, Ray; mpi4py's pool sends it again after
its silence, gpfd.discovery._jobs; a ProcessPoolExecutor breaks as a whole).

A hung environment holds its worker's main thread, so the deadline is watched by a thread of its
own (which needs the GIL, as a step in Python code releases it now and then) and, for an
environment that hangs in native code holding the GIL, by faulthandler's own thread (no GIL),
GRACE seconds later: it prints every thread's Python traceback to stderr and exits.

Before the process ends, the watching thread reports where the task was (``where``: the
environment and the step of its episode that the adapters note as they call the environment):
to stderr, or through ``report`` where the worker has a channel to its parent
(gpfd.execution._worker sends it to gpfd's pool, gpfd.execution.ray to Ray's key-value store),
and through the guard's ``tell`` on Dask and mpi4py (gpfd.execution._expired, which says where
mpi4py has no way): the executor's WorkerError names it.
"""

from __future__ import annotations

import contextlib
import faulthandler
import os
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

GRACE = 5.0  # Seconds past the deadline before faulthandler ends a worker whose thread cannot.
EXIT_CODE = 70  # A worker ended by its deadline exits with this code.

#: The adapter (gpfd.user_env.Adapter, gpfd.adapters.vector_adapter.VectorAdapter) whose environment
#: call is under way or was the last, in this process: its ``where()`` names the environment and
#: the call. The adapters set it as they call.
current: Any = None


def _print(text: str) -> None:
    print(f"gpfd: {text}", file=sys.stderr, flush=True)


#: Called with the text naming the task's environment and step, then the process exits.
report: Callable[[str], None] = _print


def seconds_of(config_text: str) -> float | None:
    """The ``task_timeout`` in seconds of a resolved config (run::formatExperimentConfig writes
    it as a number among the root table's keys, and only where it is set); None where there is
    none."""
    for line in config_text.splitlines():
        text = line.strip()
        if text.startswith("["):  # The root table's keys come first.
            return None
        key, equals, value = text.partition("=")
        if equals and key.strip() == "task_timeout":
            return float(value.split("#", 1)[0])
    return None


def where() -> str:
    """The environment and the call the task was in, as far as the adapters said."""
    adapter = current
    if adapter is None:
        return "no environment call (none had started in this process)"
    try:
        return str(adapter.where())
    except Exception as e:  # The text of a timeout must not fail.
        return f"an environment call ({type(e).__name__} naming it: {e})"


def expired_text(seconds: float) -> str:
    return f"a task ran past task_timeout={seconds:g} s in {where()} (worker pid {os.getpid()})"


@contextlib.contextmanager
def guard(seconds: float | None, tell: Callable[[str], None] | None = None) -> Iterator[None]:
    """Runs the body under a deadline of `seconds` (none where None): past it, ``report`` is
    called with expired_text, then `tell` where given (the driver's channel of an executor that
    has none of its own: gpfd.execution._expired), and the process exits with EXIT_CODE."""
    if seconds is None:
        yield
        return
    done = threading.Event()

    def watch() -> None:
        if done.wait(seconds):
            return
        text = expired_text(seconds)
        for say in (report, tell):
            with contextlib.suppress(BaseException):
                if say is not None:
                    say(text)
        os._exit(EXIT_CODE)

    watcher = threading.Thread(target=watch, name="gpfd-task-deadline", daemon=True)
    watcher.start()
    faulthandler.dump_traceback_later(seconds + GRACE, exit=True)
    try:
        yield
    finally:
        done.set()
        faulthandler.cancel_dump_traceback_later()
        watcher.join()
