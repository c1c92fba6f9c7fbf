# gpfd.sb3, an import path users have (Stable-Baselines3's VecEnv over gpfd's environments): the
# public names and the docstring of gpfd.agents.sb3, where the code is
# (scripts/check-python-imports).
from gpfd.agents import sb3 as _code
from gpfd.agents.sb3 import (
    GpfdVecEnv,
    make_vec_env,
)

__doc__ = _code.__doc__
__all__ = ["GpfdVecEnv", "make_vec_env"]
