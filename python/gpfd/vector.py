# gpfd.vector, an import path users have (gpfd's vector environment): the public names and the
# docstring of gpfd.environments.gpfd_vector, where the code is (scripts/check-python-imports).
from gpfd.environments import gpfd_vector as _code
from gpfd.environments.gpfd_vector import (
    GpfdVectorEnv,
    lane_seeds,
    parse_autoreset_mode,
    with_mask,
)

__doc__ = _code.__doc__
__all__ = ["GpfdVectorEnv", "lane_seeds", "parse_autoreset_mode", "with_mask"]
