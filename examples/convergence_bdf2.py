"""Convergence order of BDF2 against the exact event-driven solution, under rectangular pulses.

What it shows
-------------
A rigid block (mass 10, rotational inertia 5) on two tensionless soil springs at ``x = -1`` and
``x = +1`` (k = 1e5, soil dashpots attached, c = 200), assembled from its natural form with
:meth:`unilateral.Model.from_natural`. Under its weight, three rectangular pulses rock it onto
one edge, throw it into the air with a twist, and rock it onto the other edge: repeated lift-off
and re-contact and an airborne phase. The pulse edges fall between grid points for every step.

The reference is ``method="event"`` (exact integration between contact changes, events located
by root finding) on the finest grid; the CLCP of Liolios (``method="cq"``, BDF2) is solved at
``dt = 2e-3 ... 2.5e-4``. The error is the largest deviation over the whole run of the
displacements ``u``, the openings ``v`` and the reactions ``psi``, each relative to its largest
value; the order is the slope of a least-squares fit of ``log(error)`` against ``log(dt)``.

What it prints
--------------
The events of the reference (how many lift-offs and closures), a table of the errors per step,
and the fitted orders, about 2 for all three (the last line, ``orders u v psi: ...``, is what
``tests/test_examples.py`` checks). The loads are sampled by hat averages (what ``solve`` does
with a ``LoadHistory``), which keeps second order across pulse edges anywhere.

Run: ``python examples/convergence_bdf2.py`` (a few seconds).
"""

import numpy as np

import unilateral as ul
from unilateral.loads import LoadHistory, Rectangular

m, inertia, k, c, b, g = 10.0, 5.0, 1e5, 200.0, 1.0, 10.0
W = m * g
G = np.array([[1.0, 1.0], [-b, b]])                 # strains of the springs from u = (y, theta)
model = ul.Model.from_natural(G, k * np.eye(2), np.eye(2), M=np.diag([m, inertia]), C=c * G @ G.T)
load = LoadHistory([-W, 0.0], [
    ([0.0, 1.0], Rectangular(1.3 * W * b, t_start=0.0113, t_end=0.1237)),    # rock onto the right edge
    ([1.0, 0.3], Rectangular(1.6 * W, t_start=0.3031, t_end=0.3717)),        # a jump with a twist
    ([0.0, 1.0], Rectangular(-1.3 * W * b, t_start=0.6071, t_end=0.7093))])  # rock onto the left edge

DTS = (2e-3, 1e-3, 5e-4, 2.5e-4)
T_END = 1.0
ref = ul.solve(model, load, dt=DTS[-1], t_end=T_END, method="event")
assert ref.success, ref.message
kinds = list(ref.stats["event_kinds"])
print(f"reference (method='event', dt = {DTS[-1]:g}): {kinds.count('open')} lift-offs, "
      f"{kinds.count('close')} closures, airborne: {bool(np.any(np.all(ref.v > 0, axis=1)))}")

errors = []
print(f"{'dt':>8} {'error u':>10} {'error v':>10} {'error psi':>10}")
for dt in DTS:
    every = int(round(dt / DTS[-1]))
    sol = ul.solve(model, load, dt=dt, t_end=T_END, method="cq", rule="bdf2")
    assert sol.success, sol.message
    err = [np.abs(sol.u - ref.u[::every]).max() / np.abs(ref.u).max(),
           np.abs(sol.v - ref.v[::every]).max() / ref.v.max(),
           np.abs(sol.psi - ref.psi[::every]).max() / np.abs(ref.psi).max()]
    errors.append(err)
    print(f"{dt:8.2e} {err[0]:10.2e} {err[1]:10.2e} {err[2]:10.2e}")
errors = np.array(errors)
orders = [np.polyfit(np.log(DTS), np.log(errors[:, j]), 1)[0] for j in range(3)]
print("orders u v psi: " + " ".join(f"{p:.2f}" for p in orders))
