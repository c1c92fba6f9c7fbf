"""The one genome wire format (include/gpfd/expr/wire.hpp) through _core: the record that
tests/expr/wire_test.cpp pins and tests/mpi/protocol_test.cpp sends in an MPI Task
(tests/data/wire/genome-v1.bin) reads here (genome_from_wire) as the Python workers read it,
and what this side writes (genome_to_wire) is that record, byte for byte; a genome keeps its
printed form, values and fitness."""

import numpy as np
import pytest

import gpfd
from gpfd import _core

VARIABLES = ["x", "y", "z"]
# The golden genome (wire_test.cpp's golden()): what its record prints as.
GOLDEN_SEXPR = "(+ x (* 2.5 (sin z)))\n-0\n(/ y 5e-324)\n(tanh -0.3333333333333333)\n"


def golden(repo) -> bytes:
    return (repo / "tests" / "data" / "wire" / "genome-v1.bin").read_bytes()


def test_the_golden_record_reads_and_writes_back(repo):
    record = golden(repo)
    features = _core.genome_from_wire(record, VARIABLES)
    assert features.show("sexpr") == GOLDEN_SEXPR
    assert _core.genome_to_wire(features) == record
    # Through the features file's text and back: the same record, the same values to the bit.
    again = gpfd.FeatureSet(features.to_text(), variables=VARIABLES)
    assert _core.genome_to_wire(again) == record
    obs = np.random.default_rng(35).uniform(-3, 3, size=(64, 3))
    assert features(obs).tobytes() == again(obs).tobytes()


def test_a_worker_plays_the_record_gpfd_would_play():
    """Encoded here, decoded by the workers' path (trial_fitness_group): the fitness of the
    genome as the threads compute it (fitness_of_each)."""
    features = gpfd.FeatureSet.parse("dx * th\nsin(th) + 0.25", env="cartpole")
    text = _core.resolved_config("cartpole-quick", [])
    [alone] = _core.fitness_of_each("cartpole-quick", [], [features], 11)
    assert _core.trial_fitness_group(text, [(_core.genome_to_wire(features), 11)]) == [alone]


@pytest.mark.parametrize("cut", range(0, 40, 3))
def test_truncated_or_other_version_records_are_clear_errors(repo, cut):
    record = golden(repo)
    with pytest.raises(gpfd.InputError, match="genome wire format"):
        _core.genome_from_wire(record[:cut], VARIABLES)
    other = record[:2] + bytes([9]) + record[3:]
    with pytest.raises(gpfd.InputError, match="version 9, this build of gpfd reads version 1"):
        _core.genome_from_wire(other, VARIABLES)
