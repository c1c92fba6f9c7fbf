"""A worker process of gpfd's pool (gpfd.workers.WorkerPool), started as
``python -m gpfd.execution._worker TASKS RESULTS PARENT`` with two pipe descriptors and the pool's
pid. It never runs the user's ``__main__``: everything it runs comes over the TASKS pipe
(gpfd.execution._frames), pickled by cloudpickle.

Frames in: first the parent's sys.path (a plain pickle), then one task per frame, cloudpickle of
(function, args), the first being the pool's initializer. Frames out: one reply per task,
("ok", value) or ("error", pickled exception or None, its type's name, its text, the traceback),
or ("expired", text) where the task ran past its deadline (gpfd.execution._deadline) and the worker
ends. The worker ends when the TASKS pipe ends (exit 0), or when the parent ends it. SIGINT is
ignored: Ctrl-C is the parent's to handle (it ends its workers). It dies with its parent, even
in the middle of a task (a SIGKILLed parent closes nothing): on Linux by a parent-death signal
(SIGKILL once the thread of the pool that started it ends: that thread outlives a worker it is
done with), elsewhere by a thread that watches the parent's pid.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import pickle
import signal
import sys
import threading
import time
import traceback

import cloudpickle

from gpfd.execution import _deadline, _frames


def _error_reply(error: BaseException) -> tuple:
    text = "".join(traceback.format_exception(type(error), error, error.__traceback__))
    try:
        pickled: bytes | None = cloudpickle.dumps(error)
    except Exception:  # An exception that does not pickle travels as its name and text.
        pickled = None
    return ("error", pickled, type(error).__qualname__, str(error), text)


def _reply(results: int, reply: tuple) -> bool:
    """Sends `reply`; False when the parent is gone."""
    try:
        try:
            _frames.send(results, reply)
        except OSError:
            raise
        except Exception as e:  # The value does not pickle (nothing was sent): say so instead.
            error = TypeError(f"the task's result does not pickle: {e}")
            _frames.send(results, _error_reply(error))
    except OSError:
        return False
    return True


def _call(payload: bytes) -> tuple:
    try:
        function, args = cloudpickle.loads(payload)
        return ("ok", function(*args))
    except BaseException as e:  # SystemExit from user code too: reported, the worker goes on.
        return _error_reply(e)


PR_SET_PDEATHSIG = 1  # prctl(2)'s option: the signal this process gets when its parent ends.
WATCH_EVERY = 1.0  # Seconds between looks at the parent's pid where there is no prctl.


def _die_with(parent: int) -> None:
    """Ends this process (SIGKILL, nothing closed) when `parent` ends, also mid-task."""
    libc = (
        ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True)
        if sys.platform == "linux"
        else None
    )
    if libc is not None and libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0:
        if os.getppid() != parent:  # It ended before the signal was asked for.
            os._exit(1)
        return

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(WATCH_EVERY)
        os._exit(1)

    threading.Thread(target=watch, name="gpfd-parent-watch", daemon=True).start()


def main(argv: list[str]) -> int:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    tasks, results = int(argv[1]), int(argv[2])
    _die_with(int(argv[3]))
    # A task past its deadline (gpfd.execution._deadline): the pool is told where it was, then it
    # ends.
    _deadline.report = lambda text: _frames.send(results, ("expired", text))
    try:
        sys.path[:] = pickle.loads(_frames.receive_bytes(tasks))
    except EOFError:
        return 0
    while True:  # The first task is the setup (the pool's initializer).
        try:
            payload = _frames.receive_bytes(tasks)
        except EOFError:
            return 0
        if not _reply(results, _call(payload)):
            return 0


def _close_environments() -> None:
    """Closes the vector environments this worker parked (gpfd.vector_cache), which os._exit
    would skip: their own processes and files end with them. An error is printed."""
    cache = sys.modules.get("gpfd.adapters.vector_cache")  # Imported where one was parked.
    if cache is None:
        return
    try:
        cache.close()
    except Exception:
        traceback.print_exc()


if __name__ == "__main__":
    code = main(sys.argv)
    _close_environments()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)  # No interpreter teardown: native threads and environments just end.
