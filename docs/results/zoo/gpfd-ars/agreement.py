#!/usr/bin/env python3
"""Does gpfd's ars, given the Zoo's settings (scripts/zoo-check --learner gpfd), train as
sb3-contrib's ARS does? Per row of a zoo-check judged by both (same task, sets, steps and
training seeds): both means and sds, and whether gpfd's mean lies within sb3-contrib's spread
(its mean +- 2 sd over the seeds, as scripts/ars-reference asks); per task, how many rows do.
Writes agreement.md beside this file from the pairs below; trains nothing.

    .venv/bin/python docs/results/zoo/gpfd-ars/agreement.py
"""

import csv
from pathlib import Path

HERE = Path(__file__).resolve().parent
ZOO = HERE.parent
# (sb3-contrib's study, gpfd's study of the same rows)
PAIRS = [
    ("default-budget", "gpfd-ars/check"),
    ("physics-4pct", "gpfd-ars/check-4pct"),
    ("pendulum-10pct", "gpfd-ars/check-10pct"),
]


def rows(study):
    path = ZOO / study / "summary.csv"
    with open(path, newline="") as f:
        return {(r["task"], r["configuration"]): r for r in csv.DictReader(f)}


def within(theirs, ours):
    return abs(float(ours["mean"]) - float(theirs["mean"])) <= 2 * float(theirs["sd"]) + 1e-9


def main():
    lines = [
        "Written by docs/results/zoo/gpfd-ars/agreement.py from the studies' summary.csv. "
        "Within: gpfd's mean within sb3-contrib's mean +- 2 sd over the same training seeds.",
        "",
        "| sb3-contrib's study | gpfd's | task | steps | rows within / rows | raw: sb3-contrib; "
        "gpfd | the largest difference (sb3-contrib; gpfd) |",
        "|---|---|---|---|---|---|---|",
    ]
    for sb3_study, gpfd_study in PAIRS:
        if not (ZOO / sb3_study / "summary.csv").is_file():
            continue
        theirs, ours = rows(sb3_study), rows(gpfd_study)
        tasks = dict.fromkeys(task for task, _ in theirs)
        for task in tasks:
            keys = [k for k in theirs if k[0] == task and k in ours]
            agree = [k for k in keys if within(theirs[k], ours[k])]
            raw = (task, "raw")
            gap = max(keys, key=lambda k: abs(float(ours[k]["mean"]) - float(theirs[k]["mean"])))
            largest = f"{gap[1]}: {float(theirs[gap]['mean']):.1f}; {float(ours[gap]['mean']):.1f}"
            lines.append(
                f"| {sb3_study} | {gpfd_study} | {task} | {theirs[raw]['steps']} | "
                f"{len(agree)} / {len(keys)} | {float(theirs[raw]['mean']):.1f} +- "
                f"{float(theirs[raw]['sd']):.1f}; {float(ours[raw]['mean']):.1f} +- "
                f"{float(ours[raw]['sd']):.1f} | {largest} |"
            )
    (HERE / "agreement.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
