"""gpfd.evolve(env=..., threads=2) where the workers could never re-run the user's code: a script
without ``if __name__ == "__main__":``, the same code piped to ``python -``, and a Jupyter
notebook whose cell defines the environment. Each works, at once, and leaves only its own results
directory (the 60 s timeouts guard against a hang; they time nothing)."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

from test_user_env_workers import SMALL, TINY_SOURCE

CODE = (
    TINY_SOURCE
    + """
run = gpfd.evolve(env=Tiny, threads=2, seed=1, population=4, generations=1, set=SETTINGS)
print("finished", run.finished, run.dir, run.info["threads"])
"""
).replace("SETTINGS", repr(SMALL))


def check_results(directory: Path, output: str) -> None:
    """The run finished in results/Tiny, the only directory made, with 2 workers recorded."""
    assert "finished True results/Tiny 2" in output
    assert sorted(p.name for p in directory.iterdir()) == ["results"]
    assert [p.name for p in (directory / "results").iterdir()] == ["Tiny"]
    assert json.loads((directory / "results/Tiny/run.json").read_text())["threads"] == 2


@pytest.mark.parametrize("how", ["script", "stdin"])
def test_an_unguarded_script_and_stdin_work(tmp_path, how):
    script = tmp_path / "unguarded.py"
    script.write_text(CODE)
    command = [sys.executable, str(script)] if how == "script" else [sys.executable, "-"]
    done = subprocess.run(
        command,
        input=CODE if how == "stdin" else None,
        capture_output=True,
        text=True,
        timeout=60,
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    script.unlink()
    check_results(tmp_path, done.stdout)
    assert "Traceback" not in done.stderr


def test_a_notebook_that_defines_its_environment_works(tmp_path):
    import nbclient  # The test extra's: nbclient, ipykernel (a real kernel).
    import nbformat

    notebook = nbformat.v4.new_notebook()
    notebook.cells.append(nbformat.v4.new_code_cell(CODE))
    client = nbclient.NotebookClient(
        notebook,
        timeout=60,
        startup_timeout=60,
        kernel_name="python3",
        resources={"metadata": {"path": str(tmp_path)}},
    )
    client.execute()
    outputs = notebook.cells[0].outputs
    text = "".join(o.get("text", "") for o in outputs if o.get("name") == "stdout")
    check_results(tmp_path, text)
