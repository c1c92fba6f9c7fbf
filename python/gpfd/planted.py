# gpfd.planted, an import path users have (the tasks with a known answer): the public names and the
# docstring of gpfd.environments.planted, where the code is (scripts/check-python-imports).
from gpfd.environments import planted as _code
from gpfd.environments.planted import (
    TASKS,
    Array,
    PlantedEnv,
    PlantedVectorEnv,
    Task,
    register_all,
    task,
)

__doc__ = _code.__doc__
__all__ = ["Array", "PlantedEnv", "PlantedVectorEnv", "TASKS", "Task", "register_all", "task"]
