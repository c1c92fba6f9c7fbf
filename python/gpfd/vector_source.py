# gpfd.vector_source, an import path users have (vector forms and the vector adapter): the
# public names of gpfd.adapters.sources and gpfd.adapters.vector_adapter, where the code is,
# and the docstring of the sources (scripts/check-python-imports).
from gpfd.adapters import sources as _code
from gpfd.adapters.sources import (
    ENVPOOL_PREFIX,
    EnvPoolSource,
    GymnasiumSource,
    OneLaneEnv,
    VectorFactory,
    VectorSource,
    envpool_source,
    has_vector_form,
    native_single,
)
from gpfd.adapters.vector_adapter import (
    VectorAdapter,
    make_vector_adapter,
)

__doc__ = _code.__doc__
__all__ = [
    "ENVPOOL_PREFIX",
    "EnvPoolSource",
    "GymnasiumSource",
    "OneLaneEnv",
    "VectorAdapter",
    "VectorFactory",
    "VectorSource",
    "envpool_source",
    "has_vector_form",
    "make_vector_adapter",
    "native_single",
]
