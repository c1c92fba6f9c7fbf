"""examples/python/quickstart.py runs end to end (CI runs it here)."""

import subprocess
import sys


def test_quickstart_runs(repo, tmp_path):
    result = subprocess.run(
        [sys.executable, str(repo / "examples/python/quickstart.py")],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    assert "gen   5" in result.stdout
    assert "wrapped CartPole-v1" in result.stdout
    assert "REINFORCE on the features: mean return" in result.stdout
    assert (tmp_path / "results/cartpole-quick/best.features").is_file()
