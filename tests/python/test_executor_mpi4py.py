"""gpfd.evolve(executor=MPIPoolExecutor()) under ``mpiexec -n 3 python -m mpi4py.futures``: the
same run as threads=1, on this machine and across hosts made of network namespaces (marked
multihost: root only, ``pytest -m multihost``); skipped where mpi4py or mpiexec is missing.
A worker lost under mpi4py's pool ends the whole MPI job (seen with MPICH 4.0: hydra kills every
rank); the directory keeps its last complete generation for resume=. Not tested here."""

import ctypes
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import gpfd
from point_env import Point
from test_user_env_workers import SMALL, run_files

HERE = Path(__file__).resolve().parent

COMMON: dict[str, Any] = {"seed": 4, "population": 6, "generations": 2, "set": SMALL}
SCRIPT = f"""
import sys
import gpfd
from mpi4py.futures import MPIPoolExecutor
from point_env import Point

if __name__ == "__main__":
    with MPIPoolExecutor() as executor:
        gpfd.evolve(env=Point, **{COMMON!r}, executor=executor, out=sys.argv[1], verbose=False)
"""


def loaded(name: str) -> str:
    """The path of the shared library `name`, loaded into this process (Linux)."""
    ctypes.CDLL(name)
    for line in Path("/proc/self/maps").read_text().splitlines():
        if "/" + name in line:  # The file itself may be NAME.x.y.
            return line.split(maxsplit=5)[5]
    raise OSError(f"{name} is not in /proc/self/maps")


def mpi_library(tmp_path: Path) -> dict[str, str]:
    """The environment in which mpi4py's wheel finds MPICH: its wheels load libmpi.so.12, which
    Debian's MPICH names libmpich.so.12 (a link to it, on LD_LIBRARY_PATH, where needed)."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(HERE), *sys.path])}
    try:
        ctypes.CDLL("libmpi.so.12")
    except OSError:
        try:
            mpich = loaded("libmpich.so.12")
        except OSError:
            pytest.skip("no MPI library (libmpi.so.12 or libmpich.so.12)")
        (tmp_path / "lib").mkdir()
        (tmp_path / "lib/libmpi.so.12").symlink_to(mpich)
        env["LD_LIBRARY_PATH"] = f"{tmp_path / 'lib'}:{env.get('LD_LIBRARY_PATH', '')}"
    return env


def test_mpi4py_pool_gives_threads_one(tmp_path):
    pytest.importorskip("mpi4py")
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        pytest.skip("no mpiexec")
    env = mpi_library(tmp_path)
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    mpi = [mpiexec, "-n", "3", sys.executable, "-m", "mpi4py.futures", str(script)]
    done = subprocess.run(
        [*mpi, str(tmp_path / "mpi")], env=env, timeout=300, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr[-3000:]
    one = gpfd.evolve(env=Point, **COMMON, threads=1, out=tmp_path / "one", verbose=False)
    assert run_files(tmp_path / "mpi") == run_files(one.dir)


@pytest.mark.multihost
def test_mpi4py_pool_across_namespaced_hosts_gives_threads_one(tmp_path):
    """The same under scripts/multihost: three hosts made of network namespaces, the driver on
    host 0, one worker on each other, every message over the bridge (root only)."""
    pytest.importorskip("mpi4py")
    if shutil.which("mpiexec") is None:
        pytest.skip("no mpiexec")
    env = mpi_library(tmp_path)
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    multihost = [sys.executable, str(HERE.parents[1] / "scripts" / "multihost"), "--hosts", "3"]
    program = [sys.executable, "-m", "mpi4py.futures", str(script), str(tmp_path / "mpi")]
    done = subprocess.run(
        [*multihost, "--", *program], env=env, timeout=300, capture_output=True, text=True
    )
    if done.returncode == 77:
        pytest.skip(f"multihost: {done.stderr.strip()}")
    assert done.returncode == 0, done.stderr[-3000:]
    print(done.stdout.strip().splitlines()[-1])  # The time and the bytes on the wire.
    one = gpfd.evolve(env=Point, **COMMON, threads=1, out=tmp_path / "one", verbose=False)
    assert run_files(tmp_path / "mpi") == run_files(one.dir)
