"""The statistics behind gpfd's verdicts, for a user's own comparisons (the same C++ code)."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import NamedTuple

from gpfd import _core
from gpfd._core import InputError


class SignedRank(NamedTuple):
    """What ``signed_rank_test`` returns."""

    n: int  #: Non-zero differences: the pairs the test counts.
    w_plus: float  #: Sum of the ranks of the positive differences.
    p: float  #: Two-sided.
    median: float  #: Of all the differences, zeros included.


def signed_rank_test(differences: Iterable[float]) -> SignedRank:
    """Wilcoxon's signed-rank test (1945) of whether paired differences are centred on 0,
    two-sided: the test of gpfd's method-level verdict over runs. Zero differences are dropped
    (a pair that ties says nothing), tied magnitudes get their mean rank; exact up to 30 non-zero
    differences, beyond that the normal approximation with tie and continuity corrections.

    Example::

        gpfd.signed_rank_test([0.5, 1.2, -0.1, 0.8, 0.3])
        # SignedRank(n=5, w_plus=14.0, p=0.125, median=0.5)
    """
    values: list[float] = []
    for i, v in enumerate(differences):
        try:
            values.append(float(v))
        except (TypeError, ValueError):
            raise InputError(f"must be a number, not {v!r} (differences[{i}])") from None
        if not math.isfinite(values[-1]):
            raise InputError(f"must be finite, not {v} (differences[{i}])")
    n, w_plus, p, median = _core.signed_rank_test(values)
    return SignedRank(n, w_plus, p, median)
