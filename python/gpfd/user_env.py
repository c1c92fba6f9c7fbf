# gpfd.user_env, an import path users have (environments stepped in Python): the public names and
# the docstring of gpfd.adapters.user_env, where the code is (scripts/check-python-imports).
from gpfd.adapters import user_env as _code
from gpfd.adapters.user_env import (
    DEFAULT_CONFIG,
    Adapter,
    EnvError,
    is_builtin,
    make_adapter,
    register,
    resolve,
    run_name,
    state_names,
)

__doc__ = _code.__doc__
__all__ = [
    "Adapter",
    "DEFAULT_CONFIG",
    "EnvError",
    "is_builtin",
    "make_adapter",
    "register",
    "resolve",
    "run_name",
    "state_names",
]
