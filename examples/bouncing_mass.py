"""A mass bouncing on a tensionless spring, at matrix level, against the exact event-driven solution.

What it shows
-------------
The one-mass model of the README: a mass ``m`` on a spring ``k`` that carries compression only,
under gravity, thrown upwards from its static position with ``u'(0) = 1 m/s``. It is written
directly as the reduced problem of Liolios (1990),

    M u'' + K u = q + F v,   psi = F^T u - H v,   psi <= 0, v >= 0, psi^T v = 0,

with ``M = m, K = F = H = k`` (``psi = k (u - v)`` is the spring force, ``v`` the uplift), and
solved by ``method="event"``, which integrates exactly between contact changes and locates
lift-off by root finding, and by convolution quadrature (``method="cq"``, BDF2) at two time steps.
Both are compared with the closed form up to just before the landing: a harmonic oscillation
about the static position ``u_s = -m g / k`` while in contact, lift-off at ``u = 0`` with
``u'^2 = u'(0)^2 - (k/m) u_s^2`` (energy), then free flight, ``v = u``.

What it prints
--------------
The lift-off time and the peak uplift of the closed form (0.045 m), the largest difference
between ``method="event"`` and the closed form at the output times (round-off), the largest
error of CQ/BDF2 at ``dt = 1e-3`` and ``5e-4`` (about 1e-5 m) and the order observed between
them (1.3 at these steps: the uplift ``v`` has a kink at lift-off, where ``v'`` jumps from 0 to
0.95 m/s; ``examples/convergence_bdf2.py`` measures the order over a finer sequence), and the last
line ``event error ...`` that ``tests/test_examples.py`` reads.

Run: ``python examples/bouncing_mass.py`` (about a second).
"""

import numpy as np

import unilateral as ul

m, k, g = 2.0, 2000.0, 10.0             # kg, N/m, m/s^2
u_static = -m * g / k                   # static position (spring compressed), m
velocity0 = 1.0                         # thrown upwards, m/s
t_end = 0.19                            # the mass lands at t = 0.1999 s

model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])           # psi = k (u - v)
load = ul.LoadHistory(np.array([-m * g]), [])                 # gravity, constant in time
initial = {"u0": [u_static], "udot0": [velocity0]}

# the closed form
omega = np.sqrt(k / m)
liftoff = np.arcsin(-u_static * omega / velocity0) / omega
liftoff_velocity = np.sqrt(velocity0**2 - omega**2 * u_static**2)


def exact(t):
    """Displacement u (m) and uplift v (m) of the closed form at times t (before the landing)."""
    t = np.asarray(t, dtype=float)
    contact = u_static + velocity0 / omega * np.sin(omega * t)
    tau = t - liftoff
    flight = liftoff_velocity * tau - 0.5 * g * tau**2
    u = np.where(t <= liftoff, contact, flight)
    return u, np.where(t <= liftoff, 0.0, flight)


print(f"closed form: lift-off at t = {liftoff:.9f} s, peak uplift {liftoff_velocity**2 / (2 * g):.9f} m")

event = ul.solve(model, load, dt=1e-3, t_end=t_end, method="event", initial=initial)
assert event.success, event.message
u_ex, v_ex = exact(event.t)
event_error = max(np.abs(event.u[:, 0] - u_ex).max(), np.abs(event.v[:, 0] - v_ex).max())
print(f"method=event: first event at t = {event.stats['event_times'][0]:.9f} s, "
      f"largest |u - u_exact|, |v - v_exact| = {event_error:.1e} m")

errors = []
for dt in (1e-3, 5e-4):
    sol = ul.solve(model, load, dt=dt, t_end=t_end, method="cq", rule="bdf2", initial=initial)
    assert sol.success, sol.message
    u_ex, v_ex = exact(sol.t)
    error = max(np.abs(sol.u[:, 0] - u_ex).max(), np.abs(sol.v[:, 0] - v_ex).max())
    errors.append(error)
    print(f"method=cq, BDF2, dt = {dt:g} s: peak uplift {sol.v.max():.6f} m, largest error {error:.2e} m, "
          f"largest LCP error {sol.stats['max_lcp_error']:.1e}")
print(f"observed order of BDF2: {np.log2(errors[0] / errors[1]):.2f}")
print(f"event error {event_error:.1e}")
