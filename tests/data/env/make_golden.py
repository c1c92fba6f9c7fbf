#!/usr/bin/env python3
"""Golden trajectories of Acrobot and cart-pole, computed from the equations of
docs/benchmarks.md alone (plain Python floats and the math module; no gpfd code).

Run from this folder:  python3 make_golden.py
It rewrites acrobot_golden.csv and cartpole_golden.csv. Every row holds the case name, the step,
the action as given (before clipping), the state after the step, the reward and the terminal flag;
step 0 holds the initial state. tests/env/test_golden.cpp replays each case through gpfd."""
import math

PI = math.pi


def clip(v, lo, hi):
    return min(max(v, lo), hi)


def wrap(x):
    while x > PI:
        x -= 2 * PI
    while x < -PI:
        x += 2 * PI
    return x


# --- Acrobot (Sutton & Barto; Gymnasium Acrobot-v1) ---------------------------------------------
def acrobot_rates(s, tau, book):
    m1 = m2 = 1.0
    l1 = 1.0
    lc1 = lc2 = 0.5
    i1 = i2 = 1.0
    g = 9.8
    th1, th2, w1, w2 = s
    d1 = m1 * lc1 ** 2 + m2 * (l1 ** 2 + lc2 ** 2 + 2 * l1 * lc2 * math.cos(th2)) + i1 + i2
    d2 = m2 * (lc2 ** 2 + l1 * lc2 * math.cos(th2)) + i2
    phi2 = m2 * lc2 * g * math.cos(th1 + th2 - PI / 2)
    phi1 = (-m2 * l1 * lc2 * w2 ** 2 * math.sin(th2) - 2 * m2 * l1 * lc2 * w2 * w1 * math.sin(th2)
            + (m1 * lc1 + m2 * l1) * g * math.cos(th1 - PI / 2) + phi2)
    extra = m2 * l1 * lc2 * w1 ** 2 * math.sin(th2) if book else 0.0
    a2 = (tau + d2 / d1 * phi1 - extra - phi2) / (m2 * lc2 ** 2 + i2 - d2 ** 2 / d1)
    a1 = -(d2 * a2 + phi1) / d1
    return [w1, w2, a1, a2]


def rk4(f, y, h):
    k1 = f(y)
    k2 = f([a + h / 2 * b for a, b in zip(y, k1)])
    k3 = f([a + h / 2 * b for a, b in zip(y, k2)])
    k4 = f([a + h * b for a, b in zip(y, k3)])
    return [a + h / 6 * (p + 2 * q + 2 * r + s) for a, p, q, r, s in zip(y, k1, k2, k3, k4)]


def euler(f, y, h):
    return [a + h * b for a, b in zip(y, f(y))]


def acrobot_case(name, params, start, actions):
    book = params["dynamics"] == "book"
    method = rk4 if params["integrator"] == "rk4" else euler
    h = params["dt"] / params["substeps"]
    rows = [(name, 0, "", start, "", "")]
    s = list(start)
    for t, a in enumerate(actions, 1):
        if params["actions"] == "discrete":
            tau = (a - 1) * params["max_torque"]
        else:
            tau = clip(a, -params["max_torque"], params["max_torque"])
        for _ in range(params["substeps"]):
            s = method(lambda y: acrobot_rates(y, tau, book), s, h)
            s = [wrap(s[0]), wrap(s[1]), clip(s[2], -4 * PI, 4 * PI), clip(s[3], -9 * PI, 9 * PI)]
        done = -math.cos(s[0]) - math.cos(s[1] + s[0]) > 1.0
        rows.append((name, t, a, s, 0.0 if done else -1.0, int(done)))
        if done:
            break
    return rows


# --- Cart-pole (Barto et al. 1983; Gymnasium CartPole-v1) ---------------------------------------
def cartpole_rates(s, force, gravity):
    mc, mp, l = 1.0, 0.1, 0.5
    total = mc + mp
    x, v, th, w = s
    temp = (force + mp * l * w ** 2 * math.sin(th)) / total
    acc_th = (gravity * math.sin(th) - math.cos(th) * temp) / (
        l * (4.0 / 3.0 - mp * math.cos(th) ** 2 / total))
    acc_x = temp - mp * l * acc_th * math.cos(th) / total
    return [v, acc_x, w, acc_th]


def cartpole_case(name, params, start, actions):
    method = rk4 if params["integrator"] == "rk4" else euler
    h = params["dt"] / params["substeps"]
    rows = [(name, 0, "", start, "", "")]
    s = list(start)
    limit = 12 * 2 * PI / 360
    for t, a in enumerate(actions, 1):
        if params["actions"] == "discrete":
            force = params["max_force"] if a == 1 else -params["max_force"]
        else:
            force = clip(a, -params["max_force"], params["max_force"])
        for _ in range(params["substeps"]):
            s = method(lambda y: cartpole_rates(y, force, params["gravity"]), s, h)
        done = abs(s[0]) > 2.4 or abs(s[2]) > limit
        rows.append((name, t, a, s, 1.0, int(done)))
        if done:
            break
    return rows


def write(path, rows):
    with open(path, "w") as f:
        f.write("case,step,action,s0,s1,s2,s3,reward,terminated\n")
        for name, t, a, s, r, done in rows:
            f.write(",".join([name, str(t), repr(a) if a != "" else ""] + [repr(v) for v in s]
                             + [repr(r) if r != "" else "", str(done)]) + "\n")


def wave(n, scale, period=7.0, phase=0.3):
    # A deterministic action sequence that also leaves the bounds (to exercise clipping).
    return [scale * math.sin(2 * PI * t / period + phase) for t in range(n)]


if __name__ == "__main__":
    A = dict(dynamics="book", integrator="rk4", dt=0.2, substeps=1, max_torque=1.0,
             actions="continuous")
    rows = []
    rows += acrobot_case("book_rk4", A, [0.05, -0.03, 0.02, -0.01], wave(40, 1.5))
    rows += acrobot_case("nips_rk4", dict(A, dynamics="nips"), [0.05, -0.03, 0.02, -0.01],
                         wave(40, 1.5))
    rows += acrobot_case("book_euler4", dict(A, integrator="euler", substeps=4),
                         [0.05, -0.03, 0.02, -0.01], wave(40, 1.5))
    rows += acrobot_case("discrete_rk4", dict(A, actions="discrete"), [0.0, 0.0, 0.0, 0.0],
                         [t % 3 for t in range(40)])
    # Fast start: velocity clipping and angle wrapping on the first steps.
    rows += acrobot_case("clip_wrap", A, [3.0, -3.0, 12.0, -27.0], wave(10, 1.0))
    # Near the goal: ends on a terminal step.
    rows += acrobot_case("terminal", A, [2.6, 0.3, 2.0, 1.0], [1.0] * 20)
    write("acrobot_golden.csv", rows)

    C = dict(gravity=9.8, integrator="euler", dt=0.02, substeps=1, max_force=10.0,
             actions="continuous")
    rows = []
    rows += cartpole_case("gym_euler", C, [0.01, -0.02, 0.03, -0.04], wave(60, 12.0, 11.0))
    rows += cartpole_case("clsquare_rk4", dict(C, gravity=9.81, integrator="rk4", substeps=10),
                          [0.01, -0.02, 0.03, -0.04], wave(60, 12.0, 11.0))
    rows += cartpole_case("discrete", dict(C, actions="discrete"), [0.0, 0.0, 0.0, 0.0],
                          [1, 1, 0, 1, 0, 0] * 10)
    rows += cartpole_case("fall", C, [0.0, 0.0, 0.1, 0.5], [10.0] * 200)
    write("cartpole_golden.csv", rows)
