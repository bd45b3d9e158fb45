"""A three-storey tower rocking on tensionless soil: method="auto", internal forces and energy.

What it shows
-------------
A :class:`unilateral.structure.Frame2D` model: a cantilever tower of three storeys (3 m each,
floor masses 20 t) on a rigid massless foundation 6 m wide that rests on three tensionless soil
elements (spring 150 MN/m and dashpot 1.5 MN s/m in parallel, acting only in contact) under its
edges and centre. Gravity first, then a horizontal half-sine pulse of 100 kN on every floor for
0.2 s rocks the tower and lifts the foundation's left edge. Units: kN, m, s (mass kN s^2/m = t).

``unilateral.solve(..., method="auto")`` picks the method and says why (``stats["method"]``,
``stats["method_reason"]``). The structure's results are then read off the solution with
:func:`unilateral.analysis.results.structure_results` (as ``unilateral run`` writes them to
``results.nc``): element end forces (``structure/forces.py``: ``N, V, M`` on the element ends in
local axes), base shear, vertical base force and overturning moment, and the energy balance.

What it prints
--------------
The method chosen and why, the peak uplift of the left edge, the peak bending moment at the base
of the tower and the peak base shear and overturning moment with their times, two checks of
equilibrium (the vertical base force at t = 0 against the weight, and ``max |base shear - sum of
the horizontal inertia and applied forces|`` over the run), and the relative error of the energy
balance. ``tests/test_examples.py`` checks the last three lines.

Run: ``python examples/rocking_tower.py`` (a few seconds).
"""

import numpy as np

import unilateral as ul
from unilateral.analysis.results import structure_results
from unilateral.loads import HalfSine
from unilateral.structure import Frame2D

STOREY, FLOORS, MASS, HALF_WIDTH, G = 3.0, 3, 20.0, 3.0, 9.81
fr = Frame2D()
fr.node("base", 0.0, 0.0)
fr.node("left", -HALF_WIDTH, 0.0)
fr.node("right", HALF_WIDTH, 0.0)
fr.support("base", ux=True, uy=False)              # the foundation does not slide
fr.rigid_link("base", "left")                      # the foundation is rigid
fr.rigid_link("base", "right")
below = "base"
for floor in range(1, FLOORS + 1):
    fr.node(floor, 0.0, floor * STOREY)
    fr.beam(f"column{floor}", below, floor, E=30e6, A=0.5, I=0.04)     # kN/m^2, m^2, m^4
    fr.mass(floor, MASS)
    below = floor
for node in ("left", "base", "right"):
    fr.soil(f"soil_{node}", node, k=150e3, c=1.5e3)
structure = fr.build()
model = structure.to_model()

push = sum(structure.nodal_load(floor, ux=100.0) for floor in range(1, FLOORS + 1))
load = ul.LoadHistory(structure.gravity(G), [(push, HalfSine(1.0, duration=0.2))])
dt, rule = 1e-3, "bdf2"
sol = ul.solve(model, load, dt=dt, t_end=1.0, method="auto", rule=rule)
assert sol.success, sol.message
print(f"method: {sol.stats['method']} ({sol.stats['method_reason']})")
uplift = sol.v[:, structure.constraint_names.index("soil_left")]
print(f"peak uplift of the left edge: {1e3 * uplift.max():.3f} mm at t = {sol.t[uplift.argmax()]:.3f} s")

q, _ = load.grid_samples(dt, len(sol.t) - 1)       # the load the run used at the steps (N+1, n)
res = structure_results(structure, model, {"unilateral": sol}, rule=rule, load_samples=q,
                        point=(0.0, 0.0), units={"length": "m", "force": "kN", "time": "s"})
var = {name: values["unilateral"] for name, (_, values, _) in res["variables"].items()}
elements = list(res["coords"]["element"])
M_base = var["end_force"][:, elements.index("column1"), 2]     # M_i: moment on column1 at its foot
k = np.abs(M_base).argmax()
print(f"peak bending moment at the foot of the tower: {abs(M_base[k]):.1f} kN m at t = {sol.t[k]:.3f} s")
for name, unit in (("base_shear", "kN"), ("overturning_moment", "kN m")):
    y = var[name]
    k = np.abs(y).argmax()
    print(f"peak {name.replace('_', ' ')}: {y[k]:.1f} {unit} at t = {sol.t[k]:.3f} s")

weight = FLOORS * MASS * G
print(f"equilibrium at t = 0: vertical base force {var['base_vertical'][0]:.6f} kN, weight {weight:.6f} kN")
# base shear = r^T M u'' - r^T q (no damping in C): the horizontal inertia and the applied forces
r = structure.influence("ux")
accel = var["acceleration"]
residual = var["base_shear"] - (accel @ (structure.M @ r) - q @ r)
print(f"equilibrium over the run: max |base shear - (r^T M u'' - r^T q)| = {np.abs(residual).max():.2e} kN")
print(f"energy balance: largest relative error {var['energy_relative_error'].max():.2e}")
