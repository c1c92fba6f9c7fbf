# gpfd.planted_check, an import path users have (whether a feature set carries a planted task's
# answer): the public names and the docstring of gpfd.environments.planted_check, where the code is
# (scripts/check-python-imports).
from gpfd.environments import planted_check as _code
from gpfd.environments.planted_check import (
    THRESHOLD,
    Carried,
    carried,
    least_squares_fit,
    r_squared,
    sample_states,
    sign_agreement,
)

__doc__ = _code.__doc__
__all__ = [
    "Carried",
    "THRESHOLD",
    "carried",
    "least_squares_fit",
    "r_squared",
    "sample_states",
    "sign_agreement",
]
