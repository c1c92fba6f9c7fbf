"""What a features text is read against, for ``FeatureSet.parse`` and ``FeatureSet.load``."""

from __future__ import annotations

from typing import Any

from gpfd import _core
from gpfd.adapters.user_env import state_names
from gpfd.environments.gpfd_env import GpfdEnv
from gpfd.environments.registry import is_builtin


def expectation(env: Any, variables: Any, params: dict) -> tuple[str, list | None, list | None]:
    """(environment name, variables, fallback variables) for a features text.

    The file is refused when it states another environment or other variables than given. The
    fallback variables (a gpfd environment's, with default parameters) are used only when the
    file names none.
    """
    names = None if variables is None else [str(v) for v in variables]
    if env is None:
        if params:
            raise TypeError(f"environment parameters {sorted(params)} need env=")
        return "", names, None
    if isinstance(env, str):
        if is_builtin(env):
            own = list(_core.EnvBatch(env, params).state_names)
            return (env, names or own, None) if params else (env, names, own)
        if params:
            raise TypeError(f"parameters are for gpfd's environments; {env!r} is not one")
        return env, names, None
    # A Gymnasium environment, possibly wrapped.
    if params:
        raise TypeError("give parameters with a gpfd environment name, not with an environment")
    base = getattr(env, "unwrapped", env)
    if isinstance(base, GpfdEnv):
        return base.gpfd_name, names or list(base.state_names), None
    spec = getattr(env, "spec", None)
    return (spec.id if spec is not None else ""), names or state_names(env.observation_space), None
