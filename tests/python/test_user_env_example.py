"""examples/python/user_env.py (a Gymnasium class of the user's own) runs as its README says, on a
tiny budget: the original variables trained, the curve printed and written."""

import csv
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "python" / "user_env.py"


def test_the_user_env_example_trains_its_original_variables(tmp_path):
    out = tmp_path / "learn"
    done = subprocess.run(
        [sys.executable, str(EXAMPLE), "--learn", "--runs", "2", "--updates", "2"]
        + ["--threads", "1", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "policy gradient on the original variables (x, v), start anywhere, 2 runs" in done.stdout
    with open(out / "curves.csv", newline="") as f:
        updates = {int(row["update"]) for row in csv.DictReader(f) if row["set"] == "original"}
    assert updates == {0, 1, 2}
