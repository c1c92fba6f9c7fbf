"""What gpfd.evolve shows while it runs (gpfd.discovery.progress): a progress bar by default on a
terminal or in a notebook, only the verdict elsewhere, nothing with verbose=False, the command's
text with verbose=True. No test depends on timing: what is checked is drawn at fixed points (a
run's start, each generation, its end), never only by the half-second poll."""

import fcntl
import io
import os
import pty
import struct
import subprocess
import sys
import termios
import types
from typing import Any

import pytest

import gpfd
from conftest import QUICK
from gpfd.discovery import progress

TINY: dict[str, Any] = {"population": 8, "generations": 2, "set": QUICK, "seed": 2}


class Terminal(io.StringIO):
    """A text stream that says it is a terminal."""

    def isatty(self) -> bool:
        super().isatty()  # ValueError once closed, as a real stream
        return True


def test_the_bar_is_shown_only_by_default_on_a_terminal_or_in_a_notebook(monkeypatch):
    monkeypatch.setattr(sys, "stderr", Terminal())
    assert progress.shows_bar(None)
    assert not progress.shows_bar(False) and not progress.shows_bar(True)
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert not progress.shows_bar(None)
    closed = Terminal()
    closed.close()
    monkeypatch.setattr(sys, "stderr", closed)
    assert not progress.shows_bar(None)
    # A Jupyter kernel: its streams are not terminals, the bar is shown all the same.
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    shell = types.SimpleNamespace(config={"IPKernelApp": {}})
    monkeypatch.setitem(sys.modules, "ipykernel", types.ModuleType("ipykernel"))
    ipython = types.ModuleType("IPython")
    ipython.get_ipython = lambda: shell  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "IPython", ipython)
    assert progress.in_notebook() and progress.shows_bar(None)
    ipython.get_ipython = lambda: None  # type: ignore[attr-defined]
    assert not progress.in_notebook()


def test_without_a_terminal_only_the_verdict_is_printed(tmp_path, capfd):
    run = gpfd.evolve(**TINY, out=tmp_path / "run")  # pytest's streams are not terminals
    assert run.finished and run.best is not None
    out, err = capfd.readouterr()
    assert err == "" and out.count("\n") == 1, out
    # The verdict as best.features' meta holds it: the confirmed (or selection) score.
    assert out.startswith(
        ("confirmed: ", "not confirmed: ", "selection: ", "no discovered feature set")
    ), out
    assert f"{tmp_path / 'run'}/best.features" in out, out
    gpfd.evolve(**TINY, out=tmp_path / "quiet", verbose=False)
    assert capfd.readouterr() == ("", "")


def test_verbose_false_is_silent_on_a_terminal(tmp_path, capfd, monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(sys, "stdout", terminal)
    gpfd.evolve(**TINY, out=tmp_path / "run", verbose=False)
    assert terminal.getvalue() == ""
    assert capfd.readouterr() == ("", "")


def test_on_a_terminal_the_default_is_a_bar_of_generations_then_the_stages_after_them(
    tmp_path, monkeypatch
):
    terminal = Terminal()
    out = io.StringIO()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(sys, "stdout", out)
    run = gpfd.evolve(**TINY, out=tmp_path / "run")
    bar = terminal.getvalue()
    best = run.history["best"][-1]
    # The final drawing of the generations' bar: all generations, the last best GP fitness.
    assert "evolve: 100%" in bar and f"gen 2/2, best {best:.6g}" in bar, bar
    # cartpole-quick confirms its validation winner: the run ended in the confirmation stage.
    assert "confirmation: 100%" in bar, bar
    # Not the command's line per generation, but its header and outcome around the bar.
    printed = out.getvalue()
    assert "gen   0  best" not in printed + bar
    assert printed.startswith("gpfd evolve: cartpole-quick (pg on cartpole), population 8")
    assert "best.features" in printed.splitlines()[-1]


def test_verbose_true_prints_the_command_text_and_no_bar(tmp_path, monkeypatch):
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    monkeypatch.setattr(sys, "stdout", terminal)
    gpfd.evolve(**TINY, out=tmp_path / "run", verbose=True)
    printed = terminal.getvalue()
    assert "gen   0  best " in printed and "gen   1  best " in printed and "ETA" in printed
    assert "%|" not in printed and "evolve:" not in printed.replace("gpfd evolve:", "")


def test_a_real_pseudo_terminal_gets_the_bar(tmp_path):
    """End to end: a script whose output is a pseudo-terminal, verbose left at its default."""
    script = (
        "import gpfd\n"
        f"gpfd.evolve(seed=2, population=8, generations=2, set={QUICK!r}, "
        f"out={str(tmp_path / 'run')!r})\n"
    )
    leader, follower = pty.openpty()
    # A new pseudo-terminal is 0 columns wide; give it a width, and no height, as `script` does.
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 0, 100, 0, 0))
    try:
        child = subprocess.Popen(
            [sys.executable, "-c", script], stdout=follower, stderr=follower, close_fds=True
        )
        os.close(follower)
        chunks = []
        while True:
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # EIO: the child closed the terminal
                break
            if not chunk:
                break
            chunks.append(chunk)
        assert child.wait(timeout=120) == 0
    finally:
        os.close(leader)
    shown = b"".join(chunks).decode(errors="replace")
    assert "evolve: 100%" in shown and "gen 2/2, best" in shown, shown
    assert "gen   0  best" not in shown


def synthetic_run(bar, finished):
    """What the C++ run tells the bar, in order, for a run of 3 generations."""
    bar.run_started({"label": "", "dir": "d", "generations": 3, "done": 0, "population": 10})
    bar.poll("generations", 4, 10)
    for generation in range(3):
        bar.generation({"generation": generation, "best": 100.0 + generation})
    bar.poll("validation", 0, 70)
    bar.poll("confirmation", 20, 40)  # A clear difference after 2 of 4 looks.
    bar.run_ended(finished)


def test_the_bar_shows_each_stage_and_where_a_run_ended():
    shown = io.StringIO()
    synthetic_run(progress.EvolveBar(file=shown), finished=True)
    text = shown.getvalue()
    assert "4/10 evaluated" in text
    assert "gen 3/3, best 102" in text
    # Validation's trainings are counted all at once: done when the next stage starts.
    assert "validation: 100%" in text and "70/70 trainings" in text
    assert (
        "confirmation: 100%" in text
        and "20/40 trainings: a clear difference ended it early" in text
    )

    # A stopped run's bar stays where it stopped.
    shown = io.StringIO()
    bar = progress.EvolveBar(file=shown)
    bar.run_started(
        {"label": "[run 1/2] ", "dir": "d", "generations": 4, "done": 1, "population": 10}
    )
    bar.generation({"generation": 1, "best": 5.0})
    bar.run_ended(False)
    text = shown.getvalue()
    assert "[run 1/2] evolve:  50%" in text and "gen 2/4, best 5" in text
    assert "100%" not in text


def test_an_error_in_the_display_never_stops_the_run(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "stderr", Terminal())
    monkeypatch.setattr(sys, "stdout", io.StringIO())
    raised = []

    def broken(self, *args):
        raise RuntimeError("display broke")

    monkeypatch.setattr(progress.EvolveBar, "run_ended", broken)
    monkeypatch.setattr(sys, "unraisablehook", lambda info: raised.append(info.exc_value))
    run = gpfd.evolve(**TINY, out=tmp_path / "run")
    assert run.finished
    assert [str(e) for e in raised] == ["display broke"]


@pytest.mark.parametrize("verbose", [None, False])
def test_what_stops_a_run_is_always_said(tmp_path, capfd, verbose):
    gpfd.evolve(**TINY, out=tmp_path / "run", callback=lambda stats: True, verbose=verbose)
    assert "gpfd.evolve(resume=" in capfd.readouterr().err
