"""The per-run rows that docs/results keeps in place of run directories (docs/results/README.md).

A suite label (scripts/planted-suite, scripts/gymnasium-suite) keeps LABEL/runs.csv: one row per
GP run of every task, gpfd's runs.csv columns with the task in front and what the suite added
(the returned and validation-winner expressions, the planted check, the sizes). A `gpfd
reproduce` output keeps DIR/runs.csv (one row per GP run: seed, revision, returned expressions,
verdict, GP and validation costs) and DIR/assessments.csv (every assessment's summary.csv rows),
beside its own fig*/method-*.csv. A set of runs (`gpfd evolve --runs N`: runs.csv beside run-NN/)
keeps gpfd's runs.csv and sets.csv: per run, its revision, the returned set's header (its scores
and verdict) and expressions, and the validation winner's."""

import csv
import json
import re
import shutil
import sys
import tarfile
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # CPython 3.10: tomli, a dependency of gpfd there
    import tomli as tomllib


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write_csv(path, rows, first=()):
    """rows to path; the columns are the union of the rows' keys in order of appearance, those
    in first in front. Nothing is written for no rows."""
    if not rows:
        return
    fields = list(first)
    for row in rows:
        fields += [k for k in row if k not in fields]
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, restval="")
        writer.writeheader()
        writer.writerows(rows)


def expressions(features_text):
    """The expressions of a best.features text, ' ; '-joined (comments left out)."""
    lines = [line for line in features_text.splitlines() if line and not line.startswith("#")]
    return " ; ".join(lines)


def header(features_text, key):
    """A '# key: value' line's value of a best.features text ('' without one)."""
    found = re.search(rf"^# {re.escape(key)}: (.*)$", features_text, re.M)
    return found.group(1) if found else ""


def winner_expressions(run_dir):
    """The expressions of a run's validation winner (the set confirmation.csv confirmed, else
    rank 1 of validation.csv; 'original' for the original variables); '' without validation."""
    path = run_dir / "validation.csv"
    if not path.is_file():
        return ""
    first = next((r for r in read_csv(path) if r["rank"] == "1"), None)
    if first is None:
        return ""
    confirmed = run_dir / "confirmation.csv"
    if confirmed.is_file() and (rows := read_csv(confirmed)):
        first = next((r for r in rows if r["set"] == "validation-winner"), None) or {
            "set": "original"
        }
    return "original" if first["set"] == "original" else first["expressions"]


def sizes(config_path):
    """The population and generations a run's config.toml says it ran (the budget's choice)."""
    gp = tomllib.loads(config_path.read_text()).get("gp", {})
    return {k: gp.get(k, "") for k in ("population", "generations")}


def run_number(text):
    """1 of '1', 'run-01'."""
    return int(str(text).removeprefix("run-"))


def suite_task_rows(task, task_dir):
    """One task of a suite label in the layout before compaction (TASK/runs.csv, carry.csv or
    sets.csv, where-lost.csv, run-NN/): its per-run rows, with the task in front."""
    rows = {run_number(r["run"]): {"task": task, **r} for r in read_csv(task_dir / "runs.csv")}
    for name, prefix in (("carry.csv", ""), ("sets.csv", ""), ("where-lost.csv", "where_lost_")):
        if (task_dir / name).is_file():
            for extra in read_csv(task_dir / name):
                row = rows[run_number(extra.pop("run"))]
                for k, v in extra.items():
                    key = prefix + k
                    if key in row and row[key] != v:
                        sys.exit(f"{task_dir / name}: run {extra}: {key} disagrees with runs.csv")
                    row[key] = v
    for number, row in rows.items():
        run = task_dir / f"run-{number:02d}"
        if (run / "best.features").is_file():
            row["expressions"] = expressions((run / "best.features").read_text())
        row["winner_expressions"] = winner_expressions(run)
        if (run / "config.toml").is_file():
            row.update({k: row.get(k, v) for k, v in sizes(run / "config.toml").items()})
    return list(rows.values())


def suite_label_rows(label_dir, task_of):
    """Every task's per-run rows of a suite label before compaction; task_of(dir name) is the
    task's id (the summary's first column)."""
    rows = []
    for task_dir in sorted(p for p in label_dir.iterdir() if (p / "runs.csv").is_file()):
        rows += suite_task_rows(task_of(task_dir.name), task_dir)
    return rows


def run_costs(run_dir):
    """A GP run's costs (generations.csv, checkpoint.json's validation, config.toml): what
    scripts/discovery-cost sums."""
    history = read_csv(run_dir / "generations.csv")
    state = json.loads((run_dir / "checkpoint.json").read_text()).get("validation", {})
    config = tomllib.loads((run_dir / "config.toml").read_text())
    return {
        "generations": len(history),
        "gp_seconds": repr(sum(float(r["seconds"]) for r in history)),
        "evaluations": sum(int(r["evaluations"]) for r in history),
        "reevaluations": sum(int(r.get("reevaluations") or 0) for r in history),
        "validation_seconds": repr(float(state.get("seconds", 0.0))),
        "confirmed_seeds": len(state.get("confirmation", {}).get("winner", [])),
        "confirm_seeds": config.get("validation", {}).get("confirm_seeds", 0),
        "fitness_trials": config["fitness"]["trials"],
    }


def reproduce_run_rows(top):
    """One row per GP run of a `gpfd reproduce` output (FIG/evolve-NAME/run-NN, or FIG/evolve-NAME
    itself for a single run)."""
    rows = []
    for evolve in sorted(Path(top).glob("fig*/evolve-*")):
        runs = sorted(p for p in evolve.glob("run-*") if (p / "generations.csv").is_file())
        if not runs and (evolve / "generations.csv").is_file():
            runs = [evolve]
        for run in runs:
            features = (run / "best.features").read_text()
            info = (
                json.loads((run / "run.json").read_text()) if (run / "run.json").is_file() else {}
            )
            rows.append(
                {
                    "figure": evolve.parent.name,
                    "benchmark": evolve.name.removeprefix("evolve-"),
                    "run": run_number(run.name) if run != evolve else "",
                    "seed": str(info.get("seed", header(features, "seed"))),
                    "revision": info.get("revision", ""),
                    **run_costs(run),
                    "fitness": header(features, "fitness"),
                    "validated": header(features, "validated"),
                    "validated_by": header(features, "validated_by"),
                    "verdict": header(features, "verdict"),
                    "expressions": expressions(features),
                }
            )
    return rows


def assessment_rows(top):
    """Every assessment's summary.csv rows of a `gpfd reproduce` output, its figure and name in
    front."""
    rows = []
    for summary in sorted(Path(top).glob("fig*/assess-*/summary.csv")):
        figure, name = summary.parent.parent.name, summary.parent.name.removeprefix("assess-")
        rows += [{"figure": figure, "assessment": name, **r} for r in read_csv(summary)]
    return rows


def run_set_rows(top):
    """One row per run of a `gpfd evolve --runs N` output (runs.csv beside run-NN/): what
    runs.csv does not hold of each run's files."""
    rows = []
    for r in read_csv(Path(top) / "runs.csv"):
        run = Path(top) / f"run-{int(r['run']):02d}"
        features = (run / "best.features").read_text()
        info = json.loads((run / "run.json").read_text()) if (run / "run.json").is_file() else {}
        rows.append(
            {
                "run": r["run"],
                "seed": r["seed"],
                "revision": info.get("revision", ""),
                **headers(features),
                "expressions": expressions(features),
                "winner_expressions": winner_expressions(run),
            }
        )
    return rows


def headers(features_text):
    """Every '# key: value' line of a best.features text but the format's own (env, variables,
    format, seed): its scores, verdict and how they were measured, whatever gpfd version wrote
    it."""
    found = re.findall(r"^# ([a-z_]+): (.*)$", features_text, re.M)
    return {k: v for k, v in found if k not in ("env", "variables", "format", "seed")}


# What docs/results keeps of a reproduce output (beside runs.csv and assessments.csv), and what
# goes into its plots.tar.xz.
KEPT = ("report.md", "runs.csv", "assessments.csv", "fig*/method-*.csv", "fig3/jit/jit.csv")
KEPT += ("fig3/jit/jit_unary.csv", "fig3/jit/jit_summary.txt")
PLOTS = ("fig*/*.dat", "fig*/*.gp", "fig*/*/*.dat", "fig*/*/*.gp")


def keep_reproduce_output(top, dest):
    """Copies what docs/results keeps of the reproduce output top (its rows written first) into
    dest, with the plots' data and gnuplot scripts as dest/plots.tar.xz (scripts/results-plots
    draws them)."""
    top, dest = Path(top), Path(dest)
    for pattern in KEPT:
        for path in sorted(top.glob(pattern)):
            (dest / path.relative_to(top)).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, dest / path.relative_to(top))
    plots = sorted({p for pattern in PLOTS for p in top.glob(pattern)})
    with tarfile.open(dest / "plots.tar.xz", "w:xz", preset=9) as archive:
        for path in plots:
            info = archive.gettarinfo(path, arcname=path.relative_to(top).as_posix())
            info.mtime, info.uid, info.gid, info.uname, info.gname = 0, 0, 0, "", ""
            with open(path, "rb") as f:
                archive.addfile(info, f)
