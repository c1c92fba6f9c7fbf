"""The learning tasks a worker caches (python/src/trial_runner.cpp, cachedTask) are shared with
their users: an environment whose step registers a name (which makes gpfd forget every cached
task) frees no task under way, and one that does so while its task is being made (sampling
states) does not deadlock. scripts/check-lockstep-memory runs this file under ASan and valgrind,
which see a freed task used."""

import gpfd
from gpfd import _core, user_env
from point_env import Point

NAME = "python:task-cache"
SETTINGS = [
    f'env.name="{NAME}"',
    "env.params={}",
    "learner.params.updates=2",
    "learner.params.episodes=2",
    "fitness.trials=2",
]
ARMED: list[bool] = []  # Whether the next step registers a name (once).


class RegistersInStep(Point):
    """Point (20 steps) whose step, once ARMED, registers another name."""

    def __init__(self):
        super().__init__(steps=20)

    def step(self, action):
        if ARMED and ARMED.pop():
            user_env.register("python:task-cache-other", Point)
        return super().step(action)


def short_point() -> Point:
    return Point(steps=20)


def work() -> tuple[str, list, list]:
    """The config text, a fitness group and a learning run's task on NAME."""
    config = _core.resolved_config("user-env", SETTINGS)
    wire = _core.genome_to_wire(gpfd.FeatureSet("x0 * x1\nx1\n", variables=["x0", "x1"]))
    return config, [(wire, seed) for seed in (3, 4)], [((1, wire, False, 0), [5, 6])]


def train(config: str, runs: list) -> list:
    """train_runs_group's curves without their wall-clock seconds."""
    return [
        [curve[:4] + curve[5:] for curve in curves]
        for curves in _core.train_runs_group(config, 0, runs)
    ]


def reference() -> tuple[list, list]:
    user_env.register(NAME, short_point)
    config, group, runs = work()
    return _core.trial_fitness_group(config, group), train(config, runs)


def test_a_name_registered_in_a_step_frees_no_task_in_use():
    fitness, curves = reference()
    user_env.register(NAME, RegistersInStep)  # The same dynamics; forgets the tasks cached.
    config, group, runs = work()
    _core.trial_fitness_group(config, group)  # Makes and caches the task, unarmed.
    _core.train_runs_group(config, 0, runs)
    ARMED[:] = [True]
    assert _core.trial_fitness_group(config, group) == fitness
    assert not ARMED  # A step registered a name: the task in use was forgotten meanwhile.
    ARMED[:] = [True]
    assert train(config, runs) == curves
    assert not ARMED


def test_a_name_registered_while_the_task_is_made_does_not_deadlock():
    fitness, curves = reference()
    user_env.register(NAME, RegistersInStep)
    config, group, runs = work()
    ARMED[:] = [True]  # The first step is the sampling of states, as the task is made.
    assert _core.trial_fitness_group(config, group) == fitness
    assert not ARMED
    ARMED[:] = [True]
    assert train(config, runs) == curves
    assert not ARMED
