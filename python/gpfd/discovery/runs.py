"""Discovery (``gpfd evolve``), GP's fitness, assessment (``gpfd assess``) and results directories.

``evolve`` and ``assess`` call the same C++ code as the command line, with the same config loading
(a TOML file or a shipped config name, ``key=value`` overrides): the same seed and sizes give the
same ``best.features`` from Python as from ``gpfd evolve``, whatever the number of threads; a time
budget's sizes come from the clock, and ``evolve(replay=...)`` reruns such a run exactly.
"""

from __future__ import annotations

import csv
import functools
import hashlib
import json
import math
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from gpfd import _core
from gpfd._core import FeatureSet, InputError
from gpfd.adapters import user_env
from gpfd.discovery import progress
from gpfd.discovery.evaluator import Evaluator
from gpfd.environments import twins

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

Callback = Callable[[dict[str, Any]], Any]


def builtin_configs() -> list[str]:
    """The names of the shipped configs (configs/NAME.toml), usable as ``config=``.

    Example::

        gpfd.builtin_configs()  # ["acrobot-quick", "acrobot", "cartpole-quick", ...]
    """
    return list(_core.builtin_configs())


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            raise ValueError(f"config values must be finite, got {value}")
        return repr(float(value))
    if isinstance(value, str):
        return json.dumps(value)  # A TOML basic string.
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} into a config: {value!r}")


def _whole(name: str, value: Any, least: int) -> int:
    """An integer argument `name`, at least `least`: TypeError or ValueError naming it."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, not {type(value).__name__} ({value!r})")
    if value < least:
        raise ValueError(f"{name} must be at least {least}, got {value}")
    return int(value)


def _param_text(value: Any) -> str:
    """A ``--param`` value as text: strings as they are, numbers and bools as TOML writes them."""
    return value if isinstance(value, str) else _toml_value(value)


def _overrides(settings: Mapping[str, Any] | Iterable[str] | None) -> list[str]:
    """``set=`` as ``key=value`` texts: a mapping {"gp.elitism": 0.2} or texts "gp.elitism=0.2"."""
    if settings is None:
        return []
    if isinstance(settings, Mapping):
        return [f"{key}={_toml_value(value)}" for key, value in settings.items()]
    if isinstance(settings, str):
        return [settings]
    return [str(s) for s in settings]


def _twin_or_gymnasium(
    env: Any, env_kwargs: dict | None, native: bool | None, executor: Any, say: bool = True
) -> Any:
    """`env` as it will be stepped: a Gymnasium id that gpfd has a twin of (gpfd.twins) stays
    the id, stepped by the twin in C++, where ``native`` is not False, no ``executor`` is given and
    the twin takes every keyword; otherwise it becomes ``"gymnasium:ID"``, Gymnasium's own stepped
    in Python (the same task under a name of its own). Says which in one line on stderr, unless
    not ``say``."""
    if not (isinstance(env, str) and env in twins.TWINS):
        return env
    refused = sorted(set(env_kwargs or {}) - set(twins.TWINS[env][1]) - {"max_episode_steps"})
    why = (
        "native=False"
        if native is False
        else "executor= given"
        if executor is not None
        else f"its twin does not take {', '.join(refused)}"
        if refused
        else ""
    )
    if why:
        if say:
            print(f"gpfd: {env} stepped in Python by Gymnasium's own ({why})", file=sys.stderr)
        return "gymnasium:" + env
    if say:
        print(
            f"gpfd: {env} stepped in C++ by gpfd's twin of Gymnasium's, the same episodes bit "
            "for bit (native=False: Gymnasium's own, in Python)",
            file=sys.stderr,
        )
    return env


def _env_overrides(env: Any, env_kwargs: dict | None) -> tuple[list[str], Evaluator | None]:
    """The overrides that select `env`, and for an environment stepped in Python its evaluator
    (not yet started; one worker until told)."""
    if env is None:
        if env_kwargs:
            raise TypeError("env_kwargs needs env=")
        return [], None
    if isinstance(env, str) and env in twins.TWINS:  # The twin (_twin_or_gymnasium chose it).
        params = twins.twin_params(env, env_kwargs or {})
        return [f"env.name={_toml_value(env)}", "env.params={}"] + [
            f"env.params.{key}={_toml_value(value)}" for key, value in params.items()
        ], None
    if isinstance(env, str) and user_env.is_builtin(env):
        if env_kwargs:
            raise TypeError(
                f"{env} is gpfd's own environment: give its parameters with "
                f"set={{'env.params.<name>': value}}"
            )
        return [f"env.name={_toml_value(env)}"], None
    name, factory = user_env.resolve(env, env_kwargs)
    user_env.register(name, factory)
    return [f"env.name={_toml_value(name)}", "env.params={}"], Evaluator(name, factory, 1)


def _use_workers(evaluator: Evaluator | None, threads: int, executor: Any, env: Any) -> None:
    """Where the evaluator's work runs (Evaluator.use); InputError naming ``executor`` when it is
    not a concurrent.futures.Executor, or when there is no environment stepped in Python."""
    if executor is not None:
        if not isinstance(executor, Executor):
            raise InputError(
                "executor must be a concurrent.futures.Executor (ProcessPoolExecutor, loky, a "
                "Dask client's get_executor(), mpi4py's MPIPoolExecutor, gpfd.workers."
                f"WorkerPool), not {type(executor).__name__}"
            )
        context: Any = getattr(executor, "_mp_context", None)
        forks = context is not None and context.get_start_method() == "fork"
        if isinstance(executor, ProcessPoolExecutor) and forks:
            raise InputError(
                "executor: a ProcessPoolExecutor whose workers fork this process, which runs "
                "gpfd's threads: a forked copy may hold their locks and die. Make it with "
                "mp_context=multiprocessing.get_context('forkserver') (or 'spawn')"
            )
        if evaluator is None:
            which = f"{env} is gpfd's own environment" if env else "without env=, the config's"
            raise InputError(
                f"executor= runs an environment stepped in Python on the executor's workers; "
                f"{which}, stepped in C++: leave executor= out (threads= runs it on threads of "
                "this process; gpfd evolve under MPI across hosts, docs/mpi.md)"
            )
    if evaluator is not None:
        evaluator.use(threads, executor)


def _resumed_env(resume: str | os.PathLike, env: Any, env_kwargs: dict | None) -> Evaluator | None:
    """The evaluator of the run in `resume` where it is on an environment stepped in Python: of
    `env` (and `env_kwargs`) when given, else of its Gymnasium id or EnvPool task as stored (with
    `env_kwargs`)."""
    config = Path(resume, "config.toml")
    if not config.is_file():
        return None  # The C++ side says what is missing.
    stored = tomllib.loads(config.read_text())["env"]["name"]
    if user_env.is_builtin(stored):
        if env is not None and env != stored:
            raise TypeError(f"the run in {resume} is on {stored}, not {env!r}")
        return None
    if env is None:
        if stored.startswith("python:"):
            raise TypeError(
                f"the run in {resume} is on {stored.removeprefix('python:')}, stepped in Python: "
                "give env= (the callable it was started with) to resume it"
            )
        env = stored
    name, factory = user_env.resolve(env, env_kwargs)
    if name != stored and not stored.startswith("python:"):
        raise TypeError(f"the run in {resume} is on {stored}, not {name}")
    user_env.register(stored, factory)
    return Evaluator(stored, factory, 1)


def _space_text(space: Any) -> str:
    """A space in full: its kind, shape, dtype and every bound (str abbreviates long ones)."""
    parts = [type(space).__name__, repr(getattr(space, "shape", None)), str(space.dtype)]
    for attribute in ("low", "high", "n", "start", "nvec"):
        value = getattr(space, attribute, None)
        if value is not None:
            parts.append(f"{attribute}={np.asarray(value).tolist()!r}")
    return " ".join(parts)


def _json_text(value: Any) -> str:
    """A keyword argument JSON has no form for: its repr, or where that names an address (an
    object without a repr of its own) its type, the same in every session."""
    text = repr(value)
    return f"<{type(value).__module__}.{type(value).__qualname__}>" if " at 0x" in text else text


def _task_fingerprint(env: Any, env_kwargs: dict | None, evaluator: Evaluator) -> dict[str, Any]:
    """run.json's "env" for an environment stepped in Python: what a resume must find the same
    (_check_resumed_task). ``callable``: the module and qualified name of the callable (of a
    functools.partial, its function; a Gymnasium id or EnvPool task as given); ``kwargs``:
    ``env_kwargs`` with a partial's own keywords, as JSON (_json_text where JSON has none); the
    spaces of one environment made now, as text, and ``spaces``, a SHA-256 of both in full
    (kinds, shapes, dtypes, every bound)."""
    kwargs: dict[str, Any] = {}
    if isinstance(env, str):
        name = env
    else:
        target = env
        while isinstance(target, functools.partial):
            kwargs = {**target.keywords, **kwargs}
            target = target.func
        module = getattr(target, "__module__", None) or type(target).__module__
        qualname = getattr(target, "__qualname__", None) or type(target).__qualname__
        name = f"{module}.{qualname}"
    kwargs.update(env_kwargs or {})
    fingerprint: dict[str, Any] = {
        "callable": name,
        "kwargs": json.loads(json.dumps(kwargs, sort_keys=True, default=_json_text)),
    }
    try:
        made = evaluator.factory()
    except Exception:  # The run says what is wrong with the environment when it makes one.
        return fingerprint
    try:
        texts = [_space_text(made.observation_space), _space_text(made.action_space)]
    finally:
        made.close()
    fingerprint["observation_space"] = str(made.observation_space)
    fingerprint["action_space"] = str(made.action_space)
    digest = hashlib.sha256("\n".join(texts).encode()).hexdigest()
    fingerprint["spaces"] = "sha256:" + digest
    return fingerprint


def _stored_fingerprint(resume: str | os.PathLike) -> tuple[Path, dict[str, Any]] | None:
    """run.json's "env" of the run (or of the first run of the set) in `resume`, with the file;
    None where there is none (a run of an earlier gpfd, or not on an environment stepped in
    Python)."""
    for path in (Path(resume, "run.json"), *sorted(Path(resume).glob("run-*/run.json"))):
        if path.is_file():
            stored = json.loads(path.read_text()).get("env")
            return (path, stored) if isinstance(stored, dict) else None
    return None


def _check_resumed_task(resume: str | os.PathLike, now: dict[str, Any]) -> None:
    """InputError naming each difference between the task a run in `resume` was started on (its
    run.json's "env") and the one given to resume it: a resumed run continues only the same
    task."""
    found = _stored_fingerprint(resume)
    if found is None:
        return
    path, then = found
    differences = []
    if then.get("callable") != now.get("callable"):
        differences.append(f"the environment is {now.get('callable')}, not {then.get('callable')}")
    if then.get("kwargs") != now.get("kwargs"):
        differences.append(
            f"env_kwargs are {now.get('kwargs')}, not {then.get('kwargs')} (with a "
            "functools.partial's own keywords)"
        )
    if "spaces" in then and "spaces" in now and then["spaces"] != now["spaces"]:
        named = [
            f"its {key} is {now.get(key)}, not {then.get(key)}"
            for key in ("observation_space", "action_space")
            if then.get(key) != now.get(key)
        ]
        differences += named or [
            "its spaces differ in their bounds, shapes or dtypes "
            f"(spaces {now['spaces']}, not {then['spaces']})"
        ]
    if differences:
        raise InputError(
            f"resume continues only the task the run was started on: {'; '.join(differences)}; "
            f"give env= and env_kwargs= as the run was started with ({path})"
        )


def _resume_call(env: Any, env_kwargs: dict | None) -> str:
    """How to resume a run of gpfd.evolve(env=env, env_kwargs=...), with {} for its directory
    (a format string of fmt)."""
    parts = []
    if env is not None and not (isinstance(env, str) and user_env.is_builtin(env)):
        if isinstance(env, str):
            parts.append(f"env={env!r}")
        else:
            name = getattr(env, "__qualname__", "")
            if isinstance(env, functools.partial) or not name.isidentifier():
                name = "..."  # A lambda, a partial, an instance: named by no expression here.
            parts.append(f"env={name}")
        if env_kwargs:
            parts.append(f"env_kwargs={env_kwargs!r}")
    tail = "".join(", " + part for part in parts).replace("{", "{{").replace("}", "}}")
    text = 'gpfd.evolve(resume="{}"' + tail + ")"
    if "env=..." in text:
        text += " (env= as given to this run)"
    return text


class _InterruptWatch:
    """Notes Ctrl-C (SIGINT) while a run goes, so that an interruption is known as one whatever
    error it surfaces as (an environment's wrapper may turn KeyboardInterrupt into its own error).
    The handler in place (Python's, which raises KeyboardInterrupt, or a notebook kernel's) still
    runs. Only in the main thread, and only where SIGINT has a Python handler."""

    def __init__(self) -> None:
        self.seen = False
        self._previous: Any = None

    def __enter__(self) -> _InterruptWatch:
        if threading.current_thread() is not threading.main_thread():
            return self
        previous = signal.getsignal(signal.SIGINT)
        if callable(previous):

            def handler(signum: int, frame: Any) -> Any:
                self.seen = True
                return previous(signum, frame)

            signal.signal(signal.SIGINT, handler)
            self._previous = previous
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)


def _as_argument(error: InputError, key: str) -> InputError:
    """`error` naming the keyword argument `key=` where it names the command line's spelling of
    it (``(--set key)``, ``(key (--key))``): a Python caller gave no option."""
    text = str(error)
    for spelling in (f"(--set {key})", f"({key} (--{key.replace('_', '-')}))"):
        if text.endswith(spelling):
            return InputError(text[: -len(spelling)] + f"({key}=)")
    return error


def _duration_value(name: str, value: Any) -> str:
    """``time_budget=`` or ``task_timeout=`` (`name`) as a config value: seconds (a finite
    number) or text such as "10m"; InputError naming the argument (``(name=)``), not the config
    key it becomes. The config's reader checks the rest (above 0, the text's form)."""
    number = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, bool
    )
    if isinstance(value, str) or (number and math.isfinite(value)):
        return _toml_value(value)
    what = f"{value}" if number else f"{type(value).__name__} ({value!r})"
    raise InputError(
        f'{name} must be seconds (a finite number) or text such as "10m", not {what} ({name}=)'
    )


def _task_timeout(value: Any, evaluator: Evaluator | None, env: Any) -> list[str]:
    """``task_timeout=`` as overrides (none where None); InputError naming it where no worker
    could be ended when a task hangs: an environment stepped in C++, or one stepped in this
    process (one thread and no executor)."""
    if value is None:
        return []
    setting = f"task_timeout={_duration_value('task_timeout', value)}"
    if evaluator is None:
        raise InputError(
            f"task_timeout bounds a task of an environment stepped in Python on worker "
            f"processes; {env!r} is stepped in C++, on threads (task_timeout=)"
        )
    if evaluator.in_process:
        raise InputError(f"{evaluator.in_process_timeout_text()} (task_timeout=)")
    return [setting]


def evolve(
    config: str | os.PathLike | None = None,
    *,
    env: str | Callable[..., Any] | None = None,
    seed: int | None = None,
    threads: int = 0,
    population: int | None = None,
    generations: int | None = None,
    runs: int | None = None,
    out: str | os.PathLike | None = None,
    set: Mapping[str, Any] | Iterable[str] | None = None,
    callback: Callback | None = None,
    resume: str | os.PathLike | None = None,
    env_kwargs: dict[str, Any] | None = None,
    verbose: bool | None = None,
    force: bool = False,
    time_budget: float | str | None = None,
    executor: Executor | None = None,
    native: bool | None = None,
    task_timeout: float | str | None = None,
    replay: str | os.PathLike | None = None,
) -> Run:
    """Discovers features with GP, exactly as ``gpfd evolve`` does, and returns the run.

    The same seed and sizes give the same run, whatever ``threads`` or ``executor``. A time
    budget (``time_budget``, and ``user-env``'s default of 3 minutes) sizes the run from the
    clock: the population and validation from measured speed, the generations fitted to the
    deadline, the learner's settings chosen on the task; two calls with the same seed may then
    differ. Such a run says so (printed, and run.json's ``"sizes"``), and ``replay=`` reruns it
    exactly.

    config: a TOML file or a shipped config name (default ``cartpole-quick``; ``user-env`` for an
        environment stepped in Python).
    env: one of gpfd's environments (``"acrobot"``, like ``--env``), or a Gymnasium id or a
        callable returning a Gymnasium environment, stepped in Python in ``threads`` worker
        processes (see gpfd.user_env); ``env_kwargs`` go to ``gymnasium.make`` or the callable.
    native: a Gymnasium id with a twin in gpfd (CartPole-v1, Acrobot-v1, Pendulum-v1,
        MountainCar-v0, MountainCarContinuous-v0: gpfd.twins) is stepped by the twin in C++,
        the same episodes bit for bit as Gymnasium's, so the same files as the run stepped in
        Python but for the environment's name and the timings, unless ``native=False``,
        an ``executor`` is given or ``env_kwargs`` holds a keyword the twin does not take: then
        Gymnasium's own, stepped in Python. One line on stderr says which (none with
        ``verbose=False``). A ``gym.make(...)`` object or a callable is never swapped.
    seed, population, generations: override the config's, like the command's flags.
    runs: N independent runs (run r in ``run-0r``, seeded from ``seed`` and r; run 1 is the single
        run) and a verdict on the method over them, like ``gpfd evolve --runs N`` (runs.csv);
        the Run returned is their directory's.
    threads: worker threads (processes for a Python environment); 0: all cores. Never changes
        the results of given sizes (a time budget's sizes come from the clock: see ``replay``).
    executor: a ``concurrent.futures.Executor`` (a Dask client's ``get_executor()``, mpi4py's
        ``MPIPoolExecutor``, loky, ``ProcessPoolExecutor``) whose workers step an environment
        stepped in Python instead of gpfd's own worker processes; ``threads`` then only says how
        many workers to size the work for (0: the executor's own count). Never shut down by
        gpfd; never changes the results of given sizes (see ``replay``).
    out: the results directory (default ``results/<name>``, or ``results/<name>-N`` when taken:
        the config's name, or for an environment stepped in Python the environment's);
        one that already holds files needs ``force=True``, one that holds a run is resumed with
        ``resume=``, never started over. The directory is locked while the run writes into it.
    set: any config key, ``{"gp.elitism": 0.2}`` or ``["gp.elitism=0.2"]`` (``--set``).
    time_budget: seconds, or text such as ``"10m"`` (``--time-budget``): sizes the population,
        the generations and the validation to end within it, written to config.toml. The config
        ``user-env`` (the default for an environment stepped in Python) holds 3 minutes; sizes
        given (``population``, ``generations``, ``gp.population`` or ``gp.generations`` in
        ``set``) replace a budget that comes from the config. ``user-env`` also chooses its
        learner's steps on the task before the run, natural steps or Rprop's large or small
        ones, by what each makes of the original variables and of 8 random feature sets
        (``learner.choose``, ``choose_random_sets``; docs/discovery.md), written to config.toml; a
        ``learner.params`` value in ``set`` (``learner.params.step``) drops the alternatives
        that set another.
    task_timeout: seconds, or text such as ``"10m"`` (the config key ``task_timeout``, written
        to config.toml): the longest one task of an environment stepped in Python (a lockstep
        group's fitness evaluations, or learning runs) may take on a worker. Past it the worker
        ends, and the task runs again as a lost worker's: gpfd's pool (``threads``) starts a new
        worker and runs it again, up to 3 workers, then stops the run with gpfd.WorkerError naming
        the environment and the step (the directory keeps its last complete generation, which
        ``resume=`` continues); Dask and Ray run it again on a fresh worker (their last try
        failed: gpfd.WorkerError, as the pool's); mpi4py's pool sends it again to another rank
        (it cannot replace the rank; with none left, gpfd.WorkerError); a
        ``ProcessPoolExecutor`` or loky breaks as a whole (WorkerError). Refused (InputError)
        for gpfd's own environments and with one thread and no executor: nothing could end
        this process' own hung step. A task is retried with the same seeds, so a retried task
        gives the same result.
    callback: called after each generation (once its checkpoint is written) with its statistics
        (generation, best, mean, median, mean_size, mean_features, evaluations, cache_hits,
        seconds, best_features, and generations: the run's, as a time budget's deadline refits
        them); a true return value stops the run there.
    resume: continue the run in this directory (with its stored config; only ``generations`` may
        extend it, ``threads`` may change). A run on an environment stepped in Python needs
        ``env`` (and ``env_kwargs``) again where it was a callable; a Gymnasium id or EnvPool
        task is found from the stored config. It continues only the same task: another
        callable (by module and qualified name), other keyword arguments or other spaces than
        the run's ``run.json`` records (``"env"``) is an InputError naming the difference.
    verbose: None (default): a progress bar (generation, best GP fitness, ETA; then validation
        and confirmation) when stderr is a terminal or this runs in a Jupyter notebook, otherwise
        only the run's verdict, one line (as ``run.best.meta`` holds it); True: print what
        ``gpfd evolve`` prints, a line per generation and what the run returned; False: nothing.
        What stops a run is always said (gpfd.discovery.progress).

    Ctrl-C stops the run at once and raises KeyboardInterrupt, its text saying how to continue:
    the run falls back to its last checkpoint (the end of the last complete generation;
    validation and confirmation start over), and resuming it gives the run an uninterrupted one
    gives. Interrupted in generation 0, before any checkpoint, a fresh run leaves no directory.

    Example::

        run = gpfd.evolve("cartpole-quick", seed=1, threads=2)
        print(run.best.show())  # the features it returns, one per line
        run = gpfd.evolve(env="MountainCarContinuous-v0", time_budget="2m", threads=2)
    """
    threads = _whole("threads", threads, 0)
    if generations is not None:
        generations = _whole("generations", generations, 0)
    if verbose is not None and not isinstance(verbose, bool):
        raise TypeError(
            f"verbose must be None, True or False, not {type(verbose).__name__} ({verbose!r})"
        )
    env = _twin_or_gymnasium(env, env_kwargs, native, executor, say=verbose is not False)
    out_name = ""
    if replay is not None:
        given_sizes = (seed, population, set, time_budget, generations, runs, resume)
        if any(value is not None for value in given_sizes):
            raise TypeError(
                "replay runs the stored config and sizes again; only threads, executor, out, "
                "force, env and env_kwargs may be given"
            )
    stored_run = resume if resume is not None else replay
    if stored_run is not None:
        if seed is not None or population is not None or set is not None or time_budget is not None:
            raise TypeError("resume continues with the stored config; only generations may change")
        if task_timeout is not None:
            raise TypeError("resume and replay run with the stored config and its task_timeout")
        overrides: list[str] = []
        evaluator = _resumed_env(stored_run, env, env_kwargs)
        if evaluator is not None:
            given = evaluator.name if env is None or isinstance(env, str) else env
            _check_resumed_task(stored_run, _task_fingerprint(given, env_kwargs, evaluator))
    else:
        overrides, evaluator = _env_overrides(env, env_kwargs)
        if evaluator is not None or env in twins.TWINS:
            out_name = user_env.run_name(evaluator.name if evaluator is not None else str(env))
            if config is None:
                config = user_env.DEFAULT_CONFIG
        if seed is not None:
            overrides.append(f"seed={_whole('seed', seed, 0)}")
        if population is not None:
            overrides.append(f"gp.population={_whole('population', population, 1)}")
        overrides += _overrides(set)
        if time_budget is not None:
            overrides.append(f"time_budget={_duration_value('time_budget', time_budget)}")
    _use_workers(evaluator, threads, executor, env)
    overrides += _task_timeout(task_timeout, evaluator, env)
    fingerprint = ""  # run.json's "env" of each run started: what a resume checks.
    if evaluator is not None and stored_run is None:
        given = evaluator.name if isinstance(env, str) else env
        fingerprint = json.dumps(_task_fingerprint(given, env_kwargs, evaluator))

    bar = progress.EvolveBar() if progress.shows_bar(verbose) else None

    def on_generation(stats: dict[str, Any]) -> bool:
        if bar is not None:
            bar.generation(stats)
        return bool(callback(stats)) if callback is not None else False

    with _InterruptWatch() as watch:
        try:
            directory, finished, interruption = _core.evolve(
                "" if config is None else os.fspath(config),
                overrides,
                None if out is None else os.fspath(out),
                bool(force),
                "" if resume is None else os.fspath(resume),
                threads,
                generations,
                None if runs is None else _whole("runs", runs, 1),
                on_generation,
                evaluator,
                verbose,
                bar,
                out_name,
                _resume_call(env, env_kwargs),
                lambda: watch.seen,
                fingerprint,
                "" if replay is None else os.fspath(replay),
            )
        except InputError as e:
            for key, given in (("time_budget", time_budget), ("task_timeout", task_timeout)):
                if given is not None:
                    e = _as_argument(e, key)
            raise e from None
        finally:
            if evaluator is not None:
                evaluator.close()
    if interruption:
        # KeyboardInterrupt itself, not a subclass: Python then ends a script by SIGINT (130).
        raise KeyboardInterrupt(interruption) from None
    run = load_run(directory)
    run.finished = finished  # A resumed run may have been extended past its config.
    return run


def fitness(
    features: FeatureSet | str | os.PathLike,
    config: str | os.PathLike | None = None,
    *,
    env: str | Callable[..., Any] | None = None,
    seed: int = 1,
    set: Mapping[str, Any] | Iterable[str] | None = None,
    env_kwargs: dict[str, Any] | None = None,
    native: bool | None = None,
) -> float:
    """GP's fitness of a feature set: the mean score of the config's short learning trials, as
    one evaluation in ``gpfd evolve`` computes it (run::trialFitness with ``Rng(seed)``). An
    environment stepped in Python runs in this process (default config ``user-env``).

    Example::

        fs = gpfd.FeatureSet.parse("th * dth", env="cartpole")
        gpfd.fitness(fs, "cartpole-quick", seed=1)  # a float: the same for the same seed
    """
    sets = [_feature_set(features, "features")]
    env = _twin_or_gymnasium(env, env_kwargs, native, None)
    return _fitness_of_each(sets, config, env, seed, set, env_kwargs)[0]


def fitness_of_each(
    features: Sequence[FeatureSet | str | os.PathLike],
    config: str | os.PathLike | None = None,
    *,
    env: str | Callable[..., Any] | None = None,
    seed: int = 1,
    set: Mapping[str, Any] | Iterable[str] | None = None,
    env_kwargs: dict[str, Any] | None = None,
    native: bool | None = None,
) -> list[float]:
    """``fitness`` of each feature set, with the same seed, in this process; where the environment
    has a vector form, the evaluations play together in one vector environment (one lockstep
    group, as ``evolve`` plays a generation's evaluations), each vector step advancing all their
    episodes. Each value is the one ``fitness`` gives where the vector form seeds each lane
    (gpfd's own environments, SyncVectorEnv).

    Example::

        sets = [gpfd.FeatureSet.parse(text, env="cartpole") for text in ("th * dth", "x + th")]
        gpfd.fitness_of_each(sets, "cartpole-quick", seed=1)  # [fitness of each set]
    """
    if isinstance(features, (FeatureSet, str, os.PathLike)):
        raise TypeError("fitness_of_each takes a list of feature sets; fitness takes one")
    sets = [_feature_set(f, f"features[{i}]") for i, f in enumerate(features)]
    env = _twin_or_gymnasium(env, env_kwargs, native, None)
    return _fitness_of_each(sets, config, env, seed, set, env_kwargs)


def _fitness_of_each(
    sets: list[FeatureSet],
    config: str | os.PathLike | None,
    env: str | Callable[..., Any] | None,
    seed: int,
    settings: Mapping[str, Any] | Iterable[str] | None,
    env_kwargs: dict[str, Any] | None,
) -> list[float]:
    overrides, evaluator = _env_overrides(env, env_kwargs)
    overrides += _overrides(settings)
    if (evaluator is not None or env in twins.TWINS) and config is None:
        config = user_env.DEFAULT_CONFIG
    return _core.fitness_of_each(
        "" if config is None else os.fspath(config), overrides, sets, _whole("seed", seed, 0)
    )


def _feature_set(value: Any, name: str) -> FeatureSet:
    """A FeatureSet, or one read from a features file."""
    if isinstance(value, FeatureSet):
        return value
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(
            f"{name} must be a FeatureSet or a features file, not {type(value).__name__}"
        )
    return FeatureSet.load(os.fspath(value))


def _table(columns: dict[str, list], as_frame: bool | None) -> Any:
    arrays = {key: np.asarray(values) for key, values in columns.items()}
    if as_frame is False:
        return arrays
    try:
        import pandas
    except ImportError:
        if as_frame:
            raise
        return arrays
    return pandas.DataFrame(arrays)


_SUMMARY_COLUMNS = [
    "set",
    "runs",
    "mean_final",
    "std",
    "ci95",
    "diverged",
    "welch_t",
    "welch_p",
    "mann_whitney_u",
    "mann_whitney_p",
    "cohen_d",
    "a12",
    "mean_area",
    "area_ci95",
    "area_welch_p",
    "area_mann_whitney_p",
]


def assess(
    features: FeatureSet | str | os.PathLike | Iterable[FeatureSet | str | os.PathLike] = (),
    *,
    env: str | Callable[..., Any] | None = None,
    config: str | os.PathLike | None = None,
    raw: bool = False,
    with_original: bool = False,
    fourier: int = 0,
    runs: int | None = None,
    budget: int | None = None,
    params: Mapping[str, Any] | None = None,
    seed: int = 1,
    threads: int = 0,
    out: str | os.PathLike | None = None,
    force: bool = False,
    as_frame: bool | None = None,
    env_kwargs: dict[str, Any] | None = None,
    executor: Executor | None = None,
    native: bool | None = None,
    task_timeout: float | str | None = None,
) -> Any:
    """The paper's test protocol, as ``gpfd assess`` runs it: each feature set (and the original
    state variables, the baseline, first) trained with the long budget over ``runs`` runs, with
    Welch and Mann-Whitney tests against the baseline. Returns the statistics table (the columns
    of summary.csv) as a pandas DataFrame when pandas is installed (``as_frame=None``), else as a
    dict of NumPy arrays. ``out`` also writes curves, finals, summary and plots there (locked while
    written; a directory that already holds files needs ``force=True``).

    env: one of gpfd's environments, or a Gymnasium id or a callable returning a Gymnasium
        environment (``env_kwargs`` go to it), whose runs step it in Python in ``threads`` worker
        processes, as gpfd.evolve does; its default config is ``user-env``, whose learner
        settings are chosen on the task as gpfd.evolve chooses them.
    executor: runs those runs on this executor's workers, as gpfd.evolve's ``executor``.
    task_timeout: the longest one task of those runs may take on a worker, as gpfd.evolve's.
    params: ``k=v`` for the environment or the learner, like ``--param``.

    Example::

        table = gpfd.assess(run.best, config="cartpole-quick", runs=10, out="results/check")
        table["set"], table["mean_final"]  # original, the set, no-learning: a row each
    """
    if isinstance(features, (FeatureSet, str, os.PathLike)):
        features = [features]
    env = _twin_or_gymnasium(env, env_kwargs, native, executor)
    overrides, evaluator = _env_overrides(env, env_kwargs)
    # gpfd's own environment by name; one stepped in Python by the name it is registered under.
    env_name = evaluator.name if evaluator is not None else env if isinstance(env, str) else ""
    threads = _whole("threads", threads, 0)
    _use_workers(evaluator, threads, executor, env)
    if evaluator is not None or env in twins.TWINS:
        if config is None:
            config = user_env.DEFAULT_CONFIG
    else:
        overrides = []  # gpfd's own environment: the request checks it against the config's.
    overrides += _task_timeout(task_timeout, evaluator, env)
    sets = [
        f if isinstance(f, FeatureSet) else FeatureSet.load(os.fspath(f), env=env_name or None)
        for f in features
    ]
    text_params = {str(k): _param_text(v) for k, v in (params or {}).items()}
    try:
        table = _core.assess(
            "" if config is None else os.fspath(config),
            overrides,
            env_name,
            text_params,
            0 if runs is None else _whole("runs", runs, 1),
            0 if budget is None else _whole("budget", budget, 1),
            _whole("seed", seed, 0),
            threads,
            sets,
            bool(raw),
            bool(with_original),
            _whole("fourier", fourier, 0),
            None if out is None else os.fspath(out),
            bool(force),
            evaluator,
        )
    except InputError as e:
        raise (e if task_timeout is None else _as_argument(e, "task_timeout")) from None
    finally:
        if evaluator is not None:
            evaluator.close()
    return _table({key: table[key] for key in _SUMMARY_COLUMNS}, as_frame)


@dataclass
class Run:
    """A results directory of ``gpfd evolve`` (or ``gpfd.evolve``).

    Attributes:
        dir: The results directory.
        config: config.toml, fully resolved.
        info: run.json: seed, version, revision, threads.
        history: generations.csv: a DataFrame with pandas, else a dict of arrays.
        best: best.features: the best features found so far.
        finished: All the config's generations are done (or those asked for).

    Example::

        run = gpfd.load_run("results/cartpole-quick")  # or what gpfd.evolve returns
        print(run.generations, run.finished, run.best_of(0).show())
    """

    dir: Path
    config: dict[str, Any]  # config.toml, fully resolved
    info: dict[str, Any]  # run.json: seed, version, revision, threads
    history: Any  # generations.csv: DataFrame with pandas, else dict of arrays
    best: FeatureSet | None  # best.features: the best features found so far

    finished: bool = False  # All the config's generations are done (or those asked for)

    @property
    def generations(self) -> int:
        """Generations completed."""
        return len(self.history["generation"])

    def best_of(self, generation: int) -> FeatureSet:
        """The best features of one generation (best/generation-NNNN.features)."""
        return FeatureSet.load(str(self.dir / "best" / f"generation-{generation:04d}.features"))


def load_run(directory: str | os.PathLike, as_frame: bool | None = None) -> Run:
    """Reads a results directory: its config, run.json, generations.csv and best.features.

    Example::

        run = gpfd.load_run("results/cartpole-quick", as_frame=False)
        run.history["best"][-1], run.best.show()  # the last generation's best GP fitness
    """
    path = Path(directory)
    if not (path / "config.toml").is_file():
        raise FileNotFoundError(f"{path} holds no gpfd run (no config.toml)")
    config = tomllib.loads((path / "config.toml").read_text())
    info = json.loads((path / "run.json").read_text()) if (path / "run.json").is_file() else {}
    columns: dict[str, list] = {}
    history_file = path / "generations.csv"
    if history_file.is_file():
        with history_file.open(newline="") as f:
            reader = csv.DictReader(f)
            columns = {name: [] for name in reader.fieldnames or []}
            for row in reader:
                for name, value in row.items():
                    columns[name].append(float(value))
    for name in ("generation", "evaluations", "cache_hits"):
        if name in columns:
            columns[name] = [int(v) for v in columns[name]]
    if not columns:
        columns = {"generation": []}
    best_file = path / "best.features"
    best = FeatureSet.load(str(best_file)) if best_file.is_file() else None
    finished = len(columns["generation"]) >= int(config["gp"]["generations"])
    return Run(path, config, info, _table(columns, as_frame), best, finished)
