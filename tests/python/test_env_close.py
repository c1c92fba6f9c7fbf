"""Every environment gpfd makes is closed: a single Gymnasium environment when gpfd is done with
it (user_env.Adapter.close, from its C++ environment's destructor), a vector environment when its
group is over or, parked (gpfd.vector_cache), when the worker that parked it exits. Checked with
environments that note each make and close in a log, one file per process, in this process
(threads=1), on gpfd's pool, on multiprocessing's and on Dask."""

import os
from collections import Counter
from pathlib import Path
from typing import Any

import gymnasium as gym
from gymnasium.vector import SyncVectorEnv

import gpfd
from point_env import Point
from test_executors import process_pool
from test_user_env_workers import SMALL

COMMON: dict[str, Any] = {"seed": 3, "population": 6, "generations": 2, "set": SMALL}


def note(directory: str, what: str) -> None:
    with open(Path(directory, str(os.getpid())), "a") as f:
        f.write(what + "\n")


def tally(directory: Path) -> Counter:
    """Each noted line's count over every process."""
    return Counter(line for p in directory.iterdir() for line in p.read_text().split())


class Counted(Point):
    """Point (20 steps) noting "make" when made and "close" when closed."""

    def __init__(self, directory: str):
        super().__init__(steps=20)
        self.directory = directory
        note(directory, "make")

    def close(self):
        note(self.directory, "close")


class CountedVector(SyncVectorEnv):
    """CartPole's vector form noting "vmake" and "vclose"."""

    def __init__(self, directory: str, num_envs: int):
        super().__init__([lambda: gym.make("CartPole-v1")] * num_envs)
        self.directory = directory
        note(directory, "vmake")

    def close(self, **kwargs):
        if not self.closed:
            note(self.directory, "vclose")
        super().close(**kwargs)


class MakeVector:
    """A picklable make_vec(num_envs) of CountedVector logging into `directory`."""

    def __init__(self, directory: str):
        self.directory = directory

    def __call__(self, num_envs: int) -> CountedVector:
        return CountedVector(self.directory, num_envs)


def evolve_counted(tmp_path: Path, **options: Any) -> Counter:
    log = tmp_path / "log"
    log.mkdir()
    gpfd.evolve(
        env=Counted,
        env_kwargs={"directory": str(log)},
        **COMMON,
        **options,
        out=tmp_path / "run",
        verbose=False,
    )
    return tally(log)


def test_each_single_environment_is_closed_in_this_process(tmp_path):
    counts = evolve_counted(tmp_path, threads=1)
    assert counts["make"] > 0 and counts["close"] == counts["make"]


def test_each_single_environment_is_closed_on_gpfds_pool(tmp_path):
    counts = evolve_counted(tmp_path, threads=2)
    assert counts["make"] > 0 and counts["close"] == counts["make"]


def test_each_single_environment_is_closed_on_a_process_pool(tmp_path):
    with process_pool(2) as executor:
        counts = evolve_counted(tmp_path, executor=executor)
    assert counts["make"] > 0 and counts["close"] == counts["make"]


def test_each_single_environment_is_closed_on_dask(tmp_path, dask_client):
    counts = evolve_counted(tmp_path, executor=dask_client.get_executor())
    assert counts["make"] > 0 and counts["close"] == counts["make"]


def test_gpfds_workers_close_their_parked_vector_environments_as_they_exit(tmp_path):
    log = tmp_path / "log"
    log.mkdir()
    gpfd.evolve(
        env=gpfd.VectorFactory(MakeVector(str(log)), per_lane_seeds=True),
        seed=2,
        population=8,
        generations=1,
        set=SMALL,
        threads=2,
        out=tmp_path / "run",
        verbose=False,
    )
    workers = [p for p in log.iterdir() if int(p.name) != os.getpid()]
    assert workers  # The vector environments were made in the workers ...
    for path in workers:  # ... and each worker closed every one it made, parked ones too.
        counts = Counter(path.read_text().split())
        assert counts["vmake"] > 0 and counts["vclose"] == counts["vmake"], path.name
