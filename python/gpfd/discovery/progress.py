"""What ``gpfd.evolve`` shows while it runs.

``verbose=None`` (the default) shows a progress bar (tqdm; a widget in a Jupyter notebook) when
stderr is a terminal or the code runs in a notebook, and nothing otherwise (a log file, a pipe, a
batch job); ``verbose=True`` prints what ``gpfd evolve`` prints, ``verbose=False`` nothing. What
stops a run is always said, on stderr.

The bar follows the C++ run through gpfd._core.evolve's ``observer``: ``phase`` as each stage
before a run begins (choosing the learner's settings, measuring what an evaluation costs),
``run_started`` and ``run_ended`` around each run, ``poll`` every half second from a thread of
the run (the running stage: ``generations`` with the evaluations of the running generation and
the run's generations as its deadline refits them, then ``validation`` and ``confirmation`` with
their trainings), and ``generation`` after each generation (its statistics, as the callback sees
them).
"""

from __future__ import annotations

import sys
import threading
from typing import IO, Any


def in_notebook() -> bool:
    """Whether this runs in a Jupyter kernel (notebook, JupyterLab, VS Code, Colab)."""
    if "ipykernel" not in sys.modules:
        return False
    ipython = sys.modules.get("IPython")
    return ipython is not None and ipython.get_ipython() is not None


def is_terminal(stream: IO[str] | None) -> bool:
    """Whether `stream` is a terminal (a closed or detached stream is not)."""
    try:
        return stream is not None and stream.isatty()
    except (AttributeError, ValueError):
        return False


def shows_bar(verbose: bool | None) -> bool:
    """Whether ``gpfd.evolve(verbose=...)`` shows a progress bar: only with ``None``, on a
    terminal (stderr, where the bar goes) or in a notebook."""
    return verbose is None and (in_notebook() or is_terminal(sys.stderr))


class EvolveBar:
    """A tqdm progress bar of a discovery run: the generations (gen k/n, the best GP fitness so
    far, the evaluations of the running generation, elapsed time and ETA), then a bar for each
    stage after them (validation, confirmation: trainings done of all). Methods may be called
    from any thread."""

    def __init__(self, file: IO[str] | None = None) -> None:
        from tqdm.auto import tqdm  # Widgets in a notebook, text on a terminal.

        self._tqdm = tqdm
        self._file = file  # None: tqdm's default, stderr.
        self._lock = threading.Lock()
        self._bar: Any = None
        self._stage = ""
        self._label = ""
        self._generations = 0
        self._done = 0  # Generations done.
        self._population = 1
        self._best: float | None = None

    def _open(self, stage: str, total: int, initial: float) -> None:
        self._close()
        self._stage = stage
        fmt = "{desc}: {percentage:3.0f}%|{bar}| [{elapsed}<{remaining}{postfix}]"
        self._bar = self._tqdm(
            total=total,
            initial=initial,
            desc=f"{self._label}{stage}",
            file=self._file,
            bar_format=fmt,
            # One bar at a time: never hidden as an overflow, even where a terminal says it has
            # no rows (tqdm hides bars past the height it reads; `script` and some CI pseudo-
            # terminals report 0).
            nrows=20,
            smoothing=0,  # ETA from the mean speed: generations cost about the same.
            leave=True,
        )

    def _close(self, complete: bool = False) -> None:
        """Closes the bar; `complete`: its stage is over, so it ends at 100% (a confirmation
        that a clear difference ended early ends at the trainings it needed)."""
        if self._bar is None:
            return
        if complete:
            if self._stage == "confirmation" and self._bar.n < self._bar.total:
                # The run's end tells the trainings done exactly.
                self._bar.set_postfix_str(
                    f"{self._bar.n:.0f}/{self._bar.total} trainings: a clear difference ended it "
                    "early",
                    refresh=False,
                )
                self._bar.total = self._bar.n
            elif self._stage != "evolve":
                self._bar.set_postfix_str(f"{self._bar.total}/{self._bar.total} trainings")
            self._move_to(self._bar.total)
        self._bar.close()
        self._bar = None

    def _describe_generations(self, evaluated: int | None) -> None:
        text = f"gen {self._done}/{self._generations}"
        if self._best is not None:
            text += f", best {self._best:.6g}"
        if evaluated is not None and self._done < self._generations:
            text += f", {evaluated}/{self._population} evaluated"
        self._bar.set_postfix_str(text, refresh=False)

    def _move_to(self, position: float) -> None:
        self._bar.n = position
        self._bar.refresh()

    def run_started(self, info: dict[str, Any]) -> None:
        with self._lock:
            self._label = str(info["label"])
            self._generations = int(info["generations"])
            self._done = int(info["done"])
            self._population = max(1, int(info["population"]))
            self._best = None
            self._open("evolve", self._generations, self._done)
            self._describe_generations(None)
            self._bar.refresh()

    def phase(self, text: str) -> None:
        """A stage before the run starts (choosing the learner's settings, measuring what an
        evaluation costs): shown as it begins, with the time it has taken."""
        with self._lock:
            self._close()
            self._stage = "phase"
            self._bar = self._tqdm(
                total=None, desc=text, file=self._file, bar_format="{desc} [{elapsed}]", leave=True
            )
            self._bar.refresh()

    def _set_generations(self, generations: int | None) -> None:
        """The run's generations as its time budget's deadline refits them: the bar's total."""
        if generations is not None and generations > 0 and generations != self._generations:
            self._generations = generations
            self._bar.total = generations

    def generation(self, stats: dict[str, Any]) -> None:
        """After each generation, with the callback's statistics."""
        with self._lock:
            if self._bar is None or self._stage != "evolve":
                return
            self._set_generations(stats.get("generations"))
            self._done = int(stats["generation"]) + 1
            self._best = float(stats["best"])  # The generation's, as `gpfd evolve` prints it.
            self._describe_generations(None)
            self._move_to(self._done)

    def poll(self, stage: str, done: int, total: int, generations: int | None = None) -> None:
        """The running stage: `done` of `total` evaluations (generations) or trainings;
        `generations`: the run's, as its deadline refits them."""
        with self._lock:
            if self._bar is None or self._stage == "phase":
                return
            if stage == "generations":
                if self._stage == "evolve":
                    self._set_generations(generations)
                    # Within a generation: its share of evaluations (re-evaluations may pass it).
                    share = min(done / self._population, 0.99)
                    self._describe_generations(done)
                    self._move_to(min(self._done + share, self._generations))
                return
            if self._done < self._generations:
                # The hall of fame validated between generations (validation.every): a note.
                self._bar.set_postfix_str(
                    f"gen {self._done}/{self._generations}, {stage} of the hall of fame",
                    refresh=True,
                )
                return
            if self._stage != stage:
                self._close(complete=True)  # The stage before this one is over.
                self._open(stage, total, 0)
            self._bar.total = total  # Validation knows its total once it starts training.
            self._bar.set_postfix_str(f"{done}/{total} trainings", refresh=False)
            self._move_to(done)

    def run_ended(self, finished: bool) -> None:
        """The run finished (`finished`), or stopped: the bar stays where it is."""
        with self._lock:
            self._close(complete=finished)
            self._stage = ""
