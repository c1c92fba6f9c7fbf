# gpfd.features, an import path users have (what a features text is read against): the public names
# and the docstring of gpfd.discovery.features, where the code is (scripts/check-python-imports).
from gpfd.discovery import features as _code
from gpfd.discovery.features import (
    expectation,
)

__doc__ = _code.__doc__
__all__ = ["expectation"]
