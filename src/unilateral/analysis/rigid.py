"""Results of rigid contacts and rigid blocks: the energy balance with the energy lost at impacts,
contact forces and impulses, the uplift, rotation and overturning of a block.

The energy of a run of ``method="moreau-jean"`` (:mod:`unilateral.march.impact`):

    (T - T_0) + (V - V_0) + D_damping + L_impact + D_numerical = W_in

* ``T = u'^T M u' / 2`` kinetic energy, ``V = u^T K u / 2`` the potential of ``K`` (the elements,
  and for a block the second-order term of its weight, ``-W h theta^2 / 2``);
* ``W_in``: the work of the loads (gravity, ``-M r a_g``), ``h q(t + th h)^T u'_th`` per step;
* ``D_damping = sum h u'_th^T C u'_th``;
* ``L_impact``: the energy lost at impacts, ``-P^T N^T (v+ + v-) / 2`` at each located impact
  (``(1 - e^2)`` times the normal kinetic energy ``(N^T v-)^2 / (2 N^T M^-1 N)`` on one contact)
  and ``-P^T N^T u'_th`` in a step (zero for a persistent contact);
* ``D_numerical = (th - 1/2) sum (dv^T M dv + du^T K du)``: zero for ``rule="trapezoidal"``.

The march accumulates the terms as it steps, so the balance closes to round-off whatever the step
(``balance_error``); the relative error is over the largest energy of the run.
"""

from __future__ import annotations

import math

import numpy as np

from ..linalg import dense


def energy_balance(model, sol) -> dict:
    """Energies (N+1,) of a run of ``method="moreau-jean"`` and the residual of their balance.

    Parameters
    ----------
    model : the Model solved (rigid contacts only);  sol : its Solution

    Returns
    -------
    dict of (N+1,) arrays (force length): ``kinetic``, ``potential``, ``input_work``,
    ``damping_dissipated``, ``impact_loss``, ``numerical_dissipation``, ``friction_work`` (the work
    dissipated by Coulomb friction on the rigid contacts while they slide), ``balance_error``
    (``W_in - dT - dV - D - L``), and the float ``relative_error`` (the largest ``|balance_error|``
    over the largest energy of the run)
    """
    energy = sol.stats.get("energy")
    if energy is None:
        raise ValueError(f"energy_balance: the solution has no stats['energy'] (method="
                         f"{sol.stats.get('method')!r}); it is recorded by method='moreau-jean'")
    M, K = dense(model.M), dense(model.K)
    T = 0.5 * np.einsum("ki,ij,kj->k", sol.udot, M, sol.udot)
    V = 0.5 * np.einsum("ki,ij,kj->k", sol.u, K, sol.u)
    out = {"kinetic": T, "potential": V, "input_work": energy["external_work"],
           "damping_dissipated": energy["damping"], "impact_loss": energy["impact_loss"],
           "numerical_dissipation": energy["numerical_dissipation"],
           "friction_work": energy.get("friction_work", np.zeros_like(T))}
    out["balance_error"] = (out["input_work"] - (T - T[0]) - (V - V[0]) - out["damping_dissipated"]
                            - out["impact_loss"] - out["numerical_dissipation"] - out["friction_work"])
    scale = max(float(np.max(np.abs(x), initial=0.0)) for x in
                (T, V - V[0], out["input_work"], out["impact_loss"], out["damping_dissipated"]))
    out["relative_error"] = float(np.max(np.abs(out["balance_error"]))) / (scale or 1.0)
    return out


def contact_results(sol, names=None) -> dict:
    """Per rigid contact: ``force`` (N+1,) the mean contact force of each step (force),
    ``impulse`` (N+1,) the impulse of each step (force time; moreau-jean only, else ``force dt``),
    ``opening`` (N+1,) (length) and ``impacts`` (the located impacts on it: time, impulse, normal
    velocity before and after, energy lost)."""
    names = list(sol.constraint_names) if names is None else list(names)
    impulses = sol.stats.get("impulses")
    dt = float(sol.t[1] - sol.t[0]) if len(sol.t) > 1 else 0.0
    out = {}
    for name in names:
        j = sol.constraint_names.index(name)
        hits = []
        for ev in sol.stats.get("impacts", ()):
            if name in ev["contacts"]:
                i = ev["contacts"].index(name)
                hits.append({"time": ev["time"], "impulse": ev["impulses"][i], "before": ev["before"][i],
                             "after": ev["after"][i], "loss": ev["loss"]})
        out[name] = {"force": sol.v[:, j], "impulse": impulses[:, j] if impulses is not None else sol.v[:, j] * dt,
                     "opening": -sol.psi[:, j], "impacts": hits}
    return out


def block_results(structure, sol, name) -> dict:
    """The rocking of the rigid block ``name`` of a built frame (``Frame2D.rigid_block``).

    Returns
    -------
    dict with ``rotation`` (N+1,) rad (counter-clockwise), ``omega`` (N+1,) rad/s, ``uplift``
    (N+1,) the larger opening of the two base corners (length), ``corners``
    (:func:`contact_results` of the two corners), ``peak_rotation`` (rad), ``peak_uplift``,
    ``overturned`` (bool) and ``overturn_time`` (s, or None): the first time the tilt passes
    ``b / h``, the unstable equilibrium of the linearised free rocking (beyond it the free tilt
    grows without bound: the block overturns; while the base still moves it can be pulled back,
    so under a pulse this is not the overturn: ``examples/overturning_map.py`` decides it once the
    pulse is over, ``docs/rocking.md``), and ``impacts``: the located impacts on its corners
    (time, the corner struck, the ratio of the angular velocities after/before). A 3-D box
    (``Frame3D.rigid_box``): :func:`~unilateral.structure.rigid3d.box_results`.
    """
    block = structure.rigid.blocks[name]
    if hasattr(block, "by"):                    # a 3-D box on four corners
        from ..structure.rigid3d import box_results

        return box_results(structure, sol, name, contact_results(sol, block.corners))
    T = structure.dofs.T
    rows = {dof: T[structure.dofs.full_index(block.base, dof)] for dof in ("uy", "rz")}
    theta = np.asarray(rows["rz"] @ sol.u.T).ravel()
    omega = np.asarray(rows["rz"] @ sol.udot.T).ravel()
    corners = contact_results(sol, block.corners)
    uplift = np.maximum(corners[block.corners[0]]["opening"], corners[block.corners[1]]["opening"])
    past = np.flatnonzero(np.abs(theta) > block.b / block.h)
    impacts = []
    for ev in sol.stats.get("impacts", ()):
        struck = [c for c in ev["contacts"] if c in block.corners]
        if struck:
            impacts.append({"time": ev["time"], "corner": struck[0], "loss": ev["loss"]})
    return {"rotation": theta, "omega": omega, "uplift": uplift, "corners": corners,
            "peak_rotation": float(np.max(np.abs(theta))), "peak_uplift": float(np.max(uplift)),
            "overturned": bool(past.size), "overturn_time": float(sol.t[past[0]]) if past.size else None,
            "impacts": impacts}


def one_sine_pulse(a_p, omega_p, *, psi=0.0):
    """The one-sine acceleration pulse ``a_p sin(omega_p t + psi)`` for ``0 <= t <= 2 pi / omega_p``,
    0 after (a callable ``a_g(t)``, length/time^2; ``omega_p`` rad/time).

    ``psi = 0`` (default): one full sine cycle from rest; a block lifts once ``a_g`` reaches
    ``g tan(alpha)``, at ``asin(g tan(alpha) / a_p) / omega_p``, and sees the rest of the cycle.
    ``psi = rocking_onset_phase(a_p, g tan(alpha))``: Zhang & Makris' (2001) one-sine (type-A)
    pulse, the cycle started at the phase at which the block lifts (``t = 0``) and lasting a full
    period from there, so that it ends with a jump from ``a_p sin(psi) = g tan(alpha)`` to 0 (the
    ground velocity ``(a_p / omega_p) (cos(psi) - cos(omega_p t + psi))`` is back to zero).
    """
    if not (math.isfinite(a_p) and math.isfinite(omega_p) and omega_p > 0 and math.isfinite(psi)):
        raise ValueError(f"one_sine_pulse: a_p={a_p!r}, psi={psi!r} must be finite and omega_p={omega_p!r} "
                         f"finite and > 0")
    end = 2.0 * math.pi / omega_p
    return lambda t: a_p * math.sin(omega_p * t + psi) if 0.0 <= t <= end else 0.0


def rocking_onset_phase(a_p, uplift_acceleration) -> float:
    """Zhang & Makris' phase ``psi = asin(g tan(alpha) / a_p)`` of a one-sine pulse of amplitude
    ``a_p`` (``uplift_acceleration = g tan(alpha)``, ``RigidBlock.uplift_acceleration``): the block
    lifts at ``t = 0``. ``a_p`` must reach the uplift acceleration (below it nothing lifts)."""
    if not (math.isfinite(a_p) and uplift_acceleration > 0 and abs(a_p) >= uplift_acceleration):
        raise ValueError(f"rocking_onset_phase: |a_p|={a_p!r} must be at least the uplift acceleration "
                         f"{uplift_acceleration!r} (> 0): below it the block does not lift")
    return math.asin(uplift_acceleration / abs(a_p))


def frame_solution(structure, sol):
    """``(contact_load (N+1, n), frame_sol)``: the load ``N v`` of the rigid contacts' forces on the
    structure and the solution restricted to the frame's own unknowns (its first ``structure.m``),
    for the results of the frame (end forces, reactions, accelerations), as for a foundation."""
    from ..result import Solution

    m = structure.m
    load = np.asarray(sol.v[:, m:] @ structure.rigid.N.T.toarray()) if sol.v.shape[1] > m else np.zeros_like(sol.u)
    keep = lambda a: None if a is None else np.asarray(a)[:, :m]
    frame = Solution(t=sol.t, v=keep(sol.v), psi=keep(sol.psi), psiL=keep(sol.psiL), u=sol.u, udot=sol.udot,
                     success=sol.success, message=sol.message, stats=dict(sol.stats), dof_names=sol.dof_names,
                     constraint_names=list(sol.constraint_names)[:m])
    return load, frame


def rigid_ground_reactions(structure, h, sol, motions) -> tuple[dict, dict]:
    """The ground's forces on the structure through its rigid contacts and blocks: ``(forces, at)``.

    ``forces[contact]``: the compressive force ``v`` (force) along the contact's normal at its node,
    for the contacts with the ground only (a contact between two nodes, ``on``, is internal: a block
    on a floor or on another block); ``forces["<block>.base"]``: the horizontal force of the ground on
    a block or box standing on the ground (its held base, or its corners' friction), ``sum m a`` over
    the block and the blocks stacked on it, ``a`` the horizontal absolute acceleration of each centre
    (the stack is rigid bodies and the ground the only horizontal force on it; at the base's level,
    so with no moment about a point there). A block on a frame's floor has none: its forces reach
    the ground through the frame's elements (their supports' reactions). Each (N+1, 3) ``(fx, fy,
    mz)`` in 2-D, (N+1, 6) ``(fx, fy, fz, mx, my, mz)`` in 3-D; ``at``: the node of each. ``h``: the
    frame's histories (its accelerations of the rule, the mean of each step for ``moreau-jean``; a
    3-D box's ``mz`` is ``Jz rz''``, the torque of its corners' friction, a stack's the sum over its
    boxes with ``m (dx a_y - dy a_x)`` of each centre off the base); ``motions``: ``[(direction,
    a_g (N+1,))]``
    the ground's accelerations at its times, read as ``h``'s (:func:`~unilateral.analysis.result_parts.step_means`)."""
    names = tuple(structure.dofs.dof_names)
    axes = tuple(d for d in ("ux", "uy", "uz") if d in names)
    m, steps = structure.m, len(h.t)
    forces, at = {}, {}
    for j, contact in enumerate(structure.rigid.contacts):
        if getattr(contact, "on", None) is not None:
            continue                                 # between two bodies: internal
        d, f = dict(contact.terms), np.zeros((steps, len(names)))
        for k, dof in enumerate(axes):
            f[:, k] = d.get(dof, 0.0) * sol.v[:, m + j]
        forces[contact.name], at[contact.name] = f, contact.node
    ground = np.zeros((steps, len(axes)))
    for direction, a_g in motions:
        ground[:, axes.index(direction)] += a_g
    accelerations, nodes = structure.dofs.nodal(h.uddot), list(structure.dofs.nodes)
    horizontal = len(axes) - 1                       # ux (2-D); ux, uy (3-D)
    from ..structure.stacks import stack_of

    blocks = structure.rigid.blocks
    for name, block in blocks.items():
        if getattr(block, "on", None) is not None:
            continue                                 # on a floor or on a block: not on the ground
        f = np.zeros((steps, len(names)))
        for b in stack_of(blocks, block):
            f[:, :horizontal] += b.mass * (accelerations[:, nodes.index(b.node), :horizontal] + ground[:, :horizontal])
        if len(names) == 6:                          # boxes that twist on friction: Jz rz'', + a stack's offsets
            f[:, 5] = _stack_torque(structure, stack_of(blocks, block), block.base, accelerations, ground)
        forces[f"{name}.base"], at[f"{name}.base"] = f, block.base
    return forces, at


def _stack_torque(structure, stack, base, accelerations, ground) -> np.ndarray:
    """``mz`` (N+1,) of the ground on a stack of 3-D boxes about the vertical through ``base``:
    ``sum Jz rz'' + m (dx a_y - dy a_x)``, ``(dx, dy)`` each centre's plan offset from ``base`` and
    ``a`` its absolute horizontal acceleration (``ground`` (N+1, 3) the ground's)."""
    nodes, at = list(structure.dofs.nodes), np.asarray(structure.coords[base], dtype=float)
    out = np.zeros(accelerations.shape[0])
    for box in stack:
        k = nodes.index(box.node)
        dx, dy = np.asarray(structure.coords[box.node], dtype=float)[:2] - at[:2]
        a = accelerations[:, k, :2] + ground[:, :2]
        out += box.Jz * accelerations[:, k, 5] + box.mass * (dx * a[:, 1] - dy * a[:, 0])
    return out


def add_rigid_energy(energy: dict, structure, u, udot, stats) -> dict:
    """The frame's energy balance (:func:`unilateral.analysis.energy.energy_balance` with the work
    of the rigid contacts' forces as ``contact_dissipated``, as for a soil) completed for rigid
    contacts: the blocks' second-order gravity potential ``-W h theta^2 / 2`` goes into
    ``elastic_structure``; for a run of ``method="moreau-jean"`` (``stats["energy"]``) the input
    work, damping and contact terms are the march's own (the energy lost at impacts as
    ``contact_dissipated``, and ``impact_loss`` on its own), so that the balance closes to
    round-off with the trapezoidal rule. ``balance_error`` and ``relative_error`` are re-evaluated.
    """
    geometric = structure.rigid.geometric
    out = dict(energy)
    out["elastic_structure"] = energy["elastic_structure"] + 0.5 * np.einsum("ki,ki->k", u, (geometric @ u.T).T)
    march = stats.get("energy")
    if march is not None and len(march["impact_loss"]) == len(out["kinetic"]):
        out["input_work"] = march["external_work"]
        out["damping_dissipated"] = march["damping"]
        out["contact_dissipated"] = march["impact_loss"]       # moreau-jean: every unknown a rigid contact
        out["impact_loss"] = march["impact_loss"]
        out["friction_work"] = march.get("friction_work", np.zeros_like(out["kinetic"]))
        for key in ("numerical_dissipation", "numerical_storage"):      # the march's own accounting
            if key in out:
                out[key] = np.zeros_like(out["kinetic"])
    dissipated = out["damping_dissipated"] + out["contact_dissipated"] + sum(
        out[k] for k in ("plastic_work", "friction_work") if k in out)
    numerical = sum(out[k] for k in ("numerical_dissipation", "numerical_storage") if k in out)
    elastic = out["elastic_structure"] + out["elastic_unilateral"] + out.get("geometric", 0.0)
    residual = (out["input_work"] - (out["kinetic"] - out["kinetic"][0]) - (elastic - elastic[0]) - dissipated
                - numerical)
    scale = max(float(np.max(np.abs(x), initial=0.0)) for x in (out["input_work"], out["kinetic"], elastic - elastic[0],
                                                                  dissipated + numerical))
    out["balance_error"] = residual
    out["relative_error"] = np.abs(residual) / scale if scale > 0 else np.zeros_like(residual)
    out["max_relative_error"] = float(out["relative_error"].max()) if residual.size else 0.0
    return out


def rigid_summary(structure, sol) -> dict:
    """The summary of the rigid contacts and blocks of a run (JSON-ready): per contact its largest
    mean force, its number of located impacts and the energy they lost; per block its peak rotation
    and uplift (with their times), whether it overturned (and when), its impacts and their energy."""
    t = sol.t
    out = {"contacts": {}, "blocks": {}}
    for name, c in contact_results(sol, structure.rigid.names).items():
        k = int(np.argmax(c["force"]))
        out["contacts"][name] = {"max_force": float(c["force"][k]), "t_max_force": float(t[k]),
                                 "impacts": len(c["impacts"]),
                                 "impact_loss": float(sum(i["loss"] for i in c["impacts"]))}
    for name in structure.rigid.blocks:
        b = block_results(structure, sol, name)
        kr, ku = int(np.argmax(np.abs(b["rotation"]))), int(np.argmax(b["uplift"]))
        out["blocks"][name] = {"peak_rotation": b["peak_rotation"], "t_peak_rotation": float(t[kr]),
                               "peak_uplift": b["peak_uplift"], "t_peak_uplift": float(t[ku]),
                               "overturned": b["overturned"], "overturn_time": b["overturn_time"],
                               "impacts": len(b["impacts"]),
                               "impact_loss": float(sum(i["loss"] for i in b["impacts"]))}
    return out
