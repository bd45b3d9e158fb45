"""What an engineer reads off a solved 3-D frame (:class:`~unilateral.structure.Frame3D`): element end
forces in local axes, support and ground reactions, base forces and moments about the three axes,
storey drifts at the corners of the plan, absolute accelerations.

The 3-D counterparts of :mod:`unilateral.structure.forces`, whose dimension-free parts they reuse
(:class:`~unilateral.structure.forces.Histories`, the rates of the rule, the element stresses,
:func:`~unilateral.structure.forces.nodal_forces`, which in 3-D has six columns per node,
:func:`~unilateral.structure.forces.absolute_acceleration`).

Sign conventions
----------------
Global right-handed axes ``x``, ``y`` (horizontal) and ``z`` (up); nodal DOFs ``(ux, uy, uz, rx,
ry, rz)``, rotations and moments right-hand positive about the axes
(:mod:`unilateral.structure.elements3d`).

*End forces* (:func:`end_forces`) are the forces and moments **acting on the element at its ends**,
from the nodes, in the element's local axes ``x'``, ``y'``, ``z'`` (a ``beam3d``'s of
:func:`~unilateral.structure.elements3d.local_axes`; another element's ``x'`` is its direction ``d``):
``N_i, Vy_i, Vz_i, T_i, My_i, Mz_i, N_j, ..., Mz_j`` (:data:`END_COMPONENTS`). Carried back to the
global axes and added up at the nodes they are ``G sigma``: ``M u'' + C u' + G sigma = q`` at every
free DOF, the support reaction at a supported one (``tests/test_run3d_outputs.py``).

*Reactions* (:func:`reactions`) are the forces and moments **the ground exerts on the structure**:
at each supported DOF (``"node.dof"``), through every element attached to the ground (soil, springs,
dashpots on one node: ``(fx, fy, fz, mx, my, mz)`` on that node) and through the soil under the
footings of :meth:`Frame3D.foundation <unilateral.structure.Frame3D.foundation>` (per patch, the
compressive contact force ``c = -psi`` at the patch centre ``(x, y)`` reported at the footing's node
``(x0, y0)`` as ``fz = c``, ``mx = (y - y0) c``, ``my = -(x - x0) c``). They include every force the
elements transmit (elastic, Kelvin, attached dashpots and the stiffness-proportional Rayleigh part
``a1 K u'``). The forces on the DOFs of nodes tied to a master by a rigid link or a rigid diaphragm
are carried to the master (``T_tie^T f``): a support of the master carries them.

*Base forces* (:func:`base_forces`) are their resultant about a point ``p``: ``Fx``, ``Fy`` (base
shears), ``Fz`` (vertical force, up positive), and ``M = sum (r - p) x f + m``: ``Mx``, ``My`` (the
overturning moments) and ``Mz`` (the base torque), each (N+1,). Equilibrium of the whole structure:
with ``r`` the free-DOF vector of a rigid-body motion (a unit translation ``t``,
:meth:`Structure3D.influence`, or a unit rotation about an axis ``w`` through ``p``), ``q`` the
applied load (the footings' contact load ``T c`` is not in it: its forces are among the
reactions) and ``a0`` the mass-proportional Rayleigh coefficient, at every step

    t . (Fx, Fy, Fz) = r_t^T (M (u'' + a0 u') - q),   w . (Mx, My, Mz) = r_w^T (M (u'' + a0 u') - q)

(tested in ``tests/test_forces3d.py``: to ~1e-9 of the peak with the accelerations of the rule,
:class:`~unilateral.structure.forces.Histories`). Under ground motions ``q = -M sum_k r_k a_g,k + p``:
the base forces balance the inertia of the absolute accelerations (:func:`absolute_acceleration`),
the damping and the other loads ``p``. A mass on a supported DOF is not part of ``M`` and is not
counted.

*Drifts* (:func:`storey_drifts`): the displacement of a node of the upper floor minus that of the
floor below at the same plan position, along ``x`` and ``y`` (length), and its ratio to the storey
height (dimensionless).
"""

from __future__ import annotations

import numpy as np

from .dofs3d import rigid_rows
from .elements3d import DOF_NAMES, ROTATIONS
from .forces import (Histories, _element_vectors, _free_a, _ground_elements, absolute_acceleration, nodal_forces,
                     stresses, support_forces)

__all__ = ["DOF_NAMES", "BASE_COMPONENTS", "END_COMPONENTS", "Histories", "histories", "nodal_forces", "end_forces",
           "local_frame", "reactions", "base_point", "base_forces", "storeys", "storey_drifts",
           "absolute_acceleration"]

#: The keys of :func:`base_forces`.
BASE_COMPONENTS = ("Fx", "Fy", "Fz", "Mx", "My", "Mz")
#: The components of :func:`end_forces`: forces along and moments about the local axes at ends i and j.
END_COMPONENTS = ("N_i", "Vy_i", "Vz_i", "T_i", "My_i", "Mz_i", "N_j", "Vy_j", "Vz_j", "T_j", "My_j", "Mz_j")


# ---------------------------------------------------------------------- histories
def histories(structure, sol, rule, *, load0=None) -> Histories:
    """:meth:`Histories.from_solution <unilateral.structure.forces.Histories.from_solution>` of a 3-D
    structure, with or without footings on a soil medium.

    With footings (``structure.foundation``), ``sol`` is the solution of the
    :class:`~unilateral.soil.FoundationModel`: the frame's histories are those of its own constraints
    (:func:`~unilateral.structure.foundation.structural_solution`), and the soil's contact load ``T c``
    at t = 0 is added to ``load0`` for the initial acceleration.

    Parameters
    ----------
    structure : Structure3D
    sol : Solution
    rule : str or Rule, the time rule of the run
    load0 : (n,) applied load at t = 0 (force), optional (default: zero initial acceleration)
    """
    fnd = structure.foundation
    if fnd is None:
        return Histories.from_solution(structure, sol, rule, load0=load0)
    from .foundation import structural_solution

    contact = fnd.contact_load(structure, sol)
    q0 = contact[0] if load0 is None else np.asarray(load0, dtype=float) + contact[0]
    return Histories.from_solution(structure, structural_solution(sol, fnd.first), rule, load0=q0)


# ---------------------------------------------------------------------- element end forces
def local_frame(e) -> np.ndarray:
    """The local axes (3, 3) of a ``beam3d`` element, rows ``x'``, ``y'``, ``z'``
    (:func:`unilateral.structure.elements3d.local_axes`), read off its strain rows: ``x'`` is the
    twist's row on ``theta_j``, ``y'`` that of ``roty_i`` and ``z'`` that of ``rotz_i`` on ``theta_i``."""
    a = np.asarray(e.a, dtype=float)
    return np.vstack([a[1, 9:12], a[4, 3:6], a[2, 3:6]])


def _local_ends(e, sigma) -> np.ndarray:
    """Local end forces (N+1, 12) of element ``e`` from its stresses ``sigma`` (N+1, k)."""
    out = np.zeros((sigma.shape[0], len(END_COMPONENTS)))
    if e.kind == "beam3d":
        R = local_frame(e)
        glob = sigma @ e.a                                  # forces and moments on the element at its DOFs
        for end in (0, 6):
            out[:, end:end + 3] = glob[:, end:end + 3] @ R.T           # N, Vy, Vz
            out[:, end + 3:end + 6] = glob[:, end + 3:end + 6] @ R.T   # T, My, Mz
        return out
    k = sigma.shape[1]                                      # along d (, t1, t2): N (, Vy, Vz), or T
    first = 3 if all(dof in ROTATIONS for _, dof in e.dofs) else 0
    out[:, first:first + k] = -sigma
    out[:, 6 + first:6 + first + k] = sigma
    return out


def end_forces(structure, h: Histories) -> dict:
    """End forces of every element of a 3-D frame, in local axes: the forces and moments **acting on
    the element at its ends**, from the nodes.

    Components :data:`END_COMPONENTS`: ``N`` along ``x'``, ``Vy``, ``Vz`` along ``y'``, ``z'``,
    ``T`` (torque) about ``x'``, ``My``, ``Mz`` about ``y'``, ``z'`` (right-hand positive), at end
    ``i`` then end ``j``. A ``beam3d`` has its local axes (:func:`local_frame`): its natural stresses
    are ``N_j`` (the axial force, tension positive, ``N_i = -N_j``), ``T_j`` (the torque), ``Mz_i``,
    ``Mz_j``, ``My_i``, ``My_j`` (the end moments), and the shears follow from them,
    ``Vy_j = -(Mz_i + Mz_j) / L``, ``Vz_j = (My_i + My_j) / L``. Every other element acts along its
    strain's direction ``x' = d`` (from end ``i``, or the ground, to end ``j``): ``N_j = sigma``,
    ``N_i = -sigma`` (a bar, cable, spring, soil, gap, yield link, slider; a dashpot's viscous force);
    a rotational spring's moment is ``T_j = sigma`` about its axis; a contact with friction adds its
    tangential forces along ``y' = t1``, ``z' = t2``: ``Vy_j = T1``, ``Vz_j = T2``. These are the
    elastic forces plus the Kelvin dashpot of a contact (``sigma`` of the natural form), without the
    Rayleigh part ``a1 E e'``, as in 2-D (:func:`unilateral.structure.forces.end_forces`).

    Returns
    -------
    dict name -> (N+1, 12)
    """
    sigma = stresses(structure, h)
    out = {e.name: _local_ends(e, sigma[:, cols]) for e, cols, _ in _element_vectors(structure)}
    for e in structure.dashpots:
        out[e.name] = _local_ends(e, (h.udot @ _free_a(structure, e).T) @ np.asarray(e.E).T)
    return out


# ---------------------------------------------------------------------- reactions
def _onto_masters(structure, forces) -> np.ndarray:
    """Nodal forces (N+1, 6 n_nodes) with those on the tied DOFs of every slave node carried onto its
    master's DOFs, ``f_m += T_tie^T f_s`` (``u_s = u_m + theta_m x (x_s - x_m)`` of a rigid link, the
    in-plane part of a diaphragm), along chains to the last master.

    The force on a slave's DOF is what the slave exerts on all its elements, those to the ground
    included: the tie transmits all of it (the ground elements' own reactions are reported on their
    own, at the slave).
    """
    dofs, coords = structure.dofs, structure.coords
    ties = getattr(dofs, "ties", {})
    if not ties:
        return forces
    out = forces.copy()

    def push(node, dof, value):
        if node in ties and dof in ties[node][1]:
            master = ties[node][0]
            offset = np.asarray(coords[node], dtype=float) - np.asarray(coords[master], dtype=float)
            for mdof, c in rigid_rows(offset)[dof]:
                if c != 0.0:
                    push(master, mdof, c * value)
        else:
            out[:, dofs.full_index(node, dof)] += value

    for slave, (_, tied) in ties.items():
        for dof in tied:
            push(slave, dof, forces[:, dofs.full_index(slave, dof)])
    return out


def _ground_element_forces(structure, h: Histories) -> dict:
    """``name -> (N+1, 6)`` force and moment each element to the ground exerts on its node."""
    sigma = stresses(structure, h)
    a1 = structure.rayleigh[1] if structure.rayleigh else 0.0
    vectors = {e.name: cols for e, cols, _ in _element_vectors(structure)}
    out = {}
    for e in _ground_elements(structure):
        if e.name in vectors:
            s = sigma[:, vectors[e.name]]
            if a1 and not e.unilateral:
                s = s + a1 * ((h.udot @ _free_a(structure, e).T) @ e.E.T)
        else:                                       # an attached dashpot: its viscous force
            s = (h.udot @ _free_a(structure, e).T) @ e.E.T
        f = np.zeros((len(h.t), len(DOF_NAMES)))
        for col, (_, dof) in enumerate(e.dofs):
            f[:, DOF_NAMES.index(dof)] -= s @ e.a[:, col]
        out[e.name] = f
    return out


def reactions(structure, h: Histories, sol=None) -> dict:
    """Forces and moments of the ground on a 3-D structure (see the module's sign conventions).

    Parameters
    ----------
    structure : Structure3D
    h : Histories of the frame (:func:`histories`)
    sol : Solution, the full solution of the run; needed for the footings' contact forces (a
        structure with footings on a soil medium), else unused

    Returns
    -------
    dict with
    ``support`` : dict ``"node.dof"`` -> (N+1,) reaction at each supported DOF (force, or moment
        for ``rx``, ``ry``, ``rz``), the forces of the nodes tied to the node included;
    ``ground_elements`` : dict element name -> (N+1, 6) ``(fx, fy, fz, mx, my, mz)`` the element to
        the ground (soil, spring, dashpot on one node) exerts on its node;
    ``footings`` : dict contact name (``"footing.j"``) -> (N+1, 6) the soil's force on the footing's
        node through patch ``j`` (``fz = c``, ``mx = (y_j - y0) c``, ``my = -(x_j - x0) c``);
    ``at`` : dict label -> node each reaction acts on (for moments).
    """
    dofs = structure.dofs
    if len(getattr(dofs, "dof_names", ())) != len(DOF_NAMES):
        raise TypeError("reactions: the structure is not a 3-D frame (six DOFs per node); use "
                        "unilateral.structure.forces.reactions for a Frame2D structure")
    ground = _ground_element_forces(structure, h)
    at = {e.name: e.dofs[0][0] for e in _ground_elements(structure)}
    footings = {}
    fnd = structure.foundation
    if fnd is not None:
        if sol is None:
            raise ValueError("reactions: the structure stands on footings on a soil medium; give sol, the "
                             "solution of its FoundationModel, for the soil's contact forces")
        footings, where = fnd.ground_reactions(structure, sol)
        at |= where
    support = support_forces(dofs, _onto_masters(structure, nodal_forces(structure, h)), DOF_NAMES, at)
    return {"support": support, "ground_elements": ground, "footings": footings, "at": at, "steps": len(h.t)}


def base_point(structure) -> tuple[float, float, float]:
    """The centre of the base: ``(mean x, mean y, z)`` of the lowest nodes the ground acts on (a
    supported DOF, an element to the ground, a footing), within ``1e-9`` of the model's size;
    without any, of the lowest nodes."""
    coords = structure.coords
    ground = {node for node, _ in structure.dofs._restrained}
    ground |= {e.dofs[0][0] for e in _ground_elements(structure)}
    if structure.foundation is not None:
        ground |= set(structure.foundation.contact_nodes())
    nodes = [node for node in structure.dofs.nodes if node in ground] or list(structure.dofs.nodes)
    xyz = np.array([coords[node] for node in nodes], dtype=float)
    size = float(np.ptp(np.array(list(coords.values()), dtype=float), axis=0).max()) or 1.0
    low = xyz[:, 2].min()
    level = xyz[np.abs(xyz[:, 2] - low) <= 1e-9 * size]
    return float(level[:, 0].mean()), float(level[:, 1].mean()), float(low)


def base_forces(structure, reaction: dict, point=(0.0, 0.0, 0.0)) -> dict:
    """The resultant of the ground's forces on the structure about ``point``.

    Parameters
    ----------
    structure : Structure3D
    reaction : dict, the result of :func:`reactions`
    point : (3,) ``(x0, y0, z0)`` (length), the point of the moments (:func:`base_point`: the centre
        of the base)

    Returns
    -------
    dict of (N+1,) arrays: ``Fx``, ``Fy`` (base shears), ``Fz`` (vertical force, up positive)
    (force); ``Mx``, ``My`` (overturning moments), ``Mz`` (torque about the vertical through
    ``point``) (force length): ``M = sum (r - p) x f + m`` over every reaction, ``r`` its node's
    position, right-hand positive.
    """
    coords = structure.coords
    p = np.asarray(point, dtype=float)
    if p.shape != (3,):
        raise ValueError(f"point={point!r} must be (x0, y0, z0)")
    parts = [(label, _components(label, f)) for label, f in reaction["support"].items()]
    parts += list(reaction["ground_elements"].items()) + list(reaction.get("footings", {}).items())
    N1 = len(parts[0][1]) if parts else reaction.get("steps", 0)      # no support: a box free on friction
    F, M = np.zeros((N1, 3)), np.zeros((N1, 3))
    for label, f in parts:
        arm = np.asarray(coords[reaction["at"][label]], dtype=float) - p
        F += f[:, :3]
        M += f[:, 3:] + np.cross(arm, f[:, :3])
    return dict(zip(BASE_COMPONENTS, (*F.T, *M.T)))


def _components(label, f) -> np.ndarray:
    out = np.zeros((len(f), len(DOF_NAMES)))
    out[:, DOF_NAMES.index(label.rsplit(".", 1)[1])] = f
    return out


# ---------------------------------------------------------------------- storeys and drifts
def storeys(structure, *, tol=1e-6) -> list[tuple[float, list]]:
    """Floors of a 3-D frame: the nodes grouped by elevation ``z``, ``[(z, [nodes]), ...]`` bottom to
    top (nodes within ``tol max(1, |z|)`` of a level belong to it)."""
    levels: list[tuple[float, list]] = []
    for node in structure.dofs.nodes:
        z = float(structure.coords[node][2])
        for level, nodes in levels:
            if abs(level - z) <= tol * max(1.0, abs(level)):
                nodes.append(node)
                break
        else:
            levels.append((z, [node]))
    return sorted(levels, key=lambda item: item[0])


def _corners(xy, tol) -> list[int]:
    """Indices of the corner nodes of a floor: the four corners of the bounding box of its plan if
    nodes stand there, else the extreme nodes in x and y (the first of the nodes at ``min x``,
    ``max x``, ``min y``, ``max y``), without repetition."""
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    box = [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
    found = []
    for corner in box:
        hit = np.flatnonzero(np.all(np.abs(xy - corner) <= tol, axis=1))
        if hit.size == 0:
            break
        found.append(int(hit[0]))
    else:
        return list(dict.fromkeys(found))
    picks = [int(np.argmin(xy[:, 0])), int(np.argmax(xy[:, 0])), int(np.argmin(xy[:, 1])), int(np.argmax(xy[:, 1]))]
    return list(dict.fromkeys(picks))


def _plan_motion(nodal, xy, idx, at_xy, tol):
    """Displacements ``(ux, uy)`` (N+1, 2) of a floor at the plan position ``at_xy``: those of its node
    there, else of the in-plane rigid motion (``ux - rz (y - yc)``, ``uy + rz (x - xc)``) fitted by
    least squares to its nodes' ``ux``, ``uy`` (one node: its translation and its ``rz``)."""
    hit = np.flatnonzero(np.all(np.abs(xy[idx] - at_xy) <= tol, axis=1))
    if hit.size:
        return nodal[:, idx[hit[0]], :2]
    if len(idx) == 1:
        (x, y), u = xy[idx[0]], nodal[:, idx[0]]
        return np.column_stack([u[:, 0] - u[:, 5] * (at_xy[1] - y), u[:, 1] + u[:, 5] * (at_xy[0] - x)])
    pts = xy[idx]
    centre = pts.mean(axis=0)
    d = pts - centre
    # unknowns (ux_c, uy_c, rz): rows ux_k = ux_c - rz dy_k, uy_k = uy_c + rz dx_k
    A = np.zeros((2 * len(idx), 3))
    A[0::2, 0], A[0::2, 2] = 1.0, -d[:, 1]
    A[1::2, 1], A[1::2, 2] = 1.0, d[:, 0]
    b = nodal[:, idx, :2].reshape(nodal.shape[0], -1)          # (N+1, 2k): ux_1, uy_1, ux_2, ...
    sol, *_ = np.linalg.lstsq(A, b.T, rcond=None)               # (3, N+1)
    dx, dy = np.asarray(at_xy, dtype=float) - centre
    return np.column_stack([sol[0] - sol[2] * dy, sol[1] + sol[2] * dx])


def storey_drifts(structure, h: Histories, corners=True, *, tol=1e-6) -> dict:
    """Interstorey drifts of a 3-D frame along ``x`` and ``y`` at the corners of each floor's plan.

    The floors are the levels of :func:`storeys` (by ``z``); a storey is the space between two
    consecutive levels, of height ``H = z_upper - z_lower``.

    Parameters
    ----------
    structure : Structure3D
    h : Histories
    corners : bool
        True (default): at the corners of the upper floor: the nodes at the four corners of the
        bounding box of its plan if they exist, else its extreme nodes in ``x`` and ``y``. The drift
        at a corner ``(x, y)`` is its node's displacement minus that of the lower floor at the same
        ``(x, y)``: of its node there, or else of the lower floor's in-plane rigid motion fitted by
        least squares to its nodes (exact for a rigid diaphragm). False: the drift of the floors'
        mean displacements (the 2-D :func:`~unilateral.structure.forces.storey_drifts`, in x and y).
    tol : float, relative tolerance of the levels and of coincident plan positions (times the plan's
        size)

    Returns
    -------
    dict label ``"z0-z1"`` -> dict with
    ``nodes`` : tuple of the corner nodes of the upper floor (``()`` for ``corners=False``);
    ``height`` : float, ``H`` (length);
    ``x``, ``y`` : (N+1, k) drifts along x and y at the k corners (one column for ``corners=False``)
        (length, positive when the upper floor moves along +x, +y relative to the lower);
    ``ratio_x``, ``ratio_y`` : (N+1, k) drift / ``H``;
    ``max_ratio_x``, ``max_ratio_y`` : (N+1,) the largest absolute ratio over the corners.
    Empty with fewer than two levels.
    """
    nodal = structure.dofs.nodal(h.u)                           # (N+1, n_nodes, 6)
    position = {node: p for p, node in enumerate(structure.dofs.nodes)}
    xy = np.array([structure.coords[node][:2] for node in structure.dofs.nodes], dtype=float)
    size = float(np.ptp(xy, axis=0).max()) if len(xy) else 0.0
    ptol = tol * max(size, 1.0)
    levels = storeys(structure, tol=tol)
    out = {}
    for k in range(1, len(levels)):
        (z0, lower), (z1, upper) = levels[k - 1], levels[k]
        height = z1 - z0
        lo = np.array([position[node] for node in lower])
        up = np.array([position[node] for node in upper])
        if corners:
            picked = [up[c] for c in _corners(xy[up], ptol)]
            drift = np.stack([nodal[:, p, :2] - _plan_motion(nodal, xy, lo, xy[p], ptol) for p in picked], axis=1)
            names = tuple(structure.dofs.nodes[p] for p in picked)
        else:
            drift = (nodal[:, up, :2].mean(axis=1) - nodal[:, lo, :2].mean(axis=1))[:, None, :]
            names = ()
        dx, dy = drift[..., 0], drift[..., 1]
        out[f"{z0:g}-{z1:g}"] = {"nodes": names, "height": height, "x": dx, "y": dy,
                                 "ratio_x": dx / height, "ratio_y": dy / height,
                                 "max_ratio_x": np.abs(dx).max(axis=1) / height,
                                 "max_ratio_y": np.abs(dy).max(axis=1) / height}
    return out
