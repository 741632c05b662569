#!/usr/bin/env python3
"""Reference implementation of the Cross (2010) ball-on-cart model with scipy's solve_ivp, for the speed
comparison of issue 4 (snapback must be at least 1000 times faster per bounce). A measurement script, not
a test: `python3 benches/scipy_reference.py` (needs numpy and scipy).

Same model as snapback's core: N(t) = N0 sin(pi t/T), N0 = (1 + e_y) pi m v_y1 / (2T).
Sliding (Eqs. 1-3): F = dir mu N on the ball (positive backward), m dvx/dt = -F, I domega/dt = F r,
M dV/dt = F - k X. Gripping (Eqs. 4-6): F_s = k m_eff X / (M + m_eff), m_eff = m alpha / (1 + alpha).
A slide ends when the slip vx - r omega - V reaches zero (terminal event); the ball then grips if
|F_s| <= mu N, else slides the other way. A grip ends when |F_s| reaches mu N (terminal event); the ball
then slides with the friction in the direction of F_s. Integrated with DOP853, rtol 1e-12.
"""

import math
import time

import numpy as np
from scipy.integrate import solve_ivp


def bounce(angle_deg=60.0, speed=10.0, spin=-100.0, mu=0.4, duration=5e-3, ey=1.0,
           mass=0.057, radius=0.033, alpha=0.55, cart_mass=0.010, stiffness=15000.0):
    m, r, M, k, T = mass, radius, cart_mass, stiffness, duration
    inertia = alpha * m * r * r
    m_eff = m * alpha / (1.0 + alpha)
    grip_gain = k * m_eff / (M + m_eff)
    w = math.pi / T
    theta = math.radians(angle_deg)
    vx1, vy1 = speed * math.cos(theta), speed * math.sin(theta)
    n0 = (1.0 + ey) * math.pi * m * vy1 / (2.0 * T)

    def normal(t):
        return n0 * math.sin(w * t)

    def slide_rhs(direction):
        def rhs(t, y):
            vx, omega, x, v = y
            f = direction * mu * normal(t)
            return [-f / m, f * r / inertia, v, (f - k * x) / M]
        return rhs

    def grip_rhs(t, y):
        vx, omega, x, v = y
        f = grip_gain * x
        return [-f / m, f * r / inertia, v, (f - k * x) / M]

    def slip(t, y):
        return y[0] - r * y[1] - y[3]

    def grip_margin(t, y):
        return abs(grip_gain * y[2]) - mu * normal(t)

    grip_margin.terminal = True
    grip_margin.direction = 1.0

    options = dict(method="DOP853", rtol=1e-12, atol=1e-12)
    t, y = 0.0, np.array([vx1, spin, 0.0, 0.0])
    phases = []
    s0 = slip(t, y)
    mode, direction = ("slide", math.copysign(1.0, s0))
    while t < T * (1.0 - 1e-12):
        if mode == "slide":
            def slip_event(tt, yy, d=direction):
                return d * slip(tt, yy)
            slip_event.terminal = True
            slip_event.direction = -1.0
            sol = solve_ivp(slide_rhs(direction), (t, T), y, events=slip_event, **options)
        else:
            sol = solve_ivp(grip_rhs, (t, T), y, events=grip_margin, **options)
        phases.append(mode)
        t, y = sol.t[-1], sol.y[:, -1]
        if sol.status != 1:
            break
        t, y = sol.t_events[0][0], sol.y_events[0][0]
        if mode == "slide":
            f_static = grip_gain * y[2]
            if abs(f_static) <= mu * normal(t):
                mode = "grip"
            else:
                direction = math.copysign(1.0, f_static)
        else:
            mode, direction = "slide", (-1.0 if y[2] < 0 else 1.0)
    vx2, omega2 = y[0], y[1]
    ex = -(vx2 - r * omega2) / (vx1 - r * spin)
    return omega2, vx2, ex, "-".join(phases)


def main():
    omega2, vx2, ex, phases = bounce()
    print(f"Fig. 3(c): omega2 = {omega2:.6f} rad/s, vx2 = {vx2:.6f} m/s, e_x = {ex:.6f}, phases {phases}")
    runs = 50
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        bounce()
        times.append(time.perf_counter() - start)
    times.sort()
    print(f"solve_ivp DOP853 rtol 1e-12, per bounce over {runs} runs: "
          f"min {times[0] * 1e3:.3f} ms, median {times[runs // 2] * 1e3:.3f} ms")


if __name__ == "__main__":
    main()
