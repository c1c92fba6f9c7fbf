"""Whether a feature set carries what a planted task needs (gpfd.planted): a test of values.

A set carries a needed feature f when f is, on states the task visits, nearly a linear function
of the set's features plus a constant: the least-squares fit of f on [1, phi_1, ..., phi_k] leaves
R^2 >= ``THRESHOLD``. On a tracking task the best linear policy on the set then loses
(1 - R^2) Var(f) per step to the best policy, 1% of what a policy that ignores the state loses
(Var(f)), which is below the noise of the learner's own exploration (its Gaussian's variance,
0.25 in normalised units, against Var(f) of 0.11 to 0.33 for the planted tasks). A constant, a
function of one variable or a set without the interaction leaves R^2 near 0 (by the tasks'
symmetries), so the threshold tells them apart by far.

Where only a needed feature's sign matters (``Task.by_sign``: the switch, whose best action is
where s x < 0), the set carries it when a linear function of its features plus a constant has
that sign on at least ``THRESHOLD`` of the visited states (a logistic regression, fitted by
Newton's method: ``sign_agreement``); R^2 is reported beside it.

A variable the task leaves out (its distractor) must not move any feature: the features are
evaluated again with that variable drawn anew, and any change larger than ``1e-9`` of a
feature's scale marks the set as using it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gpfd._core import FeatureSet, InputError
from gpfd.environments.planted import PlantedVectorEnv, Task, task

#: R^2 at or above which a needed feature counts as carried.
THRESHOLD = 0.99


@dataclass
class Carried:
    """What the check found: R^2 of each needed feature, the left-out variables used.

    Attributes:
        r2: R^2 of each needed feature's fit on the set, by the feature's name.
        uses_left_out: The left-out variables that move a feature.
    """

    r2: dict[str, float]
    uses_left_out: list[int]
    #: Where only the signs matter: the share of states where the best linear fit has the sign.
    agreement: dict[str, float] | None = None

    @property
    def carries(self) -> bool:
        """Every needed feature carried, and no left-out variable used."""
        scores = self.r2 if self.agreement is None else self.agreement
        return all(v >= THRESHOLD for v in scores.values()) and not self.uses_left_out


def sample_states(t: Task, n: int = 2000, seed: int = 0) -> np.ndarray:
    """n states (n x d) the task visits under uniformly random actions, from episodes seeded
    from `seed`."""
    lanes = 50
    envs = PlantedVectorEnv(t.name, lanes)
    rng = np.random.default_rng(seed)
    rows = [envs.reset(seed=seed)[0]]
    while sum(len(r) for r in rows) < n:
        rows.append(envs.step(_random_actions(t, rng, lanes))[0])
    return np.concatenate(rows)[:n]


def _random_actions(t: Task, rng: np.random.Generator, lanes: int) -> np.ndarray:
    if t.discrete:
        return rng.integers(0, 2, lanes)
    return rng.uniform(-1.0, 1.0, (lanes, 1))


def least_squares_fit(target: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """The fitted values (N,) of the least-squares fit of `target` (N,) on a constant and the
    columns of phi (N, k); k may be 0."""
    design = np.column_stack([np.ones(len(target)), phi])
    coef, *_ = np.linalg.lstsq(design, target, rcond=None)
    return design @ coef


def r_squared(target: np.ndarray, phi: np.ndarray) -> float:
    """R^2 of the least-squares fit of `target` (N,) on a constant and the columns of phi (N, k)."""
    residual = target - least_squares_fit(target, phi)
    total = float(np.sum((target - target.mean()) ** 2))
    if total == 0.0:
        raise ValueError("the needed feature is constant on the sampled states")
    return 1.0 - float(np.sum(residual**2)) / total


def sign_agreement(target: np.ndarray, phi: np.ndarray, iterations: int = 50) -> float:
    """The share of states where a linear function of the columns of phi (N, k), thresholded,
    gives the sign of `target` (states where it is 0 left out): the direction of a logistic
    regression of target > 0 on them (standardised; a small ridge, 1e-6, keeps separable data
    finite), with the threshold that agrees most."""
    keep = target != 0
    y = (target[keep] > 0).astype(np.float64)
    x = phi[keep]
    sd = x.std(axis=0)
    x = (x - x.mean(axis=0)) / np.where(sd > 0, sd, 1.0)
    design = np.column_stack([np.ones(len(y)), x])
    w = np.zeros(design.shape[1])
    ridge = 1e-6 * np.eye(len(w))
    for _ in range(iterations):
        z = np.clip(design @ w, -30.0, 30.0)
        p = 1.0 / (1.0 + np.exp(-z))
        hessian = design.T @ (design * (p * (1 - p))[:, None]) + ridge
        w = w + np.linalg.solve(hessian, design.T @ (y - p) - ridge @ w)
    # Its direction, with the threshold that agrees most (the fit's own is pulled by far states).
    z = x @ w[1:]
    order = np.argsort(z, kind="stable")
    below = np.concatenate([[0.0], np.cumsum(1.0 - y[order])])  # Negatives at or below a cut.
    above = np.concatenate([np.cumsum(y[order][::-1])[::-1], [0.0]])  # Positives above it.
    return float(np.max(below + above) / len(y))


def carried(features: FeatureSet, task_name: str, n: int = 2000, seed: int = 0) -> Carried:
    """How far `features` (read against the task's variables x0 .. x{d-1}) carry what the task
    `task_name` needs, on n visited states.

    Example::

        fs = gpfd.FeatureSet.parse("x0 * x1", variables=["x0", "x1"])
        gpfd.planted_check.carried(fs, "Product").carries  # True: R^2 1.0
    """
    t = task(task_name)
    if features.input_dim != t.variables:
        raise InputError(
            f"{t.gym_id} has {t.variables} variables (x0 .. x{t.variables - 1}); the feature set "
            f"reads {features.input_dim} ({', '.join(features.variables)})"
        )
    states = sample_states(t, n, seed)
    phi = np.asarray(features(states), dtype=np.float64).reshape(n, -1)
    r2 = {name: r_squared(f(states), phi) for name, f in t.needed}
    agreement = (
        {name: sign_agreement(f(states), phi) for name, f in t.needed} if t.by_sign else None
    )
    used = []
    rng = np.random.default_rng(seed + 1)
    for var in t.left_out:
        moved = states.copy()
        moved[:, var] = rng.permutation(moved[:, var])
        change = np.abs(np.asarray(features(moved)).reshape(n, -1) - phi)
        scale = np.maximum(np.abs(phi).max(axis=0), 1.0)
        if (change > 1e-9 * scale).any():
            used.append(var)
    return Carried(r2, used, agreement)
