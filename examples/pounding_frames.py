"""Pounding of two frames across a seismic joint: relative displacement against the gap.

What it shows
-------------
``examples/pounding.toml`` read from Python (:func:`unilateral.modelfile.load_model_file`): a one-
storey frame and a two-storey frame 40 mm apart, shaken by a synthetic 0.35 g record, with a
compression-only contact spring (1 GN/m) across the joint at the first floor (a gap element:
it engages once the 40 mm clearance has closed). The run is solved by ``method="auto"`` for the
first 3 s of the record, and the relative displacement across the joint, ``e = ux(7) - ux(4)``
(opening positive), is compared with the gap: the frames are in contact exactly when ``e`` reaches
``-gap``, and then the contact force is ``k (gap + e)`` (the spring is compressed by the overlap).

What it prints
--------------
The method chosen, the number of impacts (contact phases) with the start time, duration and peak
force of each, the closest approach ``min(e)`` against ``-gap``, and the largest difference between
the contact force ``-psi`` and ``k max(0, -(gap + e))``, an identity of the gap element (round-off)
that ``tests/test_examples.py`` checks, as it does the number of impacts.

Run: ``python examples/pounding_frames.py`` (a few seconds).
"""

from pathlib import Path

import numpy as np

import unilateral as ul
from unilateral.modelfile import load_model_file

HERE = Path(__file__).resolve().parent
spec = load_model_file(HERE / "pounding.toml")
structure, model = spec.structure, spec.model
joint = spec.document.unilateral[0]                  # the gap element of the model file
gap, k = joint.gap, joint.k
sol = ul.solve(model, spec.load, dt=spec.analysis["dt"], t_end=3.0, method="auto", rule=spec.analysis["rule"])
assert sol.success, sol.message
print(f"method: {sol.stats['method']}; {len(sol.t) - 1} steps of {spec.analysis['dt']:g} s")

i = structure.constraint_names.index(joint.name)
e, _ = structure.element_deformations(sol.u, sol.v)
e = e[:, i]                                          # relative displacement across the joint, m
force = -sol.psi[:, i]                               # contact force, kN (compression positive)
contact = force > 1e-9 * k * gap
starts = np.flatnonzero(np.diff(contact.astype(int)) == 1) + 1
ends = np.flatnonzero(np.diff(contact.astype(int)) == -1) + 1
print(f"impacts: {len(starts)}")
for s, f in zip(starts, ends):
    print(f"  t = {sol.t[s]:.3f} s, {1e3 * (sol.t[f] - sol.t[s]):.0f} ms, peak force {force[s:f].max():.0f} kN")
print(f"closest approach: min e = {1e3 * e.min():.3f} mm against -gap = {-1e3 * gap:.1f} mm "
      f"(overlap {1e3 * max(0.0, -(gap + e.min())):.3f} mm)")
identity = np.abs(force - k * np.maximum(0.0, -(gap + e))).max()
print(f"contact force against k * overlap: largest difference {identity:.2e} kN")
