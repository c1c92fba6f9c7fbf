"""The environments registered from Python, in this process: each name's factory.

A leaf module: gpfd.user_env registers (``gpfd.evolve(env=...)``, each worker process at its
start), gpfd.adapters.sources and gpfd.envs read; gpfd's registry in C++ holds the same names and
makes their instances through gpfd.user_env.make_adapter.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from gpfd import _core

# The environment factory of each registered name (a callable returning a Gymnasium
# environment; a gpfd.adapters.sources.VectorSource where the environment has a vector form).
_factories: dict[str, Callable[[], Any]] = {}


def add(name: str, factory: Callable[[], Any]) -> None:
    """Makes `name` a gpfd environment whose instances `factory` makes (in this process); a name
    registered again gets the new factory."""
    _factories[name] = factory
    _core.register_python_env(name, "a Gymnasium environment stepped in Python")


def factory(name: str) -> Callable[[], Any] | None:
    """The factory registered as `name`, or None."""
    return _factories.get(name)


def is_builtin(name: str) -> bool:
    """Whether `name` is one of gpfd's own (C++) environments, not one registered from Python."""
    return name in _core.env_names() and name not in _factories
