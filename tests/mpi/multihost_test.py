#!/usr/bin/env python3
"""`gpfd evolve` across hosts: the ctest tests labelled `multihost` (cmake/mpi.cmake).

    tests/mpi/multihost_test.py --gpfd GPFD --tmp DIR SCENARIO

Each scenario runs gpfd under scripts/multihost (network namespaces on a private bridge,
mpiexec across them, every message on the wire) and compares every file the run writes with
a threads-only run of the same config and seed, byte for byte but wall-clock times; run.json
may differ only in `mpi_processes`. The reference runs are the fixture scenarios
`reference-*`. Exits 77 (ctest: skipped) where namespaces cannot be made (not root).

Scenarios:
  reference-cartpole  gpfd evolve multihost-cartpole.toml --threads 2 (no MPI)
  identical           the same on 3 hosts (master + 2 workers with 2 threads each): identical
                      files; prints the time and the bytes on the wire per generation
"""

import argparse
import importlib.machinery
import json
import os
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


def compare_outputs():
    """scripts/compare-outputs as a module: its comparison of two results directories."""
    path = str(SOURCE / "scripts" / "compare-outputs")
    return importlib.machinery.SourceFileLoader("compare_outputs", path).load_module()


def differences(reference: Path, run: Path) -> list[str]:
    """Files that differ beyond timings; run.json may differ in mpi_processes only."""
    found = compare_outputs().compare(reference, run)
    if "differs: run.json" in found:

        def setup_free(path: Path) -> dict:
            data = json.loads(path.read_text())
            for key in ("seconds", "revision", "mpi_processes"):
                data.pop(key, None)
            return data

        if setup_free(reference / "run.json") == setup_free(run / "run.json"):
            found.remove("differs: run.json")
    return found


class Scenarios:
    def __init__(self, gpfd: Path, tmp: Path):
        self.gpfd, self.tmp = gpfd, tmp

    def fresh(self, name: str) -> Path:
        path = self.tmp / name
        shutil.rmtree(path, ignore_errors=True)
        return path

    def gpfd_run(self, args: list[str]) -> subprocess.CompletedProcess:
        return subprocess.run([str(self.gpfd), *args], capture_output=True, text=True)

    def multihost(self, hosts: int, out: Path, args: list[str], *options: str) -> dict:
        """`gpfd ARGS` on `hosts` hosts under scripts/multihost; its report."""
        report = out.with_suffix(".json")
        command = [
            sys.executable, str(SOURCE / "scripts" / "multihost"), "--hosts", str(hosts),
            "--watch", str(out), "--report", str(report), *options, "--",
            str(self.gpfd), *args, "--out", str(out),
        ]  # fmt: skip
        result = subprocess.run(command, capture_output=True, text=True)
        print(result.stdout + result.stderr)
        if result.returncode == SKIP:
            raise SystemExit(SKIP)
        return json.loads(report.read_text())

    def reference(self, config: str) -> Path:
        return self.tmp / f"reference-{config}"

    def make_reference(self, config: str, *extra: str) -> None:
        out = self.fresh(f"reference-{config}")
        toml = str(DATA / f"multihost-{config}.toml")
        result = self.gpfd_run(["evolve", toml, *extra, "--threads", "2", "--quiet", "--out",
                                str(out)])  # fmt: skip
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
        toml = str(DATA / "multihost-cartpole.toml")
        report = self.multihost(3, out, ["evolve", toml, "--threads", "2", "--quiet"])
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


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gpfd", type=Path, required=True)
    parser.add_argument("--tmp", type=Path, required=True)
    parser.add_argument("scenario")
    args = parser.parse_args()
    args.tmp.mkdir(parents=True, exist_ok=True)
    scenarios = Scenarios(args.gpfd.resolve(), args.tmp.resolve())
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
