"""Newmark's sliding block: Coulomb friction as a rate-type constraint family, against the closed form.

What it shows
-------------
A rigid block of mass ``m`` rests on a horizontal plane with friction coefficient ``mu``. The base
accelerates by ``a > mu g`` for ``t_p`` seconds (towards +x), and the block slides back relative
to the base until friction stops it (Newmark 1965). The permanent slip is

    d = (a - mu g) t_p^2 / 2 + ((a - mu g) t_p)^2 / (2 mu g).

The block is written at matrix level as the reduced problem with three constraint unknowns and
two constraint families (:mod:`unilateral.constraints`): a normal contact (the paper's unilateral
contact, a stiff spring ``kN`` that only pushes) and a Coulomb slip pair (``s+``, ``s-``: rate-type
multipliers on a stiff tangential stick spring ``kt``, limited by ``|T| <= mu N``). Every step is
one LCP with the same matrix ``W0`` as the contact problem; its friction rows ``+-T - mu N`` make it
nonsymmetric. The run uses ``method="direct"`` (compiled) with BDF2; ``cq`` and ``modal`` give the
same discrete solution.

What it prints
--------------
The closed-form slip (0.519 m), the computed slip and its relative error at ``dt`` = 1e-3, 1e-4 and
1e-5 s (about 1.9e-3, 1.9e-4, 3e-5: first order, from the stick-slip transitions), the time at which
the block stops (1.02 s closed form), and the last line ``slip error ...`` that
``tests/test_examples.py`` reads. It writes ``sliding_block.png`` (slip and relative velocity
against time) in the working directory.

Run: ``python examples/sliding_block.py`` (about two seconds).
"""

import numpy as np

import unilateral as ul
from unilateral.constraints import Contact, Friction

m, g, mu = 1000.0, 9.81, 0.2            # kg, m/s^2, -
a, t_p = 4.0, 0.5                       # base acceleration (m/s^2) and its duration (s)
kN, kt = 1e11, 1e13                     # normal and tangential (stick) stiffness, N/m

# DOFs (ux, uy) of the block relative to the base; strains: 0 tangential spring, 1 normal spring;
# unknowns: 0 the normal opening v (contact), 1 and 2 the slips s+ and s- (friction).
model = ul.Model.from_natural(
    G=np.eye(2), E=np.diag([kt, kN]), B=[[0.0, 1.0, -1.0], [1.0, 0.0, 0.0]], M=m * np.eye(2),
    C=np.diag([0.0, 2 * 0.05 * np.sqrt(kN * m)]),
    families=[Contact([0]), Friction([1, 2], normal=[0, 0], mu=mu)],
    dof_names=["ux", "uy"], constraint_names=["contact", "slip+", "slip-"])
# gravity, and the base acceleration as the inertia load -m a(t) on the relative motion
load = ul.LoadHistory([0.0, -m * g], [([-m, 0.0], ul.loads.Rectangular(a, t_end=t_p))])

exact = (a - mu * g) * t_p ** 2 / 2 + ((a - mu * g) * t_p) ** 2 / (2 * mu * g)
t_stop = t_p + (a - mu * g) * t_p / (mu * g)
print(f"closed form: permanent slip {exact:.6f} m, block stops at t = {t_stop:.4f} s")
for dt in (1e-3, 1e-4, 1e-5):
    sol = ul.solve(model, load, dt=dt, t_end=1.3, method="direct", rule="bdf2")
    assert sol.success, sol.message
    slip = sol.v[:, 2] - sol.v[:, 1]              # towards -x: s- grows
    moving = np.flatnonzero(np.abs(np.diff(slip)) > 1e-12)
    print(f"dt = {dt:.0e} s: slip {slip[-1]:.6f} m, relative error {(slip[-1] - exact) / exact:+.2e}, "
          f"stops at t = {sol.t[moving[-1] + 1]:.4f} s")
error = abs(slip[-1] - exact) / exact
print(f"slip error {error:.3e} at dt = 1e-05")

from matplotlib.figure import Figure  # noqa: E402  (the figure only)

fig = Figure(figsize=(7, 3.2), layout="constrained")
ax1, ax2 = fig.subplots(1, 2)
ax1.plot(sol.t, slip, label="computed")
ax1.axhline(exact, color="k", ls=":", label="closed form")
ax1.set(xlabel="time [s]", ylabel="slip [m]", title="Permanent slip")
ax1.legend()
ax2.plot(sol.t, -sol.udot[:, 0])
ax2.set(xlabel="time [s]", ylabel="sliding velocity [m/s]", title="Relative velocity")
fig.savefig("sliding_block.png", dpi=110)
