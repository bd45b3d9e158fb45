"""Queries in OpenSees's layout and signs: ``nodeDisp``, ``nodeVel``, ``nodeAccel``, ``eleForce``,
``eleResponse``, ``reactions`` and ``nodeReaction``.

* Nodal values are those of the nodal DOFs (``ux, uy, rz``); with a ``UniformExcitation`` they
  are relative to the ground, as in OpenSees. A DOF that is fixed, or a rotation nothing
  stiffens, is 0.
* ``eleForce`` of an ``elasticBeamColumn``: its global end forces ``(Fx, Fy, Mz)`` at ``i`` then
  ``j``, the forces the nodes exert on the element (``K_e u_e``: no Rayleigh damping force, as in
  OpenSees);
  of a ``zeroLength``: ``-f`` at ``i`` and ``+f`` at ``j`` along each direction, ``f`` the material
  force (tension positive).
* ``eleResponse(zeroLength, 'deformation' | 'basicDeformation')``: the material deformations
  ``u_j - u_i``; ``'basicForce'``: the material forces; ``'force'``: as ``eleForce``. For a beam
  ``'force'``/``'globalForce'``, ``'localForce'`` and ``'basicForce'`` ``(N, M_i, M_j)``.
* ``reactions()`` then ``nodeReaction``: the sum of the element forces at the node minus the nodal
  loads applied there (OpenSees's static reactions: no inertia, no damping forces).
"""

from __future__ import annotations

import numpy as np

from .elements import BeamColumn, Truss
from .elements3d import BeamColumn3D, beam_stiffness3d
from .eleloads import element_load_forces
from .pdelta import element_geometric
from .refusals import refuse
from .springs import spring_table

__all__ = ["nodal", "element_force", "material_forces", "spring_state", "spring_kind", "element_response",
           "nodal_reactions"]


_NODAL = {"u": "nodeDisp", "ud": "nodeVel", "udd": "nodeAccel"}


def _pick(values, dof, what):
    values = [float(x) for x in values]
    if dof is None or dof == -1:
        return values
    if not 1 <= int(dof) <= len(values):
        refuse(what, f"DOF {dof} is not among 1..{len(values)}", "a DOF of the node")
    return values[int(dof) - 1]


def _ready(analysis, what):
    if analysis.built is None or analysis.built_version != analysis.domain.version:
        analysis.current()
    return analysis.built


def nodal(analysis, which, tag, dof=-1):
    """``nodeDisp``, ``nodeVel`` or ``nodeAccel``.

    Parameters
    ----------
    analysis : Analysis
    which : str, ``"u"``, ``"ud"`` or ``"udd"``
    tag : int, the node
    dof : int, 1, 2 or 3; -1: all three

    Returns
    -------
    float or list of 3 floats
    """
    what = _Label(_NODAL[which], tag)
    tag = int(tag)
    if tag not in analysis.domain.nodes:
        refuse(what, f"node {tag} is not defined", "a defined node")
    b = _ready(analysis, what)
    U = _state(analysis)[which]
    return _pick(U[b.row[tag]:b.row[tag] + b.ndf], dof, what)


class _Label:
    """The name of a query in a refusal, formatted only if one is raised."""

    def __init__(self, command, tag, args=()):
        self.command, self.tag, self.args = command, tag, args

    def __str__(self):
        return f"{self.command}({', '.join(map(repr, (self.tag, *self.args)))})"

    __format__ = lambda self, spec: format(str(self), spec)


def _element(analysis, tag, what):
    tag = int(tag)
    e = analysis.domain.elements.get(tag)
    if e is None:
        refuse(what, f"element {tag} is not defined", "a defined element")
    return tag, e


def material_forces(analysis, tag):
    """``[(e, f), ...]``: deformation and force of each material of the zeroLength or truss ``tag``,
    one material at a time (the reference of the vectorised :func:`spring_state`)."""
    b = analysis.built
    e = analysis.domain.elements[tag]
    state = _state(analysis)
    U, Ud, sigma = state["u"], state["ud"], state["sigma"]
    out = []
    ri, rj, nf = b.row[e.i], b.row[e.j], b.ndf
    for material, direction, reads, damp in b.springs[tag]:
        de = float(direction @ (U[rj:rj + nf] - U[ri:ri + nf]))
        dv = float(direction @ (Ud[rj:rj + nf] - Ud[ri:ri + nf]))
        forces = [sign * sigma[strain] for strain, sign in reads]
        out.append((de, material.force(de, dv, forces) + damp * material.E * dv))
    return out


def _state(analysis) -> dict:
    """The nodal ``u``, ``ud``, ``udd`` and the element stresses of the current state, computed once
    per state (the queries of one step share them; the springs' responses are
    added by :func:`spring_state`)."""
    b = analysis.built
    cache = getattr(analysis, "_query_cache", None)
    if cache is not None:
        key = cache[0]
        if (key[0] is b and key[1] is analysis.u and key[2] is analysis.ud and key[3] is analysis.udd
                and key[4] is analysis.v):
            return cache[1]
    key = (b, analysis.u, analysis.ud, analysis.udd, analysis.v)
    state = _StateValues(key)
    analysis._query_cache = (key, state)                  # (holding the arrays: their identity is the key)
    return state


class _StateValues(dict):
    """``{"u", "ud", "udd", "sigma"}`` of the state ``key`` (``(built, u, ud, udd, v)``), each
    computed on its first use (a ``nodeDisp`` needs no stresses)."""

    def __init__(self, key):
        super().__init__()
        self.key = key

    def __missing__(self, name):
        b, u, ud, udd, v = self.key
        if name == "sigma":
            value = b.stresses(u, v)
        elif name in ("u", "ud", "udd"):
            value = b.nodal({"u": u, "ud": ud, "udd": udd}[name])
        else:
            raise KeyError(name)
        self[name] = value
        return value


def spring_state(analysis) -> dict:
    """The responses of every spring (zeroLength or truss material) in the current state, computed
    once per state for all of them (:class:`~.springs.SpringTable`).

    Returns
    -------
    dict
        ``{"e": (1, columns), "f": (1, columns), "force": (1, elements, 2 ndf)}``: the materials'
        deformations and forces and the springs' global end forces (without a truss's inertia
        load), with ``.table`` the :class:`~.springs.SpringTable` (its ``columns`` and ``elements``
        by tag).
    """
    state = _state(analysis)
    springs = state.get("springs")
    if springs is None:
        b = analysis.built
        table = spring_table(b, analysis.domain)
        springs = state["springs"] = table.state(state["u"][None], state["ud"][None],
                                                 state["sigma"][None, b.stress[0]])
    return springs


def spring_kind(e, name):
    """What ``eleResponse(tag, name)`` of the zeroLength or truss ``e`` reads from :func:`spring_state`:
    ``"force"`` (global end forces), ``"e"`` (deformations), ``"f"`` (material forces), or None (not in
    the subset)."""
    truss = isinstance(e, Truss)
    if name in ("force", "forces") or (truss and name == "globalForce"):
        return "force"
    if name in ("deformation", "deformations", "basicDeformation", "basicDeformations"):
        return "e"
    if name in ("basicForce", "basicForces") or (truss and name == "axialForce"):
        return "f"
    return None


def element_force(analysis, tag, dof=-1):
    """``eleForce(tag, dof)``.

    Parameters
    ----------
    analysis : Analysis
    tag : int, the element
    dof : int, 1..6; -1: all six

    Returns
    -------
    float or list of 6 floats (``i`` then ``j``, global axes)
    """
    springs = _current_springs(analysis)
    if springs is not None:
        at = springs.table.lookup.get(("eleForce", tag))
        if at is not None:
            values = springs["force"][0, at]
            if dof is None or dof == -1:
                return values.tolist()
            if dof in _DOFS and dof <= values.size:
                return float(values[int(dof) - 1])
    what = _Label("eleForce", tag)
    tag, e = _element(analysis, tag, what)
    b = _ready(analysis, what)
    if tag in b.springs and not (isinstance(e, Truss) and e.rho):
        springs = spring_state(analysis)
        springs.table.lookup[("eleForce", tag)] = springs.table.elements[tag]
    return _pick(_global_force(analysis, b, tag, e), dof, what)


#: The DOFs of an element's end forces (2 nodes x 3 or 6 DOFs) a query's fast path takes.
_DOFS = frozenset(range(1, 13))


def _current_springs(analysis):
    """The springs' responses (:func:`spring_state`) of the current state if they are computed
    already, else None (the queries' fast path: a lookup in the table of the responses asked)."""
    cache = getattr(analysis, "_query_cache", None)
    if cache is None or analysis.built_version != analysis.domain.version:
        return None
    key, state = cache
    if (key[0] is analysis.built and key[1] is analysis.u and key[2] is analysis.ud and key[3] is analysis.udd
            and key[4] is analysis.v):
        return state.get("springs")
    return None


def _global_force(analysis, b, tag, e, geometric=True):
    """The global end forces of element ``tag``; a ``PDelta`` beam's with its string forces
    ``N (v_i - v_j) / L`` unless ``geometric`` is False (OpenSees's local and basic forces have none)."""
    if isinstance(e, (BeamColumn, BeamColumn3D)):
        rows, Ke, _ = b.beams[tag]
        U = _state(analysis)["u"][rows]
        if geometric and b.pdelta and tag in b.pdelta:
            Ke = Ke + element_geometric(b.pdelta, tag, b.axial[tag])
        if isinstance(e, BeamColumn):                     # minus its element loads' nodal loads
            return Ke @ U - element_load_forces(analysis.domain, tag, analysis.domain.time)
        return Ke @ U
    springs = spring_state(analysis)
    out = springs["force"][0, springs.table.elements[tag]]
    if isinstance(e, Truss) and e.rho:
        out = out + _truss_inertia_load(analysis, b, e)
    return out


def _truss_inertia_load(analysis, b, e):
    """OpenSees's truss holds the ground motion's inertia load ``-m a_g`` of its lumped masses
    ``m = rho L / 2`` in its resisting force (``eleForce`` is ``A sigma`` at the ends plus ``m a_g``)."""
    d = analysis.domain
    half = e.rho * float(np.hypot(*np.subtract(d.nodes[e.j], d.nodes[e.i]))) / 2
    out = np.zeros(2 * b.ndf)
    for p in d.patterns.values():
        if p.kind == "UniformExcitation" and p.direction <= 2:
            a_g = p.frozen if p.frozen is not None else p.factor * float(d.series[p.series](np.array([d.time]))[0])
            out[[p.direction - 1, b.ndf + p.direction - 1]] += half * a_g
    return out


def _beam_response(analysis, b, tag, e, name):
    """``'localForce'`` or ``'basicForce'`` of a beam (2-D: ``N, M_i, M_j``; 3-D: ``N, Mz_i, Mz_j, My_i,
    My_j, T``), or None for another response."""
    f = _global_force(analysis, b, tag, e, geometric=False)
    if isinstance(e, BeamColumn3D):
        local = beam_stiffness3d(analysis.domain, e)[1] @ f
        basic = local[[6, 5, 11, 4, 10, 9]]
    else:
        xi, xj = np.array(analysis.domain.nodes[e.i]), np.array(analysis.domain.nodes[e.j])
        c, s = (xj - xi) / np.hypot(*(xj - xi))
        R = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
        local = np.r_[R @ f[:3], R @ f[3:]]
        basic = local[[3, 2, 5]]
    if name in ("localForce", "localForces"):
        return [float(x) for x in local]
    if name in ("basicForce", "basicForces"):
        return [float(x) for x in basic]
    return None


def element_response(analysis, tag, *args):
    """``eleResponse(tag, *args)``.

    Parameters
    ----------
    analysis : Analysis
    tag : int, the element
    args : the response, e.g. ``'force'``, ``'deformation'``, ``'basicForce'``, ``'localForce'``

    Returns
    -------
    list of floats
    """
    if len(args) == 1 and isinstance(args[0], str):
        springs = _current_springs(analysis)
        if springs is not None:
            hit = springs.table.lookup.get((tag, args[0]))
            if hit is not None:
                return springs[hit[0]][hit[1]].tolist()
    what = _Label("eleResponse", tag, args)
    tag, e = _element(analysis, tag, what)
    b = _ready(analysis, what)
    name = args[0] if args else None
    if tag in b.springs:                                  # a zeroLength or a truss
        kind = spring_kind(e, name)
        if kind == "force":
            if not (isinstance(e, Truss) and e.rho):
                _remember(analysis, (tag, name), kind, spring_state(analysis).table.elements[tag])
            return _global_force(analysis, b, tag, e).tolist()
        if kind is not None:
            springs = spring_state(analysis)
            _remember(analysis, (tag, name), kind, springs.table.columns[tag])
            return springs[kind][0, springs.table.columns[tag]].tolist()
    else:
        if name in ("force", "forces", "globalForce", "globalForces"):
            return [float(x) for x in _global_force(analysis, b, tag, e)]
        values = _beam_response(analysis, b, tag, e, name)
        if values is not None:
            return values
    refuse(what, "the response is not in the subset", "'force' or 'deformation' (zeroLength); 'force', "
           "'localForce' or 'basicForce' (elasticBeamColumn); 'force', 'axialForce' or 'deformation' (truss)")


def _remember(analysis, key, kind, at):
    """Enter the response ``key`` (``(tag, name)``) of a spring in the table of the fast path:
    ``springs[kind][0, at]``."""
    if isinstance(key[1], str):
        spring_state(analysis).table.lookup[key] = (kind, (0, at))


def nodal_reactions(analysis, *args):
    """``reactions()``.

    Parameters
    ----------
    analysis : Analysis
    args : none (``'-dynamic'`` and ``'-rayleigh'`` are refused)

    Returns
    -------
    dict
        ``{node tag: (3,) [Rx, Ry, Mz]}``.
    """
    if args:
        refuse(f"reactions{args}", "reactions with inertia or damping ('-dynamic', '-rayleigh') are not in the "
               "subset", "reactions() (the static reactions: element forces minus nodal loads)")
    b = _ready(analysis, "reactions")
    d = analysis.domain
    R = np.zeros(b.mass.size)
    nf = b.ndf
    for tag, e in d.elements.items():
        f = _global_force(analysis, b, tag, e)
        R[b.row[e.i]:b.row[e.i] + nf] += f[:nf]
        R[b.row[e.j]:b.row[e.j] + nf] += f[nf:]
    for p in d.patterns.values():
        if p.kind != "Plain":
            continue
        factor = p.frozen if p.frozen is not None else p.factor * float(d.series[p.series](np.array([d.time]))[0])
        for node, values in p.loads:
            R[b.row[node]:b.row[node] + nf] -= factor * values
    return {tag: R[b.row[tag]:b.row[tag] + nf] for tag in d.nodes}
