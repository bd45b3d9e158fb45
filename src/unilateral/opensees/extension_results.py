"""The queries of the extension elements (:mod:`.extensions`): ``eleForce`` and ``eleResponse``.

Their forces are the constraint reactions ``psi`` of the state the analysis reached (those of the
stepping, or of the static state), so a Kelvin contact's force includes its dashpot's:

* ``kelvinContact``: as a ``zeroLength`` from ``i`` to ``j``: ``eleForce`` ``-f`` at ``i`` and ``+f``
  at ``j`` along its direction (``f <= 0`` the contact force, tension positive; with friction also
  the tangential force ``T`` along the direction turned 90 degrees clockwise); ``eleResponse``
  ``'basicForce'`` ``[f]`` (``[f, T]``), ``'deformation'`` ``[u_j - u_i]`` along ``-dir``,
  ``'opening'`` the contact's unknown ``v`` (the gap's opening, 0 in contact);
* ``footing``, ``springFooting``: ``eleForce`` ``[Fx, Fy, Mz]`` at the footing's node, the forces the
  node exerts on the footing (minus the soil's resultant on it about the node: compression
  negative, as a ``zeroLength`` from the ground); ``eleResponse`` ``'force'`` the same,
  ``'contactForce'`` each patch's or spring's compressive force (>= 0), ``'uplift'`` each one's
  opening (>= 0), ``'slip'`` (a footing that slides) each patch's net slip, ``'settlement'`` (a
  spring footing with ``-qult``) each spring's plastic settlement;
* ``rigidContact``: ``eleForce`` ``[Fx, Fy, Mz]`` at its node, minus the ground's force on it (the
  contact force ``c >= 0`` along ``-dir``); ``'contactForce'`` ``[c]``, ``'opening'`` ``[u . d + gap]``.
"""

from __future__ import annotations

import numpy as np

from .extension_elements import Footing, KelvinContact, RigidContact, SpringFooting
from .refusals import refuse

__all__ = ["end_forces", "response", "response_names", "command_name", "pick", "state_psi"]

#: The command that defines each kind of extension element.
_COMMANDS = {Footing: "footing", SpringFooting: "springFooting", KelvinContact: "kelvinContact",
             RigidContact: "rigidContact"}
_FORCE = ("force", "forces", "globalForce", "globalForces")



def pick(values, dof, what):
    """All ``values`` (``dof`` -1 or None), or the ``dof``-th (1-based)."""
    values = [float(x) for x in values]
    if dof is None or dof == -1:
        return values
    if not 1 <= int(dof) <= len(values):
        refuse(what, f"DOF {dof} is not among 1..{len(values)}", "a DOF of the element")
    return values[int(dof) - 1]


def state_psi(analysis) -> np.ndarray:
    """The reactions ``psi`` (m,) of the state the analysis holds."""
    if analysis.built is None or analysis.built_version != analysis.domain.version:
        analysis.current()
    sim = analysis.sim
    if sim is not None and sim["sim"].n and sim["sim"].state.v is analysis.v:
        return sim["sim"].state.psi
    static = getattr(analysis, "static_result", None)
    if static is not None and static.v is analysis.v:
        return static.psi
    refuse("the force of an extension element", "no static or transient step has been analysed on the model as "
           "it is (a DisplacementControl state has no reactions of its own here)", "analyze() first")


def _index(model, name):
    return list(model.constraint_names).index(name)


def _kelvin(analysis, tag, e):
    """``(f, T or None, deformation, opening)`` of the Kelvin contact ``tag``."""
    b = analysis.built
    model = b.model
    psi, v = state_psi(analysis), analysis.v
    k = _index(model, f"x{tag}")
    U = b.nodal(analysis.u)
    d = e.direction - 1
    de = float(U[b.row[e.j] + d] - U[b.row[e.i] + d])
    tangential = None
    if e.mu is not None:                           # the stick spring's force: kt (e_t - s+ + s-)
        st = b.structure
        nat, at = st.natural, 0
        for element in st.elements:
            if element.name == f"x{tag}":
                break
            at += element.E.shape[0]
        mp = np.shape(nat.B)[1]
        eps = np.asarray(nat.G.T @ (b.ties @ analysis.u)).ravel() - np.asarray(nat.B @ v[:mp]).ravel() \
            - np.asarray(nat.theta(0.0)).ravel()
        tangential = float(np.asarray(nat.E @ eps).ravel()[at + 1])
    return float(psi[k]), tangential, de, float(v[k])


def _footing_rows(analysis, tag, e):
    """``(x of each contact from the node, the contacts' rows, the rows of the shears (a footing that
    slides) or of the settlements (a spring footing with ``-qult``), or None)`` of a footing."""
    b = analysis.built
    model = b.model
    name = f"x{tag}"
    st = b.structure
    x0 = float(analysis.domain.nodes[e.node][0])
    if isinstance(e, SpringFooting):
        names = [f"{name}.{j + 1}" for j in range(e.springs)]
        x = [float(st.coords[n][0]) - x0 for n in names]
        rows = [_index(model, n) for n in names]
        plastic = [_index(model, f"{n}.plastic-") for n in names] if e.q_ult is not None else None
        return x, rows, plastic
    fnd = st.foundation
    footing = next(f for f in fnd.footings if f.name == name)
    first = list(fnd.contact_names).index(footing.contact_names[0])
    x = [float(c) - x0 for c in footing.patches.centres[:, 0]]
    patches = range(first, first + footing.m)
    rows = [int(model.contacts[p]) for p in patches]
    shears = [int(model.shears[p]) for p in patches] if footing.sliding else None
    return x, rows, shears


def _footing(analysis, tag, e):
    """``(soil's force on the node (3,), contact forces, openings, other v)`` of a footing."""
    psi, v = state_psi(analysis), analysis.v
    x, rows, other = _footing_rows(analysis, tag, e)
    c = -psi[rows]                                    # compressive contact forces (both kinds: psi = -c, sigma)
    F = np.array([0.0, float(c.sum()), float(np.dot(c, x))])
    if isinstance(e, Footing) and other is not None:
        F[0] = float(psi[other].sum())                 # the soil's horizontal force on the footing
    return F, c, v[rows], (None if other is None else v[other])


def _rigid(analysis, tag, e):
    """``(contact force >= 0, opening >= 0)`` of the rigid contact ``tag``."""
    b = analysis.built
    if b is None or analysis.built_version != analysis.domain.version:
        b = analysis.current()
    U = b.nodal(analysis.u)
    return float(analysis.v[_index(b.model, f"x{tag}")]), float(U[b.row[e.node] + e.direction - 1] + e.gap)


def end_forces(analysis, tag) -> np.ndarray:
    """``eleForce`` of the extension element ``tag`` (see the module)."""
    e = analysis.domain.extensions[tag]
    nf = analysis.built.ndf if analysis.built is not None else analysis.domain.ndf
    if isinstance(e, RigidContact):
        force = np.zeros(nf)
        force[e.direction - 1] = -_rigid(analysis, tag, e)[0]
        return force
    if isinstance(e, KelvinContact):
        f, t, _, _ = _kelvin(analysis, tag, e)
        direction = np.zeros(nf)
        direction[e.direction - 1] = 1.0
        force = f * direction
        if t is not None:                              # the tangent: the direction turned clockwise
            turned = np.zeros(nf)
            turned[:2] = (direction[1], -direction[0])
            force = force + t * turned
        return np.r_[-force, force]
    F, *_ = _footing(analysis, tag, e)
    return -F


def command_name(e) -> str:
    """The command (``"footing"``, ``"springFooting"``, ...) that defines the extension element ``e``."""
    return _COMMANDS[type(e)]


def response_names(e) -> tuple:
    """The names ``eleResponse`` of the extension element ``e`` answers (its ``'force'`` first), as the
    error messages list them; ``'forces'``, ``'globalForce(s)'`` and ``'basicDeformation'`` are synonyms
    accepted too."""
    if isinstance(e, RigidContact):
        return ("force", "contactForce", "opening")
    if isinstance(e, KelvinContact):
        return ("force", "basicForce", "deformation", "opening")
    names = ("force", "contactForce", "uplift")
    if isinstance(e, Footing) and e.mu is not None:
        return names + ("slip",)
    if isinstance(e, SpringFooting) and e.q_ult is not None:
        return names + ("settlement",)
    return names


def accepted(e, name) -> bool:
    """Whether ``eleResponse(tag, name)`` of the extension element ``e`` is one of its responses."""
    return name in response_names(e) or name in _FORCE or (isinstance(e, KelvinContact) and name == "basicDeformation")


def response(analysis, tag, *args) -> list:
    """``eleResponse`` of the extension element ``tag`` (see the module)."""
    e = analysis.domain.extensions[tag]
    name = args[0] if args else None
    what = f"eleResponse({', '.join(map(repr, (tag, *args)))})"
    if not accepted(e, name):
        refuse(what, f"the response {name!r} is not one of this {command_name(e)}'s",
               ", ".join(map(repr, response_names(e))))
    if name in _FORCE:
        return [float(x) for x in end_forces(analysis, tag)]
    if isinstance(e, RigidContact):
        c, opening = _rigid(analysis, tag, e)
        table = {"contactForce": [c], "opening": [opening]}
    elif isinstance(e, KelvinContact):
        f, t, de, opening = _kelvin(analysis, tag, e)
        table = {"basicForce": [f] if t is None else [f, t], "deformation": [de], "basicDeformation": [de],
                 "opening": [opening]}
    else:
        _, c, openings, other = _footing(analysis, tag, e)
        table = {"contactForce": c, "uplift": openings}
        if other is not None:
            table["slip" if isinstance(e, Footing) else "settlement"] = other
    return [float(x) for x in table[name]]
