# gpfd.wrappers, an import path users have (the feature wrappers): the public names and the
# docstring of gpfd.agents.wrappers, where the code is (scripts/check-python-imports).
from gpfd.agents import wrappers as _code
from gpfd.agents.wrappers import (
    FeatureObservation,
    VectorFeatureObservation,
    check_features,
)

__doc__ = _code.__doc__
__all__ = ["FeatureObservation", "VectorFeatureObservation", "check_features"]
