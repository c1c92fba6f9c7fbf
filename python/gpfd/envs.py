# gpfd.envs, an import path users have (gpfd's environments in Gymnasium): the public names and the
# docstring of gpfd.environments.gpfd_env, where the code is (scripts/check-python-imports).
from gpfd.environments import gpfd_env as _code
from gpfd.environments.gpfd_env import (
    TASKS,
    GpfdEnv,
    action_space,
    check_params,
    gym_id,
    observation_space,
    register_all,
    seed64,
)

__doc__ = _code.__doc__
__all__ = [
    "GpfdEnv",
    "TASKS",
    "action_space",
    "check_params",
    "gym_id",
    "observation_space",
    "register_all",
    "seed64",
]
