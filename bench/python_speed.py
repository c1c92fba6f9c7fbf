#!/usr/bin/env python3
"""gpfd from Python against Gymnasium and NumPy, side by side in one run (docs/python.md).

Usage, with the package installed (scripts/test installs it in .venv):
  .venv/bin/python bench/python_speed.py [--quick] [--sections 123]

1. Environment steps per second: one environment through gymnasium.make (gpfd's vs Gymnasium's
   CartPole-v1 and Acrobot-v1, the same tasks), and vector environments of N = 64: gpfd's
   (one C++ call per step) vs Gymnasium's SyncVectorEnv (and, for CartPole, Gymnasium's own NumPy
   vector environment). Random actions drawn beforehand; auto-reset as each does it.
2. FeatureSet throughput (states per second) for N = 1 and N = 4096 states per call, against the
   same features as the NumPy function of `gpfd features export --format python`.
3. The cost of one fitness evaluation (GP's short learning trials) on cart-pole built in (stepped
   in C++), on gpfd's cart-pole stepped in Python through Gymnasium (gpfd/CartPole-v0) and on
   Gymnasium's CartPole-v1, each one environment at a time and through its vector form (all
   lanes in one vector step), and on EnvPool's CartPole-v1 where EnvPool is installed; and per
   evaluation where 16 evaluations play together in one lockstep group (gpfd.fitness_of_each,
   as gpfd.evolve plays a generation: all their lanes in one vector step).
Every figure is the median of 3 repetitions, timed in CPU seconds of this process (everything
here runs on one thread), so that other jobs on the machine disturb it less than wall time.
"""

import argparse
import functools
import platform
import statistics
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

import gpfd

REPO = Path(__file__).resolve().parents[1]
REPEATS = 3
GROUP = gpfd.evaluator.LOCKSTEP_GROUP  # As gpfd.evolve plays a generation's evaluations.


def median_rate(measure):
    """The median over REPEATS of measure() -> (items, seconds), as items per second."""
    rates = []
    for _ in range(REPEATS):
        items, seconds = measure()
        rates.append(items / seconds)
    return statistics.median(rates)


def single_env_rate(env, steps, actions):
    picks = np.random.default_rng(0).integers(0, actions, size=steps)

    def measure():
        env.reset(seed=0)
        start = time.process_time()
        for a in picks:
            _, _, terminated, truncated, _ = env.step(int(a))
            if terminated or truncated:
                env.reset()
        return steps, time.process_time() - start

    return median_rate(measure)


def vector_env_rate(envs, steps):
    envs.action_space.seed(0)
    picks = [envs.action_space.sample() for _ in range(steps)]

    def measure():
        envs.reset(seed=0)
        start = time.process_time()
        for a in picks:
            envs.step(a)
        return steps * envs.num_envs, time.process_time() - start

    return median_rate(measure)


def environments(scale):
    print("1. environment steps per second (random discrete actions)")
    print(f"{'task':<10} {'':<28} {'gpfd':>12} {'Gymnasium':>12} {'ratio':>7}")
    for task, ours_id, theirs_id, actions in [
        ("CartPole", "gpfd/CartPole-v0", "CartPole-v1", 2),
        ("Acrobot", "gpfd/Acrobot-v0", "Acrobot-v1", 3),
    ]:
        kwargs = {"actions": "discrete", "max_steps": 500}
        ours = single_env_rate(gym.make(ours_id, **kwargs), 20000 * scale, actions)
        theirs = single_env_rate(gym.make(theirs_id), 20000 * scale // 4, actions)
        print(
            f"{task:<10} {'one env (gymnasium.make)':<28} {ours:>12,.0f} {theirs:>12,.0f} "
            f"{ours / theirs:>6.1f}x"
        )
        n = 64
        ours = vector_env_rate(gym.make_vec(ours_id, num_envs=n, **kwargs), 2000 * scale)
        sync = gym.make_vec(theirs_id, num_envs=n, vectorization_mode="sync")
        theirs = vector_env_rate(sync, 200 * scale)
        print(
            f"{task:<10} {f'N = {n}: vs SyncVectorEnv':<28} {ours:>12,.0f} {theirs:>12,.0f} "
            f"{ours / theirs:>6.1f}x"
        )
        if task == "CartPole":
            numpy_vec = gym.make_vec(theirs_id, num_envs=n, vectorization_mode="vector_entry_point")
            theirs = vector_env_rate(numpy_vec, 2000 * scale)
            print(
                f"{task:<10} {f'N = {n}: vs its NumPy vector env':<28} {ours:>12,.0f} "
                f"{theirs:>12,.0f} {ours / theirs:>6.1f}x"
            )


def calls_rate(function, x, calls, n):
    """(states, CPU seconds) of `calls` calls of function(x) on n states."""
    start = time.process_time()
    for _ in range(calls):
        function(x)
    return calls * n, time.process_time() - start


def feature_sets(scale):
    path = REPO / "tests/data/results/features/paper-fig6-swimmer5.features"
    fs = gpfd.FeatureSet.load(str(path))
    namespace = {}
    exec(fs.export("python"), namespace)
    numpy_features = namespace["features"]

    def as_matrix(x):
        return np.stack(np.broadcast_arrays(*numpy_features(x)), axis=-1)

    print(
        f"\n2. FeatureSet: {fs.n_features} features of the 5-segment swimmer ({path.name} of "
        f"Figure 6, {fs.input_dim} variables), states per second"
    )
    print(f"{'states per call':<16} {'FeatureSet':>14} {'NumPy export':>14} {'ratio':>7}")
    rng = np.random.default_rng(0)
    for n, calls in [(1, 20000 * scale), (4096, 50 * scale)]:
        x = rng.normal(size=(n, fs.input_dim)) if n > 1 else rng.normal(size=fs.input_dim)
        assert np.array_equal(fs(x), as_matrix(x))  # The same values, bit for bit.

        a = median_rate(lambda f=fs, x=x, k=calls, n=n: calls_rate(f, x, k, n))
        fewer = max(1, calls // 10)  # NumPy is slower: fewer calls for the same time.
        b = median_rate(lambda f=as_matrix, x=x, k=fewer, n=n: calls_rate(f, x, k, n))
        print(f"{n:<16} {a:>14,.0f} {b:>14,.0f} {a / b:>6.1f}x")


def envpool_available():
    try:
        import envpool  # noqa: F401
    except ImportError:
        return False
    return True


def fitness_cost(scale):
    settings = {"learner.params.updates": 10, "learner.params.episodes": 10, "fitness.trials": 3}
    builtin = {**settings, "env.params.actions": "discrete", "env.params.max_steps": 500}
    raw = gpfd.FeatureSet.parse("x\ndx\nth\ndth\n", env="cartpole")
    python_raw = gpfd.FeatureSet.parse("x0\nx1\nx2\nx3\n", variables=["x0", "x1", "x2", "x3"])
    seeds = range(1, 1 + 3 * scale)
    discrete = {"actions": "discrete", "max_steps": 500}

    def python(env, **kwargs):
        return lambda s: gpfd.fitness(python_raw, env=env, set=settings, seed=s, **kwargs)

    def group(env, **kwargs):
        # Per evaluation: the time of the group divided by its size (the loop below divides by
        # the number of seeds; each seed is one group here).
        return lambda s: gpfd.fitness_of_each(
            [python_raw] * GROUP, env=env, set=settings, seed=s, **kwargs
        )

    # A callable (here gymnasium.make of the id) has no vector form: one environment at a time.
    cases = [
        ("cartpole built in (C++)", lambda s: gpfd.fitness(raw, set=builtin, seed=s)),
        (
            "gpfd/CartPole-v0, one env at a time",
            python(functools.partial(gym.make, "gpfd/CartPole-v0", **discrete)),
        ),
        ("gpfd/CartPole-v0, its vector form", python("gpfd/CartPole-v0", env_kwargs=discrete)),
        ("CartPole-v1, one env at a time", python(functools.partial(gym.make, "CartPole-v1"))),
        ("CartPole-v1, its vector form", python("CartPole-v1")),
    ]
    if envpool_available():
        cases.append(("envpool/CartPole-v1", python("envpool/CartPole-v1")))
    grouped = [
        (f"gpfd/CartPole-v0, group of {GROUP}", group("gpfd/CartPole-v0", env_kwargs=discrete)),
        (f"CartPole-v1, group of {GROUP}", group("CartPole-v1")),
    ]
    if envpool_available():
        grouped.append((f"envpool/CartPole-v1, group of {GROUP}", group("envpool/CartPole-v1")))
    cases += grouped
    # gpfd's vector environment through its Python step (a VectorFactory is not stepped through
    # the C++ engine the way its id is): the cost of gpfd's generic vector path.
    gpfd_vec = functools.partial(_gpfd_vec, kwargs=discrete)
    cases.append(
        (
            "gpfd/CartPole-v0 via Python's step",
            python(gpfd.VectorFactory(gpfd_vec, per_lane_seeds=True)),
        )
    )
    print(
        "\n3. one fitness evaluation: 3 trials x 11 batches of 10 episodes, raw variables, "
        "policy gradient (cartpole-quick's learner); the cases interleaved"
        + ("" if envpool_available() else "; EnvPool not installed")
    )
    times = {name: [] for name, _ in cases}
    values: dict[str, list[float]] = {}  # Each case's fitness values, seed by seed.
    for _ in range(REPEATS):
        for name, run in cases:
            start = time.process_time()
            results = [run(seed) for seed in seeds]
            per_call = GROUP if (name, run) in grouped else 1
            times[name].append((time.process_time() - start) / len(seeds) / per_call)
            values[name] = [v for r in results for v in (r if isinstance(r, list) else [r])]
    base = statistics.median(times[cases[0][0]])
    # The mean fitness of a case's evaluations: the same on every Python and platform where the
    # runs are the same (bit for bit), so that machines and versions compare at a glance.
    print(f"{'':<36} {'CPU time':>12} {'':>8} {'mean fitness':>18}")
    for name, _ in cases:
        seconds = statistics.median(times[name])
        mean = statistics.fmean(values[name])
        print(f"{name:<36} {seconds * 1000:>9.1f} ms {seconds / base:>7.1f}x {mean:>18.10g}")
    vector_step_floor(python_raw, settings, seeds)


def _gpfd_vec(num_envs, kwargs):
    return gym.make_vec("gpfd/CartPole-v0", num_envs=num_envs, **kwargs)


class _Counting:
    """make_vec's vector environment, its step calls counted."""

    calls = 0

    def __init__(self, make):
        self.make = make

    def __call__(self, num_envs):
        envs = self.make(num_envs)
        step = envs.step

        def counted(actions):
            _Counting.calls += 1
            return step(actions)

        envs.step = counted
        return envs


def vector_step_floor(features, settings, seeds):
    """What the vector environments' own steps cost in one evaluation: its vector steps (counted
    on Gymnasium's CartPole-v1 through a VectorFactory) times one bare step of 30 lanes."""
    make = functools.partial(gym.make_vec, "CartPole-v1", vectorization_mode="vector_entry_point")
    _Counting.calls = 0
    for seed in seeds:
        gpfd.fitness(features, env=gpfd.VectorFactory(_Counting(make)), set=settings, seed=seed)
    steps = _Counting.calls / len(seeds)
    makers = {"CartPole-v1 (vector_entry_point)": make}
    if envpool_available():
        import envpool

        makers["EnvPool CartPole-v1, 1 thread"] = lambda n: envpool.make_gymnasium(
            "CartPole-v1", num_envs=n, batch_size=n, num_threads=1, seed=0
        )
    print(
        f"   {steps:.0f} vector steps per evaluation (3 trials x 10 episodes = 30 lanes); "
        "a bare step of 30 lanes, and that many of them:"
    )
    actions = np.random.default_rng(0).integers(0, 2, size=(2000, 30))
    for label, maker in makers.items():
        envs = maker(30)
        rate = vector_env_rate_of(envs, actions)
        print(f"   {label:<34} {1e6 / rate:>7.1f} us {steps / rate * 1000:>8.1f} ms per evaluation")
        envs.close()


def vector_env_rate_of(envs, actions):
    """Vector steps per CPU second through `actions` (median of REPEATS)."""

    def measure():
        envs.reset(seed=0)
        start = time.process_time()
        for a in actions:
            envs.step(a)
        return len(actions), time.process_time() - start

    return median_rate(measure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a tenth of the work (a smoke test)")
    parser.add_argument("--sections", default="123", help="which sections to run (default 123)")
    args = parser.parse_args()
    warnings.filterwarnings("ignore")
    scale = 1 if args.quick else 10
    print(
        f"gpfd {gpfd.__version__}, Python {platform.python_version()}, Gymnasium "
        f"{gym.__version__}, NumPy {np.__version__}; median of {REPEATS}, CPU time\n"
    )
    if "1" in args.sections:
        environments(scale)
    if "2" in args.sections:
        feature_sets(scale)
    if "3" in args.sections:
        fitness_cost(max(1, scale // 5))


if __name__ == "__main__":
    main()
