"""docs/results keeps each study's table beside the per-run rows it was made from (issue 54): every
count, mean and verdict figure of a table is computed again here from its rows, so that a table
cannot lose (or gain) a row unseen. Suite labels: summary.csv against LABEL/runs.csv, and
summary.md against summary.csv. Reproduce outputs: the report's method-level summary and
docs/results/README.md's tables against fig*/method-*.csv (scripts/method-table), and runs.csv
against the same runs."""

import csv
import re
import statistics
import subprocess
import sys

import pytest

from conftest import REPO, script_module

RESULTS = REPO / "docs/results"
SUITE_LABELS = sorted(
    p.parent for p in RESULTS.rglob("summary.csv") if (p.parent / "runs.csv").exists()
)
REPRODUCE = sorted({p.parent.parent for p in RESULTS.rglob("method-*.csv")})
RUN_SETS = sorted(
    p.parent for p in RESULTS.rglob("sets.csv") if (p.parent / "verdict.txt").exists()
)
# scripts/zoo-check's outputs: summary.csv and README-table.md beside the scores.csv they came from.
ZOO_CHECKS = sorted(
    p.parent for p in (RESULTS / "zoo").rglob("summary.csv") if (p.parent / "scores.csv").exists()
)


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def mean(rows, key):
    values = [float(r[key]) for r in rows if r.get(key)]
    return f"{sum(values) / len(values):.4g}" if values else ""


def span(values):
    values = [int(v) for v in values if v != ""]
    if not values:
        return ""
    return str(min(values)) if min(values) == max(values) else f"{min(values)}-{max(values)}"


def md_table(text, heading=None):
    """The rows (lists of cells) of the first Markdown table after heading (or in text)."""
    if heading is not None:
        text = text[text.index(heading) :]
    lines = text[text.index("\n|") + 1 :].splitlines()
    rows = []
    for line in lines:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    return rows[2:]


def test_every_study_with_rows_is_found():
    assert len(SUITE_LABELS) >= 60
    assert {p.relative_to(RESULTS).as_posix() for p in REPRODUCE} >= {
        "robust-quick/new",
        "robust-quick/old",
        "paper-runs",
        "halving/bench/fig1",
    }


@pytest.mark.parametrize("label", SUITE_LABELS, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_suite_summary_is_its_rows(label):
    runs = read(label / "runs.csv")
    summary = read(label / "summary.csv")
    tasks = {r["task"] for r in summary if r["runs"] != "0"}
    assert {r["task"] for r in runs} == tasks, "runs.csv and summary.csv name other tasks"
    for row in summary:
        if row["runs"] == "0":  # refused: no runs
            continue
        mine = [r for r in runs if r["task"] == row["task"]]
        assert sorted(int(r["run"]) for r in mine) == list(range(1, len(mine) + 1))
        expected = {
            "runs": str(len(mine)),
            "discovered": str(sum(r["returned"] == "discovered" for r in mine)),
            "mean_original": mean(mine, "original_mean"),
            "mean_no_learning": mean(mine, "no_learning_mean"),
            "mean_reported": mean(mine, "reported_mean"),
        }
        if "carrying" in row:  # the planted suite's check
            expected["carrying"] = str(sum(int(r["carries"]) for r in mine))
            if row["winners_carrying"] != "":
                expected["winners_carrying"] = str(sum(r["winner_carries"] == "1" for r in mine))
        if "population" in row:  # the gymnasium suite: the sizes the budget chose
            expected["population"] = span(r["population"] for r in mine)
            expected["generations"] = span(r["generations"] for r in mine)
        assert {k: row[k] for k in expected} == expected, row["task"]
        assert all(r["expressions"] for r in mine), "a run without its returned features"
        p = re.search(r"over runs p = (\S+)\)", row["verdict"])
        assert row["wilcoxon_p"] == (p.group(1) if p else "")


@pytest.mark.parametrize("label", SUITE_LABELS, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_suite_table_shows_its_summary(label):
    summary = {r["task"]: r for r in read(label / "summary.csv")}
    table = md_table((label / "summary.md").read_text())
    assert [cells[0] for cells in table] == list(summary)
    for cells in table:
        row = summary[cells[0]]
        if row["runs"] == "0":
            continue
        # The last columns: discoveries, p, the three means, (the sizes,) the wall time.
        k = 2 if "population" in row else 1
        assert cells[-(k + 5)] == f"{row['discovered']} / {row['runs']}"
        means = [row[m] for m in ("mean_original", "mean_no_learning", "mean_reported")]
        assert cells[-(k + 4) : -k] == [row["wilcoxon_p"], *means]
        if "population" in row:
            assert cells[-2] == f"{row['population']} x {row['generations']}"
        if "carrying" in row:
            assert cells[2] == f"{row['carrying']} / {row['runs']}"
        assert cells[-1] == row["wall_s"]


@pytest.mark.parametrize("top", REPRODUCE, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_report_method_summary_is_its_rows(top):
    table = script_module("method-table").table(top)
    report = (top / "report.md").read_text()
    if "## Method-level summary" not in report:  # one run per benchmark: no method table
        return
    shown = md_table(report, "## Method-level summary")
    assert [cells[0] for cells in shown] == list(table)
    columns = ["runs", "original (final)", "median change", "better / worse", "Wilcoxon p"]
    columns += ["area: median change", "area: Wilcoxon p"]
    for cells in shown:
        assert cells[1:8] == [table[cells[0]][k] for k in columns], cells[0]


@pytest.mark.parametrize("top", REPRODUCE, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_reproduce_output_keeps_a_row_per_run(top):
    runs = read(top / "runs.csv")
    for method in sorted(top.glob("fig*/method-*.csv")):
        name = method.stem.removeprefix("method-")
        assessed = [r for r in read(method) if r["run"].isdigit()]
        mine = [r for r in runs if r["benchmark"] == name and r["run"] != ""]
        if not mine:  # single-run reproductions: evolve-NAME itself
            mine = [r for r in runs if r["benchmark"] == name]
        assert [(r["run"] or "1", r["seed"]) for r in mine] == [
            (r["run"], r["seed"]) for r in assessed
        ], name
        assert all(r["expressions"] for r in mine)


@pytest.mark.parametrize("top", RUN_SETS, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_run_set_verdict_is_its_rows(top):
    # user-envs: `gpfd evolve --runs 8`'s runs.csv, the sets it returned, and its verdict line.
    runs, sets = read(top / "runs.csv"), read(top / "sets.csv")
    assert [(r["run"], r["seed"]) for r in sets] == [(r["run"], r["seed"]) for r in runs]
    assert all(r["expressions"] for r in sets)
    verdict = next(
        line for line in (top / "verdict.txt").read_text().splitlines() if " runs: " in line
    )
    beat = [r for r in runs if r["returned"] == "discovered" and float(r["difference"]) > 0]
    significant = [r for r in beat if float(r["p_vs_original"]) < 0.05]
    assert verdict.startswith(f"{len(runs)} runs: ")
    assert f"on confirmation in {len(beat)} ({len(significant)} with p < 0.05)" in verdict


# docs/results/README.md's two tables: each row's benchmark, its reproduce output and method file.
README_ROWS = {
    "cart-pole (50 PG updates)": ("robust-quick/new", "cartpole-quick"),
    "swimmer, 5 segments (200 updates)": ("robust-quick/new", "swimmer5-quick"),
    "swimmer, 3 segments (300 updates)": ("robust-quick/new", "swimmer3-quick"),
    "Acrobot (300 updates)": ("robust-quick/new", "acrobot-quick"),
    "Tetris 12x8, + the 18 variables (15 x 50 games)": ("robust-quick/new", "tetris-quick"),
    "swimmer, 5 segments": ("paper-runs", "swimmer5"),
    "swimmer, 3 segments": ("paper-runs", "swimmer3"),
    "Acrobot": ("paper-runs", "acrobot"),
    "cart-pole, final level": ("paper-runs", "cartpole"),
    "Tetris 12x8, + the 18 variables": ("paper-runs", "tetris"),
}


def plain(cell):
    return cell.replace("**", "").split(" (")[0]


def test_the_results_readme_tables_are_the_rows():
    readme = (RESULTS / "README.md").read_text()
    method_table = script_module("method-table")
    tables = {
        "robust-quick/new": method_table.table(
            RESULTS / "robust-quick/new", RESULTS / "robust-quick/old"
        ),
        "paper-runs": method_table.table(RESULTS / "paper-runs"),
    }
    shown = md_table(readme, "### Quick scale") + md_table(readme, "### Paper scale")
    seen = set()
    for cells in shown:
        if cells[0] not in README_ROWS:
            assert cells[0] == "cart-pole, mean over the learning curve"
            row = tables["paper-runs"]["cartpole"]
            assert plain(cells[3]) == row["area: median change"]
            assert plain(cells[4]) == row["area: better / worse"]
            assert plain(cells[5]) == row["area: Wilcoxon p"]
            continue
        top, name = README_ROWS[cells[0]]
        seen.add(cells[0])
        row = tables[top][name]
        assert cells[1] == row["original (final)"], cells[0]
        assert cells[2] == row["discovered returned"], cells[0]
        change = row["median change"].split(" (")[-1].rstrip(")")
        assert plain(cells[3]) in (change.replace("+0.0%", "0%"), change), cells[0]
        assert plain(cells[4]) == row["better / worse"], cells[0]
        assert plain(cells[5]) == row["Wilcoxon p"], cells[0]
        if top == "robust-quick/new":
            baseline = row["baseline: median change"].split(" (")[-1].rstrip(")")
            assert cells[6].replace("**", "") == f"{baseline}, {row['baseline: better / worse']}"
    assert seen == set(README_ROWS)


def zoo_rows(top):
    """summary.csv's rows with their numbers as scripts/zoo-check's summarise gives them."""
    rows = read(top / "summary.csv")
    for r in rows:
        for key in ("mean", "sd", "fraction"):
            r[key] = float(r[key])
        r["wilcoxon_p"] = float(r["wilcoxon_p"]) if r["wilcoxon_p"] else ""
        for key in ("above_raw", "below_raw", "seeds", "steps", "zoo_steps"):
            r[key] = int(r[key]) if r[key] else ""
        r["first_seed"] = int(r.get("first_seed") or 1)  # A column only where it is not 1.
    return rows


def test_every_zoo_check_is_found():
    assert {p.relative_to(RESULTS).as_posix() for p in ZOO_CHECKS} >= {"zoo"}


@pytest.mark.parametrize("top", ZOO_CHECKS, ids=lambda p: p.relative_to(RESULTS).as_posix())
def test_a_zoo_summary_is_its_scores(top):
    """Every row's mean, sd, paired Wilcoxon p and counts, computed again from scores.csv (the
    training seeds 1..N at the row's steps, or first_seed on where the row says; the last score of
    a key, as the script reads them),
    and README-table.md as the script writes it from those rows."""
    zoo = script_module("zoo-check")
    scores = zoo.read_scores(top / "scores.csv")
    rows = zoo_rows(top)
    assert rows
    for r in rows:
        first = r["first_seed"]
        seeds = range(first, first + r["seeds"])
        values = [scores[(r["task"], r["observation"], s, r["steps"])] for s in seeds]
        raw = [scores[(r["task"], "raw", s, r["steps"])] for s in seeds]
        where = f"{r['task']} {r['configuration']}"
        assert r["mean"] == pytest.approx(statistics.mean(values), rel=1e-12), where
        assert r["sd"] == pytest.approx(statistics.stdev(values), rel=1e-12, abs=1e-12), where
        if r["configuration"] == "raw":
            assert r["observation"] == "raw"
            continue
        p, above, below = zoo.paired(values, raw)
        assert r["wilcoxon_p"] == pytest.approx(p, rel=1e-12), where
        assert (r["above_raw"], r["below_raw"]) == (above, below), where
    table = (top / "README-table.md").read_text()
    header = table.splitlines()[0]
    learner = "gpfd" if "--learner gpfd" in header else "sb3-contrib"
    assert zoo.markdown(rows, header, learner) == table


def test_a_suite_summary_regenerates_from_its_rows(tmp_path):
    # The cheapest table's regeneration command, run: the planted suite's parsimony label.
    label = tmp_path / "parsimony"
    label.mkdir()
    for name in ("runs.csv", "summary.csv"):
        (label / name).write_bytes((RESULTS / "planted/parsimony" / name).read_bytes())
    done = subprocess.run(
        [sys.executable, str(REPO / "scripts/planted-suite"), "--from-files"]
        + ["--out", str(tmp_path), "--label", "parsimony"],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    for name in ("summary.csv", "summary.md"):
        assert (label / name).read_bytes() == (RESULTS / "planted/parsimony" / name).read_bytes()
    # A row dropped from runs.csv changes the table.
    lines = (label / "runs.csv").read_text().splitlines(keepends=True)
    (label / "runs.csv").write_text("".join(lines[:1] + lines[2:]))
    subprocess.run(
        [sys.executable, str(REPO / "scripts/planted-suite"), "--from-files"]
        + ["--out", str(tmp_path), "--label", "parsimony"],
        check=True,
        capture_output=True,
    )
    assert "| 7 / 7 |" in (label / "summary.md").read_text()


def test_no_results_directory_keeps_run_directories():
    runs = [p for p in RESULTS.rglob("run-[0-9]*") if p.is_dir()]
    assert runs == []
    assert not list(RESULTS.rglob("checkpoint.json"))


def test_results_stay_small():
    files = [p for p in RESULTS.rglob("*") if p.is_file()]
    assert len(files) < 500
    assert sum(p.stat().st_size for p in files) < 10 * 2**20
