# gpfd.ray, an import path users have (Ray tasks as an executor): the public names and the
# docstring of gpfd.execution.ray, where the code is (scripts/check-python-imports).
from gpfd.execution import ray as _code
from gpfd.execution.ray import (
    Executor,
)

__doc__ = _code.__doc__
__all__ = ["Executor"]
