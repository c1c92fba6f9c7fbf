"""The work of a discovery or an assessment on an environment stepped in Python, run on an
executor: GP's fitness evaluations (``Evaluator.__call__``, python/src/discovery_bindings.cpp)
and the learning runs of validation, confirmation and assessment (``Evaluator.run_trials``,
python/src/trial_runner.cpp).

With one worker the work runs in this process; with more, on an executor of that many workers
(``make_executor``; gpfd.workers.WorkerPool by default, whose workers are fresh interpreters).
Each worker gets the environment's factory once (``_init_worker``); a task carries only the config
text, the packed genomes or feature sets and the seeds. A fitness depends on its genome and seed
only, a curve on its features, budget and seed (and, on a vector form seeded as a whole, the
lockstep group, whose make-up never depends on the workers), so any number of workers gives the
same run.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from concurrent.futures import Executor
from typing import Any

import cloudpickle
import gymnasium as gym

from gpfd import _core, user_env, vector_cache, vector_source
from gpfd.workers import WorkerPool

# Fitness evaluations played together in one vector environment (a lockstep group) where the
# environment has a vector form: 30 lanes each for cartpole-quick's 3 trials of 10 episodes.
LOCKSTEP_GROUP = 16

#: make_executor(workers, initializer, initargs): the executor an Evaluator runs on.
ExecutorFactory = Callable[[int, Callable[..., Any], tuple], Executor]


def _init_worker(name: str, factory: Callable[[], gym.Env]) -> None:
    """A worker's setup: the environment `name` made by `factory` there."""
    user_env.register(name, factory)


def _fitness_group_task(task: tuple[str, list[tuple[bytes, int]]]) -> list[float]:
    return _core.trial_fitness_group(*task)


def _runs_group_task(task: tuple[str, int, list[tuple[tuple, list[int]]]]) -> list[list]:
    return _core.train_runs_group(*task)


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


class Evaluator:
    """evaluate(config_text, [(genome, seed), ...]) for gpfd's discovery: run::trialFitness of
    each genome; and run_trials for the learning runs of validation, confirmation and assessment.
    In this process (workers == 1) or on an executor of `workers` workers, started at the first
    work and ended by close()."""

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
        self._busy = False  # A round of work is under way (or was left unfinished).

    def __call__(self, config_text: str, tasks: list[tuple[bytes, int]]) -> list[float]:
        groups = [(config_text, group) for group in self._groups(tasks)]
        return [fitness for done in self._map(_fitness_group_task, groups) for fitness in done]

    @property
    def lockstep(self) -> bool:
        """Whether the environment has a vector form, whose calls go in lockstep groups
        (_lockstep_groups), each group's episodes in one vector environment
        (python/src/lockstep_group.hpp)."""
        return vector_source.has_vector_form(self.name)

    def _groups(self, tasks: list) -> list[list]:
        """Lockstep groups where the environment has a vector form, else one task each."""
        return _lockstep_groups(tasks) if self.lockstep else [[task] for task in tasks]

    def run_trials(
        self, config_text: str, budget: int, tasks: list[tuple[tuple, list[int]]]
    ) -> Iterator[list]:
        """The curves of each task (a feature set and the seeds of its runs) under the config
        and budget (run::LearningTask::Budget), in task order, as each is done
        (python/src/trial_runner.cpp)."""
        groups = [(config_text, budget, group) for group in self._groups(tasks)]
        return (curves for done in self._map(_runs_group_task, groups) for curves in done)

    def _map(self, function: Callable[[Any], Any], work: list) -> Iterator:
        """function over work, in order, as each is done: here, or on the executor."""
        if self.workers == 1:
            return map(function, work)
        return self._round(self._started().map(function, work))

    def _round(self, results: Iterator) -> Iterator:
        self._busy = True
        yield from results
        self._busy = False

    def _started(self) -> Executor:
        if self._executor is None:
            try:
                cloudpickle.dumps(self.factory)
            except Exception as e:
                raise TypeError(
                    f"{self.name}: the environment's factory cannot be sent to the worker "
                    f"processes: cloudpickle cannot pickle it ({type(e).__name__}: {e}); make it "
                    "picklable, or use threads=1 to run in this process"
                ) from e
            self._executor = self.make_executor(
                self.workers, _init_worker, (self.name, self.factory)
            )
        return self._executor

    def close(self) -> None:
        """Ends the executor: at once when a round was left unfinished (an interruption, an
        error), its workers terminated; else once they are idle. This process' idle vector
        environments of the name are closed (gpfd.vector_cache; each worker closes its own at
        exit)."""
        vector_cache.close(self.name)
        executor, self._executor = self._executor, None
        if executor is None:
            return
        terminate = getattr(executor, "terminate", None)
        if self._busy and terminate is not None:
            terminate()
        else:
            executor.shutdown(wait=not self._busy, cancel_futures=True)
        self._busy = False
