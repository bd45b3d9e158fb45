"""Housner's rocking block: rigid contacts (H = 0) and a rigid block built by ``Frame2D.rigid_block``.

What it shows
-------------
A rigid rectangular block (width 2b = 0.4 m, height 2h = 1.2 m, mass 1 t; kN, m, s) stands on its
two base corners, each a rigid unilateral contact with the ground (no compliance: a column of
``F`` with ``H = 0``, its unknown the contact force, its row the opening:
:mod:`unilateral.structure.rigid`). Its base cannot slide (the base node's ``ux`` is supported)
and the weight's second-order term ``-W h`` on the rotation gives the linearised rocking equation
``I0 theta'' = W (h theta - b)`` about the pivot corner (``docs/rocking.md``).

Released at rest from the tilt theta0 = 0.05 rad, it rocks freely; each impact on the other corner
loses energy. Housner's ratio of the angular velocities after/before an impact (angular momentum
about the new corner conserved) is ``r = 1 - 2 m b^2 / I0 = 1 - 3/2 sin^2 alpha = 0.85``, and the
first impact of the linearised equation is at ``t1 = acosh((b/h) / (b/h - theta0)) / p``.
The run uses ``method="direct"`` with BDF1 (the position-level impact of BDF1 is perfectly
plastic: Moreau's sweeping process as dt -> 0), the consistent initial contact force
(:func:`~unilateral.structure.rigid.initial_forces`), at dt = 1e-3, 2.5e-4 and 6.25e-5 s.
Then the block at rest on a base shaken at 0.9 and 1.5 times the uplift acceleration ``g b / h``.

What it prints
--------------
For each dt: every impact's time (against the linearised Housner sequence,
:meth:`~unilateral.structure.rigid.RigidBlock.impact_times`) and measured ratio (from the block's energy before and after,
:func:`~unilateral.structure.rigid.impacts`) against Housner's r, and the error of the first
impact time (about -5.5e-4, -1.4e-4, -3.5e-5 s: first order). The shaken block: its peak
rotation (0 below the threshold, to round-off) and the number of contact changes. Between the
two, the same free rocking by ``method="moreau-jean"`` (Newton's impact law with ``e = 0`` at the
velocity level, each impact located within its step): the impact times to second order (first
impact -1.6e-7, -1.0e-8, -6.3e-10 s at dt = 1e-3, 2.5e-4, 6.25e-5) and Housner's ratio at every
impact to round-off.
``--quick``: the coarsest dt only.

Run: ``python examples/rocking_block.py`` (a few seconds).
"""

import sys

import numpy as np

import unilateral as ul
from unilateral.loads import LoadHistory, Tabulated
from unilateral.structure import Frame2D, rigid

THETA0 = 0.05


def build():
    """The block: ``(structure, model, block)``."""
    fr = Frame2D()
    fr.node("centre", 0.0, 0.6)
    block = fr.rigid_block("block", "centre", width=0.4, height=1.2, mass=1.0)
    structure = fr.build()
    return structure, structure.to_model(), block


def free_rocking(dt, t_end=1.2):
    """Released from THETA0 on the right corner: the impacts of the BDF1 solution."""
    st, model, block = build()
    u0 = np.array([block.b * THETA0, -THETA0])               # base uy, rz: the left corner lifted
    q = st.gravity(block.g)
    v0 = rigid.initial_forces(model, u0, q)                   # the right corner carries the block
    sol = ul.solve(model, LoadHistory(q), dt=dt, t_end=t_end, method="direct", rule="bdf1",
                   initial={"u0": u0, "v0": v0})
    assert sol.success, sol.message
    return rigid.impacts(st, sol, "block"), block


def shaken(factor, dt=1e-3, t_end=1.0):
    """At rest on a base shaken at ``factor`` times the uplift acceleration, 2 Hz: the solution."""
    st, model, block = build()
    q = st.gravity(block.g)
    t = np.linspace(0.0, t_end, 2001)
    a_g = Tabulated(t, factor * block.uplift_acceleration * np.sin(2 * np.pi * 2.0 * t))
    v0 = rigid.initial_forces(model, np.zeros(model.n), q)
    sol = ul.solve(model, LoadHistory(q, [rigid.ground_motion(st, a_g)]), dt=dt, t_end=t_end,
                   method="direct", rule="bdf1", initial={"u0": np.zeros(model.n), "v0": v0})
    assert sol.success, sol.message
    return sol


def main(quick=False):
    _, _, block = build()
    t1 = block.first_impact_time(THETA0)
    print(f"block 2b x 2h = {2 * block.b:g} x {2 * block.h:g} m, I0 = {block.I0:.6f} t m^2, "
          f"p = {block.p:.6f} rad/s, Housner r = {block.restitution:.6f}, first impact t1 = {t1:.6f} s")
    for dt in (1e-3,) if quick else (1e-3, 2.5e-4, 6.25e-5):
        impacts, _ = free_rocking(dt)
        exact = block.impact_times(THETA0, len(impacts))
        print(f"dt = {dt:.3g} s: first impact error {impacts[0]['time'] - t1:+.3e} s")
        for k, (imp, te) in enumerate(zip(impacts, exact), 1):
            print(f"  impact {k}: t = {imp['time']:.6f} s (Housner {te:.6f}), ratio {imp['ratio']:.6f} "
                  f"(Housner {block.restitution:.6f}, error {imp['ratio'] - block.restitution:+.2e})")
    st, model, block = build()
    for dt in (1e-3,) if quick else (1e-3, 2.5e-4, 6.25e-5):          # the velocity-level impact law
        sol = ul.solve(model, LoadHistory(st.gravity(block.g)), dt=dt, t_end=1.2, method="moreau-jean",
                       rule="trapezoidal", initial={"u0": np.array([block.b * THETA0, -THETA0])})
        impacts = sol.stats["impacts"]
        ratios = ", ".join(f"{ev['udot_after'][1] / ev['udot_before'][1]:.12f}" for ev in impacts[:5])
        print(f"moreau-jean (trapezoidal, Newton e = 0, impacts located), dt = {dt:.3g} s: first impact error "
              f"{impacts[0]['time'] - t1:+.3e} s, ratios {ratios} (Housner {block.restitution:.6f})")
    for factor in (0.9, 1.5):
        sol = shaken(factor)
        print(f"base shaken at {factor:g} g b/h: peak rotation {np.abs(sol.u[:, 1]).max():.3e} rad, "
              f"{sol.stats['contact_changes']} contact changes")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv[1:])
