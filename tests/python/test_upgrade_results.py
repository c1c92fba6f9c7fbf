"""scripts/upgrade-results: configs of the format before gp.operators (9aaabe9) become the text
gpfd writes now, with the old operator probabilities bit for bit and negative seeds as their
uint64 text; checkpoints change in their config alone; the committed results are read by gpfd."""

import json
import shutil
import subprocess
import sys

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

# A config as older gpfd wrote it (sorted keys, nested tables indented), the paper's rates and a
# seed of 2^63 or more stored as a negative integer.
OLD = """name = 'tiny'
seed = -2715827634856397383

[env]
name = 'cartpole'

[gp]
crossover = 0.69999999999999996
elitism = 0.10000000000000001
generations = 2
list_crossover_share = 0.16666666669999999
node_mutation_weight = 2.0
population = 4
shrinkage_weight = 1.0
tournament_size = 3
tree_mutation_weight = 1.0

[learner]
name = 'pg'

    [learner.params]
    updates = '5'
"""

# What gpfd writes for it now: the seed as text (2^64 - 2715827634856397383), the operators'
# weights as in configs/*.toml since 9aaabe9, after [gp]'s keys.
NEW = """name = 'tiny'
seed = '15730916438853154233'

[env]
name = 'cartpole'

[gp]
elitism = 0.10000000000000001
generations = 2
population = 4
tournament_size = 3

    [gp.operators]
    feature_list_crossover = 0.11666666668999999
    node_mutation = 0.15000000000000002
    shrinkage = 0.075000000000000011
    subtree_crossover = 0.58333333331000004
    tree_mutation = 0.075000000000000011

[learner]
name = 'pg'

    [learner.params]
    updates = '5'
"""


def checkpoint(config):
    """A checkpoint.json as gpfd writes it (nlohmann::json, dump(1), keys sorted)."""
    return (
        '{\n "cache": [\n  [\n   "x[0] ; (* x[1] 0.5)",\n   -1775.9316129032256,\n   5\n'
        '  ]\n ],\n "config": ' + json.dumps(config, ensure_ascii=False) + ",\n"
        ' "format": "gpfd-checkpoint-2",\n "generation": 1,\n "operator_counts": [\n  3,\n'
        '  0,\n  1,\n  0,\n  0\n ],\n "rng": {\n  "words": [\n   13569340513354758100\n'
        '  ]\n },\n "version": "0.1.0"\n}\n'
    )


def upgrade(repo, *dirs):
    return subprocess.run(
        [sys.executable, str(repo / "scripts" / "upgrade-results"), *dirs],
        capture_output=True,
        text=True,
    )


def test_a_results_tree_becomes_the_current_format(repo, tmp_path):
    run = tmp_path / "set" / "run-01"
    run.mkdir(parents=True)
    (tmp_path / "set" / "config.toml").write_text(OLD)  # A set of runs' config.
    (run / "config.toml").write_text(OLD)
    (run / "checkpoint.json").write_text(checkpoint(OLD))
    done = upgrade(repo, str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert "migrated 3 files" in done.stdout
    assert (tmp_path / "set" / "config.toml").read_text() == NEW
    assert (run / "config.toml").read_text() == NEW
    assert (run / "checkpoint.json").read_text() == checkpoint(NEW)
    again = upgrade(repo, str(tmp_path))
    assert again.returncode == 0, again.stderr
    assert "migrated 0 files, 3 already in the current format" in again.stdout
    assert (run / "config.toml").read_text() == NEW


def old_probabilities(c, share, node, tree, shrink):
    """442790e:src/gp/evolution.cpp, operatorProbabilities."""
    mutation, total = 1.0 - c, node + tree + shrink
    return [
        c * (1.0 - share),
        c * share,
        mutation * node / total,
        mutation * tree / total,
        mutation * shrink / total,
    ]


def new_probabilities(weights):
    """src/gp/evolution.cpp: weight / total, the total summed in registration order."""
    total = 0.0
    for w in weights:
        total += w
    return [w / total for w in weights]


def test_the_weights_give_the_old_probabilities_bit_for_bit(repo, tmp_path):
    # 0.5 of crossover, a tenth of it on feature lists, 1 : 1 : 1: the old probabilities sum to
    # 1 - 2^-53 in gpfd's order, so as weights they would not give themselves back.
    old = (
        OLD.replace("0.69999999999999996", "0.5")
        .replace("0.16666666669999999", "0.1")
        .replace("node_mutation_weight = 2.0", "node_mutation_weight = 1.0")
    )
    (tmp_path / "config.toml").write_text(old)
    done = upgrade(repo, str(tmp_path))
    assert done.returncode == 0, done.stderr
    table = tomllib.loads((tmp_path / "config.toml").read_text())["gp"]["operators"]
    weights = [
        table[name]
        for name in (
            "subtree_crossover",
            "feature_list_crossover",
            "node_mutation",
            "tree_mutation",
            "shrinkage",
        )
    ]
    expected = old_probabilities(0.5, 0.1, 1.0, 1.0, 1.0)
    assert new_probabilities(expected) != expected
    assert new_probabilities(weights) == expected


def test_a_half_migrated_config_leaves_the_tree_as_it_was(repo, tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "a" / "config.toml").write_text(OLD)
    half = OLD.replace("shrinkage_weight = 1.0\n", "")
    (tmp_path / "b").mkdir()
    (tmp_path / "b" / "config.toml").write_text(half)
    done = upgrade(repo, str(tmp_path))
    assert done.returncode == 2
    assert str(tmp_path / "b" / "config.toml") in done.stderr
    assert "shrinkage_weight" in done.stderr
    assert (tmp_path / "a" / "config.toml").read_text() == OLD
    assert (tmp_path / "b" / "config.toml").read_text() == half


def test_the_committed_results_are_in_the_current_format(repo):
    configs = sorted((repo / "docs" / "results").rglob("config.toml"))
    assert configs
    for path in configs:
        config = tomllib.loads(path.read_text())
        assert "operators" in config["gp"] and "crossover" not in config["gp"], path
        assert not isinstance(config["seed"], int) or config["seed"] >= 0, path


def test_gpfd_reads_a_committed_run_and_formats_its_config_alike(cli, repo, tmp_path):
    # The run's config.toml and its checkpoint's config text, read by gpfd, must be the same
    # config (the run predates keys added since, gp.distinct_offspring among them: they read as
    # their defaults); the run is finished, so nothing is computed.
    run = tmp_path / "run"
    shutil.copytree(repo / "tests/data/results/acrobot-quick-run", run)
    done = subprocess.run(
        [cli, "evolve", str(run / "config.toml"), "--resume", str(run)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert "already complete" in done.stdout + done.stderr
