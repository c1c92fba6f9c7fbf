"""What scripts/compare-outputs and scripts/compare-python-outputs share: two directories of
outputs compared file by file, byte for byte but timings (wall-clock seconds, durations and ETAs
in printed text, the revision a binary names; images are left out)."""

import json
import re
from pathlib import Path

# A revision as gpfd names it: 12 hex digits (then -dirty), or "unknown" outside a git checkout
# (a wheel built from an sdist).
REVISION = re.compile(r"\b(?:[0-9a-f]{12}(?:-dirty)?|unknown)\b")
DURATION = re.compile(r"\b\d+(\.\d+)?( ?s\b| s\b|m\d+s\b|h\d+m\b| min\b| seconds\b)")


def timeless(text: str) -> str:
    """Printed text without revisions, ETAs and durations."""
    text = REVISION.sub("REV", text)
    text = re.sub(r"ETA \S+", "ETA", text)
    return DURATION.sub("T", text)


def without_timings(path: Path) -> str:
    text = path.read_text(errors="replace")
    if path.name == "generations.csv":
        rows = [line.split(",") for line in text.splitlines()]
        column = rows[0].index("seconds") if rows and "seconds" in rows[0] else None
        if column is not None:
            for row in rows:
                if len(row) > column:
                    row[column] = "-"
        return "\n".join(",".join(row) for row in rows)
    if path.suffix == ".json":

        def strip(value):
            if isinstance(value, dict):
                return {k: strip(v) for k, v in value.items() if k not in ("seconds", "revision")}
            if isinstance(value, list):
                return [strip(v) for v in value]
            return timeless(value) if isinstance(value, str) else value  # A report's prose.

        try:
            return json.dumps(strip(json.loads(text)), sort_keys=True)
        except json.JSONDecodeError:
            pass
    return timeless(text)


def compare(old: Path, new: Path) -> list[str]:
    def files(root: Path) -> set[Path]:
        return {p.relative_to(root) for p in root.rglob("*") if p.is_file()}

    differ = []
    for relative in sorted(files(old) | files(new)):
        if relative.name in ("seconds.txt", ".gpfd.lock") or relative.suffix in (".png", ".svg"):
            continue
        a, b = old / relative, new / relative
        if not a.is_file() or not b.is_file():
            differ.append(f"only in {'new' if b.is_file() else 'old'}: {relative}")
        elif without_timings(a) != without_timings(b):
            differ.append(f"differs: {relative}")
    return differ
