# gpfd.workers, an import path users have (gpfd's worker pool): the public names and the
# docstring of gpfd.execution.workers, where the code is (scripts/check-python-imports).
from gpfd.execution import workers as _code
from gpfd.execution.workers import (
    RemoteTraceback,
    WorkerError,
    WorkerPool,
)

__doc__ = _code.__doc__
__all__ = ["RemoteTraceback", "WorkerError", "WorkerPool"]
