"""gpfd's own pool of worker processes: a ``concurrent.futures.Executor`` whose workers are fresh
interpreters running gpfd._worker, never the user's ``__main__``.

A script without ``if __name__ == "__main__":``, code piped to ``python -`` and a notebook all work
alike: what a worker runs (the environment's factory, the task functions) travels to it pickled by
cloudpickle, which pickles ``__main__``'s classes and functions by value. Each worker gets the
initializer once (the environment's factory, kept there), then one task at a time.

A worker that dies is never replaced: its task and every task not yet done fail with WorkerError,
naming the worker and how it ended, and so does every later submit. Workers run in a session of
their own and ignore SIGINT: Ctrl-C reaches only this process, which ends them (``terminate``).
gpfd.evaluator runs the discovery's work on such an executor.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import queue
import signal
import subprocess
import sys
import threading
from collections.abc import Callable
from concurrent.futures import Executor, Future
from typing import Any

import cloudpickle

from gpfd import _frames


class WorkerError(RuntimeError):
    """A worker process of gpfd's pool could not start or ended while the pool needed it."""


class RemoteTraceback(Exception):
    """The traceback of an error raised in a worker (the cause of the error re-raised here)."""

    def __str__(self) -> str:
        return "\n\n" + str(self.args[0]) if self.args else ""


def _no_setup() -> None:
    """The initializer of a pool without one."""


def _error_of(reply: tuple) -> BaseException:
    """The exception of a worker's ("error", pickled, type name, text, traceback) reply, its
    traceback as its cause."""
    _, pickled, type_name, text, trace = reply
    error: BaseException | None = None
    if pickled is not None:
        try:
            error = cloudpickle.loads(pickled)
        except Exception:
            error = None
    if not isinstance(error, BaseException):
        error = RuntimeError(f"{type_name}: {text}")
    error.__cause__ = RemoteTraceback(trace.rstrip())
    return error


def _how_it_ended(process: subprocess.Popen) -> str:
    try:
        code = process.wait(timeout=5)
    except subprocess.TimeoutExpired:
        return "closed its pipe but is still running"
    if code < 0:
        try:
            return f"was killed by {signal.Signals(-code).name}"
        except ValueError:
            return f"was killed by signal {-code}"
    return f"exited with code {code}"


class _Worker:
    """One worker process and the two pipes to it; used by one thread of the pool."""

    def __init__(self, number: int) -> None:
        self.number = number
        task_read, self.tasks = os.pipe()
        self.results, result_write = os.pipe()
        try:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "gpfd._worker", str(task_read), str(result_write)],
                pass_fds=(task_read, result_write),
                stdin=subprocess.DEVNULL,
                start_new_session=True,  # Ctrl-C at a terminal reaches this process only.
            )
        except BaseException:
            os.close(self.tasks)
            os.close(self.results)
            raise
        finally:
            os.close(task_read)
            os.close(result_write)

    def name(self) -> str:
        return f"gpfd worker {self.number} (pid {self.process.pid})"

    def call(self, payload: bytes) -> tuple:
        """Sends one task and returns its reply; WorkerError when the worker ends first."""
        try:
            _frames.send_bytes(self.tasks, payload)
            return _frames.receive(self.results)
        except (OSError, EOFError):
            raise WorkerError(
                f"{self.name()} {_how_it_ended(self.process)} while running a task; gpfd does not "
                "restart workers, so the run stops here"
            ) from None

    def close(self) -> None:
        """Ends the task pipe (the worker exits when it next reads) and the result pipe."""
        for fd in (self.tasks, self.results):
            with contextlib.suppress(OSError):
                os.close(fd)
        self.tasks = self.results = -1


class WorkerPool(Executor):
    """``workers`` worker processes; ``initializer(*initargs)`` runs once in each before its
    first task. ``submit(fn, *args)`` runs ``fn(*args)`` on the first free worker; ``fn``, the
    arguments and the result travel pickled (cloudpickle). ``map`` gives results in order."""

    def __init__(
        self,
        workers: int,
        initializer: Callable[..., Any] | None = None,
        initargs: tuple = (),
    ) -> None:
        if workers < 1:
            raise ValueError(f"a pool needs at least one worker, got {workers}")
        self._setup = cloudpickle.dumps((initializer or _no_setup, tuple(initargs)))
        self._queue: queue.SimpleQueue = queue.SimpleQueue()
        self._lock = threading.Lock()
        self._broken: BaseException | None = None
        self._shut = False
        self._terminating = False
        self._workers: list[_Worker] = []
        self._threads: list[threading.Thread] = []
        try:
            for number in range(workers):
                worker = _Worker(number)
                self._workers.append(worker)
                thread = threading.Thread(
                    target=self._serve, args=(worker,), name=f"gpfd-worker-{number}", daemon=True
                )
                thread.start()
                self._threads.append(thread)
        except BaseException:
            self.terminate()
            raise

    @property
    def workers(self) -> int:
        return len(self._workers)

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Future:
        if kwargs:
            raise TypeError("gpfd's worker pool passes positional arguments only")
        with self._lock:
            if self._broken is not None:
                raise WorkerError(f"the worker pool is broken: {self._broken}")
            if self._shut:
                raise RuntimeError("cannot submit to a worker pool that is shut down")
            future: Future = Future()
            self._queue.put((future, cloudpickle.dumps((fn, args))))
        return future

    def _serve(self, worker: _Worker) -> None:
        """A thread per worker: the setup, then the queue's tasks one at a time until a None."""
        with contextlib.suppress(OSError):  # A worker gone: the call below says how it ended.
            _frames.send_bytes(worker.tasks, pickle.dumps(list(sys.path)))
        try:
            reply = worker.call(self._setup)
        except WorkerError as e:
            self._break(e)
            return
        if reply[0] != "ok":
            error = _error_of(reply)
            self._break(
                WorkerError(f"{worker.name()} could not set up: {type(error).__name__}: {error}")
            )
            return
        while True:
            item = self._queue.get()
            if item is None:
                return
            future, payload = item
            if self._broken is not None:
                future.set_exception(self._broken)
                continue
            if not future.set_running_or_notify_cancel():
                continue
            try:
                reply = worker.call(payload)
            except WorkerError as died:
                error = WorkerError("the worker pool was terminated") if self._terminating else died
                future.set_exception(error)
                self._break(error)
                return
            if reply[0] == "ok":
                future.set_result(reply[1])
            else:
                future.set_exception(_error_of(reply))

    def _break(self, error: BaseException) -> None:
        """Fails every queued task with `error`, and every later submit."""
        with self._lock:
            if self._broken is None:
                self._broken = error
        for future, _ in self._drain():
            if future.set_running_or_notify_cancel():
                future.set_exception(error)

    def _drain(self) -> list[tuple[Future, bytes]]:
        """Takes every task still queued (not the Nones that end the threads)."""
        taken, ends = [], 0
        while True:
            try:
                item = self._queue.get_nowait()
            except queue.Empty:
                break
            if item is None:
                ends += 1
            else:
                taken.append(item)
        for _ in range(ends):
            self._queue.put(None)
        return taken

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        """No more tasks: the workers end once the queued ones are done (or cancelled)."""
        with self._lock:
            first = not self._shut
            self._shut = True
        if cancel_futures:
            for future, _ in self._drain():
                future.cancel()
        if first:
            for _ in self._threads:
                self._queue.put(None)
        if wait:
            self._join()

    def terminate(self) -> None:
        """Ends the workers now (SIGTERM, then SIGKILL): queued tasks are cancelled, running
        ones fail with WorkerError. After an interruption or an error."""
        self._terminating = True
        self.shutdown(wait=False, cancel_futures=True)
        for worker in self._workers:
            if worker.process.poll() is None:
                worker.process.terminate()
        for worker in self._workers:
            try:
                worker.process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                worker.process.kill()
        self._join()

    def _join(self) -> None:
        for thread in self._threads:
            thread.join()
        for worker in self._workers:
            worker.close()
            worker.process.wait()
