"""Prints one pip constraints file: the pins of BASE, with those of OVERRIDE in place of BASE's
pins of the same packages (names compared as pip compares them), e.g. constraints/ci.txt with the
lower bounds of constraints/oldest.txt.
    python3 scripts/lib/merge_pins.py BASE OVERRIDE > merged.txt"""

import re
import sys
from pathlib import Path


def pins(path: str) -> dict[str, str]:
    """Each requirement line of a constraints file by its normalised package name."""
    found = {}
    for number, line in enumerate(Path(path).read_text().splitlines(), 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        name = re.match(r"[A-Za-z0-9][A-Za-z0-9._-]*", text)
        if name is None:
            sys.exit(f"merge_pins: no package name in {path}:{number}: {line!r}")
        found[re.sub(r"[-_.]+", "-", name.group(0)).lower()] = text
    return found


def main() -> None:
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    merged = pins(sys.argv[1]) | pins(sys.argv[2])
    print("\n".join(merged[name] for name in sorted(merged)))


if __name__ == "__main__":
    main()
