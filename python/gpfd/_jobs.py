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

A task's result depends on its job, genomes and seeds only, never on where it ran or how many
times it was sent: the same seed gives the same run on any executor.
"""

from __future__ import annotations

import hashlib
import pickle
import threading
from collections import OrderedDict
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from typing import Any

import cloudpickle

from gpfd import _core, user_env

KEEP_JOBS = 16
KEEP_ENVS = 4


class NeedJob:
    """A worker's answer to a task whose job it does not hold: send the task again with it."""

    def __init__(self, key: str) -> None:
        self.key = key


# ---- the worker's side: what this process holds ----

_lock = threading.Lock()  # One task at a time per process (tasks hold the GIL while they step).
_jobs: OrderedDict[str, tuple[str, str]] = OrderedDict()  # key -> (environment key, config)
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
    _keep(_jobs, key, (env_key, config_text), KEEP_JOBS)


def run(key: str, payload: bytes | None, function: Callable[..., Any], *args: Any) -> Any:
    """A task, in a worker: ``function(config_text, *args)`` under the job `key`, with the job's
    environment registered under its name; NeedJob when this process holds no such job and
    `payload` (the job, from Jobs.payload) is None."""
    with _lock:
        if key not in _jobs or _jobs[key][0] not in _envs:
            if payload is None:
                return NeedJob(key)
            _install(key, payload)
        _jobs.move_to_end(key)
        env_key, config_text = _jobs[key]
        _envs.move_to_end(env_key)
        name, factory = _envs[env_key]
        if _registered.get(name) != env_key:  # Registering again drops the learning tasks built.
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
        self._jobs: dict[str, tuple[str, bytes]] = {}  # config text -> (key, payload)
        self._sent: set[str] = set()  # Keys sent at least once.
        self.payloads_sent = 0  # Tasks sent with their job attached (tests read it).
        self.pending: set[Future] = set()  # The futures of the round under way.

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
        started are then cancelled (as they are when the iterator is dropped: Evaluator.close)."""
        key, payload = self.job(config_text)
        first = key not in self._sent
        self._sent.add(key)
        index: dict[Future, int] = {}

        def submit(i: int, attach: bool) -> None:
            future = executor.submit(run, key, payload if attach else None, function, *work[i])
            self.payloads_sent += attach
            index[future] = i
            self.pending.add(future)

        results: dict[int, Any] = {}
        try:
            for i in range(len(work)):
                submit(i, first and i < copies)
            turn = 0
            while turn < len(work):
                done, _ = wait(self.pending, return_when=FIRST_COMPLETED)
                for future in done:
                    self.pending.discard(future)
                    i = index.pop(future)
                    value = future.result()
                    if isinstance(value, NeedJob):
                        submit(i, True)
                    else:
                        results[i] = value
                while turn in results:
                    yield results.pop(turn)
                    turn += 1
        finally:
            self.cancel()

    def cancel(self) -> None:
        """Cancels the tasks of the round under way that have not started."""
        for future in self.pending:
            future.cancel()
        self.pending.clear()
