"""What an engineer reads off a solved frame: end forces, reactions, base forces, drifts, accelerations.

Sign conventions
----------------
Global axes ``x`` (right), ``y`` (up), moments and rotations counter-clockwise positive.

*End forces* (:func:`end_forces`) are the forces and moments **acting on the element at its
ends**, from the nodes, in the element's local axes: ``x`` along the chord from end ``i`` to
end ``j``, ``y`` the chord turned 90 degrees counter-clockwise; for a spring, dashpot, soil or gap
element ``x`` is its direction ``d`` (from end ``i``, or the ground, to end ``j``). Components
``N_i, V_i, M_i, N_j, V_j, M_j``. An element without span loads is in equilibrium:

    N_i + N_j = 0,   V_i + V_j = 0,   M_i + M_j + V_j L = 0

so ``N_j`` is the axial force, tension positive (``N_i = -N_j``), and the beam's bending moment
in the usual "sagging positive" sense is ``-M_i`` at ``i`` and ``+M_j`` at ``j``. End forces are
the elastic forces (plus the Kelvin dashpot of a contact): ``sigma`` of the natural form; a
dashpot's end forces are its viscous force ``c e'``.

*Reactions* (:func:`reactions`) are the forces **the ground exerts on the structure**: at each
supported DOF (``node.dof``), and through every element attached to the ground (soil, springs,
dashpots with one end on the ground). They include every force the elements transmit: elastic,
Kelvin, attached dashpots and the stiffness-proportional Rayleigh part ``a1 K u'`` (the element
forces ``a1 E e'``), so that the structure as a whole is in equilibrium. The *base shear* is the
sum of their ``x`` components, the *base vertical force* the sum of their ``y`` components, and the
*overturning moment* about a point ``(x0, y0)`` the sum of their moments about it
(counter-clockwise positive, support moments included).

Equilibrium of the whole structure (tested in ``tests/test_structure_results.py``): with ``r``
the influence vector of a rigid translation along ``x`` (:meth:`Structure.influence`), ``q`` the
applied load and ``a0 M`` the mass-proportional Rayleigh damping, at every step

    base_shear = r^T M (u'' + a0 u') - r^T q

and under a ground motion ``q = -M r a_g + p``: ``base_shear = sum m (u'' + a_g) + a0 r^T M u' - r^T p``,
the inertia of the absolute accelerations. A mass on a supported DOF is not part of ``M`` and
is not counted.

Accelerations (:func:`rates`) are those of the time-discretisation rule (the same relations the
stepping used), so the equations of motion hold at every step with them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .elements import DOF_NAMES

END_COMPONENTS = ("N_i", "V_i", "M_i", "N_j", "V_j", "M_j")


# ---------------------------------------------------------------------- rates of the rule
def rates(y, rule, dt, *, rate0=None, second0=None) -> tuple[np.ndarray, np.ndarray]:
    """First and second rates of a history by the relations of a time-discretisation rule.

    For every step ``y'_n = c1 y_n - h1``, ``y''_n = c0 y_n - h2`` with the rule's history
    (:mod:`unilateral.rules`), started as the stepping starts (``rule.start(y_0, rate0,
    second0)``). Applied to the displacements of a solution it gives back its velocities and the
    accelerations of the rule; applied to ``v`` with zero initial rates, the ``v'`` of Kelvin
    elements.

    Parameters
    ----------
    y : (N+1, k) values at ``t_n = n dt``
    rule : Rule
    dt : float
    rate0, second0 : (k,) rates at t = 0 (default zero)

    Returns
    -------
    yd, ydd : (N+1, k)
    """
    y = np.asarray(y, dtype=float)
    N1, k = y.shape
    yd0 = np.zeros(k) if rate0 is None else np.asarray(rate0, dtype=float)
    ydd0 = np.zeros(k) if second0 is None else np.asarray(second0, dtype=float)
    name = getattr(rule, "name", "")
    if name in ("bdf1", "bdf2"):
        ys, yds = rule.start(y[0], yd0, ydd0, dt)
        yd = _bdf(y, ys[1:], rule.order, dt)
        yd[0] = yd0
        ydd = _bdf(yd, yds[1:], rule.order, dt)
        ydd[0] = ydd0
        return yd, ydd
    if getattr(rule, "alpha", 0.0) == 0.0 and name in ("trapezoidal", "newmark") and \
            (rule.gamma, rule.beta) == (0.5, 0.25):
        yd = _trapezoidal(y, yd0, dt)
        return yd, _trapezoidal(yd, ydd0, dt)
    c1, c0 = rule.coefficients(dt)
    yd, ydd = np.empty_like(y), np.empty_like(y)
    yd[0], ydd[0] = yd0, ydd0
    state = rule.start(y[0], yd0, ydd0, dt)
    for n in range(1, N1):
        h1, h2 = rule.history(state, dt)
        yd[n] = c1 * y[n] - h1
        ydd[n] = c0 * y[n] - h2
        state = rule.advance(state, y[n], yd[n], ydd[n])
    return yd, ydd


def _bdf(y, past, order, dt):
    """BDF derivative of the rows of ``y`` with the past values ``past`` before row 0."""
    ext = np.vstack([np.reshape(np.asarray(past)[::-1], (order - 1, y.shape[1])), y]) if order > 1 else y
    s = order - 1
    out = np.empty_like(y)
    if order == 1:
        out[1:] = (y[1:] - y[:-1]) / dt
    else:
        out[1:] = (1.5 * ext[s + 1:] - 2.0 * ext[s:-1] + 0.5 * ext[s - 1:-2]) / dt
    return out


def _trapezoidal(y, yd0, dt):
    """``y'_n = 2 (y_n - y_{n-1}) / dt - y'_{n-1}``, ``y'_0 = yd0`` (a recursive filter)."""
    dy = np.diff(y, axis=0) * (2.0 / dt)
    out = np.empty_like(y)
    out[0] = yd0
    if len(dy):
        from scipy.signal import lfilter      # imported here: scipy.signal takes seconds to import

        out[1:], _ = lfilter([1.0], [1.0, 1.0], dy, axis=0, zi=-yd0[None, :])
    return out


# ---------------------------------------------------------------------- histories
@dataclass
class Histories:
    """The state of a solved structure at every step: what the results are computed from.

    Attributes
    ----------
    t : (N+1,);  u, udot, uddot : (N+1, n) displacements (relative to the ground), velocities and
    accelerations of the rule;  v, vdot : (N+1, m) unilateral deformations and their rates
    """

    t: np.ndarray
    u: np.ndarray
    udot: np.ndarray
    uddot: np.ndarray
    v: np.ndarray
    vdot: np.ndarray

    @classmethod
    def from_solution(cls, structure, sol, rule, *, load0=None) -> Histories:
        """Rates of a :class:`~unilateral.Solution` of ``structure`` by ``rule`` (name or Rule).

        ``load0`` (n,) is the applied load at t = 0 the run used (for the initial acceleration,
        ``M u''_0 = q_0 - internal forces`` on the DOFs with mass); default: zero acceleration.
        """
        from ..rules import get_rule

        rule = get_rule(rule) if isinstance(rule, str) else rule
        if sol.u is None:
            raise ValueError("the solution has no displacements (a kernel model): no structural results")
        dt = float(sol.t[1] - sol.t[0]) if len(sol.t) > 1 else 1.0
        a0 = np.zeros(structure.n)
        if load0 is not None:
            vd0 = np.zeros(structure.m)
            sigma = structure.natural.stresses(sol.t[:1], sol.u[:1], sol.v[:1], sol.udot[:1], vd0[None])
            f = np.asarray(load0, dtype=float) - np.asarray(structure.natural.G @ sigma[0]).ravel()
            if structure.C is not None:
                f = f - structure.C @ sol.udot[0]
            a0 = _solve_massive(structure.M, f)
        vdot, _ = rates(sol.v, rule, dt)
        _, uddot = rates(sol.u, rule, dt, rate0=sol.udot[0], second0=a0)
        return cls(t=np.asarray(sol.t, dtype=float), u=np.asarray(sol.u, dtype=float),
                   udot=np.asarray(sol.udot, dtype=float), uddot=uddot, v=np.asarray(sol.v, dtype=float),
                   vdot=vdot)


def _solve_massive(M, f):
    """``a`` with ``M a = f`` on the DOFs with mass, 0 on the massless ones."""
    d = M.diagonal()
    idx = np.flatnonzero(d > 0)
    a = np.zeros_like(f)
    if idx.size:
        Mm = M[idx][:, idx]
        Mm = Mm.toarray() if sp.issparse(Mm) else np.asarray(Mm)
        a[idx] = np.linalg.solve(Mm, f[idx])
    return a


# ---------------------------------------------------------------------- element forces
def stresses(structure, h: Histories) -> np.ndarray:
    """Natural stresses ``sigma`` (N+1, ne) of the elements: elastic plus Kelvin."""
    return structure.natural.stresses(h.t, h.u, h.v, h.udot, h.vdot)


def _full_rows(structure, element):
    return np.array([structure.dofs.full_index(node, dof) for node, dof in element.dofs])


def _element_vectors(structure):
    """Per element (natural form, then dashpots): (element, strain slice, full rows, ground end)."""
    out, start = [], 0
    for e in structure.elements:
        k = e.a.shape[0]
        out.append((e, slice(start, start + k), _full_rows(structure, e)))
        start += k
    return out


def _local_ends(e, coords, forces):
    """Local ``N, V, M`` at both ends (N+1, 6) from the global end forces (N+1, d) of ``e``."""
    out = np.zeros((forces.shape[0], 6))
    if e.kind == "beam":
        (i, _), (j, _) = e.dofs[0], e.dofs[3]
        d = coords[j] - coords[i]
        c, s = d / np.hypot(*d)
        for end, cols in ((0, (0, 1, 2)), (3, (3, 4, 5))):
            fx, fy, mz = (forces[:, col] for col in cols)
            out[:, end] = c * fx + s * fy
            out[:, end + 1] = -s * fx + c * fy
            out[:, end + 2] = mz
        return out
    if e.kind in ("bar", "cable"):
        (i, _), (j, _) = e.dofs[0], e.dofs[2]
        d = coords[j] - coords[i]
        c, s = d / np.hypot(*d)
        out[:, 0] = c * forces[:, 0] + s * forces[:, 1]
        out[:, 3] = c * forces[:, 2] + s * forces[:, 3]
        return out
    return None


def end_forces(structure, h: Histories) -> dict:
    """End forces of every element, in local axes (see the module's sign conventions).

    Returns
    -------
    dict name -> (N+1, 6) array of ``N_i, V_i, M_i, N_j, V_j, M_j``. For springs, dashpots, soil
    and gaps ``N_j = sigma`` (tension positive) and ``N_i = -sigma``; ``V``, ``M`` are zero except
    for a rotational spring (``M_j = sigma``, ``M_i = -sigma``).
    """
    sigma = stresses(structure, h)
    coords = structure.coords or {}
    out = {}
    for e, cols, _ in _element_vectors(structure):
        out[e.name] = _local(e, coords, sigma[:, cols])
    for e in structure.dashpots:
        force = (h.udot @ _free_a(structure, e).T)[:, :1] * e.E[0, 0]
        out[e.name] = _local(e, coords, force)
    return out


def _local(e, coords, sigma):
    """Local end forces of element ``e`` from its stresses (N+1, k)."""
    glob = sigma @ e.a                                  # forces on the element at its DOFs
    local = _local_ends(e, coords, glob)
    if local is not None:
        return local
    out = np.zeros((sigma.shape[0], 6))
    rotational = all(dof == "rz" for _, dof in e.dofs)
    column = 2 if rotational else 0
    out[:, column] = -sigma[:, 0]
    out[:, 3 + column] = sigma[:, 0]
    return out


def _free_a(structure, e):
    """Strain rows of element ``e`` on the free DOFs: ``a T_e`` (k, n)."""
    rows = _full_rows(structure, e)
    return np.asarray((sp.csr_matrix(e.a) @ structure.dofs.T[rows]).toarray())


def axial_forces(structure, h: Histories) -> dict:
    """Force of every element along its axis, tension positive: ``N_j`` of :func:`end_forces`."""
    return {name: f[:, 3] if np.any(f[:, 3]) or not np.any(f[:, 5]) else f[:, 5]
            for name, f in end_forces(structure, h).items()}


# ---------------------------------------------------------------------- reactions
def nodal_forces(structure, h: Histories) -> np.ndarray:
    """Forces (N+1, 3 n_nodes) the nodes exert on all elements together, every force included.

    Elastic and Kelvin stresses, attached dashpots and the Rayleigh ``a1`` element forces.
    """
    sigma = stresses(structure, h)
    a1 = structure.rayleigh[1] if structure.rayleigh else 0.0
    out = np.zeros((len(h.t), structure.dofs.T.shape[0]))
    for e, cols, rows in _element_vectors(structure):
        s = sigma[:, cols]
        if a1 and not e.unilateral:
            s = s + a1 * ((h.udot @ _free_a(structure, e).T) @ e.E.T)
        out[:, rows] += s @ e.a
    for e in structure.dashpots:
        rows = _full_rows(structure, e)
        out[:, rows] += (h.udot @ _free_a(structure, e).T) @ e.E.T @ e.a
    return out


def _ground_elements(structure):
    """Elements with one end on the ground: directional elements on a single node."""
    return [e for e in list(structure.elements) + list(structure.dashpots)
            if e.kind in ("spring", "dashpot", "soil", "gap") and len({node for node, _ in e.dofs}) == 1]


def reactions(structure, h: Histories) -> dict:
    """Forces of the ground on the structure.

    Returns
    -------
    dict with
    ``support`` : dict ``"node.dof"`` -> (N+1,) reaction at each supported DOF;
    ``ground_elements`` : dict element name -> (N+1, 3) ``(fx, fy, mz)`` the element exerts on its
    node (the ground reaction through soil, springs and dashpots to the ground);
    ``at`` : dict label -> node of each reaction (for moments).
    """
    forces = nodal_forces(structure, h)
    dofs = structure.dofs
    support, at = {}, {}
    for node in dofs.nodes:
        for dof in DOF_NAMES:
            if (node, dof) in dofs._restrained:
                row = dofs.full_index(node, dof)
                label = f"{node}.{dof}"
                support[label] = forces[:, row]
                at[label] = node
    ground = {}
    sigma = stresses(structure, h)
    a1 = structure.rayleigh[1] if structure.rayleigh else 0.0
    vectors = {e.name: (cols, rows) for e, cols, rows in _element_vectors(structure)}
    for e in _ground_elements(structure):
        if e.name in vectors:
            cols, rows = vectors[e.name]
            s = sigma[:, cols]
            if a1 and not e.unilateral:
                s = s + a1 * ((h.udot @ _free_a(structure, e).T) @ e.E.T)
        else:
            rows = _full_rows(structure, e)
            s = (h.udot @ _free_a(structure, e).T) @ e.E.T
        f = np.zeros((len(h.t), 3))
        for col, (node, dof) in enumerate(e.dofs):
            f[:, DOF_NAMES.index(dof)] -= s[:, 0] * e.a[0, col]
        ground[e.name] = f
        at[e.name] = e.dofs[0][0]
    return {"support": support, "ground_elements": ground, "at": at}


def base_forces(structure, reaction: dict, point=(0.0, 0.0)) -> dict:
    """Base shear, base vertical force and overturning moment about ``point`` (N+1,) each.

    ``reaction`` is the result of :func:`reactions`. The moment of a force ``(fx, fy)`` at
    ``(x, y)`` about ``(x0, y0)`` is ``(x - x0) fy - (y - y0) fx`` (counter-clockwise positive).
    """
    coords = structure.coords
    x0, y0 = point
    parts = [(label, _components(label, f)) for label, f in reaction["support"].items()]
    parts += list(reaction["ground_elements"].items())
    N1 = len(next(iter(parts))[1]) if parts else 0
    fx, fy, mz = np.zeros(N1), np.zeros(N1), np.zeros(N1)
    for label, f in parts:
        x, y = coords[reaction["at"][label]]
        fx += f[:, 0]
        fy += f[:, 1]
        mz += f[:, 2] + (x - x0) * f[:, 1] - (y - y0) * f[:, 0]
    return {"base_shear": fx, "base_vertical": fy, "overturning_moment": mz}


def _components(label, f):
    out = np.zeros((len(f), 3))
    out[:, DOF_NAMES.index(label.rsplit(".", 1)[1])] = f
    return out


# ---------------------------------------------------------------------- ground motion and storeys
def absolute_acceleration(structure, h: Histories, ground_motions) -> np.ndarray:
    """``u'' + sum r_k a_g,k(t)`` (N+1, n): the accelerations relative to a fixed frame.

    ``ground_motions``: sequence of ``(direction, a_g)`` with ``a_g`` a time function (or an
    array of samples at ``h.t``).
    """
    out = h.uddot.copy()
    for direction, a_g in ground_motions:
        samples = np.asarray(a_g(h.t) if callable(a_g) else a_g, dtype=float)
        out += np.outer(samples, structure.influence(direction))
    return out


def storeys(structure, *, tol=1e-6) -> list[tuple[float, list]]:
    """Levels of the nodes: ``[(elevation, [nodes]), ...]`` bottom to top (more than one level)."""
    levels: list[tuple[float, list]] = []
    for node in structure.dofs.nodes:
        y = float(structure.coords[node][1])
        for k, (level, nodes) in enumerate(levels):
            if abs(level - y) <= tol * max(1.0, abs(level)):
                nodes.append(node)
                break
        else:
            levels.append((y, [node]))
    return sorted(levels, key=lambda item: item[0])


def storey_drifts(structure, h: Histories, pairs=None) -> dict:
    """Interstorey drifts ``ux(upper) - ux(lower)`` and drift ratios (drift / height).

    Parameters
    ----------
    pairs : sequence of ``(lower_node, upper_node)``, optional
        The storeys to report; default: the levels of :func:`storeys`, each level's ``ux`` the mean
        over its nodes (only if there are at least two levels and the frame sways in x).

    Returns
    -------
    dict label -> ``(drift (N+1,), ratio (N+1,))``; labels ``"y0-y1"`` (levels) or
    ``"lower-upper"`` (pairs).
    """
    nodal = structure.dofs.nodal(h.u)                    # (N+1, n_nodes, 3)
    position = {node: p for p, node in enumerate(structure.dofs.nodes)}
    out = {}
    if pairs is not None:
        for lower, upper in pairs:
            height = structure.coords[upper][1] - structure.coords[lower][1]
            if height == 0:
                raise ValueError(f"storey ({lower!r}, {upper!r}): the nodes are at the same elevation")
            drift = nodal[:, position[upper], 0] - nodal[:, position[lower], 0]
            out[f"{lower}-{upper}"] = (drift, drift / height)
        return out
    levels = storeys(structure)
    if len(levels) < 2:
        return out
    mean = [nodal[:, [position[node] for node in nodes], 0].mean(axis=1) for _, nodes in levels]
    for k in range(1, len(levels)):
        height = levels[k][0] - levels[k - 1][0]
        drift = mean[k] - mean[k - 1]
        out[f"{levels[k - 1][0]:g}-{levels[k][0]:g}"] = (drift, drift / height)
    return out
