"""gpfd from Python: feature discovery for reinforcement learning with genetic programming.

The core is gpfd's C++ library; this package is a thin front over it:

- ``FeatureSet``: discovered features, JIT-compiled, callable on NumPy observations.
- ``gpfd/Acrobot-v0``, ``gpfd/CartPole-v0``, ``gpfd/Swimmer-v0``, ``gpfd/Tetris-v0``: gpfd's
  environments in Gymnasium (``gymnasium.make``, ``gymnasium.make_vec``), registered on import;
  ``gpfd/GymnasiumCartPole-v1``: Gymnasium's CartPole-v1 task (two pushes, 500 steps), where
  ``gpfd/CartPole-v0`` defaults to a continuous force and 1000 steps.
- ``gpfd/Planted<Name>-v0``: small tasks with a known answer (gpfd.planted; gpfd.planted_check
  tells whether a feature set carries it).
- ``wrappers.FeatureObservation``: a Gymnasium wrapper that shows an agent the features.
- ``evolve``, ``fitness`` (``fitness_of_each``: many sets at once), ``assess``, ``load_run``:
  discovery, GP's fitness, the test protocol and results directories, as ``gpfd evolve`` and
  ``gpfd assess`` run them; ``evolve`` also runs on any Gymnasium environment with a Box
  observation space, stepped in Python (where it has a vector form, ``VectorFactory`` and
  gpfd.adapters.sources, the lanes of up to 16 evaluations at once).
- ``signed_rank_test`` (gpfd.stats): the Wilcoxon signed-rank test of gpfd's method-level
  verdict, for a user's own paired comparisons.

docs/python.md in gpfd's repository is the guide.
"""

from gpfd import wrappers  # The public module, gpfd/wrappers.py.
from gpfd._core import FeatureSet, InputError, __version__
from gpfd.discovery.runs import (
    Run,
    assess,
    builtin_configs,
    evolve,
    fitness,
    fitness_of_each,
    load_run,
)
from gpfd.discovery.stats import signed_rank_test
from gpfd.environments import gpfd_env as _envs
from gpfd.environments import planted as _planted
from gpfd.environments import twins as _twins
from gpfd.errors import EnvError
from gpfd.vector_source import VectorFactory  # The module its class names (adapters/sources.py).

_envs.register_all()
_planted.register_all()
_twins.register_all()

__all__ = [
    "EnvError",
    "FeatureSet",
    "InputError",
    "Run",
    "VectorFactory",
    "__version__",
    "assess",
    "builtin_configs",
    "evolve",
    "fitness",
    "fitness_of_each",
    "load_run",
    "signed_rank_test",
    "wrappers",
]
