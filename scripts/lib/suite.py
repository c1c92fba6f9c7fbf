"""What the result suites (scripts/planted-suite, scripts/gymnasium-suite) share: one task's N GP
runs through gpfd.evolve with its verbose output kept word for word, the per-run files kept
beside it, and gpfd's method-level verdict read back from what it printed."""

import contextlib
import csv
import io
import re
import shutil
import sys
import time

import gpfd

# Each run's files kept in the results (the GP's own directories stay in the work directory).
KEPT = ("best.features", "config.toml", "run.json", "validation.csv", "confirmation.csv")


class Tee(io.TextIOBase):
    """Writes to several streams (the terminal and the log)."""

    def __init__(self, *streams):
        self.streams = streams

    def write(self, text):
        for s in self.streams:
            s.write(text)
            s.flush()
        return len(text)


def parse_set(values, program):
    """--set key=value items as a dict; a malformed one stops the program, naming it."""
    settings = {}
    for item in values:
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"{program}: --set {item!r} is not key=value")
        settings[key] = value
    return settings


def run_task(env, args, settings, dest, work):
    """gpfd.evolve(env=env, runs=args.runs) into work, verbose; copies log.txt, runs.csv and each
    run's KEPT files into dest, with wall.txt. Returns read_task(dest)."""
    log = io.StringIO()
    start = time.monotonic()
    with contextlib.redirect_stdout(Tee(sys.stdout, log)):
        gpfd.evolve(
            env=env,
            seed=args.seed,
            threads=args.threads,
            runs=args.runs,
            out=work,
            force=True,
            verbose=True,
            set=[f"{k}={v}" for k, v in settings.items()] or None,
        )
    wall = time.monotonic() - start
    dest.mkdir(parents=True, exist_ok=True)
    (dest / "log.txt").write_text(log.getvalue())
    (dest / "wall.txt").write_text(f"{wall:.1f}\n")
    shutil.copy(work / "runs.csv", dest / "runs.csv")
    for r in range(1, args.runs + 1):
        name = f"run-{r:02d}"
        (dest / name).mkdir(exist_ok=True)
        for file in KEPT:
            if (work / name / file).is_file():
                shutil.copy(work / name / file, dest / name / file)
    return read_task(dest)


def read_task(dest):
    """(runs.csv's rows, the summary's common fields) of a task's kept files in dest: runs.csv,
    log.txt (gpfd's verdict line), wall.txt (absent: no wall time)."""
    with open(dest / "runs.csv", newline="") as f:
        runs = list(csv.DictReader(f))
    log = (dest / "log.txt").read_text()
    verdict = [line for line in log.splitlines() if re.match(r"\d+ runs: ", line)]
    p = re.search(r"Wilcoxon signed-rank over runs p = (\S+)\)", verdict[0]) if verdict else None
    wall = dest / "wall.txt"
    return runs, {
        "runs": len(runs),
        "discovered": sum(r["returned"] == "discovered" for r in runs),
        "wilcoxon_p": p.group(1) if p else "",
        "mean_original": mean(runs, "original_mean"),
        "mean_no_learning": mean(runs, "no_learning_mean"),
        "mean_reported": mean(runs, "reported_mean"),
        "wall_s": wall.read_text().strip() if wall.is_file() else "",
        "verdict": verdict[0] if verdict else "(no verdict printed)",
    }


def mean(rows, key):
    values = [float(r[key]) for r in rows if r.get(key)]
    return f"{sum(values) / len(values):.4g}" if values else ""


def merge_summary(path, rows, fields, order):
    """Writes rows to the summary CSV at path, keeping the rows of tasks this command did not run;
    sorted by order(row). Returns all rows."""
    if path.is_file():
        with open(path, newline="") as f:
            done = {row["task"] for row in rows}
            rows = [r for r in csv.DictReader(f) if r["task"] not in done] + rows
    rows.sort(key=order)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, restval="")
        writer.writeheader()
        writer.writerows(rows)
    return rows
