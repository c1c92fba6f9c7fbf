"""The work of a discovery or an assessment on an environment stepped in Python, run on an
executor: GP's fitness evaluations (``Evaluator.__call__``, python/src/python_evaluator.cpp)
and the learning runs of validation, confirmation and assessment (``Evaluator.run_trials``,
python/src/trial_runner.cpp).

With one worker and no executor the work runs in this process. Otherwise it runs on an executor:
the user's (``executor=``: any ``concurrent.futures.Executor``, never shut down here), or one
of ``workers`` workers made at the first work and ended by ``close`` (``make_executor``;
gpfd.workers.WorkerPool by default, whose workers are fresh interpreters). Both go through
gpfd.discovery._jobs: each worker gets the environment's factory and the config text once; a task
carries only the packed genomes or feature sets and the seeds. A fitness depends on its genome and
seed only, a curve on its features, budget and seed (and, on a vector form seeded as a whole, the
lockstep group, whose make-up never depends on the workers), so any executor and any number of
workers give the same run.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterator
from concurrent.futures import BrokenExecutor, CancelledError, Executor
from typing import Any

import gymnasium as gym

from gpfd.adapters import sources, vector_cache
from gpfd.discovery import _jobs
from gpfd.errors import InputError
from gpfd.execution import _deadline, _expired
from gpfd.execution.workers import WorkerError, WorkerPool

# Fitness evaluations played together in one vector environment (a lockstep group) where the
# environment has a vector form: 30 lanes each for cartpole-quick's 3 trials of 10 episodes.
LOCKSTEP_GROUP = 16

#: make_executor(workers): the executor an Evaluator makes, and ends, where it is given none.
ExecutorFactory = Callable[[int], Executor]


def _lockstep_groups(tasks: list) -> list[list]:
    """Consecutive groups of at most LOCKSTEP_GROUP tasks, as equal as may be, an even number of
    them (two workers share them evenly; 21 evaluations: 11 and 10, not 16 and 5). Their number
    follows from the tasks alone, never from the workers, so that a vector form seeded as a whole
    (one seed mixed from a group's lanes) gives the same run for any number of workers."""
    n = len(tasks)
    count = -(-n // LOCKSTEP_GROUP)
    if count % 2 == 1 and n > 1:
        count += 1
    groups, start = [], 0
    for i in range(count):
        size = n // count + (1 if i < n % count else 0)
        groups.append(tasks[start : start + size])
        start += size
    return groups


def executor_workers(executor: Executor) -> int | None:
    """How many workers `executor` has, where it says: gpfd's pool, ProcessPoolExecutor and loky
    (``_max_workers``), a Dask client's executor (the threads of its workers); else None."""
    for attribute in ("workers", "_max_workers"):
        count = getattr(executor, attribute, None)
        if isinstance(count, int) and count > 0:
            return count
    client = getattr(executor, "_client", None)  # distributed.client.ClientExecutor
    nthreads = getattr(client, "nthreads", None)
    if callable(nthreads):
        try:
            return sum(nthreads().values()) or None
        except Exception:  # A client that cannot answer now: the caller's default.
            return None
    return None


class Evaluator:
    """evaluate(config_text, [(genome, seed), ...]) for gpfd's discovery: run::trialFitness of
    each genome; and run_trials for the learning runs of validation, confirmation and assessment.
    In this process (one worker, no executor) or on an executor: the one given (``use``), or one
    of `workers` workers made by `make_executor` at the first work and ended by close()."""

    def __init__(
        self,
        name: str,
        factory: Callable[[], gym.Env],
        workers: int,
        make_executor: ExecutorFactory = WorkerPool,
    ):
        self.name = name
        self.factory = factory
        self.workers = workers if workers > 0 else (os.cpu_count() or 1)
        self.make_executor = make_executor
        self._executor: Executor | None = None
        self._given = False  # The executor is the caller's: never shut down here.
        self._jobs: _jobs.Jobs | None = None
        self._busy = False  # A round of work is under way (or was left unfinished).

    def use(self, threads: int, executor: Executor | None = None) -> None:
        """Runs on `executor` (the caller's; `threads` > 0 says how many workers to size the work
        for, else the executor's own count or the cores), or without one on `threads` workers
        (0: one per core). The number is run.json's `threads`; it never changes the results."""
        self._executor, self._given = executor, executor is not None
        count = executor_workers(executor) if executor is not None and threads == 0 else None
        self.workers = threads or count or os.cpu_count() or 1

    def __call__(self, config_text: str, tasks: list[tuple[bytes, int]]) -> list[float]:
        groups = [(group,) for group in self._groups(tasks)]
        done = self._map(_jobs.fitness_group, config_text, groups)
        return [fitness for group in done for fitness in group]

    @property
    def lockstep(self) -> bool:
        """Whether the environment has a vector form, whose calls go in lockstep groups
        (_lockstep_groups), each group's episodes in one vector environment
        (python/src/lockstep_group.hpp)."""
        return sources.has_vector_form(self.name)

    def _groups(self, tasks: list) -> list[list]:
        """Lockstep groups where the environment has a vector form, else one task each."""
        return _lockstep_groups(tasks) if self.lockstep else [[task] for task in tasks]

    def run_trials(
        self, config_text: str, budget: int, tasks: list[tuple[tuple, list[int]]]
    ) -> Iterator[list]:
        """The curves of each task (a feature set and the seeds of its runs) under the config
        and budget (run::LearningTask::Budget), in task order, as each is done
        (python/src/trial_runner.cpp)."""
        groups = [(budget, group) for group in self._groups(tasks)]
        return (
            curves for done in self._map(_jobs.runs_group, config_text, groups) for curves in done
        )

    @property
    def in_process(self) -> bool:
        """Whether the work runs in this process (one worker and no executor)."""
        return self._executor is None and self.workers == 1

    def in_process_timeout_text(self) -> str:
        return (
            f"task_timeout needs worker processes: {self.name} is stepped in this process "
            "(threads=1 and no executor), which nothing could end when a step hangs; give "
            "threads=2 or more, or an executor"
        )

    def _map(self, function: Callable[..., Any], config_text: str, work: list[tuple]) -> Iterator:
        """function(config_text, *args) for each args of work, in order, as each is done: here,
        or on the executor under the jobs of gpfd.discovery._jobs. InputError where the config sets
        a task_timeout and the work would run here (nothing could end a hung step)."""
        if self.in_process:
            if _deadline.seconds_of(config_text) is not None:
                raise InputError(f"{self.in_process_timeout_text()} (task_timeout)")
            return (function(config_text, *args) for args in work)
        executor = self._started()
        assert self._jobs is not None
        results = self._jobs.map(executor, function, config_text, work, self.workers)
        return self._round(results, _deadline.seconds_of(config_text))

    def _round(self, results: Iterator, expiry: float | None) -> Iterator:
        """`results`, a lost worker's or a broken executor's error a WorkerError saying that
        resume= continues (`expiry`: the task_timeout, which a Dask error names, with where its
        task was as the last worker its deadline ended told: gpfd.execution._expired)."""
        self._busy = True
        started = time.time()  # Dask's events are stamped by the scheduler's time.time().
        try:
            yield from results
        except WorkerError as e:  # gpfd's pool: a task that lost its workers (or a timeout's).
            if "resume=" in str(e):
                raise
            raise WorkerError(
                f"{e}. The work stops; a discovery's directory keeps its last complete "
                "generation, which resume= continues."
            ) from e
        except BrokenExecutor as e:
            raise WorkerError(
                f"the executor broke ({type(e).__name__}: {e}): one of its workers died and "
                f"{type(self._executor).__name__} cannot go on without it. The work stops; a "
                "discovery's directory keeps its last complete generation, which resume= "
                "continues (with a new executor). gpfd's own pool (threads=N) and Dask run a "
                "lost worker's tasks elsewhere instead."
            ) from e
        except CancelledError as e:  # Not by gpfd: it cancels only once it stops waiting.
            raise WorkerError(
                f"the executor ({type(self._executor).__name__}) cancelled a task: a Dask "
                "client's tasks are cancelled when its scheduler goes away or it closes. The "
                "work stops; a discovery's directory keeps its last complete generation, which "
                "resume= continues (with a working executor)."
            ) from e
        except Exception as e:
            if type(e).__name__ != "KilledWorker":  # Dask's: a task whose workers all died.
                raise
            ended = ""
            if expiry is not None:
                told = _expired.dask_text(self._executor, getattr(e, "task", None), started)
                said = f"the last worker it ended said: {told}"
                if not told:
                    said = "its stderr names the environment's step"
                ended = f", each ended by task_timeout={expiry:g} s if it ran past it ({said})"
            raise WorkerError(
                f"Dask gave up a task of {self.name}: its workers died running it{ended} ({e}). "
                "The work stops; a discovery's directory keeps its last complete generation, "
                "which resume= continues."
            ) from e
        self._busy = False

    def _started(self) -> Executor:
        if self._jobs is None:
            self._jobs = _jobs.Jobs(self.name, self.factory)  # TypeError where it cannot travel.
        if self._executor is None:
            self._executor = self.make_executor(self.workers)
        return self._executor

    def close(self) -> None:
        """Ends the round under way, its tasks not yet started cancelled, and the executor made
        here: at once when a round was left unfinished (an interruption, an error), its workers
        terminated; else once they are idle. An executor given to ``use`` goes on. This
        process' idle vector environments of the name are closed (gpfd.vector_cache; each worker
        closes its own at exit)."""
        vector_cache.close(self.name)
        if self._jobs is not None:
            self._jobs.cancel()
        executor, self._executor = self._executor, None
        if executor is None or self._given:
            self._busy = False
            return
        terminate = getattr(executor, "terminate", None)
        if self._busy and terminate is not None:
            terminate()
        else:
            executor.shutdown(wait=not self._busy, cancel_futures=True)
        self._busy = False
