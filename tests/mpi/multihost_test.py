#!/usr/bin/env python3
"""`gpfd evolve` across hosts: the ctest tests labelled `multihost` (cmake/mpi.cmake).

    tests/mpi/multihost_test.py --gpfd GPFD --plugin libgpfd_test_plugin.so --tmp DIR SCENARIO

Each scenario runs gpfd under scripts/multihost (network namespaces on a private bridge,
mpiexec across them, every message on the wire) and compares every file the run writes with
a threads-only run of the same config and seed, byte for byte but wall-clock times; run.json
may differ only in how the run was spread (`mpi_processes`, `threads`). The reference runs are
the fixture scenarios `reference-*`. Exits 77 (ctest: skipped) where namespaces cannot be made
(not root).

Scenarios:
  reference-cartpole  gpfd evolve multihost-cartpole.toml --threads 2 (no MPI)
  identical           the same on 3 hosts (master + 2 workers with 2 threads each): identical
                      files; prints the time and the bytes on the wire per generation
  reference-sleep     gpfd evolve multihost-sleep.toml --threads 2 (no MPI; the test plug-in's
                      learner `sleep`: 40 ms per evaluation)
  worker-killed       the same on 3 hosts under `mpiexec -disable-auto-cleanup`, --mpi-timeout 3;
  worker-stopped      worker 2 gets SIGKILL / SIGSTOP / its host's cable pulled 50 ms into
  link-down           generation 2: the master says it lost the worker and gave its evaluations
                      to the other, the job ends with exit code 0, every file is identical
  node-lost           3 hosts x 2 ranks (threads 1); rank 4 gets SIGKILL in generation 2: hydra's
                      proxy on its host ends rank 5 too, the master loses both and goes on with
                      the 3 other workers; exit code 0, identical files. Not in ctest: now and
                      then hydra's mpiexec itself dies then (SIGPIPE; docs/mpi.md)
  master-killed       the master gets SIGKILL in generation 2: the workers leave (the job ends);
                      resumed on 2 hosts, the run ends identical to the reference
  slurm               examples/slurm/gpfd-evolve.sbatch in an emulated Slurm allocation of 3
                      hosts (scripts/multihost --slurm); the master gets SIGKILL in generation
                      2: the script resumes on its own, exit code 0, identical files
"""

import argparse
import importlib.machinery
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
DATA = SOURCE / "tests" / "data" / "mpi"
SKIP = 77
# A hung launch fails its test instead of blocking it (hydra ends the job after this many s).
os.environ["MPIEXEC_TIMEOUT"] = "100"


class Failure(Exception):
    pass


def output_compare():
    """scripts/lib/output_compare.py, scripts/compare-outputs' comparison of two results
    directories."""
    path = str(SOURCE / "scripts" / "lib" / "output_compare.py")
    return importlib.machinery.SourceFileLoader("output_compare", path).load_module()


def differences(reference: Path, run: Path) -> list[str]:
    """Files that differ beyond timings; run.json may differ in mpi_processes and threads."""
    found = output_compare().compare(reference, run)
    if "differs: run.json" in found:

        def setup_free(path: Path) -> dict:
            data = json.loads(path.read_text())
            for key in ("seconds", "revision", "mpi_processes", "threads"):
                data.pop(key, None)
            return data

        if setup_free(reference / "run.json") == setup_free(run / "run.json"):
            found.remove("differs: run.json")
    return found


class Scenarios:
    def __init__(self, gpfd: Path, plugin: Path, tmp: Path):
        self.gpfd, self.plugin, self.tmp = gpfd, plugin, tmp
        self.output = ""  # What the last multihost run printed.

    def fresh(self, name: str) -> Path:
        path = self.tmp / name
        shutil.rmtree(path, ignore_errors=True)
        return path

    def gpfd_run(self, args: list[str]) -> subprocess.CompletedProcess:
        return subprocess.run([str(self.gpfd), *args], capture_output=True, text=True)

    def config(self, name: str) -> list[str]:
        """gpfd's arguments that name tests/data/mpi/multihost-<name>.toml (and its plug-in)."""
        toml = str(DATA / f"multihost-{name}.toml")
        return ["--plugin", str(self.plugin), toml] if name == "sleep" else [toml]

    def multihost(
        self, hosts: int, out: Path, args: list[str], *options: str, hydra=(), new_out=True
    ) -> dict:
        """`gpfd ARGS [--out OUT]` on `hosts` hosts under scripts/multihost (its OPTIONS, and
        HYDRA: mpiexec's); its report. OUT is followed (--watch) either way."""
        report = out.with_suffix(".json")
        command = [
            sys.executable, str(SOURCE / "scripts" / "multihost"), "--hosts", str(hosts),
            "--watch", str(out), "--report", str(report), *options, "--", *hydra,
            str(self.gpfd), *args, *(["--out", str(out)] if new_out else []),
        ]  # fmt: skip
        result = subprocess.run(command, capture_output=True, text=True)
        self.output = result.stdout + result.stderr
        print(self.output)
        if result.returncode == SKIP:
            raise SystemExit(SKIP)
        return json.loads(report.read_text())

    def reference(self, config: str) -> Path:
        return self.tmp / f"reference-{config}"

    def make_reference(self, config: str) -> None:
        out = self.fresh(f"reference-{config}")
        args = ["evolve", *self.config(config), "--threads", "2", "--quiet", "--out", str(out)]
        result = self.gpfd_run(args)
        if result.returncode != 0:
            raise Failure(f"the threads-only reference run failed: {result.stderr}")

    def expect_identical(self, config: str, out: Path) -> None:
        differ = differences(self.reference(config), out)
        if differ:
            raise Failure("differs from the threads-only run: " + "; ".join(differ))
        print(f"identical to the threads-only run: every file of {out.name}")

    def reference_cartpole(self) -> None:
        self.make_reference("cartpole")

    def identical(self) -> None:
        out = self.fresh("identical")
        args = ["evolve", *self.config("cartpole"), "--threads", "2", "--quiet"]
        report = self.multihost(3, out, args)
        if report["exit"] != 0:
            raise Failure(f"mpiexec exited with {report['exit']}")
        self.expect_identical("cartpole", out)
        first, later = report["generations"][0], report["generations"][1:]
        count = sum(g["count"] for g in later)  # Generations after the one with the launch.
        wire = sum(g["wire_bytes"] for g in later)
        if count == 0 or wire == 0:
            raise Failure("no bytes crossed the bridge after the launch")
        print(
            f"per generation after the launch (mean of {count}): "
            f"{sum(g['seconds'] for g in later) / count:.3f} s, {wire / count:.0f} bytes on the"
            f" wire; the launch and generation 0: {first['seconds']} s, {first['wire_bytes']} bytes"
        )

    def reference_sleep(self) -> None:
        self.make_reference("sleep")

    def lost_worker(self, fault: str, rank: int = 2, per_host: int = 1) -> None:
        """Rank `rank` meets `fault` in generation 2; the run must not notice. Every rank on its
        host is lost with it (hydra's proxy there ends them)."""
        out = self.fresh(f"{fault}-{rank}-of-{per_host}")
        threads = "2" if per_host == 1 else "1"
        args = ["evolve", *self.config("sleep"), "--threads", threads, "--quiet"]
        report = self.multihost(
            3, out, [*args, "--mpi-timeout", "3"], "--ranks-per-host", str(per_host),
            "--fault", fault, "--fault-rank", str(rank), "--fault-at-generation", "2",
            hydra=["-disable-auto-cleanup"],
        )  # fmt: skip
        if not report.get("fault") or "error" in report["fault"]:
            raise Failure(f"the fault was not injected: {report.get('fault')}")
        host = rank // per_host
        for lost in range(host * per_host, (host + 1) * per_host):
            said = re.search(
                rf"MPI worker {lost} on h{host} lost \(.*\); the (\d+) evaluation", self.output
            )
            if not said:
                raise Failure(f"the master did not say that it lost worker {lost}")
            if lost == rank and int(said.group(1)) == 0:
                raise Failure(f"worker {rank} held no evaluation when lost: none was reassigned")
        if report["exit"] != 0:
            raise Failure(f"mpiexec exited with {report['exit']}")
        self.expect_identical("sleep", out)

    def worker_killed(self) -> None:
        self.lost_worker("kill")

    def worker_stopped(self) -> None:
        self.lost_worker("stop")

    def link_down(self) -> None:
        self.lost_worker("link")

    def node_lost(self) -> None:
        self.lost_worker("kill", rank=4, per_host=2)

    def master_killed(self) -> None:
        out = self.fresh("master-killed")
        args = ["evolve", *self.config("sleep"), "--threads", "2", "--quiet", "--mpi-timeout", "3"]
        report = self.multihost(
            3,
            out,
            args,
            "--fault",
            "kill",
            "--fault-rank",
            "0",
            "--fault-at-generation",
            "2",
            hydra=["-disable-auto-cleanup"],
        )
        if report["exit"] == 0:
            raise Failure("mpiexec reported success although the master was killed")
        done = len((out / "generations.csv").read_text().splitlines()) - 1
        if not 1 <= done < 5:
            raise Failure(f"{done} generations done before the master was killed")
        resume = ["evolve", "--plugin", str(self.plugin), "--resume", str(out)]
        report = self.multihost(2, out, [*resume, "--threads", "2", "--quiet"], new_out=False)
        if report["exit"] != 0:
            raise Failure(f"the resumed run exited with {report['exit']}")
        self.expect_identical("sleep", out)

    def slurm(self) -> None:
        out = self.fresh("slurm")
        report = out.with_suffix(".json")
        command = [
            sys.executable, str(SOURCE / "scripts" / "multihost"), "--hosts", "3", "--slurm",
            "--watch", str(out), "--report", str(report), "--fault", "kill", "--fault-rank", "0",
            "--", "bash", str(SOURCE / "examples" / "slurm" / "gpfd-evolve.sbatch"),
        ]  # fmt: skip
        environment = dict(
            os.environ,
            GPFD=str(self.gpfd),
            GPFD_ARGS=f"--plugin {self.plugin}",
            CONFIG=str(DATA / "multihost-sleep.toml"),
            OUT=str(out),
            MPI_TIMEOUT="3",
        )
        result = subprocess.run(command, capture_output=True, text=True, env=environment)
        print(result.stdout + result.stderr)
        if result.returncode == SKIP:
            raise SystemExit(SKIP)
        if "attempt 1 ended" not in result.stderr:
            raise Failure("the batch script did not start the run again")
        if json.loads(report.read_text())["exit"] != 0:
            raise Failure(f"the batch script exited with {result.returncode}")
        self.expect_identical("sleep", out)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gpfd", type=Path, required=True)
    parser.add_argument("--plugin", type=Path, required=True, help="libgpfd_test_plugin.so")
    parser.add_argument("--tmp", type=Path, required=True)
    parser.add_argument("scenario")
    args = parser.parse_args()
    args.tmp.mkdir(parents=True, exist_ok=True)
    scenarios = Scenarios(args.gpfd.resolve(), args.plugin.resolve(), args.tmp.resolve())
    run = getattr(scenarios, args.scenario.replace("-", "_"), None)
    if run is None or args.scenario.startswith("_"):
        print(f"unknown scenario {args.scenario}", file=sys.stderr)
        return 2
    try:
        run()
    except Failure as failure:
        print(f"FAILED: {failure}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
