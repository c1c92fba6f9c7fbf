# gpfd.stats, an import path users have (the signed-rank test): the public names and the
# docstring of gpfd.discovery.stats, where the code is (scripts/check-python-imports).
from gpfd.discovery import stats as _code
from gpfd.discovery.stats import (
    SignedRank,
    signed_rank_test,
)

__doc__ = _code.__doc__
__all__ = ["SignedRank", "signed_rank_test"]
