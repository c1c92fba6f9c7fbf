# gpfd.vector_cache, an import path users have (the idle vector environments): the public names and
# the docstring of gpfd.adapters.vector_cache, where the code is (scripts/check-python-imports).
from gpfd.adapters import vector_cache as _code
from gpfd.adapters.vector_cache import (
    PER_KEY,
    close,
    count,
    park,
    take,
)

__doc__ = _code.__doc__
__all__ = ["PER_KEY", "close", "count", "park", "take"]
