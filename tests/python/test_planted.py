"""The planted-feature tasks (gpfd.planted) and the check that a set carries their answer
(gpfd.planted_check): spaces, determinism, the vector form against the single one, the check."""

import json
import sys

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import gpfd
from gpfd import planted, planted_check

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

IDS = [t.gym_id for t in planted.TASKS.values()]


def fs(text, task):
    """A feature set over the task's variables x0 .. x{d-1}."""
    return gpfd.FeatureSet.parse(text, env=gym.make(task))


def random_actions(space, rng, n):
    if isinstance(space, gym.spaces.Discrete):
        return rng.integers(0, space.n, n)
    return rng.uniform(-1.0, 1.0, (n, 1))


def episode(env, seed, actions):
    obs, _ = env.reset(seed=seed)
    rows = [obs]
    rewards = []
    for a in actions:
        obs, reward, terminated, truncated, _ = env.step(a)
        rows.append(obs)
        rewards.append(reward)
        if terminated or truncated:
            break
    return np.array(rows), np.array(rewards)


@pytest.mark.parametrize("env_id", IDS)
def test_spaces_and_episode_length(env_id):
    t = planted.task(env_id)
    env = gym.make(env_id)
    assert env.observation_space.shape == (t.variables,)
    if t.discrete:
        assert env.action_space == gym.spaces.Discrete(2)
    else:
        assert isinstance(env.action_space, gym.spaces.Box) and env.action_space.shape == (1,)
    actions = random_actions(env.action_space, np.random.default_rng(0), 100)
    rows, rewards = episode(env, 3, actions)
    assert len(rewards) == t.steps and np.isfinite(rows).all() and (rewards <= 0).all()
    assert gym.spec(env_id).vector_entry_point == "gpfd.planted:PlantedVectorEnv"


@pytest.mark.parametrize("env_id", IDS)
def test_deterministic_given_seed(env_id):
    env = gym.make(env_id)
    actions = random_actions(env.action_space, np.random.default_rng(1), 40)
    a = episode(env, 7, actions)
    b = episode(gym.make(env_id), 7, actions)
    c = episode(env, 8, actions)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    assert not np.array_equal(a[0], c[0])


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
@pytest.mark.parametrize("env_id", IDS)
def test_vector_form_agrees_with_single(env_id, mode):
    """Lane i reset with seed s + i plays step for step what the single environment plays from
    seed s + i, with its next episode (the stream going on) after the autoreset."""
    n, seed = 3, 11
    envs = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point")
    if mode != AutoresetMode.NEXT_STEP:
        envs = planted.PlantedVectorEnv(planted.task(env_id).name, n, mode)
    singles = [gym.make(env_id) for _ in range(n)]
    steps = planted.task(env_id).steps
    rng = np.random.default_rng(2)
    actions = [random_actions(singles[0].action_space, rng, n) for _ in range(2 * steps + 2)]
    obs, _ = envs.reset(seed=seed)
    expected = np.array([s.reset(seed=seed + i)[0] for i, s in enumerate(singles)])
    assert np.array_equal(obs, expected)
    restart = np.zeros(n, dtype=bool)
    for a in actions:
        obs, rewards, terminated, truncated, info = envs.step(a)
        for i, single in enumerate(singles):
            if restart[i]:  # Next-step autoreset: this step resets the lane.
                assert np.array_equal(obs[i], single.reset()[0]) and rewards[i] == 0
                continue
            o, r, te, tr, _ = single.step(a[i])
            assert rewards[i] == r and terminated[i] == te and truncated[i] == tr
            if mode == AutoresetMode.SAME_STEP and (te or tr):
                assert np.array_equal(info["final_obs"][i], o)
                o = single.reset()[0]
            assert np.array_equal(obs[i], o)
        restart = (terminated | truncated) if mode == AutoresetMode.NEXT_STEP else restart


def test_vector_form_takes_a_seed_per_lane_and_a_reset_mask():
    envs = planted.PlantedVectorEnv("Product", 2, AutoresetMode.DISABLED)
    obs, _ = envs.reset(seed=[5, None])
    assert np.array_equal(obs[0], gym.make("gpfd/PlantedProduct-v0").reset(seed=5)[0])
    again, _ = envs.reset(seed=[None, 5], options={"reset_mask": np.array([False, True])})
    assert np.array_equal(again[0], obs[0]) and np.array_equal(again[1], obs[0])
    with pytest.raises(ValueError, match="expected 2 seeds"):
        envs.reset(seed=[1])


def test_bad_input_is_named():
    with pytest.raises(gpfd.InputError, match="no planted task 'Sum'.*Product"):
        planted.task("Sum")
    with pytest.raises(gpfd.InputError, match="num_envs must be at least 1"):
        planted.PlantedVectorEnv("Ratio", 0)
    three = gpfd.FeatureSet.parse("x0 * x2\n", variables=["x0", "x1", "x2"])
    with pytest.raises(gpfd.InputError, match="PlantedProduct-v0 has 2 variables.*reads 3"):
        planted_check.carried(three, "Product")


def test_the_raw_variables_carry_nothing_needed():
    """Each task's symmetry: a linear fit of what it needs on its raw variables explains almost
    nothing (else the task would prove nothing)."""
    for t in planted.TASKS.values():
        states = planted_check.sample_states(t, 4000)
        for _, f in t.needed:
            assert planted_check.r_squared(f(states), states) < 0.05, t.name


@pytest.mark.parametrize(
    "task,text",
    [
        ("Product", "x0 * x1"),
        ("Product", "3 * x0 * x1 - 2"),  # Scaled and shifted.
        ("Product", "x0\nx1 * x0 + x0\nsin(x1)"),  # Among other features.
        ("Ratio", "x0 / x1"),
        ("Ratio", "x0\nx0 / x1 * 2 + 1"),
        ("Energy", "x1 * x1 / 2 - cos(x0)"),
        ("Energy", "cos(x0)\nx1 * x1"),  # Its parts, each alone: a linear combination carries it.
        ("Distractor", "x1 * x0"),
        ("Switch", "x0 * x1"),
        ("Switch", "sqrt(x1 - x0)"),  # Only the sign of s x decides: this has it (threshold 1).
        ("Switch", "x0 * x0 * x0 * x1"),
    ],
)
def test_check_accepts_the_planted_feature(task, text):
    result = planted_check.carried(fs(text, planted.task(task).gym_id), task)
    assert result.carries, result


@pytest.mark.parametrize(
    "task,text",
    [
        ("Product", "1"),  # A constant.
        ("Product", "x1"),  # One variable.
        ("Product", "sin(x0)"),
        ("Product", "x0\nx1\nx0 * x0\nx1 * x1"),  # Every term but the interaction.
        ("Ratio", "x0 * x1"),  # The product, not the ratio.
        ("Energy", "x1 * x1"),  # Half the energy.
        ("Distractor", "x0 * x1\nx2"),  # Carries the product but uses the distractor.
        ("Distractor", "x0 * x2"),
        ("Switch", "x0\nx1"),
        ("Switch", "1"),
        ("Switch", "x1 / x0 - x1"),  # The sign of s x only where |x| < 1.
    ],
)
def test_check_rejects_what_misses_the_interaction(task, text):
    result = planted_check.carried(fs(text, planted.task(task).gym_id), task)
    assert not result.carries, result


def test_r_squared_of_a_constant_target_is_refused():
    with pytest.raises(ValueError, match="constant"):
        planted_check.r_squared(np.ones(10), np.arange(10.0).reshape(10, 1))


@pytest.mark.parametrize(
    "env_id, chosen",
    [
        # Rprop's large steps harm the raw variables here; natural steps with a learned std do not.
        ("gpfd/PlantedProduct-v0", {"step": "natural", "updates": "30", "learn_std": "true"}),
        ("CartPole-v1", {"rprop": "large"}),  # Natural and Rprop's small steps learn less here.
    ],
)
def test_user_env_chooses_the_learner_settings_on_the_task(tmp_path, env_id, chosen):
    # user-env's learner.choose: the original variables and 8 random feature sets trained with
    # each alternative before the run; the one that does best with either is written into
    # config.toml, with no choice left.
    out = tmp_path / "run"
    gpfd.evolve(
        env=env_id,
        seed=1,
        population=6,
        generations=1,
        threads=2,
        out=out,
        callback=lambda stats: True,
        verbose=False,
    )  # Stopped after generation 0.
    config = tomllib.loads((out / "config.toml").read_text())
    for key, value in chosen.items():
        assert str(config["learner"]["params"][key]).lower() == value, key
    assert "choose" not in config["learner"]
    info = json.loads((out / "run.json").read_text())["learner_choice"]
    assert info["chosen"] == chosen
    assert len(info["tried"]) == 3
    merits = [max(t["mean"], t["random_sets_best"]) for t in info["tried"]]
    best = max(range(3), key=lambda i: merits[i])
    assert info["tried"][best]["settings"] == chosen
    assert sorted(merits)[-2] < merits[best]
