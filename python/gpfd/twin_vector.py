# gpfd.twin_vector, an import path users have (the twins' vector form): the public names and the
# docstring of gpfd.environments.twin_vector, where the code is (scripts/check-python-imports).
from gpfd.environments import twin_vector as _code
from gpfd.environments.twin_vector import (
    TwinVectorEnv,
)

__doc__ = _code.__doc__
__all__ = ["TwinVectorEnv"]
