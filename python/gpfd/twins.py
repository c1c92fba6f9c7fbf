# gpfd.twins, an import path users have (the twins of Gymnasium's tasks): the public names and the
# docstring of gpfd.environments.twins, where the code is (scripts/check-python-imports).
from gpfd.environments import twins as _code
from gpfd.environments.twins import (
    TWINS,
    TwinEnv,
    numpy_rule,
    reference,
    register_all,
    seed_words,
    twin_params,
)

__doc__ = _code.__doc__
__all__ = [
    "TWINS",
    "TwinEnv",
    "numpy_rule",
    "reference",
    "register_all",
    "seed_words",
    "twin_params",
]
