"""Work shipped once: what a worker needs to play (the environment's factory and the config text,
from which it builds the learning task) travels to each worker once and is kept there; a task
carries only a job key, the genomes or feature sets and the seeds. Any
``concurrent.futures.Executor`` runs the tasks, and none can aim a task at a worker, so:

- the driver (``Jobs.map``) submits each task with the key of its job: a hash of the job's
  bytes. While a job is new it attaches the job itself to the first ``copies`` tasks of its
  round (one per worker, as far as the executor hands tasks to idle workers in turn);
- a worker (``run``) that holds the key plays the task; one that lacks it and was not sent the
  job answers ``NeedJob``, and the driver submits that task again with the job attached. A task
  needs at most one resubmission; a worker that joins later (a replacement, a new host) gets the
  job the same way;
- each worker keeps its last ``KEEP_JOBS`` jobs and ``KEEP_ENVS`` environments (least recently
  used first out); an environment is unpickled once per worker, whatever the number of jobs on it.

An executor that loses a task silently when its worker is lost (mpi4py's ``MPIPoolExecutor``:
the task's future never completes) gets its lost tasks sent again: once no result of a round has
come for ``max(LOST_AFTER, LOST_FACTOR x`` the longest any task of its job took from submission
to result``)``, each task of the round out that long, on a worker, is sent again (job attached);
the first result of a task is the one taken, its other copies cancelled or ignored. Such an
executor cannot replace a worker that a task's ``task_timeout`` ended
(gpfd.execution._deadline): with a deadline T, every task ends within T + GRACE (or its worker
does), so a round that has had no result for ``2 x (T + GRACE + LOST_AFTER)`` (from the silence
that sends lost tasks again, at least) has no worker left that takes its tasks, and stops with
WorkerError, naming the environment's step that each ended worker told the driver
(gpfd.execution._expired: where mpi4py's master is in its workers' COMM_WORLD; each also prints
it on its stderr, the job's).

A task's result depends on its job, genomes and seeds only, never on where it ran or how many
times it was sent: the same seed gives the same run on any executor.
"""

from __future__ import annotations

import hashlib
import pickle
import sys
import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from typing import Any

import cloudpickle

from gpfd import _core
from gpfd.adapters import user_env
from gpfd.execution import _deadline, _expired
from gpfd.execution.workers import WorkerError

KEEP_JOBS = 16
KEEP_ENVS = 4

# Executors (by the module of their class) whose lost worker takes its task with it, silently.
# mpi4py.futures' MPIPoolExecutor (4.1.2, _core.client_exec) waits for a rank's answer until it
# comes: under `mpiexec -disable-auto-cleanup` a dead rank's task stays running for ever, and the
# rank gets no other task (docs/cluster.md, "mpi4py under srun or mpiexec"). Dask, Ray and gpfd's
# pool run such a task again themselves; the others break as a whole (gpfd.evaluator).
SILENT_LOSS = ("mpi4py.",)
LOST_AFTER = 5.0  # Seconds: the least silence after which a task is taken as lost.
LOST_FACTOR = 3.0  # ... and at least this many times its job's slowest task.
RESEND_PAUSE = 0.5  # Seconds before a task that could not be sent to a worker is sent again.


class NeedJob:
    """A worker's answer to a task whose job it does not hold: send the task again with it."""

    def __init__(self, key: str) -> None:
        self.key = key


# ---- the worker's side: what this process holds ----

_lock = threading.Lock()  # One task at a time per process (tasks hold the GIL while they step).
# key -> (environment key, config text, its task_timeout in seconds or None)
_jobs: OrderedDict[str, tuple[str, str, float | None]] = OrderedDict()
_envs: OrderedDict[str, tuple[str, Callable[[], Any]]] = OrderedDict()  # key -> (name, factory)
_registered: dict[str, str] = {}  # environment name -> key of the factory registered as it here


def _keep(cache: OrderedDict, key: str, value: Any, most: int) -> None:
    cache[key] = value
    cache.move_to_end(key)
    while len(cache) > most:
        cache.popitem(last=False)


def _install(key: str, payload: bytes) -> None:
    env_key, env_bytes, config_text = pickle.loads(payload)
    if env_key not in _envs:
        _keep(_envs, env_key, cloudpickle.loads(env_bytes), KEEP_ENVS)
    _keep(_jobs, key, (env_key, config_text, _deadline.seconds_of(config_text)), KEEP_JOBS)


def run(key: str, payload: bytes | None, function: Callable[..., Any], *args: Any) -> Any:
    """A task, in a worker: ``function(config_text, *args)`` under the job `key`, with the job's
    environment registered under its name; NeedJob when this process holds no such job and
    `payload` (the job, from Jobs.payload) is None. Past the config's ``task_timeout`` the
    process ends (gpfd.execution._deadline), having told the driver where the task was where the
    executor has no channel of its own (gpfd.execution._expired): the executor takes its worker
    as lost."""
    with _lock:
        if key not in _jobs or _jobs[key][0] not in _envs:
            if payload is None:
                return NeedJob(key)
            _install(key, payload)
        _jobs.move_to_end(key)
        env_key, config_text, timeout = _jobs[key]
        _envs.move_to_end(env_key)
        name, factory = _envs[env_key]
        with _deadline.guard(timeout, None if timeout is None else _expired.teller()):
            if _registered.get(name) != env_key:  # Registering again drops the tasks built.
                user_env.register(name, factory)
                _registered[name] = env_key
            return function(config_text, *args)


def fitness_group(config_text: str, group: list[tuple[bytes, int]]) -> list[float]:
    """run::trialFitness of each (genome wire record, seed) of a lockstep group."""
    return _core.trial_fitness_group(config_text, group)


def runs_group(config_text: str, budget: int, group: list[tuple[tuple, list[int]]]) -> list[list]:
    """The learning curves of each (features, seeds) of a lockstep group."""
    return _core.train_runs_group(config_text, budget, group)


# ---- the driver's side ----


def loses_tasks_silently(executor: Executor) -> bool:
    """Whether a task of `executor` may never complete when its worker is lost (SILENT_LOSS)."""
    return type(executor).__module__.startswith(SILENT_LOSS)


def undelivered(error: BaseException) -> bool:
    """Whether `error`, a task's, was raised by a silently losing executor's own machinery, the
    task never reaching a worker: mpi4py's pool sets the MPI error of a send to a dead rank
    (``Endpoint timeout`` once UCX has seen its connection close: docs/mpi.md, "Lost workers")
    on the task's future. An error raised in a worker comes with the worker's traceback as its
    cause (mpi4py's RemoteTraceback), and gpfd's tasks make no MPI call."""
    remote = type(error.__cause__).__name__ == "RemoteTraceback"
    return type(error).__module__.startswith(SILENT_LOSS) and not remote


def _digest(*parts: bytes) -> str:
    hasher = hashlib.sha256()
    for part in parts:
        hasher.update(len(part).to_bytes(8, "big"))
        hasher.update(part)
    return hasher.hexdigest()


class Jobs:
    """The jobs of one environment (`name`, made by `factory`), one per config text, and the
    rounds of tasks run on an executor under them."""

    def __init__(self, name: str, factory: Callable[[], Any]) -> None:
        try:
            self._env_bytes = cloudpickle.dumps((name, factory))
        except Exception as e:
            raise TypeError(
                f"{name}: the environment's factory cannot be sent to the worker processes: "
                f"cloudpickle cannot pickle it ({type(e).__name__}: {e}); make it picklable, or "
                "use threads=1 to run in this process"
            ) from e
        self._env_key = _digest(self._env_bytes)
        self.name = name
        self._jobs: dict[str, tuple[str, bytes]] = {}  # config text -> (key, payload)
        self._sent: set[str] = set()  # Keys sent at least once.
        self.payloads_sent = 0  # Tasks sent with their job attached (tests read it).
        self.resent = 0  # Tasks sent again, taken as lost (tests read it).
        self.pending: set[Future] = set()  # The futures of the round under way.
        self._slowest: dict[str, float] = {}  # Job key -> longest submission-to-result seconds.
        self._told = False  # Whether a task that could not be sent was reported.

    def job(self, config_text: str) -> tuple[str, bytes]:
        """(key, payload) of the job of `config_text`."""
        if config_text not in self._jobs:
            payload = pickle.dumps((self._env_key, self._env_bytes, config_text))
            self._jobs[config_text] = (_digest(self._env_bytes, config_text.encode()), payload)
        return self._jobs[config_text]

    def map(
        self,
        executor: Executor,
        function: Callable[..., Any],
        config_text: str,
        work: list[tuple],
        copies: int,
    ) -> Iterator[Any]:
        """``function(config_text, *args)`` for each args of `work` on `executor`, results in
        order as each is done. A task's error is raised as soon as it comes; the tasks not yet
        started are then cancelled (as they are when the iterator is dropped: Evaluator.close).
        On an executor that loses tasks silently, a task taken as lost is sent again (above)."""
        key, payload = self.job(config_text)
        first = key not in self._sent
        self._sent.add(key)
        index: dict[Future, int] = {}
        sent_at: dict[Future, float] = {}
        out: dict[int, list[Future]] = {}  # Task -> its copies out.
        silent = loses_tasks_silently(executor)
        # With a deadline, a copy out this long has lost its worker (above), on such executors;
        # the round hears where each such worker's task was, where it can (gpfd.execution._expired).
        expiry = _deadline.seconds_of(config_text) if silent else None
        dead_after = None if expiry is None else expiry + _deadline.GRACE + LOST_AFTER
        heard = None if expiry is None else _expired.MpiListener()
        # Tasks whose copy could not be sent -> when: sent again at the next result, or after
        # RESEND_PAUSE.
        unsent: dict[int, float] = {}
        failures: dict[int, int] = {}  # Task -> the sends that failed since the last result.

        def submit(i: int, attach: bool) -> None:
            future = executor.submit(run, key, payload if attach else None, function, *work[i])
            self.payloads_sent += attach
            index[future] = i
            sent_at[future] = time.monotonic()
            out.setdefault(i, []).append(future)
            self.pending.add(future)

        def drop(future: Future) -> None:
            self.pending.discard(future)
            index.pop(future, None)
            sent_at.pop(future, None)

        results: dict[int, Any] = {}
        answered = last = time.monotonic()  # The round's start, then its last result ...
        try:
            for i in range(len(work)):
                submit(i, first and i < copies)
            turn = 0
            while turn < len(work):
                quiet = self._quiet(key) if silent else None
                if quiet is None:  # No result yet to measure by: the deadline's, where one is set.
                    quiet = dead_after
                timeout = None if quiet is None else max(0.0, last + quiet - time.monotonic())
                if expiry is not None and dead_after is not None and quiet is not None:
                    given_up = answered + max(quiet, dead_after) + dead_after
                    timeout = max(0.0, min(last + quiet, given_up) - time.monotonic())
                    if time.monotonic() >= given_up:
                        silence = time.monotonic() - answered
                        raise self._no_worker_left(executor, expiry, silence, heard)
                if unsent:
                    due = max(0.0, min(unsent.values()) + RESEND_PAUSE - time.monotonic())
                    timeout = due if timeout is None else min(timeout, due)
                done, _ = wait(self.pending, timeout=timeout, return_when=FIRST_COMPLETED)
                if quiet is not None and time.monotonic() - last >= quiet:
                    # ... or, for the silence that makes a task lost, the last sent again.
                    last = self._send_lost(executor, out, sent_at, quiet, unsent, submit)
                error: Exception | None = None
                # In the tasks' order, so that results before a failed task are yielded first.
                for future in sorted(done, key=lambda f: index.get(f, -1)):
                    if future not in index:  # Dropped: a copy of a task already answered.
                        continue
                    i, began = index[future], sent_at[future]
                    drop(future)
                    out[i].remove(future)
                    try:
                        value = future.result()
                    except Exception as e:
                        if not (silent and undelivered(e)):
                            error = e
                            break
                        failures[i] = failures.get(i, 0) + 1
                        silence = time.monotonic() - answered
                        self._unsent(executor, e, failures[i], copies, silence, quiet, heard)
                        unsent[i] = time.monotonic()
                        continue
                    if isinstance(value, NeedJob):
                        submit(i, True)
                        continue
                    results[i] = value
                    answered = last = time.monotonic()
                    failures.clear()
                    self._slowest[key] = max(self._slowest.get(key, 0.0), last - began)
                    for other in out.pop(i):  # Copies sent again, or the one taken as lost.
                        other.cancel()
                        drop(other)
                now = time.monotonic()
                for i, when in sorted(unsent.items()) if error is None else ():
                    if answered >= when or now >= when + RESEND_PAUSE:
                        del unsent[i]
                        submit(i, True)
                while turn in results:
                    yield results.pop(turn)
                    turn += 1
                if error is not None:
                    raise error
        finally:
            self.cancel()
            if heard is not None:
                heard.close()

    def _unsent(
        self,
        executor: Executor,
        error: Exception,
        times: int,
        workers: int,
        silence: float,
        quiet: float | None,
        heard: _expired.MpiListener | None,
    ) -> None:
        """Takes a task that `executor` could not send to a worker (`error`, its `times`-th
        failure since the round's last result, `silence` seconds ago) as lost, to be sent again;
        a WorkerError once it has failed more often than there are workers and the round has
        gone `quiet` (LOST_AFTER before any result) without a result: no worker is reachable.
        mpi4py's pool keeps a dead rank among its idle ones, first in line after a live one's
        task: a send to it fails again and again while the live ones are busy. The error names
        what the workers that a deadline ended told it (`heard`)."""
        name = type(executor).__name__
        if times > max(workers, 1) and silence >= (LOST_AFTER if quiet is None else quiet):
            said = heard.texts() if heard is not None else []
            ended = f" (ended by a task's deadline: {_expired.named(said)})" if said else ""
            raise WorkerError(
                f"{name} could not send a task to any worker ({times} tries, no result for "
                f"{silence:.1f} s; the last error: {type(error).__name__}: {error}): its workers "
                f"are lost{ended}. The work stops; a discovery's directory keeps its last "
                "complete generation, which resume= continues (with a working executor)."
            ) from error
        self.resent += 1
        if not self._told:
            self._told = True
            last_line = (str(error).strip().splitlines() or [""])[-1].strip()[:200]
            print(
                f"gpfd: {name} could not send a task to one of its workers ({last_line}): taken "
                "as lost with its worker, and sent again (said once)",
                file=sys.stderr,
                flush=True,
            )

    def _no_worker_left(
        self, executor: Executor, expiry: float, silence: float, heard: _expired.MpiListener | None
    ) -> WorkerError:
        """The error of a round whose workers its deadline has all ended, naming where the tasks
        were, as the workers told (`heard`), or else saying where they printed it."""
        said = heard.texts() if heard is not None else []
        where = (
            f"where the tasks were, as the workers told: {_expired.named(said)}"
            if said
            else "each ended by its task's deadline printed where the task was, the "
            "environment's step, to its stderr: the job's"
        )
        return WorkerError(
            f"no result from {type(executor).__name__} for {silence:.1f} s, while a task of "
            f"{self.name} ends within task_timeout={expiry:g} s or ends its worker: its workers "
            f"are lost, which it cannot replace ({where})"
        )

    def _quiet(self, key: str) -> float | None:
        """How long a round of job `key` may go without a result before its tasks out that long
        are taken as lost; None before any task has come back (nothing to measure against)."""
        slowest = self._slowest.get(key, max(self._slowest.values(), default=None))
        return None if slowest is None else max(LOST_AFTER, LOST_FACTOR * slowest)

    def _send_lost(
        self,
        executor: Executor,
        out: dict[int, list[Future]],
        sent_at: dict[Future, float],
        quiet: float,
        unsent: dict[int, float],
        submit: Callable[[int, bool], None],
    ) -> float:
        """Sends again, job attached, each task whose copies have all been out `quiet` seconds
        and handed to a worker (running), none answering; returns the time it did (the silence
        counts again from then). A copy still queued waits for a worker: none is added to it, so
        with every worker lost the round waits, one copy of each lost task queued."""
        now = time.monotonic()
        lost = [
            i
            for i, futures in out.items()
            if futures
            and i not in unsent
            and all(f.running() and now - sent_at[f] >= quiet for f in futures)
        ]
        for i in lost:
            submit(i, True)
        self.resent += len(lost)
        if lost:
            print(
                f"gpfd: no result from {type(executor).__name__} for {quiet:.1f} s: {len(lost)} "
                "task(s) out that long taken as lost with their worker(s), and sent again",
                file=sys.stderr,
                flush=True,
            )
        return now

    def cancel(self) -> None:
        """Cancels the tasks of the round under way that have not started."""
        for future in self.pending:
            future.cancel()
        self.pending.clear()
