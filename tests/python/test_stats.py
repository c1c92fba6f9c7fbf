"""gpfd.signed_rank_test: the Wilcoxon signed-rank test of gpfd's verdicts, from Python."""

import math

import pytest

import gpfd


def test_known_exact_values():
    assert gpfd.signed_rank_test([1, 2, 3, 4, 5]).p == 2 / 32  # All one way: the least p, n = 5.
    test = gpfd.signed_rank_test([1, -2, 3, -4, 5, 6, 7, 8])
    assert (test.n, test.w_plus, test.p) == (8, 30.0, 28 / 256)  # W- = 6: 14 of 256 each side.
    assert gpfd.signed_rank_test([2, 2, -2]).p == 1.0  # Ranks 2, 2, 2: W+ = 4, none nearer 3.
    assert gpfd.signed_rank_test(range(1, 21)).p == pytest.approx(2 / 2**20)  # Exact up to 30.


def test_zero_differences_are_dropped():
    test = gpfd.signed_rank_test([0.0, 0.0, 3.0, 0.0])
    assert (test.n, test.p, test.median) == (1, 1.0, 0.0)
    assert gpfd.signed_rank_test([]).n == 0


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_a_non_finite_difference_is_an_input_error_naming_it(bad):
    with pytest.raises(gpfd.InputError, match=r"differences\[1\]"):
        gpfd.signed_rank_test([1.0, bad])


def test_a_difference_that_is_not_a_number_is_an_input_error_naming_it():
    with pytest.raises(gpfd.InputError, match=r"must be a number, not 'a' \(differences\[1\]\)"):
        gpfd.signed_rank_test([1.0, "a"])  # type: ignore[list-item]  # Bad input on purpose.
