"""gpfd.evolve(executor=gpfd.ray.Executor()) on a local Ray cluster of 2 CPUs: the same run as
threads=1, and with a worker killed mid-generation (Ray runs its task again); skipped where Ray
is not installed (the extra executors installs it)."""

import os
import sys

import pytest

import gpfd
from test_executor_faults import evolve
from test_user_env_workers import run_files

ray = pytest.importorskip("ray")
import gpfd.ray  # noqa: E402  (after the skip: it needs Ray)


@pytest.fixture(scope="module")
def ray_cluster():
    """A local Ray cluster whose workers import this directory's modules as this process does."""
    path = os.pathsep.join(sys.path)
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        runtime_env={"env_vars": {"PYTHONPATH": path}},
    )
    yield
    ray.shutdown()


def test_ray_gives_threads_one_and_survives_a_killed_worker(tmp_path, ray_cluster):
    reference = run_files(evolve(tmp_path, "one", threads=1).dir)
    executor = gpfd.ray.Executor()
    assert executor.workers == 2
    run = evolve(tmp_path, "ray", executor=executor)
    assert (tmp_path / "ray-flags/died").exists()  # A Ray worker died mid-generation.
    assert run.info["threads"] == 2
    assert run_files(run.dir) == reference


def test_ray_executor_after_shutdown_refuses_work():
    executor = gpfd.ray.Executor()
    executor.shutdown()
    with pytest.raises(RuntimeError, match="shut down"):
        executor.submit(abs, -1)
