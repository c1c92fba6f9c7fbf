"""gpfd's twins of Gymnasium's classic-control tasks against Gymnasium's own, side by side: the
same observations (bit for bit, dtype included), rewards, terminated and truncated, for hundreds
of seeds, seeded and unseeded resets, 1,000+ steps, random and adversarial actions."""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import gpfd
import gpfd.twins
from gpfd.twins import TWINS

TASKS = list(TWINS)


def _same(ours: Any, theirs: Any, what: str) -> None:
    a, b = np.asarray(ours), np.asarray(theirs)
    assert a.dtype == b.dtype and a.shape == b.shape, (what, a.dtype, b.dtype, a.shape, b.shape)
    assert a.tobytes() == b.tobytes(), (what, a, b)


def _same_reward(ours: float, theirs: float, what: str) -> None:
    assert (math.isnan(ours) and math.isnan(theirs)) or ours == theirs, (what, ours, theirs)


def _same_reward_of(task: str, action: Any, ours: float, theirs: float, what: str) -> None:
    """Bit for bit, but within 1 ulp where Gymnasium's own torque square is inexact."""
    if _gymnasiums_torque_square_is_inexact(task, action) and math.isfinite(theirs):
        assert abs(ours - theirs) <= math.ulp(theirs), (what, ours, theirs)
    else:
        _same_reward(ours, theirs, what)


def _gymnasiums_torque_square_is_inexact(task: str, action: Any) -> bool:
    """Whether Gymnasium's Pendulum-v1 squares this action's torque other than correctly rounded:
    under NumPy 1.x a float32 torque's `u**2` goes through the float64 `np.power` ufunc, which on
    CPUs with AVX-512 is SVML's vectorised pow (within 1 ulp), about twice in 100,000 steps; the
    twin gives the correctly rounded square there, as NumPy does elsewhere (docs/twins.md)."""
    if task != "Pendulum-v1":
        return False
    u = np.clip(np.asarray(action), -2.0, 2.0)[0]
    square = u**2  # As Gymnasium computes it, in the type NumPy's rules give.
    exact = u.astype(square.dtype) * u.astype(square.dtype)  # Correctly rounded in that type.
    return not math.isnan(float(u)) and bool(square != exact)


def _actions(env: gym.Env, rng: np.random.Generator, adversarial: bool) -> Any:
    """A random action of the space; with `adversarial`, often a limit, and for continuous
    spaces values beyond the bounds, huge ones and NaN, as float32 or float64 arrays or lists."""
    space = env.action_space
    if isinstance(space, gym.spaces.Discrete):
        return int(rng.integers(space.n)) if rng.random() < 0.5 else np.int64(rng.integers(space.n))
    if not adversarial:
        return space.sample()
    pick = rng.random()
    assert isinstance(space, gym.spaces.Box)
    low, high = float(space.low[0]), float(space.high[0])
    value = [low, high, 0.0, low * 3, high * 1e6, float("nan"), rng.uniform(low, high)][
        int(rng.integers(7))
    ]
    if pick < 0.4:
        return np.array([value], dtype=np.float32)
    if pick < 0.8:
        return np.array([value], dtype=np.float64)
    return [value]


def _play(task: str, seeds: range, steps: int, adversarial: bool, **make: Any) -> tuple[int, int]:
    """(steps played, the longest episode's length)."""
    ours, theirs = gym.make(f"gpfd/{task}", **make), gym.make(task, **make)
    rng = np.random.default_rng(len(seeds) + steps)
    theirs.action_space.seed(len(seeds) + steps)  # space.sample()'s actions, the same each run.
    played = longest = 0
    for seed in seeds:
        for s in (seed, None):  # A seeded reset, then one that continues the stream.
            obs, _ = ours.reset(seed=s)
            their_obs, _ = theirs.reset(seed=s)
            _same(obs, their_obs, f"reset(seed={s})")
            start = played
            for _ in range(steps):
                action = _actions(theirs, rng, adversarial)
                if task == "CartPole-v1" and adversarial and rng.random() < 0.9:
                    action = int(obs[2] + 0.5 * obs[3] > 0)  # Balancing, for long episodes.
                obs, reward, terminated, truncated, _ = ours.step(action)
                their_obs, their_reward, t2, tr2, _ = theirs.step(action)
                what = f"{task} seed {seed} step {played} action {action!r}"
                _same(obs, their_obs, what)
                _same_reward_of(task, action, float(reward), float(their_reward), what)
                assert (terminated, truncated) == (t2, tr2), what
                played += 1
                if terminated or truncated:
                    break
            longest = max(longest, played - start)
    return played, longest


@pytest.mark.parametrize("task", TASKS)
def test_hundreds_of_seeds_give_gymnasiums_episodes(task):
    assert _play(task, range(200), 60, adversarial=False)[0] > 2000


@pytest.mark.parametrize("task", TASKS)
def test_long_episodes_with_adversarial_actions(task):
    # 1,500 steps per episode (the time limit raised on both), actions at and beyond the limits.
    played, longest = _play(task, range(1000, 1004), 1500, adversarial=True, max_episode_steps=1500)
    assert longest >= 1000, longest


@pytest.mark.parametrize("task", TASKS)
def test_the_time_limit_and_the_spec_are_gymnasiums(task):
    ours, theirs = gym.spec(f"gpfd/{task}"), gym.spec(task)
    assert ours.max_episode_steps == theirs.max_episode_steps
    assert ours.reward_threshold == theirs.reward_threshold
    env, reference = gym.make(f"gpfd/{task}"), gym.make(task)
    assert env.observation_space == reference.observation_space
    assert env.action_space == reference.action_space


def test_a_balanced_cartpole_is_truncated_at_500_as_gymnasiums():
    ours, theirs = gym.make("gpfd/CartPole-v1"), gym.make("CartPole-v1")
    obs, _ = ours.reset(seed=4)
    theirs.reset(seed=4)
    for step in range(1, 501):
        action = int(obs[2] + 0.5 * obs[3] > 0)  # A balancing policy.
        obs, r, terminated, truncated, _ = ours.step(action)
        their = theirs.step(action)
        _same(obs, their[0], f"step {step}")
        assert (r, terminated, truncated) == (their[1], their[2], their[3])
        if terminated or truncated:
            break
    assert truncated and step == 500


@pytest.mark.parametrize("task", ["CartPole-v1", "MountainCar-v0"])
def test_an_invalid_discrete_action_is_refused_as_gymnasium_refuses_it(task):
    ours, theirs = gym.make(f"gpfd/{task}"), gym.make(task)
    ours.reset(seed=0)
    theirs.reset(seed=0)
    for bad in (5, -1, 1.0, "1"):
        with pytest.raises(AssertionError) as mine:
            ours.step(bad)
        with pytest.raises(AssertionError) as gyms:
            theirs.step(bad)
        assert str(mine.value) == str(gyms.value)


def test_acrobot_takes_what_its_torque_list_takes_and_names_the_rest():
    ours, theirs = gym.make("gpfd/Acrobot-v1"), gym.make("Acrobot-v1")
    ours.reset(seed=1)
    theirs.reset(seed=1)
    for a in (-1, -3, 2, True, np.int32(0)):  # Python's indexing of [-1.0, 0.0, +1].
        _same(ours.step(a)[0], theirs.step(a)[0], repr(a))
    with pytest.raises(IndexError, match="0, 1 or 2"):
        ours.step(3)
    with pytest.raises(TypeError, match="integer"):
        ours.step(1.5)


@pytest.mark.parametrize("task", ["Pendulum-v1", "MountainCarContinuous-v0"])
def test_a_continuous_action_of_the_wrong_shape_or_type_is_a_clear_error(task):
    env = gym.make(f"gpfd/{task}")
    env.reset(seed=0)
    for bad, error in (
        (np.float32(0.5), ValueError),
        (np.zeros((1, 1)), ValueError),
        (np.array([], dtype=np.float32), ValueError),
        (np.array([1], dtype=np.float16), TypeError),
    ):
        with pytest.raises(error, match=task):
            env.step(bad)


def test_keywords_of_the_task_are_taken_and_others_refused():
    ours = gym.make("gpfd/Pendulum-v1", g=9.81)
    theirs = gym.make("Pendulum-v1", g=9.81)
    _same(ours.reset(seed=2)[0], theirs.reset(seed=2)[0], "reset")
    action = np.array([1.5], dtype=np.float32)
    for _ in range(50):
        _same(ours.step(action)[0], theirs.step(action)[0], "g=9.81")
    with pytest.raises(TypeError, match="render_fps|takes g"):
        gym.make("gpfd/Pendulum-v1", render_fps=3)


def test_a_bad_seed_is_refused_as_gymnasium_refuses_it():
    env = gym.make("gpfd/CartPole-v1")
    with pytest.raises(gym.error.Error):
        env.reset(seed=-1)


def test_big_seeds_take_numpys_words():
    ours, theirs = gym.make("gpfd/CartPole-v1"), gym.make("CartPole-v1")
    for seed in (2**32, 2**63 + 5, 2**100 + 7):
        _same(ours.reset(seed=seed)[0], theirs.reset(seed=seed)[0], f"seed {seed}")


def _same_rewards(task: str, actions: Any, ours: Any, theirs: Any, what: str) -> None:
    """Each env's reward as _same_reward_of compares one."""
    a, b = np.asarray(ours), np.asarray(theirs)
    assert a.dtype == b.dtype and a.shape == b.shape, (what, a.dtype, b.dtype, a.shape, b.shape)
    for i, (mine, gyms) in enumerate(zip(a.tolist(), b.tolist(), strict=True)):
        _same_reward_of(task, actions[i], mine, gyms, f"{what} env {i}")


def _step_both(ours, theirs, actions, what, task):
    mine, gyms = ours.step(actions), theirs.step(actions)
    _same_rewards(task, actions, mine[1], gyms[1], f"{what}: reward")
    for index, name in ((0, "obs"), (2, "terminated"), (3, "truncated")):
        _same(mine[index], gyms[index], f"{what}: {name}")
    if "final_obs" in gyms[4] or "final_obs" in mine[4]:
        _same(mine[4]["_final_obs"], gyms[4]["_final_obs"], f"{what}: _final_obs")
        for i in np.flatnonzero(gyms[4]["_final_obs"]):
            _same(mine[4]["final_obs"][i], gyms[4]["final_obs"][i], f"{what}: final_obs {i}")
    return gyms


@pytest.mark.parametrize("mode", ["NextStep", "SameStep", "Disabled"])
@pytest.mark.parametrize("task", TASKS)
def test_the_vector_form_steps_as_sync_vector_env_in_every_autoreset_mode(task, mode):
    from gymnasium.vector import AutoresetMode, SyncVectorEnv

    n = 8
    ours = gym.make_vec(f"gpfd/{task}", num_envs=n, autoreset_mode=mode)
    theirs = SyncVectorEnv([lambda: gym.make(task)] * n, autoreset_mode=AutoresetMode(mode))
    assert ours.single_observation_space == theirs.single_observation_space
    _same(ours.reset(seed=7)[0], theirs.reset(seed=7)[0], "reset")
    rng = np.random.default_rng(3)
    theirs.action_space.seed(3)  # The same actions each run.
    ended = 0
    for step in range(600):
        actions = theirs.action_space.sample()
        if step % 50 == 0 and not isinstance(theirs.single_action_space, gym.spaces.Discrete):
            actions = actions.astype(np.float64) * 3  # Beyond the bounds, as float64.
        gyms = _step_both(ours, theirs, actions, f"{task} {mode} step {step}", task)
        done = gyms[2] | gyms[3]
        ended += int(done.sum())
        if mode == "Disabled" and done.any():
            seeds: Any = [int(rng.integers(1000)) if d else None for d in done]
            options = {"reset_mask": done}
            _same(
                ours.reset(seed=seeds, options=options)[0],
                theirs.reset(seed=seeds, options=options)[0],
                f"{task} reset_mask at {step}",
            )
    assert ended > 0 or task == "MountainCarContinuous-v0"  # Its episodes run 999 steps.


ONE_EPISODE = {
    "learner.params.updates": 3,
    "learner.params.episodes": 1,
    "learner.params.max_episode_steps": 60,
    "fitness.trials": 1,
}


SEVERAL_EPISODES = {
    "learner.params.updates": 3,
    "learner.params.episodes": 4,
    "learner.params.max_episode_steps": 60,
    "fitness.trials": 2,
}


@pytest.mark.parametrize("task", ["Pendulum-v1", "MountainCarContinuous-v0", "Acrobot-v1"])
def test_fitness_on_the_twin_plays_the_episodes_gymnasium_plays(task, capsys):
    """The fitness is equal only if every episode is (the seeds, actions, rewards and the float32
    observations the learner reads: Acrobot-v1's and Pendulum-v1's were once left unrounded)."""
    (dim,) = gym.make(task).observation_space.shape or (0,)
    names = " ".join(f"x{i}" for i in range(dim))
    fs = gpfd.FeatureSet.parse(f"# variables: {names}\nx0\nx1 * x{dim - 1}\n")
    native = gpfd.fitness(fs, env=task, set=SEVERAL_EPISODES, seed=4)
    said = capsys.readouterr().err
    assert f"{task} stepped in C++ by gpfd's twin" in said
    python = gpfd.fitness(fs, env=task, set=SEVERAL_EPISODES, seed=4, native=False)
    assert "stepped in Python by Gymnasium's own (native=False)" in capsys.readouterr().err
    assert native == python


def test_a_whole_run_on_the_twin_gives_gymnasiums_files(tmp_path):
    """The same files, byte for byte, but for the environment's name and the timings."""
    small: dict[str, Any] = {"seed": 2, "population": 6, "generations": 2, "verbose": False}
    # The learner's choice in 2 seeds and no random sets: it trains confirmation-length runs.
    choice = {"learner.choose_seeds": 2, "learner.choose_random_sets": 0}
    small |= {"set": SEVERAL_EPISODES | choice, "threads": 1}
    twin = gpfd.evolve(env="Pendulum-v1", out=tmp_path / "twin", **small)
    python = gpfd.evolve(env="Pendulum-v1", native=False, out=tmp_path / "python", **small)
    for name in ["validation.csv", "confirmation.csv"]:
        assert (twin.dir / name).read_bytes() == (python.dir / name).read_bytes(), name
    for name in ["best.features", "best/generation-0000.features", "best/generation-0001.features"]:
        ours = (
            (twin.dir / name)
            .read_text()
            .replace("# env: Pendulum-v1", "# env: gymnasium:Pendulum-v1")
        )
        assert ours == (python.dir / name).read_text(), name
    timeless = [
        [row.split(",")[:-1] for row in (run.dir / "generations.csv").read_text().splitlines()]
        for run in (twin, python)
    ]
    assert timeless[0] == timeless[1]


def test_a_run_on_an_id_names_the_twin_or_gymnasiums_own(tmp_path, capsys):
    small: dict[str, Any] = {
        "seed": 1,
        "population": 4,
        "generations": 1,
        "set": ONE_EPISODE,
        "verbose": False,
    }
    twin = gpfd.evolve(env="CartPole-v1", out=tmp_path / "twin", threads=1, **small)
    assert "name = 'CartPole-v1'" in (twin.dir / "config.toml").read_text()
    python = gpfd.evolve(
        env="CartPole-v1", native=False, out=tmp_path / "python", threads=1, **small
    )
    assert "name = 'gymnasium:CartPole-v1'" in (python.dir / "config.toml").read_text()
    capsys.readouterr()
    fs = gpfd.FeatureSet.parse("# variables: x0 x1 x2\nx0\n")
    with pytest.raises((TypeError, gpfd.EnvError)):  # Gymnasium's own refuses it too.
        gpfd.fitness(fs, env="Pendulum-v1", env_kwargs={"bogus": 1}, set=ONE_EPISODE)
    assert "its twin does not take bogus" in capsys.readouterr().err


def test_the_twins_follow_the_numpy_installed():
    rule = "2" if int(np.__version__.split(".")[0]) >= 2 else "1"
    assert gpfd.twins.numpy_rule() == rule
