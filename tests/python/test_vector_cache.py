"""gpfd.vector_cache: a closed VectorAdapter parks its vector environment for the next one, and
every parked one is closed when no longer needed: when its environment's name is registered
again, by close(name), and at the exit of the process, the main one or a pool's worker."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import gymnasium as gym
from gymnasium.vector import SyncVectorEnv

import gpfd
from gpfd import user_env, vector_cache, vector_source

CLOSED: list[int] = []  # The ids of the vector environments closed, in this process.
_CLOSED_KEPT: list[SyncVectorEnv] = []  # Kept alive, so that no later environment reuses an id.


class Logged(SyncVectorEnv):
    def close(self, **kwargs):
        if not self.closed:
            CLOSED.append(id(self))
            _CLOSED_KEPT.append(self)
        super().close(**kwargs)


def make_vec(num_envs: int) -> Logged:
    return Logged([lambda: gym.make("CartPole-v1")] * num_envs)


def parked(name: str) -> int:
    """Registers `name`, plays one reset on its vector form and closes the adapter; the id of the
    vector environment it parked."""
    user_env.register(name, gpfd.VectorFactory(make_vec, per_lane_seeds=True))
    adapter = vector_source.make_vector_adapter(name, 4, 2, [], [])
    adapter.reset([1, 2])
    envs = id(adapter.envs)
    adapter.close()
    return envs


def test_a_parked_environment_serves_the_next_adapter_of_its_key():
    name = "python:cache-reuse"
    first = parked(name)
    assert vector_cache.count(name) == 1 and first not in CLOSED
    adapter = vector_source.make_vector_adapter(name, 4, 2, [], [])
    adapter.reset([3, 4])
    assert id(adapter.envs) == first and vector_cache.count(name) == 0
    adapter.close()
    vector_cache.close(name)
    assert first in CLOSED and vector_cache.count(name) == 0


def test_registering_the_name_again_closes_its_parked_environments():
    name, other = "python:cache-again", "python:cache-other"
    envs, kept = parked(name), parked(other)
    user_env.register(name, gpfd.VectorFactory(make_vec))
    assert envs in CLOSED and vector_cache.count(name) == 0
    assert kept not in CLOSED and vector_cache.count(other) == 1  # Not another name's.
    vector_cache.close()
    assert kept in CLOSED and vector_cache.count() == 0


def test_every_one_is_closed_though_a_close_raises():
    class Raises(Logged):
        def close(self, **kwargs):
            super().close(**kwargs)
            raise RuntimeError("close failed")

    first, second = Raises([lambda: gym.make("CartPole-v1")]), make_vec(1)
    assert vector_cache.park(("python:cache-raises", None, 1), first)
    assert vector_cache.park(("python:cache-raises", None, 2), second)
    try:
        vector_cache.close("python:cache-raises")
    except RuntimeError as e:
        assert str(e) == "close failed"
    else:
        raise AssertionError("the close's error was lost")
    assert {id(first), id(second)} <= set(CLOSED)
    assert vector_cache.count("python:cache-raises") == 0


def test_no_more_than_per_key_are_parked():
    key = ("python:cache-full", None, 1)
    envs = [make_vec(1) for _ in range(vector_cache.PER_KEY + 1)]
    assert [vector_cache.park(key, e) for e in envs] == [True] * vector_cache.PER_KEY + [False]
    vector_cache.close("python:cache-full")
    envs[-1].close()


def test_the_exit_of_the_process_and_of_a_pools_worker_closes_them(tmp_path: Path):
    """A worker of a forkserver pool parks one and is ended by pool.close(); then the main process
    parks one and exits. Each writes its pid as its environment closes."""
    log = tmp_path / "closed.log"
    (tmp_path / "parking.py").write_text(
        textwrap.dedent(
            f"""
            import os
            import sys

            import gymnasium as gym
            from gymnasium.vector import SyncVectorEnv

            import gpfd
            from gpfd import user_env, vector_source


            class Logged(SyncVectorEnv):
                def close(self, **kwargs):
                    # Closed by gpfd, not by the interpreter's teardown (VectorEnv.__del__).
                    with open({str(log)!r}, "a") as f:
                        f.write(f"{{os.getpid()}} {{sys.is_finalizing()}}\\n")
                    super().close(**kwargs)


            def make_vec(n):
                return Logged([lambda: gym.make("CartPole-v1")] * n)


            def park(name):
                user_env.register(name, gpfd.VectorFactory(make_vec, per_lane_seeds=True))
                adapter = vector_source.make_vector_adapter(name, 4, 2, [], [])
                adapter.reset([1, 2])
                adapter.close()
                return os.getpid()
            """
        )
    )
    script = textwrap.dedent(
        """
        import multiprocessing

        import parking

        if __name__ == "__main__":
            pool = multiprocessing.get_context("forkserver").Pool(1)
            worker = pool.apply(parking.park, ("python:in-a-worker",))
            pool.close()
            pool.join()
            print(worker, parking.park("python:in-main"))
        """
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), *sys.path])}
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, env=env, cwd=tmp_path
    )
    assert done.returncode == 0, done.stderr
    worker, main = done.stdout.split()
    assert worker != main
    assert log.read_text().splitlines() == [f"{worker} False", f"{main} False"]
