"""A hung environment does not hang the run (task_timeout, gpfd.execution._deadline): past the
deadline a task's worker ends and the task runs again as a lost worker's, giving the same run; a
task that outlasts it on every try stops the run with WorkerError naming the environment and the
step, and the directory resumes to the same run. Bad values, gpfd's own environments and work in
this process are InputErrors."""

import json
import os
import re
import subprocess
import sys
import textwrap
import time
from pathlib import Path
from typing import Any

import pytest

import gpfd
from gpfd.execution import _deadline, _expired
from gpfd.workers import WorkerError
from point_env import Point
from test_executors import process_pool
from test_user_env_workers import SMALL, run_files

TIMEOUT = 4  # Seconds: a task of these runs takes milliseconds, also on a loaded machine.
COMMON: dict[str, Any] = {"seed": 5, "population": 6, "generations": 3, "set": SMALL}


class Hangs(Point):
    """Point whose step hangs (sleeps an hour) in a process other than `parent` once
    `directory`/armed exists: in every such process, or with `once` in the first only."""

    def __init__(self, directory: str, parent: int, once: bool):
        super().__init__(steps=30)
        self.directory, self.parent, self.once = Path(directory), parent, once

    def step(self, action):
        if os.getpid() != self.parent and (self.directory / "armed").exists():
            try:
                os.close(os.open(self.directory / "hung", os.O_CREAT | os.O_EXCL | os.O_WRONLY))
                first = True
            except FileExistsError:
                first = False
            if first or not self.once:
                time.sleep(3600)
        return super().step(action)


def evolve(tmp_path: Path, name: str, once: bool, arm: bool, **options: Any) -> gpfd.Run:
    """A run on Hangs, armed after generation 0 where `arm`."""
    directory = tmp_path / f"{name}-flags"
    directory.mkdir(exist_ok=True)

    def callback(stats: dict) -> None:
        if arm and stats["generation"] == 0:
            (directory / "armed").touch()

    return gpfd.evolve(
        env=Hangs,
        env_kwargs={"directory": str(directory), "parent": os.getpid(), "once": once},
        **options,
        callback=callback,
        out=tmp_path / name,
        verbose=False,
    )


def with_deadline(files: dict[str, str], seconds: float) -> dict[str, str]:
    """A run's files (run_files) as they read with task_timeout = `seconds` in its config: a run
    under another deadline is otherwise the same run."""
    line = re.compile(r"^task_timeout = .*$", re.MULTILINE)
    assert line.search(files["config.toml"]), files["config.toml"]
    return {**files, "config.toml": line.sub(f"task_timeout = {seconds:.1f}", files["config.toml"])}


def reference_files(tmp: Path) -> dict[str, str]:
    """The run on gpfd's pool with the deadline, nothing hung (test_executor_ray and
    test_executor_mpi4py compare theirs to it too)."""
    run = evolve(tmp, "ref", once=True, arm=False, **COMMON, threads=2, task_timeout=TIMEOUT)
    assert run.config["task_timeout"] == TIMEOUT
    return run_files(run.dir)


def resumed_mended(directory: Path) -> dict[str, str]:
    """The files, read as under TIMEOUT (with_deadline), of the run in `directory` that its hung
    environment stopped, resumed on gpfd's pool once mended (DIRECTORY-flags/armed removed),
    with the keywords it was started with (run.json)."""
    Path(f"{directory}-flags/armed").unlink()
    started = json.loads((directory / "run.json").read_text())["env"]["kwargs"]
    run = gpfd.evolve(resume=directory, env=Hangs, env_kwargs=started, threads=2, verbose=False)
    assert run.finished
    return with_deadline(run_files(run.dir), TIMEOUT)


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> dict[str, str]:
    return reference_files(tmp_path_factory.mktemp("ref"))


def test_a_task_hung_once_runs_again_on_a_new_worker_of_gpfds_pool(tmp_path, reference):
    run = evolve(tmp_path, "pool", once=True, arm=True, **COMMON, threads=2, task_timeout=TIMEOUT)
    assert (tmp_path / "pool-flags/hung").exists()
    assert run.finished and run_files(run.dir) == reference


def test_a_task_hung_once_runs_again_on_dask(tmp_path, reference, dask_client):
    executor = dask_client.get_executor()
    run = evolve(
        tmp_path, "dask", once=True, arm=True, **COMMON, executor=executor, task_timeout=TIMEOUT
    )
    assert (tmp_path / "dask-flags/hung").exists()
    assert run_files(run.dir) == reference


def test_a_task_hung_on_every_dask_worker_stops_and_resumes(tmp_path, reference):
    """Dask gives a task up once its workers died running it more than allowed-failures times
    (1 here, for a short test; the nanny restarts each): gpfd.WorkerError naming the
    environment, the directory resumable to the same run."""
    distributed = pytest.importorskip("distributed")
    import dask

    with dask.config.set({"distributed.scheduler.allowed-failures": 1}):
        cluster = distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        )
    try:
        with distributed.Client(cluster) as client, pytest.raises(WorkerError) as caught:
            evolve(
                tmp_path,
                "run",
                once=False,
                arm=True,
                **COMMON,
                executor=client.get_executor(),
                task_timeout=3,
            )
    finally:
        cluster.close()
    text = str(caught.value)
    assert "a task of python:Hangs" in text and "task_timeout=3 s" in text, text
    assert "task_timeout=3 s in python:Hangs: step " in text, text  # A worker told the step.
    assert "resume= continues" in text, text
    assert resumed_mended(tmp_path / "run") == reference


def test_the_deadline_from_the_config_key_is_the_same(tmp_path, reference):
    common = {**COMMON, "set": {**SMALL, "task_timeout": TIMEOUT}}
    run = evolve(tmp_path, "key", once=True, arm=True, **common, threads=2)
    assert (tmp_path / "key-flags/hung").exists()
    assert run_files(run.dir) == reference


@pytest.mark.long  # The mechanism on every Python: the tests of a task hung once.
def test_a_task_hung_on_every_worker_stops_naming_the_step_and_resumes(tmp_path, reference):
    with pytest.raises(WorkerError) as caught:
        evolve(tmp_path, "run", once=False, arm=True, **COMMON, threads=2, task_timeout=TIMEOUT)
    text = str(caught.value)
    assert f"task_timeout={TIMEOUT} s in python:Hangs: step " in text, text
    assert "of its episode" in text and "the task has lost 3 workers" in text, text
    assert "resume= continues" in text, text
    assert resumed_mended(tmp_path / "run") == reference


def test_a_process_pool_breaks_with_a_clear_error(tmp_path):
    with process_pool(2) as executor, pytest.raises(WorkerError, match="executor broke"):
        evolve(
            tmp_path, "pp", once=True, arm=True, **COMMON, executor=executor, task_timeout=TIMEOUT
        )
    assert (tmp_path / "pp-flags/hung").exists()


@pytest.mark.parametrize(
    "value, message",
    [
        (-1, r"task_timeout must be in \[0, "),
        (0, "task_timeout must be above 0"),
        ("abc", "abc"),
        (True, "task_timeout must be seconds"),
        (float("nan"), "task_timeout must be seconds"),
    ],
)
def test_a_bad_value_is_an_input_error_naming_the_argument(tmp_path, value, message):
    with pytest.raises(gpfd.InputError, match=message) as caught:
        evolve(tmp_path, "bad", once=True, arm=False, **COMMON, threads=2, task_timeout=value)
    assert str(caught.value).endswith("(task_timeout=)"), str(caught.value)
    assert not (tmp_path / "bad").exists()


def test_a_bad_config_key_is_an_input_error_naming_the_key(tmp_path):
    common = {**COMMON, "set": {**SMALL, "task_timeout": -2}}
    with pytest.raises(gpfd.InputError, match=r"task_timeout must be in \[0, .*--set task_timeout"):
        evolve(tmp_path, "bad", once=True, arm=False, **common, threads=2)


def test_no_deadline_where_nothing_could_end_a_hung_step(tmp_path):
    with pytest.raises(gpfd.InputError, match=r"threads=1 and no executor.*\(task_timeout=\)"):
        evolve(tmp_path, "one", once=True, arm=False, **COMMON, threads=1, task_timeout=5)
    with pytest.raises(gpfd.InputError, match=r"stepped in C\+\+.*\(task_timeout=\)"):
        gpfd.evolve(env="acrobot", **COMMON, task_timeout=5, out=tmp_path / "c", verbose=False)
    with pytest.raises(gpfd.InputError, match=r"threads=1 and no executor"):  # The config key.
        common = {**COMMON, "set": {**SMALL, "task_timeout": 5}}
        evolve(tmp_path, "key", once=True, arm=False, **common, threads=1)


def test_an_error_names_the_first_texts_told_and_counts_the_rest():
    texts = [f"step {i}" for i in range(5)]
    assert _expired.named(texts[:2]) == "step 0; step 1"
    assert _expired.named(texts) == "step 0; step 1; step 2; and 2 more"


def test_dasks_text_is_its_tasks_else_the_last_told_in_the_round():
    """Dask gives up a task queued on workers that other tasks' deadlines ended (a death counts
    against every task processing on the worker): no worker ran it, so the text is the last told
    since the round began; an earlier round's is never taken."""

    class Events:
        def __init__(self, events):
            self.events = events

        def get_events(self, topic):
            assert topic == _expired.TOPIC
            return self.events

    class Executor:
        def __init__(self, events):
            self._client = Events(events)

    told = [
        (90.0, {"task": "old", "text": "an earlier round's"}),
        (101.0, {"task": "a", "text": "a's step"}),
        (102.0, {"task": "b", "text": "b's step"}),
    ]
    assert _expired.dask_text(Executor(told), "a", since=100.0) == "a's step"
    assert _expired.dask_text(Executor(told), "queued", since=100.0) == "b's step"
    assert _expired.dask_text(Executor(told[:1]), "queued", since=100.0) is None
    assert _expired.dask_text(Executor(told), None, since=100.0) is None


def test_a_process_that_is_no_dask_worker_has_no_one_to_tell():
    pytest.importorskip("distributed")  # Imported: get_worker() is asked, and finds none.
    assert _expired.teller() is None


def test_seconds_of_reads_the_root_key_only():
    assert _deadline.seconds_of('name = "x"\ntask_timeout = 2.5\n[gp]\npopulation = 4\n') == 2.5
    assert _deadline.seconds_of('name = "x"\n[gp]\ntask_timeout = 3\n') is None
    assert _deadline.seconds_of("") is None


def run_guarded(body: str, grace: float) -> subprocess.CompletedProcess:
    script = textwrap.dedent(
        f"""
        import re, time
        from gpfd.execution import _deadline
        _deadline.GRACE = {grace}
        with _deadline.guard(1.0):
            {body}
        print("finished")
        """
    )
    return subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300
    )


def test_the_guard_ends_a_process_past_its_deadline_saying_where():
    done = run_guarded("time.sleep(600)", grace=5.0)
    assert done.returncode == _deadline.EXIT_CODE, done.stderr
    assert "task_timeout=1 s in no environment call" in done.stderr
    assert "finished" not in done.stdout


def test_a_hang_that_holds_the_gil_is_ended_by_faulthandler():
    """A regular expression's backtracking holds the GIL, as native code may: the watching
    thread cannot run; faulthandler ends the process GRACE seconds later, with tracebacks."""
    done = run_guarded('re.match(r"(a+)+b", "a" * 64)', grace=1.0)
    assert done.returncode == 1 and "Timeout" in done.stderr, done.stderr
    assert "finished" not in done.stdout


def test_a_task_within_its_deadline_is_untouched():
    done = run_guarded("time.sleep(0.1)", grace=1.0)
    assert done.returncode == 0 and done.stdout.strip() == "finished", done.stderr
