"""What an engineer reads off a solved frame: end forces, reactions, base forces, drifts, accelerations.

Sign conventions
----------------
Global axes ``x`` (right), ``y`` (up), moments and rotations counter-clockwise positive.

*End forces* (:func:`end_forces`) are the forces and moments **acting on the element at its
ends**, from the nodes, in the element's local axes: ``x`` along the chord from end ``i`` to
end ``j``, ``y`` the chord turned 90 degrees counter-clockwise; for a spring, dashpot, soil, gap,
yield link or slider ``x`` is its direction ``d`` (from end ``i``, or the ground, to end ``j``). Components
``N_i, V_i, M_i, N_j, V_j, M_j``. An element without span loads is in equilibrium:

    N_i + N_j = 0,   V_i + V_j = 0,   M_i + M_j + V_j L = 0

so ``N_j`` is the axial force, tension positive (``N_i = -N_j``), and the beam's bending moment
in the usual "sagging positive" sense is ``-M_i`` at ``i`` and ``+M_j`` at ``j``. End forces are
the elastic forces (plus the Kelvin dashpot of a contact): ``sigma`` of the natural form; a
dashpot's end forces are its viscous force ``c e'``.

*Reactions* (:func:`reactions`) are the forces **the ground exerts on the structure**: at each
supported DOF (``node.dof``), and through every element attached to the ground (soil, springs,
dashpots, yield links and sliders with one end on the ground). They include every force the elements transmit: elastic,
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

from .elements import DIRECTIONAL_KINDS, DOF_NAMES

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
    y, yd0, ydd0 = _initial_rates(y, rate0, second0)
    if _is_bdf(rule):
        ys, yds = rule.start(y[0], yd0, ydd0, dt)
        yd = _bdf(y, ys[1:], yd0, rule.order, dt)
        return yd, _bdf(yd, yds[1:], ydd0, rule.order, dt)
    if _is_trapezoidal(rule):
        yd = _trapezoidal(y, yd0, dt)
        return yd, _trapezoidal(yd, ydd0, dt)
    return _recursion(y, rule, dt, yd0, ydd0)


def rate(y, rule, dt, *, rate0=None, second0=None) -> np.ndarray:
    """The first rate ``yd`` (N+1, k) of :func:`rates` alone (the same values, half the work for
    the BDF and trapezoidal rules)."""
    y, yd0, ydd0 = _initial_rates(y, rate0, second0)
    if _is_bdf(rule):
        ys, _ = rule.start(y[0], yd0, ydd0, dt)
        return _bdf(y, ys[1:], yd0, rule.order, dt)
    if _is_trapezoidal(rule):
        return _trapezoidal(y, yd0, dt)
    return _recursion(y, rule, dt, yd0, ydd0)[0]


def _initial_rates(y, rate0, second0):
    """``(y, yd0, ydd0)`` as float arrays, the initial rates zero by default."""
    y = np.asarray(y, dtype=float)
    k = y.shape[1]
    yd0 = np.zeros(k) if rate0 is None else np.asarray(rate0, dtype=float)
    ydd0 = np.zeros(k) if second0 is None else np.asarray(second0, dtype=float)
    return y, yd0, ydd0


def _is_bdf(rule) -> bool:
    return getattr(rule, "name", "") in ("bdf1", "bdf2")


def _is_trapezoidal(rule) -> bool:
    return getattr(rule, "alpha", 0.0) == 0.0 and getattr(rule, "name", "") in ("trapezoidal", "newmark") and \
        (rule.gamma, rule.beta) == (0.5, 0.25)


def _recursion(y, rule, dt, yd0, ydd0):
    """Rates of any rule by its step relations, one step after the other."""
    c1, c0 = rule.coefficients(dt)
    yd, ydd = np.empty_like(y), np.empty_like(y)
    yd[0], ydd[0] = yd0, ydd0
    state = rule.start(y[0], yd0, ydd0, dt)
    for n in range(1, y.shape[0]):
        h1, h2 = rule.history(state, dt)
        yd[n] = c1 * y[n] - h1
        ydd[n] = c0 * y[n] - h2
        state = rule.advance(state, y[n], yd[n], ydd[n])
    return yd, ydd


def _bdf(y, past, rate0, order, dt):
    """BDF derivative of the rows of ``y`` with the past values ``past`` before row 0; row 0 is ``rate0``.

    Works on any memory layout of ``y`` (the result has the layout of ``y``).
    """
    out = np.empty_like(y)
    out[0] = rate0
    if order == 1:
        out[1:] = (y[1:] - y[:-1]) / dt
    elif len(y) > 1:
        out[1] = (1.5 * y[1] - 2.0 * y[0] + 0.5 * np.asarray(past[0])) / dt
        out[2:] = (1.5 * y[2:] - 2.0 * y[1:-1] + 0.5 * y[:-2]) / dt
    return out


def _trapezoidal(y, yd0, dt):
    """``y'_n = 2 (y_n - y_{n-1}) / dt - y'_{n-1}``, ``y'_0 = yd0`` (a recursive filter).

    With ``s_n = (-1)^n y'_n`` the recursion is ``s_n = s_{n-1} + (-1)^n dy_n``, a cumulative sum
    (sequential, so each step rounds as the recursion does; no scipy.signal, which takes a second
    to import)."""
    dy = np.diff(y, axis=0) * (2.0 / dt)
    out = np.empty_like(y)
    out[0] = yd0
    if len(dy):
        sign = np.where(np.arange(1, len(y)) % 2 == 0, 1.0, -1.0).reshape(-1, *([1] * (y.ndim - 1)))
        s = np.concatenate([np.asarray(yd0, dtype=float)[None], sign * dy])
        out[1:] = sign * np.cumsum(s, axis=0)[1:]
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
        ``M u''_0 = q_0 - internal forces`` on the DOFs with mass); default: zero acceleration. A run
        of ``method="moreau-jean"`` (velocities that jump at impacts) has for ``uddot`` the mean
        acceleration of each step, ``(u'_k - u'_{k-1}) / dt`` (impulsive at an impact step).
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
        if (getattr(sol, "stats", None) or {}).get("method") == "moreau-jean" and len(sol.t) > 1:
            # velocities that jump at impacts: the mean acceleration of each step, (u'_k - u'_k-1)/dt
            # (the rule's recurrence from u would ring at every jump: +-1e5 after one impact)
            uddot = np.vstack([a0[None], np.diff(np.asarray(sol.udot, dtype=float), axis=0) / dt])
        else:
            _, uddot = rates(sol.u, rule, dt, rate0=sol.udot[0], second0=a0)
        return cls(t=np.asarray(sol.t, dtype=float), u=np.asarray(sol.u, dtype=float),
                   udot=np.asarray(sol.udot, dtype=float), uddot=uddot, v=np.asarray(sol.v, dtype=float),
                   vdot=vdot)


@dataclass(frozen=True)
class StateRows:
    """The state of a run with one row per unknown and one column per step: what the operators
    :class:`BaseForceOperator` and :class:`~unilateral.analysis.energy.EnergyBalance` multiply
    (a matrix times all the steps at once).

    Attributes
    ----------
    x : (n + m, N+1) ``[u; v]``: displacements (relative to the ground) and unilateral deformations
    xdot : (n + m, N+1) ``[u'; v']``: their rates
    n : int, number of DOFs (``u = x[:n]``)
    t : (N+1,) the times of the steps (s), or None; needed with support motions (``theta(t)``)
    """

    x: np.ndarray
    xdot: np.ndarray
    n: int
    t: np.ndarray | None = None

    @classmethod
    def of(cls, u, udot, v, vdot, t=None) -> StateRows:
        """From histories ``u, udot`` (N+1, n) and ``v, vdot`` (N+1, m), at the times ``t`` (N+1,)."""
        n = u.shape[1]
        return cls(x=_rows(u, v), xdot=_rows(udot, vdot), n=n, t=None if t is None else np.asarray(t, dtype=float))

    @classmethod
    def of_solution(cls, sol, rule) -> StateRows:
        """``u``, ``u'``, ``v`` of a :class:`~unilateral.Solution` and the ``v'`` of ``rule`` (name or
        Rule), as :meth:`Histories.from_solution` has them (without the accelerations)."""
        from ..rules import get_rule

        rule = get_rule(rule) if isinstance(rule, str) else rule
        n = sol.u.shape[1]
        x = _rows(sol.u, sol.v)
        xdot = np.empty_like(x)
        xdot[:n] = sol.udot.T
        xdot[n:] = rate(x[n:].T, rule, float(sol.t[1] - sol.t[0])).T
        return cls(x=x, xdot=xdot, n=n, t=np.asarray(sol.t, dtype=float))


def _rows(a, b) -> np.ndarray:
    """``[a^T; b^T]`` (ka + kb, N+1) of two histories (N+1, ka), (N+1, kb)."""
    out = np.empty((a.shape[1] + b.shape[1], a.shape[0]))
    out[:a.shape[1]] = a.T
    out[a.shape[1]:] = b.T
    return out


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
    """Natural stresses ``sigma`` (N+1, ne) of the elements: elastic plus Kelvin.

    Computed once for ``structure`` and the arrays of ``h`` (the end forces, reactions, nodal forces
    and yield forces of a case all start from them) and kept on ``h``, read-only."""
    key = (structure, h.t, h.u, h.v, h.udot, h.vdot)
    cached = getattr(h, "_stresses", None)
    if cached is not None and len(cached[0]) == len(key) and all(a is b for a, b in zip(cached[0], key)):
        return cached[1]
    sigma = structure.natural.stresses(h.t, h.u, h.v, h.udot, h.vdot)
    sigma.flags.writeable = False
    h._stresses = (key, sigma)
    return sigma


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
    dict name -> (N+1, 6) array of ``N_i, V_i, M_i, N_j, V_j, M_j``. For springs, dashpots, soil,
    gaps, yield links and sliders ``N_j = sigma`` (tension positive) and ``N_i = -sigma``; ``V``,
    ``M`` are zero except for a rotational spring or yield link (``M_j = sigma``, ``M_i = -sigma``)
    and a contact with friction: its tangential force ``T`` acts along ``t``, the direction ``d``
    turned clockwise, i.e. along minus the local ``y``, so ``V_j = -T`` and ``V_i = T``.
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
    if sigma.shape[1] == 2:                             # the tangential force of a contact with friction
        out[:, 1] = sigma[:, 1]
        out[:, 4] = -sigma[:, 1]
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


def _onto_masters(structure, forces) -> np.ndarray:
    """Nodal forces (N+1, 3 n_nodes) with those of rigidly linked (slave) nodes added onto their
    master's rows: a support of the master carries them (``T_link^T f`` of
    ``u_s = u_m + rz_m x (x_s - x_m)``), the forces of the slaves' own ground elements included (the
    link transmits the slave's whole nodal force; those elements are ground reactions of their own
    besides)."""
    dofs, coords = structure.dofs, structure.coords
    if not dofs.masters:
        return forces
    out = forces.copy()
    for slave, master in dofs.masters.items():
        s, m = dofs.full_index(slave, "ux"), dofs.full_index(master, "ux")
        dx, dy = np.asarray(coords[slave], dtype=float) - np.asarray(coords[master], dtype=float)
        fx, fy, mz = (forces[:, s + k] for k in range(3))
        out[:, m] += fx
        out[:, m + 1] += fy
        out[:, m + 2] += mz - dy * fx + dx * fy
    return out


def _ground_elements(structure):
    """Elements with one end on the ground: directional elements on a single node."""
    return [e for e in list(structure.elements) + list(structure.dashpots)
            if e.kind in DIRECTIONAL_KINDS and len({node for node, _ in e.dofs}) == 1]


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
    dofs = structure.dofs
    ground, at = {}, {}
    sigma = stresses(structure, h)
    a1 = structure.rayleigh[1] if structure.rayleigh else 0.0
    vectors = {e.name: (cols, rows) for e, cols, rows in _element_vectors(structure)}
    for e in _ground_elements(structure):
        if e.name in vectors:
            cols, _ = vectors[e.name]
            s = sigma[:, cols]
            if a1 and not e.unilateral:
                s = s + a1 * ((h.udot @ _free_a(structure, e).T) @ e.E.T)
        else:
            s = (h.udot @ _free_a(structure, e).T) @ e.E.T
        f = np.zeros((len(h.t), 3))
        for col, (node, dof) in enumerate(e.dofs):
            f[:, DOF_NAMES.index(dof)] -= s @ e.a[:, col]
        ground[e.name] = f
        at[e.name] = e.dofs[0][0]
    support = support_forces(dofs, _onto_masters(structure, nodal_forces(structure, h)), DOF_NAMES, at)
    return {"support": support, "ground_elements": ground, "at": at}


def support_forces(dofs, forces, dof_names, at: dict) -> dict:
    """``{"node.dof": (N+1,)}``: the columns of the nodal forces ``forces`` (N+1, all DOFs, slaves'
    forces carried to their masters) at the supported DOFs, the supports' reactions; ``at`` gains each
    label's node."""
    support = {}
    for node in dofs.nodes:
        for dof in dof_names:
            if (node, dof) in dofs._restrained:
                label = f"{node}.{dof}"
                support[label] = forces[:, dofs.full_index(node, dof)]
                at[label] = node
    return support


def base_point(structure) -> tuple[float, float]:
    """The default point of the overturning moment: the centre of the base.

    The base is the set of nodes the ground acts on (a supported DOF, an element to the ground, a
    footing's contact nodes); of those at the lowest elevation (within ``1e-9`` of the model's
    size), ``(mean x, y)``. Without any such node: the mean x of the lowest nodes.
    """
    coords = structure.coords
    ground = {node for node, _ in structure.dofs._restrained}
    ground |= {e.dofs[0][0] for e in _ground_elements(structure)}
    fnd = getattr(structure, "foundation", None)
    if fnd is not None:
        ground |= set(fnd.contact_nodes())
    nodes = [node for node in structure.dofs.nodes if node in ground] or list(structure.dofs.nodes)
    xy = np.array([coords[node] for node in nodes], dtype=float)
    size = float(np.ptp(np.array(list(coords.values()), dtype=float), axis=0).max()) or 1.0
    low = xy[:, 1].min()
    level = xy[np.abs(xy[:, 1] - low) <= 1e-9 * size]
    return float(level[:, 0].mean()), float(low)


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


def frames(structure) -> list[list]:
    """The separate frames of a structure: groups of nodes joined by anything but a gap element.

    Two buildings that pound through ``gap`` links are two frames; beams, bars, springs between
    nodes, rigid links and every other two-node element join nodes into one. Returns the node
    groups (each in the order of ``structure.dofs.nodes``), largest first; one group for a single
    frame.
    """
    parent = {node: node for node in structure.coords}

    def root(node):
        while parent[node] != node:
            parent[node] = parent[parent[node]]
            node = parent[node]
        return node

    def join(a, b):
        parent[root(a)] = root(b)

    for e in list(structure.elements) + list(structure.dashpots):
        if e.kind == "gap":
            continue
        nodes = list(dict.fromkeys(node for node, _ in e.dofs))
        for other in nodes[1:]:
            join(nodes[0], other)
    for slave, master in structure.dofs.masters.items():
        join(slave, master)
    groups = {}
    for node in structure.coords:
        groups.setdefault(root(node), []).append(node)
    return sorted(groups.values(), key=len, reverse=True)


def base_forces_per_frame(structure, reaction: dict, point=(0.0, 0.0)) -> dict:
    """:func:`base_forces` of each separate frame (:func:`frames`), if there are several.

    Returns
    -------
    dict frame label (``"frame of node <first node>"``) -> the dict of :func:`base_forces`; empty
    for a single frame.
    """
    groups = [g for g in frames(structure) if any(reaction["at"][label] in g for label in reaction["at"])]
    if len(groups) < 2:
        return {}
    out = {}
    for nodes in groups:
        members = set(nodes)
        part = {"support": {k: v for k, v in reaction["support"].items() if reaction["at"][k] in members},
                "ground_elements": {k: v for k, v in reaction["ground_elements"].items()
                                    if reaction["at"][k] in members},
                "at": reaction["at"]}
        out[f"frame of node {nodes[0]}"] = base_forces(structure, part, point)
    return out


def _components(label, f):
    out = np.zeros((len(f), 3))
    out[:, DOF_NAMES.index(label.rsplit(".", 1)[1])] = f
    return out


@dataclass(frozen=True)
class BaseForceOperator:
    """The base forces of :func:`base_forces` as a linear function of the state, assembled once.

    Every force of :func:`reactions` is linear in the state. With ``P`` (ne, 3) and ``P_d``
    (nd, 3) the weights of the element stresses and of the attached dashpots' forces in
    ``(base_shear, base_vertical, overturning_moment)`` (a support's row of the nodal forces, an
    element to the ground its own force, each with its lever arm about ``point``),

        base^T = P^T sigma_tot + P_d^T sigma_d = X [u; v] + X_d [u'; v'] + c

    where ``sigma_tot = E eps + E_v eps' + a1 E_b G^T u'`` (``E_b``: the bilateral elements),
    ``eps = G^T u - B v - theta``, ``eps' = G^T u' - B v'`` and ``sigma_d = E_d G_d^T u'``, so

        X = P^T E [G^T, -B],   X_d = P^T E_v [G^T, -B] + P^T a1 E_b [G^T, 0] + P_d^T E_d [G_d^T, 0],
        c = -P^T E theta

(the Rayleigh part acts on the total strain rate, plastic hinge rotations of beams included).
    With support motions (:mod:`~unilateral.structure.support_motion`) ``theta(t)`` and its rate
    vary: ``c(t) = -P^T (E theta(t) + E_v theta'(t))`` at the times of the :class:`StateRows`
    (:attr:`imposed`; the Rayleigh ``a1`` term is refused with them, so it has no ``theta'``).

    A run's base forces then cost two products of its :class:`StateRows` with (3, n + m)
    matrices instead of every element's forces at every step; they equal :func:`base_forces` of
    :func:`reactions` to round-off (``tests/test_structure_results.py``). A foundation on a soil
    medium adds the soil's contact forces (:meth:`Footings.ground_reactions`), which this
    operator leaves out, as :func:`reactions` does.

    Attributes
    ----------
    X, X_d : (3, n + m);  c : (3,) force unit (rows: base shear, base vertical force,
    overturning moment about ``point``), at ``t = 0`` with support motions
    imposed : :class:`ImposedBase` ``c(t)`` with support motions, else None
    """

    X: np.ndarray
    X_d: np.ndarray
    c: np.ndarray
    imposed: object = None

    @classmethod
    def of(cls, structure, point=(0.0, 0.0)) -> BaseForceOperator:
        """The operator of ``structure`` for moments about ``point`` (x0, y0)."""
        from ..model import ConstantStrain

        nat = structure.natural
        P, P_d = _ground_weights(structure, point)
        strains = sp.hstack([sp.csr_matrix(nat.G).T, -sp.csr_matrix(nat.B)]).tocsr()     # [G^T, -B]
        EtP = np.asarray(nat.E.T @ P)
        viscous = np.zeros_like(P) if nat.E_v is None else np.asarray(nat.E_v.T @ P)
        X_d = np.asarray(strains.T @ viscous).T
        a1 = structure.rayleigh[1] if structure.rayleigh else 0.0
        if a1:
            bilateral = np.ones(P.shape[0], dtype=bool)
            bilateral[structure.unilateral_strains] = False
            X_d[:, :structure.n] += a1 * np.asarray(nat.G @ (nat.E.T @ (P * bilateral[:, None]))).T
        for e, weights in zip(structure.dashpots, P_d):
            X_d[:, :structure.n] += (_free_a(structure, e).T @ (e.E.T @ weights[None])).T
        imposed = None
        if not isinstance(nat.theta, ConstantStrain) or nat.theta_rate is not None:
            imposed = ImposedBase(nat, EtP, None if nat.E_v is None else viscous)
        return cls(X=np.asarray(strains.T @ EtP).T, X_d=X_d, c=-(nat.theta(0.0) @ EtP), imposed=imposed)

    def __call__(self, state: StateRows) -> dict:
        """Base forces (N+1,) each of a run's :class:`StateRows`.

        Returns
        -------
        dict ``base_shear``, ``base_vertical``, ``overturning_moment`` as :func:`base_forces`.
        """
        base = self.X @ state.x + self.X_d @ state.xdot + self._offset(state)
        return {"base_shear": base[0], "base_vertical": base[1], "overturning_moment": base[2]}

    def base_shear(self, state: StateRows) -> np.ndarray:
        """The base shear (N+1,) alone (one row of the products)."""
        return self.X[0] @ state.x + self.X_d[0] @ state.xdot + self._offset(state)[0]

    def _offset(self, state) -> np.ndarray:
        """``c`` (3, 1), or ``c(t)`` (3, N+1) at the state's times with support motions."""
        if self.imposed is None:
            return self.c[:, None]
        return self.imposed(state.t, state.x.shape[1])


class ImposedBase:
    """``c(t) = -P^T (E theta(t) + E_v theta'(t))`` (3, N+1): the part of the base forces of imposed
    strains varying in time (support motions).

    Parameters
    ----------
    natural : :class:`~unilateral.model.NaturalForm` with ``theta(t)`` (and ``theta'(t)``)
    EtP : (ne, 3) ``E^T P``;  EvtP : (ne, 3) ``E_v^T P`` or None (no Kelvin elements)
    """

    def __init__(self, natural, EtP, EvtP):
        self.natural, self.EtP, self.EvtP = natural, EtP, EvtP

    def __call__(self, t, steps) -> np.ndarray:
        """``c`` at the times ``t`` (``steps`` of them, the columns of the state)."""
        if t is None or len(t) != steps:
            raise ValueError(f"state: the base forces with support motions need the {steps} times of the steps "
                             f"(StateRows.of(..., t=)), got {None if t is None else len(t)}")
        t = np.asarray(t, dtype=float)
        theta = np.broadcast_to(self.natural.imposed_strains(t), (len(t), self.EtP.shape[0]))
        c = -(theta @ self.EtP)
        rate = self.natural.theta_rate
        if self.EvtP is not None and rate is not None:
            c = c - np.array([np.asarray(rate(tk), dtype=float) for tk in t]) @ self.EvtP
        return c.T


def _ground_weights(structure, point) -> tuple[np.ndarray, np.ndarray]:
    """Weights ``P`` (ne, 3) and ``P_d`` (nd, 3) of the element stresses and dashpot forces in the base forces.

    A supported DOF's reaction is its row of :func:`nodal_forces` (``sigma_e a_e`` of the elements
    at it, and of those at the nodes rigidly linked to it); an element to the ground adds
    ``-sigma_e a_e`` at its node (:func:`reactions`). Each
    force component at ``(x, y)`` counts with ``arm = (1, 0, -(y - y0))`` (x), ``(0, 1, x - x0)``
    (y) or ``(0, 0, 1)`` (moment).
    """
    coords, dofs = structure.coords, structure.dofs
    W = np.zeros((dofs.T.shape[0], 3))
    for node, dof in dofs._restrained:
        W[dofs.full_index(node, dof)] = _arm(coords[node], dof, point)
    # a rigidly linked slave's nodal forces reach its master's supports (_onto_masters)
    for slave, master in dofs.masters.items():
        s, m = dofs.full_index(slave, "ux"), dofs.full_index(master, "ux")
        dx, dy = np.asarray(coords[slave], dtype=float) - np.asarray(coords[master], dtype=float)
        W[s] += W[m] - dy * W[m + 2]
        W[s + 1] += W[m + 1] + dx * W[m + 2]
        W[s + 2] += W[m + 2]
    ground = {e.name for e in _ground_elements(structure)}

    def weights(e, rows):
        w = e.a @ W[rows]
        if e.name in ground:
            node = e.dofs[0][0]
            w -= e.a @ np.array([_arm(coords[node], dof, point) for _, dof in e.dofs])
        return w

    P = np.zeros((structure.natural.G.shape[1], 3))
    for e, cols, rows in _element_vectors(structure):
        P[cols] = weights(e, rows)
    P_d = np.array([weights(e, _full_rows(structure, e))[0] for e in structure.dashpots]).reshape(-1, 3)
    return P, P_d


def _arm(xy, dof, point) -> np.ndarray:
    """``(fx, fy, mz)`` of a unit force component ``dof`` at ``xy``, the moment about ``point``."""
    (x, y), (x0, y0) = xy, point
    return np.array({"ux": (1.0, 0.0, -(y - y0)), "uy": (0.0, 1.0, x - x0), "rz": (0.0, 0.0, 1.0)}[dof])


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
