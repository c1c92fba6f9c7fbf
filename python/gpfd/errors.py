"""gpfd's errors, named as the package documents them: ``gpfd.InputError`` and ``gpfd.EnvError``.

A leaf module: it imports nothing of gpfd but the extension module, so every other module may
raise these.
"""

from __future__ import annotations

from gpfd._core import InputError


class EnvError(RuntimeError):
    """A Gymnasium environment stepped by gpfd misbehaved: it raised, or returned an observation
    that is not finite or not of its space's size.

    Example::

        try:
            gpfd.evolve(env=make_my_env, threads=2)
        except gpfd.EnvError as e:
            print(e)  # names the environment, the call and the step
    """


# Tracebacks and reprs name the classes where users find them, gpfd.EnvError and gpfd.InputError;
# pickling finds them there too. The extension names its class gpfd._core.InputError, where its
# stubs (nanobind's stubgen, which imports gpfd._core alone) declare it.
EnvError.__module__ = "gpfd"
InputError.__module__ = "gpfd"

__all__ = ["EnvError", "InputError"]
