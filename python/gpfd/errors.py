"""gpfd's errors, named as the package documents them: ``gpfd.InputError`` and ``gpfd.EnvError``.

A leaf module: it imports nothing of gpfd but the extension module, so every other module may
raise these.
"""

from __future__ import annotations

from gpfd._core import InputError


class EnvError(RuntimeError):
    """A Gymnasium environment stepped by gpfd misbehaved: it raised, or returned an observation
    that is not finite or not of its space's size."""


# Tracebacks and reprs name the classes where users find them: gpfd.EnvError, gpfd.InputError
# (the extension names InputError so itself); pickling finds them there too.
EnvError.__module__ = "gpfd"

__all__ = ["EnvError", "InputError"]
