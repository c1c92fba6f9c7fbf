"""Idle vector environments, parked by a closed gpfd.adapters.vector_adapter.VectorAdapter for the
next one of the same environment, source and size: making one costs more than a short fitness
evaluation's resets.

Each is closed when no longer needed: when its environment's name is registered again
(gpfd.user_env.register), by ``close(name)`` when a run is over, and at the exit of the
process (the main one, or a worker of a pool that is closed).
"""

from __future__ import annotations

import contextlib
import multiprocessing.util
import os
from collections.abc import Hashable

from gymnasium.vector import VectorEnv

#: The vector environments kept per key: the lockstep groups alive at once in a process.
PER_KEY = 4

# (environment name, source, num_envs) -> idle vector environments.
_idle: dict[tuple[str, Hashable, int], list[VectorEnv]] = {}
# The process whose exit closes what is parked (a forked worker registers its own).
_exit_hook_pid: int | None = None


def park(key: tuple[str, Hashable, int], envs: VectorEnv) -> bool:
    """Keeps `envs` for ``take(key)``; False (and nothing kept) when the key has PER_KEY."""
    idle = _idle.setdefault(key, [])
    if len(idle) >= PER_KEY:
        return False
    _close_at_exit()
    idle.append(envs)
    return True


def take(key: tuple[str, Hashable, int]) -> VectorEnv | None:
    """An idle vector environment parked under `key`, now the caller's; None if there is none."""
    idle = _idle.get(key)
    return idle.pop() if idle else None


def count(name: str | None = None) -> int:
    """How many are parked for the environment `name` (all environments where None)."""
    return sum(len(envs) for key, envs in _idle.items() if name is None or key[0] == name)


def close(name: str | None = None) -> None:
    """Closes the idle vector environments of `name` (of every environment where None). Every
    one is closed even if some ``close`` raises; then the last error propagates.

    Example::

        gpfd.vector_cache.close()  # the runs are over: close every kept vector environment
    """
    keys = [key for key in _idle if name is None or key[0] == name]
    with contextlib.ExitStack() as stack:
        for key in keys:
            for envs in _idle.pop(key):
                stack.callback(envs.close)


def _close_at_exit() -> None:
    """Registers close() to run when this process exits. multiprocessing's finalizers run at
    the main process' exit (atexit) and at a worker's (which skips atexit handlers); one
    registered before a fork is skipped in the child, hence one per process."""
    global _exit_hook_pid
    if _exit_hook_pid != os.getpid():
        _exit_hook_pid = os.getpid()
        # An error of a close is printed there, and the others still run.
        multiprocessing.util.Finalize(None, close, exitpriority=0)
