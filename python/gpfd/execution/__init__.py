"""Executors and their workers, knowing nothing of environments: gpfd's own pool of worker
processes (workers, its workers' main _worker, their wire _frames), Ray tasks as an executor (ray),
and a task's deadline in a worker (_deadline).

Layer 1 of the package (scripts/check-python-imports): it imports only gpfd._core and gpfd.errors.
"""
