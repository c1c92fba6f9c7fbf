"""gpfd's own pool of worker processes: a ``concurrent.futures.Executor`` whose workers are fresh
interpreters running gpfd.execution._worker, never the user's ``__main__``.

A script without ``if __name__ == "__main__":``, code piped to ``python -`` and a notebook all work
alike: what a worker runs (the environment's factory, the task functions) travels to it pickled by
cloudpickle, which pickles ``__main__``'s classes and functions by value. Each worker runs the
initializer once, then one task at a time (gpfd.evaluator sends the environment's factory once
per worker with its tasks instead: gpfd.discovery._jobs).

A worker that dies is replaced by a fresh one (set up again), which runs the task it was running
again: a lost worker loses no task. A task that has lost ``attempts`` workers (3: it may be what
kills them) fails with WorkerError, naming the last worker and how it ended. A worker that cannot
start or set up breaks the pool: every task not yet done fails with WorkerError, and so does
every later submit. Workers run in a session of their own and ignore SIGINT: Ctrl-C reaches only
this process, which ends them (``terminate``); they die with this process, also when it is
SIGKILLed in the middle of a task (gpfd.execution._worker). A task that runs past its config's
``task_timeout`` ends its worker (gpfd.execution._deadline), which is then lost as above, the error
naming where the task hung. gpfd.evaluator runs the discovery's work on such an executor.
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

from gpfd.execution import _frames


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
        self.owner = threading.current_thread()  # The worker ends when this thread does.
        task_read, self.tasks = os.pipe()
        self.results, result_write = os.pipe()
        try:
            self.process = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "gpfd.execution._worker",
                    str(task_read),
                    str(result_write),
                    str(os.getpid()),
                ],
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
        """Sends one task and returns its reply; WorkerError when the worker ends first (also
        past the task's deadline, gpfd.execution._deadline: naming where the task was)."""
        try:
            _frames.send_bytes(self.tasks, payload)
            reply = _frames.receive(self.results)
        except (OSError, EOFError):
            raise WorkerError(
                f"{self.name()} {_how_it_ended(self.process)} while running a task"
            ) from None
        if reply[0] == "expired":
            raise WorkerError(f"{self.name()} ended: {reply[1]}")
        return reply

    def close(self) -> None:
        """Ends the task pipe (the worker exits when it next reads) and the result pipe."""
        for fd in (self.tasks, self.results):
            with contextlib.suppress(OSError):
                os.close(fd)
        self.tasks = self.results = -1


class WorkerPool(Executor):
    """``workers`` worker processes; ``initializer(*initargs)`` runs once in each before its
    first task. ``submit(fn, *args)`` runs ``fn(*args)`` on the first free worker; ``fn``, the
    arguments and the result travel pickled (cloudpickle). ``map`` gives results in order. A task
    runs on at most ``attempts`` workers: one more each time its worker dies under it."""

    def __init__(
        self,
        workers: int,
        initializer: Callable[..., Any] | None = None,
        initargs: tuple = (),
        attempts: int = 3,
    ) -> None:
        if workers < 1:
            raise ValueError(f"a pool needs at least one worker, got {workers}")
        if attempts < 1:
            raise ValueError(f"a task needs at least one attempt, got {attempts}")
        self._attempts = attempts
        self._started = 0  # Workers started, replacements included: the next one's number.
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
                thread = threading.Thread(
                    target=self._serve, name=f"gpfd-worker-{number}", daemon=True
                )
                thread.start()
                self._threads.append(thread)
        except BaseException:
            self.terminate()
            raise

    @property
    def workers(self) -> int:
        """How many workers serve the pool at once."""
        return len(self._threads)

    def _start_worker(self) -> _Worker:
        """A fresh worker, started by (and ending with) the calling thread of the pool."""
        with self._lock:
            number, self._started = self._started, self._started + 1
        worker = _Worker(number)
        with self._lock:
            self._workers.append(worker)
        return worker

    def _workers_of(self, thread: threading.Thread) -> list[_Worker]:
        with self._lock:
            return [worker for worker in self._workers if worker.owner is thread]

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

    def _set_up(self, worker: _Worker) -> bool:
        """Sends the worker sys.path and the setup; False, the pool broken, where that fails."""
        with contextlib.suppress(OSError):  # A worker gone: the call below says how it ended.
            _frames.send_bytes(worker.tasks, pickle.dumps(list(sys.path)))
        try:
            reply = worker.call(self._setup)
        except WorkerError as e:
            self._break(e)
            return False
        if reply[0] != "ok":
            error = _error_of(reply)
            self._break(
                WorkerError(f"{worker.name()} could not set up: {type(error).__name__}: {error}")
            )
            return False
        return True

    def _serve(self) -> None:
        """A thread per worker: starts it (and its replacements), sets it up, then runs the
        queue's tasks one at a time until a None; returns once its worker has exited. A worker
        ends with the thread that started it (gpfd.execution._worker's parent-death signal), so
        this thread outlives it: the worker closes what it holds first."""
        try:
            worker = self._start_worker()
        except BaseException as e:
            self._break(WorkerError(f"a worker did not start: {type(e).__name__}: {e}"))
            return
        try:
            self._serve_with(worker)
        finally:
            for started in self._workers_of(threading.current_thread()):
                started.close()  # The worker exits as it next reads ...
                started.process.wait()  # ... or was ended (terminate).

    def _serve_with(self, worker: _Worker) -> None:
        if not self._set_up(worker):
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
            replacement = self._run(worker, future, payload)
            if replacement is None:
                return
            worker = replacement

    def _run(self, worker: _Worker, future: Future, payload: bytes) -> _Worker | None:
        """Runs one task, on a fresh worker again each time its worker dies under it, up to the
        attempts; the worker to go on with, None when the pool is terminated or broken."""
        for attempt in range(1, self._attempts + 1):
            try:
                reply = worker.call(payload)
            except WorkerError as died:
                if self._terminating:
                    future.set_exception(WorkerError("the worker pool was terminated"))
                    return None
                if attempt == self._attempts:
                    future.set_exception(
                        WorkerError(f"{died}; the task has lost {attempt} workers")
                    )
                replacement = self._replace(worker)
                if replacement is None:
                    if attempt < self._attempts:
                        future.set_exception(self._broken or died)
                    return None
                worker = replacement
                continue
            if reply[0] == "ok":
                future.set_result(reply[1])
            else:
                future.set_exception(_error_of(reply))
            return worker
        return worker

    def _replace(self, lost: _Worker) -> _Worker | None:
        """A fresh worker, set up, for one that died; None (the pool broken) when it fails."""
        lost.close()
        try:
            worker = self._start_worker()
        except BaseException as e:
            self._break(WorkerError(f"a worker to replace {lost.name()} did not start: {e}"))
            return None
        return worker if self._set_up(worker) else None

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
        with self._lock:
            workers = list(self._workers)
        for worker in workers:
            if worker.process.poll() is None:
                worker.process.terminate()
        for worker in workers:
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
