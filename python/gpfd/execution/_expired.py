"""Where a task's deadline ended its worker (gpfd.execution._deadline's text: the environment and
the step), told to the driver by executors that have no channel of their own for it (gpfd's pool
has its pipe, gpfd.execution._worker; Ray its key-value store, gpfd.execution.ray):

- Dask: the worker logs the text as an event on the scheduler (topic TOPIC, with the key of its
  task) and has the scheduler's answer before it exits; the driver reads back the events of the
  task that Dask gave up (``dask_text``, the key of the KilledWorker), or, where that task never
  ran on a worker that its deadline ended (Dask counts a death against every task queued on the
  worker too), the last event logged since the round began.
- mpi4py's pool, where its master is the one rank of the workers' COMM_WORLD that is no worker
  (``python -m mpi4py.futures``; MPICommExecutor on COMM_WORLD): the rank sends the text to the
  master on COMM_WORLD, tag TAG, synchronously (an Issend completes once the master's receive has
  taken it); the master has a receive open from each other rank during a round with a deadline
  (``MpiListener``). Workers spawned by MPIPoolExecutor, or serving a service, share no
  communicator with the master that gpfd can reach (mpi4py keeps its own private): nothing is
  told there. Both sides need MPI_THREAD_MULTIPLE (mpi4py's default), as the text is sent from
  the deadline's thread and received in the driver's own thread beside mpi4py's; without it,
  nothing is told either.

A worker waits at most WAIT seconds for the driver's side to take the text, then ends anyway (the
text is on its stderr in every case).
"""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Callable
from typing import Any

TOPIC = "gpfd-task-expired"  # Dask: the scheduler's event topic.
TAG = 26_470  # mpi4py: the tag of the text on COMM_WORLD (below MPI's least TAG_UB, 32767).
LIMIT = 4096  # Bytes of text at most (mpi4py: the size of each receive).
WAIT = 2.0  # Seconds a worker waits at most for the text to be taken.
POLL = 0.01  # Seconds between a rank's looks at its send.
SHOWN = 3  # Texts named in an error at most.


def teller() -> Callable[[str], None] | None:
    """How this worker process tells its driver the text of a task that ran past its deadline
    (gpfd.execution._deadline.guard's `tell`): on a Dask worker or a rank of mpi4py's pool whose
    master is in its COMM_WORLD, a function of the text that returns once the driver's side holds
    it (or after WAIT seconds); None elsewhere. Call it in the task's thread: both executors
    know their task by the thread that runs it."""
    return _dask_teller() or _mpi_teller()


def named(texts: list[str]) -> str:
    """The texts that workers told (the first SHOWN, and how many more), for an error."""
    more = f"; and {len(texts) - SHOWN} more" if len(texts) > SHOWN else ""
    return "; ".join(texts[:SHOWN]) + more


# ---- Dask ----


def _dask_teller() -> Callable[[str], None] | None:
    if "distributed" not in sys.modules:  # A Dask worker has imported it.
        return None
    import distributed
    from distributed.utils import sync

    try:
        worker = distributed.get_worker()
        task = str(worker.get_current_task())
    except (ValueError, KeyError):  # No worker here, or no task of it in this thread.
        return None

    def tell(text: str) -> None:  # Returns with the scheduler's answer: the event is logged.
        message = {"task": task, "text": text}
        log = worker.scheduler.log_event  # The scheduler's handler, as Client.log_event calls it.
        sync(worker.loop, log, topic=TOPIC, msg=message, callback_timeout=WAIT)

    return tell


def dask_text(executor: Any, task: Any, since: float = 0.0) -> str | None:
    """What the last worker that its deadline ended told while running the Dask task `task` (a
    key: KilledWorker's), else the last that any told at or after `since` (the round's start, in
    time.time()'s seconds, as the scheduler stamps its events), where `executor` is a Dask
    client's (``client.get_executor()``); None where none told."""
    client = getattr(executor, "_client", None)
    if client is None or task is None:
        return None
    try:
        events = client.get_events(TOPIC)
    except Exception:  # No scheduler to ask: nothing told.
        return None
    told = [(stamp, m) for stamp, m in events if isinstance(m, dict) and "text" in m]
    own = [m["text"] for _, m in told if m.get("task") == str(task)]
    recent = [m["text"] for stamp, m in told if stamp >= since]
    texts = own or recent
    return texts[-1] if texts else None


# ---- mpi4py ----


def _threads_enough(mpi: Any) -> bool:
    live = mpi.Is_initialized() and not mpi.Is_finalized()
    return bool(live and mpi.Query_thread() >= mpi.THREAD_MULTIPLE)


def _mpi_teller() -> Callable[[str], None] | None:
    futures = sys.modules.get("mpi4py.futures")  # A rank of mpi4py's pool has imported it.
    if futures is None:
        return None
    from mpi4py import MPI

    try:
        workers = futures.get_comm_workers()  # This thread's: the pool's workers.
    except RuntimeError:  # Not a task's thread of a pool's worker.
        return None

    def tell(text: str) -> None:
        master = _master(MPI, workers)
        if master is None:
            return
        data = text.encode()[:LIMIT]
        request = MPI.COMM_WORLD.Issend([data, MPI.BYTE], master, TAG)
        end = time.monotonic() + WAIT
        while not request.Test() and time.monotonic() < end:
            time.sleep(POLL)

    return tell


def _master(mpi: Any, workers: Any) -> int | None:
    """The COMM_WORLD rank of the master of the pool of `workers` (their intracommunicator): the
    one rank of the world that is not among them. None where there is none (workers spawned or
    serving a service: the master is in another world) or MPI lacks the threads."""
    if workers == mpi.COMM_NULL or not _threads_enough(mpi):
        return None
    world, theirs = mpi.COMM_WORLD.Get_group(), workers.Get_group()
    rest = mpi.Group.Difference(world, theirs)
    try:
        return int(rest.Translate_ranks([0], world)[0]) if rest.Get_size() == 1 else None
    finally:
        for group in (world, theirs, rest):
            group.Free()


class MpiListener:
    """The master's side, for a round of mpi4py's pool: a receive open from each other rank of
    COMM_WORLD (none where MPI is not initialized with MPI_THREAD_MULTIPLE); ``texts`` what the
    ranks told, ``close`` cancels the receives still open. A rank tells once: it then ends."""

    def __init__(self) -> None:
        self._open: list[tuple[Any, bytearray]] = []  # (request, its buffer)
        self._told: list[str] = []
        self._mpi: Any = None
        if "mpi4py.MPI" not in sys.modules:  # mpi4py's pool has imported it.
            return
        from mpi4py import MPI

        if not _threads_enough(MPI):
            return
        self._mpi = MPI
        world = MPI.COMM_WORLD
        for rank in range(world.Get_size()):
            buffer = bytearray(LIMIT)  # Kept with its request: MPI writes into it.
            if rank != world.Get_rank():
                with contextlib.suppress(MPI.Exception):  # A rank MPI knows lost: none.
                    self._open.append((world.Irecv([buffer, MPI.BYTE], rank, TAG), buffer))

    def texts(self) -> list[str]:
        """What the ranks have told so far."""
        still = []
        for request, buffer in self._open:
            status = self._mpi.Status()
            try:
                done = request.Test(status)
            except self._mpi.Exception:  # The receive failed with its rank: nothing told.
                continue
            if done:
                size = status.Get_count(self._mpi.BYTE)
                self._told.append(bytes(buffer[:size]).decode(errors="replace"))
            else:
                still.append((request, buffer))
        self._open = still
        return list(self._told)

    def close(self) -> None:
        for request, _ in self._open:
            with contextlib.suppress(Exception):  # Failed with its rank: nothing to cancel.
                request.Cancel()
                request.Wait()
        self._open = []
