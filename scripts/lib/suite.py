"""What the result suites (scripts/planted-suite, scripts/gymnasium-suite) share: one task's N GP
runs through gpfd.evolve with its verbose output shown, the runs' per-run rows kept in the
label's runs.csv (result_rows.py; the GP's own directories stay in the work directory), and
gpfd's method-level verdict read back from what it printed."""

import contextlib
import csv
import io
import re
import sys
import time

import result_rows

import gpfd


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


def run_task(env, args, settings, work):
    """gpfd.evolve(env=env, runs=args.runs) into work, verbose. Returns (the runs' rows, the
    task's facts: wall seconds and gpfd's verdict line)."""
    log = io.StringIO()
    start = time.monotonic()
    with contextlib.redirect_stdout(Tee(sys.stdout, log)):
        gpfd.evolve(
            env=env,
            config=getattr(args, "config", None),
            seed=args.seed,
            threads=args.threads,
            runs=args.runs,
            out=work,
            force=True,
            verbose=True,
            set=[f"{k}={v}" for k, v in settings.items()] or None,
        )
    wall = time.monotonic() - start
    verdict = [line for line in log.getvalue().splitlines() if re.match(r"\d+ runs: ", line)]
    facts = {"wall_s": f"{wall:.1f}", "verdict": verdict[0] if verdict else "(no verdict printed)"}
    return result_rows.suite_task_rows(env, work), facts


def task_rows(out, task):
    """A task's rows of the label's runs.csv (none without it)."""
    path = out / "runs.csv"
    return [r for r in result_rows.read_csv(path) if r["task"] == task] if path.is_file() else []


def recorded(out, task):
    """The task's row of the label's summary.csv: its facts as recorded (wall seconds, verdict,
    command); empty without one."""
    path = out / "summary.csv"
    rows = result_rows.read_csv(path) if path.is_file() else []
    return next((r for r in rows if r["task"] == task), {})


def keep_rows(out, task, rows):
    """Writes the task's rows into the label's runs.csv in place of its earlier ones (the other
    tasks' rows kept where they were; a new task's at the end)."""
    path = out / "runs.csv"
    kept = result_rows.read_csv(path) if path.is_file() else []
    at = next((i for i, r in enumerate(kept) if r["task"] == task), len(kept))
    others = [r for r in kept if r["task"] != task]
    out.mkdir(parents=True, exist_ok=True)
    result_rows.write_csv(path, others[:at] + rows + others[at:], first=("task", "run"))


def summarize(runs, facts):
    """The summary's common fields of a task's rows and facts (wall_s, verdict)."""
    p = re.search(r"Wilcoxon signed-rank over runs p = (\S+)\)", facts["verdict"])
    return {
        "runs": len(runs),
        "discovered": sum(r["returned"] == "discovered" for r in runs),
        "wilcoxon_p": p.group(1) if p else "",
        "mean_original": mean(runs, "original_mean"),
        "mean_no_learning": mean(runs, "no_learning_mean"),
        "mean_reported": mean(runs, "reported_mean"),
        "wall_s": facts.get("wall_s", ""),
        "verdict": facts["verdict"],
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
