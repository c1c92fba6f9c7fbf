# gpfd.evaluator, an import path users have (the evaluations on an executor): the public names and
# the docstring of gpfd.discovery.evaluator, where the code is (scripts/check-python-imports).
from gpfd.discovery import evaluator as _code
from gpfd.discovery.evaluator import (
    LOCKSTEP_GROUP,
    Evaluator,
    ExecutorFactory,
    executor_workers,
)

__doc__ = _code.__doc__
__all__ = ["Evaluator", "ExecutorFactory", "LOCKSTEP_GROUP", "executor_workers"]
