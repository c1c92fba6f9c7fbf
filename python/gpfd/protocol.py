# gpfd.protocol, an import path users have (what C++ looks up on the adapters): the public names
# and the docstring of gpfd.adapters.protocol, where the code is (scripts/check-python-imports).
from gpfd.adapters import protocol as _code
from gpfd.adapters.protocol import (
    AdapterProtocol,
    VectorAdapterProtocol,
)

__doc__ = _code.__doc__
__all__ = ["AdapterProtocol", "VectorAdapterProtocol"]
