"""Times gpfd.evolve's time budget as a whole call (issue 53, point 2) on slow environments stepped
in Python, and says whether it ended within the budget + 10% or was refused within 10% of it.

    .venv/bin/python docs/results/budget-call/measure.py CASE BUDGET [--out DIR] [--seed S]

CASE: ``sleepy`` (CartPole-v1 whose step sleeps 0.2 ms), ``acrobot`` (Acrobot-v1, Gymnasium's
own: native=False), ``swimmer`` (Swimmer-v5, needs gymnasium[mujoco]), ``mountaincar``
(MountainCar-v0 as a user calls it: gpfd's twin). BUDGET: seconds, or
``default`` (user-env's 3 minutes). Runs the call in a child interpreter with verbose=True and
prints each line it prints with the seconds since the call began, then one summary line (JSON):
the wall time, the first line's time, the outcome, and the generations said.
"""

import argparse
import json
import subprocess
import sys
import time

CHILD = r"""
import sys, time
import gymnasium as gym
import gpfd

class Sleepy(gym.Wrapper):
    def step(self, action):
        time.sleep(0.0002)
        return self.env.step(action)

def sleepy():
    return Sleepy(gym.make("CartPole-v1"))

case, budget, out, seed = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
env = {"sleepy": sleepy, "acrobot": "Acrobot-v1", "swimmer": "Swimmer-v5",
       "mountaincar": "MountainCar-v0"}[case]
kwargs = {} if budget == "default" else {"time_budget": float(budget)}
if case != "mountaincar":
    kwargs["native"] = False
print("call", flush=True)
try:
    run = gpfd.evolve(env=env, threads=2, seed=seed, out=out, verbose=True, **kwargs)
    print("finished", run.finished, flush=True)
except gpfd.InputError as e:
    print("refused:", e, flush=True)
"""


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("case", choices=["sleepy", "acrobot", "swimmer", "mountaincar"])
    parser.add_argument("budget")
    parser.add_argument("--out", default="/tmp/budget-call")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    out = f"{args.out}/{args.case}-{args.budget}-{args.seed}"
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, args.case, args.budget, out, str(args.seed)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
    )
    start, first, outcome, lines = None, None, "", []
    for line in child.stdout:
        now = time.monotonic()
        if start is None and line.startswith("call"):
            start = now  # The call begins once gpfd is imported.
            continue
        if start is None:
            continue
        if first is None:
            first = now - start
        print(f"{now - start:7.1f} s  {line.rstrip()[:300]}", flush=True)
        lines.append(line)
        if line.startswith(("finished", "refused:")):
            outcome = line.strip()
            wall = now - start
    child.wait()
    budget = 180.0 if args.budget == "default" else float(args.budget)
    summary = {
        "case": args.case,
        "budget": budget,
        "wall": round(wall, 1),
        "ratio": round(wall / budget, 3),
        "first_line": round(first, 1) if first is not None else None,
        "outcome": outcome[:400],
        "within": wall <= 1.1 * budget,
    }
    print(json.dumps(summary), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
