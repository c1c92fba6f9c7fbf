"""gpfd.evolve(executor=) on Dask across hosts: three network namespaces on a private bridge
(scripts/multihost's Network), the scheduler and the driver on host 0, one worker (a nanny and
its worker process, one thread) on each of hosts 1 and 2; every message crosses the bridge. The
run, with a worker process killed mid-generation (DiesOnce), gives threads=1's files. Skipped
unless this process may make network namespaces (root, iproute2) and Dask is installed.

Marked multihost: left out of the default run (pyproject.toml's addopts), as ctest's multihost
tests are; run with ``pytest -m multihost`` (.ci/run does, after ``ctest -L multihost``)."""

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import script_module
from test_executor_faults import evolve
from test_user_env_workers import run_files

pytestmark = pytest.mark.multihost
HERE = Path(__file__).resolve().parent
SUBNET = "10.78.0"

DRIVER = f"""
import os, sys
from pathlib import Path
from distributed import Client
import gpfd
from test_executor_faults import COMMON, DiesOnce, arm_after_generation_0

address, out, flags = sys.argv[1:4]
client = Client(address, timeout=60)
client.wait_for_workers(2, timeout=60)
assert {{w["host"] for w in client.scheduler_info()["workers"].values()}} == {{
    "{SUBNET}.2", "{SUBNET}.3"}}
gpfd.evolve(env=DiesOnce, env_kwargs={{"directory": flags, "parent": os.getpid()}}, **COMMON,
            executor=client.get_executor(), callback=arm_after_generation_0(Path(flags)),
            out=out, verbose=False)
client.close()
"""


def test_dask_across_namespaced_hosts_gives_threads_one_with_a_worker_killed(tmp_path):
    pytest.importorskip("distributed")
    multihost = script_module("multihost")  # Its Network of namespaced hosts.
    why = multihost.usable()
    if why:
        pytest.skip(f"multihost: {why}")
    reference = run_files(evolve(tmp_path, "one", threads=1).dir)
    flags = tmp_path / "dask-flags"
    flags.mkdir()
    (tmp_path / "driver.py").write_text(DRIVER)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(HERE), *sys.path])}
    address = f"tcp://{SUBNET}.1:8786"
    python = [sys.executable, "-m"]
    processes: list[subprocess.Popen] = []
    log = (tmp_path / "dask.log").open("w")
    with multihost.Network(3, SUBNET, tmp_path) as net:
        try:
            scheduler = [
                "distributed.cli.dask_scheduler",
                "--host",
                f"{SUBNET}.1",
                "--port",
                "8786",
            ]
            processes.append(
                subprocess.Popen(
                    [*net.enter(0), *python, *scheduler, "--no-dashboard"],
                    env=env,
                    stdout=log,
                    stderr=log,
                )
            )
            for host in (1, 2):
                worker = ["distributed.cli.dask_worker", address, "--nthreads", "1"]
                worker += ["--host", f"{SUBNET}.{host + 1}", "--no-dashboard"]
                processes.append(
                    subprocess.Popen(
                        [*net.enter(host), *python, *worker], env=env, stdout=log, stderr=log
                    )
                )
            start = time.monotonic()
            driver = [sys.executable, str(tmp_path / "driver.py"), address]
            done = subprocess.run(
                [*net.enter(0), *driver, str(tmp_path / "dask"), str(flags)],
                env=env,
                capture_output=True,
                text=True,
                timeout=240,
            )
            seconds = time.monotonic() - start
            wire = net.wire_bytes()
        finally:
            for process in processes:
                process.kill()
                process.wait()
            log.close()
    assert done.returncode == 0, done.stderr[-4000:]
    print(f"dask on 2 namespaced hosts: {seconds:.1f} s, {wire} bytes on the wire")
    assert (flags / "died").exists()  # A worker process died mid-generation.
    assert run_files(tmp_path / "dask") == reference
