"""The recorded :class:`~.domain.Domain` -> a :class:`~unilateral.structure.Frame2D`, its
:class:`~unilateral.structure.Structure` and the :class:`~unilateral.Model` solved.

The nodes are those of the script (``ux, uy, rz``; a rotation nothing stiffens is not a DOF, as
in ``Frame2D``); ``fix`` removes DOFs; ``equalDOF`` ties are eliminated exactly: the DOFs of
the built structure are ``T u`` of the reduced ones (one per group of tied DOFs), so that
``G -> T^T G`` and ``M -> T^T M T``. The masses (nodal and the lumped ``-mass`` of beams) and the
damping are assembled here as OpenSees assembles them: Rayleigh ``alphaM`` on the masses of the
nodes and elements that existed when ``rayleigh`` was called, ``betaK + betaKinit + betaKcomm`` on
the stiffness of those elastic beams and ``-doRayleigh`` Elastic springs (the tangent, initial and
committed stiffness of an elastic element are one), never on contacts or yield springs (OpenSees's
``zeroLength`` default); a material's ``eta`` is a dashpot.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..model import Model
from ..structure import Frame2D, Frame3D
from .elements import BeamColumn, Truss, beam_stiffness
from .elements3d import BeamColumn3D, beam_stiffness3d
from .extension_elements import add_to_frame
from .materials import DIRECTIONS
from .pdelta import pdelta_table, with_axial
from .refusals import OpenSeesRefused, refuse

__all__ = ["Built", "build"]


@dataclass
class Built:
    """A built domain.

    Attributes
    ----------
    structure : Structure, of the Frame2D (DOFs before the ties)
    model : Model, on the reduced DOFs
    P : (3 nodes, n) csr, the nodal DOFs ``U = P u`` of the reduced ``u`` (rows ``3 p + d``)
    row : dict node tag -> ``3 p``, its first row of ``P``
    mass : (3 nodes,) the lumped masses of the nodal DOFs
    beams : dict tag -> (rows (6,), K_e (6, 6), stiffness damping factor)
    springs : dict tag -> list of (material, direction (ndf,) unit vector on the nodal DOFs,
        [(strain index, sign) of the elements read], damping factor) of a zeroLength's materials or a
        truss's material (as a force-deformation law, :meth:`~.materials.Material.on_truss`)
    ties : (n_structure, n) csr, the structure's DOFs ``T u`` of the reduced ``u`` (the equalDOF ties)
    pdelta : dict tag -> the P-Delta table of the beams of a ``PDelta`` transformation (:mod:`.pdelta`)
    linear : Model, the model without their geometric stiffness (``model`` is it plus ``K_G(axial)``)
    axial : dict tag -> the axial force of their geometric stiffness in ``model``
    """

    structure: object
    model: Model
    P: sp.csr_matrix
    row: dict
    mass: np.ndarray
    beams: dict
    springs: dict
    ties: sp.csr_matrix = None
    ndf: int = 3
    stress: tuple = None
    pdelta: dict = None
    linear: Model = None
    axial: dict = None

    def stresses(self, u, v) -> np.ndarray:
        """The element stresses (ne,) of the reduced ``u`` and ``v``, at the strains the queries read
        (zero elsewhere)."""
        rows, S_u, S_v, s0, ne = self.stress
        sigma = np.zeros(ne)
        if rows.size:
            sigma[rows] = S_u @ u - S_v @ v[:S_v.shape[1]] - s0      # (the frame's own v: not a soil's, a rigid contact's)
        return sigma

    def nodal(self, u) -> np.ndarray:
        """The nodal DOFs (3 nodes,) of the reduced ``u``."""
        return np.asarray(self.P @ u).ravel()

    def reduced(self, f_full) -> np.ndarray:
        """The reduced load ``P^T f`` of nodal forces ``f`` (3 nodes,)."""
        return np.asarray(self.P.T @ f_full).ravel()


def build(domain) -> Built:
    """Build the model of ``domain``.

    Parameters
    ----------
    domain : Domain
        The record of the script's commands.

    Returns
    -------
    Built

    Raises
    ------
    OpenSeesRefused
        For a model that cannot be built (a free DOF without stiffness, every DOF fixed).
    """
    if not domain.nodes:
        refuse("analyze", "the model has no nodes", "define nodes and elements first")
    nf = domain.ndf
    try:
        fr = _frame(domain)
        names = _add_elements(fr, domain)
        st = fr.build()
    except (ValueError, TypeError) as exc:
        if isinstance(exc, OpenSeesRefused):
            raise
        raise OpenSeesRefused("analyze", f"the model cannot be built: {exc}",
                              "give every free DOF a stiffness (an element, a fix or an equalDOF)") from None
    T, reduced_names = _ties(domain, st)
    P = (st.dofs.T @ T).tocsr()
    row = {tag: nf * p for p, tag in enumerate(st.dofs.nodes)}
    mass, alpha_mass = _masses(domain, row)
    factors = domain.damping[0] if domain.damping else (0.0, 0.0, 0.0, 0.0)
    beta = factors[1] + factors[2] + factors[3]
    beams, springs, K_damped = _element_tables(domain, st, row, names, beta)
    M = (P.T @ sp.diags(mass) @ P).tocsr()
    C = factors[0] * (P.T @ sp.diags(alpha_mass) @ P) + P.T @ K_damped @ P
    if st.C is not None:
        C = C + T.T @ st.C @ T
    nat = st.natural
    A = nat.A if np.any(nat.A) else None
    C = sp.csr_matrix(C) if C.nnz else None
    if getattr(st, "rigid", None) is None:
        model = Model.from_natural((T.T @ nat.G).tocsr(), nat.E, nat.B, M=M, A=A, r=nat.r, theta=nat.theta(0.0),
                                   C=C, E_v=nat.E_v, dof_names=reduced_names,
                                   constraint_names=list(st.constraint_names), families=st.families())
    else:                                         # rigid contacts (.extensions): their columns appended
        from .soil_model import rigid_model

        model = rigid_model(st, T, M, C, reduced_names)
    built = Built(st, model, P, row, mass, beams, springs, T, nf, _stress_rows(st, T, springs),
                  pdelta_table(domain, row), model, {})
    if st.foundation is not None:
        from .soil_model import on_soil

        on_soil(built)
    if built.pdelta:
        with_axial(built, {})
    return built


def _stress_rows(st, T, springs):
    """``(rows, S_u, S_v, s0, ne)``: ``sigma[rows] = S_u u - S_v v - s0`` (``E (G^T T u - B v - theta)``)
    at the strains the queries of the zeroLength elements read."""
    nat = st.natural
    rows = np.array(sorted({strain for table in springs.values() for *_, reads, _ in table
                            for strain, _ in reads}), dtype=np.int64)
    E = sp.csr_matrix(nat.E)[rows]
    theta = np.asarray(nat.theta(0.0), dtype=float)
    S_u = (E @ sp.csr_matrix(nat.G).T @ T).tocsr()
    S_v = sp.csr_matrix(E @ sp.csr_matrix(nat.B))
    return rows, S_u, S_v, np.asarray(E @ theta).ravel(), sp.csr_matrix(nat.E).shape[0]


def _frame(domain):
    """The Frame2D or Frame3D of the nodes, supports, rotary masses and rigid links and diaphragms."""
    if domain.ndm == 2:
        fr = Frame2D()
        for tag, (x, y) in domain.nodes.items():
            fr.node(tag, x, y)
        for tag, flags in domain.fixes.items():
            if any(flags):
                fr.support(tag, ux=bool(flags[0]), uy=bool(flags[1]), rz=bool(flags[2]))
        for tag, (_, _, J) in domain.masses.items():
            if J > 0:
                fr.mass(tag, 0.0, J=J)                   # (a rotational mass makes rz a DOF)
        for kind, master, slaves in domain.rigid:
            fr.rigid_link(master, slaves[0])
        return fr
    fr = Frame3D()
    for tag, (x, y, z) in domain.nodes.items():
        fr.node(tag, x, y, z)
    for kind, master, slaves in domain.rigid:
        if kind == "link":
            fr.rigid_link(master, slaves[0])
        else:
            fr.rigid_diaphragm(master, slaves)
    for tag, flags in domain.fixes.items():
        if any(flags):
            fr.support(tag, **{d: bool(f) for d, f in zip(("ux", "uy", "uz", "rx", "ry", "rz"), flags)})
    for tag, values in domain.masses.items():
        if any(values[3:]):
            fr.mass(tag, 0.0, Jx=values[3], Jy=values[4], Jz=values[5])
    return fr


def _add_elements(fr, domain) -> dict:
    """Add every element to ``fr``; ``{(tag, k): [(element name, sign), ...]}`` of the zeroLength materials."""
    names = {}
    dofs = DIRECTIONS[domain.ndf]
    for tag, e in domain.elements.items():
        if isinstance(e, BeamColumn):
            fr.beam(f"e{tag}", e.i, e.j, E=e.E, A=e.A, I=e.I)
            continue
        if isinstance(e, BeamColumn3D):
            fr.beam(f"e{tag}", e.i, e.j, E=e.E, A=e.A, Iy=e.Iy, Iz=e.Iz, G=e.G, J=e.J,
                    vecxz=domain.transforms[e.transf][1])
            continue
        if isinstance(e, Truss):
            material, chord = truss_material(domain, e)
            names[(tag, 0)] = material.add(fr, f"e{tag}.0", e.i, e.j, tuple(chord))
            continue
        for k, (mat, direction) in enumerate(zip(e.materials, e.directions)):
            name = f"e{tag}.{k}"
            names[(tag, k)] = domain.materials[mat].add(fr, name, e.i, e.j, dofs[direction])
    add_to_frame(fr, domain)
    return names


def truss_material(domain, e):
    """The material of the truss ``e`` as its force-deformation law and its chord ``(c, s)``."""
    d = np.subtract(domain.nodes[e.j], domain.nodes[e.i])
    L = float(np.hypot(*d))
    return domain.materials[e.material].on_truss(e.A, L), d / L


def _ties(domain, st):
    """``T`` (n_structure, n_reduced) of the equalDOF ties and the names of the reduced DOFs."""
    free = list(st.dofs.free)
    parent = {}

    def find(x):
        """The root of the group of tied DOFs of ``x``."""
        while parent.get(x, x) != x:
            x = parent[x]
        return x

    names = DIRECTIONS[domain.ndf]
    for master, slave, dofs in domain.ties:
        for d in dofs:
            a, b = find((master, names[d])), find((slave, names[d]))
            if a != b:
                parent[b] = a
    fixed = {find((tag, names[d + 1])) for tag, flags in domain.fixes.items() for d in range(domain.ndf)
             if flags[d]}
    groups, rows, cols = {}, [], []
    for k, dof in enumerate(free):
        root = find(dof)
        if root in fixed:                                 # fixed, or tied to a fixed DOF
            continue
        col = groups.setdefault(root, len(groups))
        rows.append(k)
        cols.append(col)
    names = [None] * len(groups)
    for k, col in zip(rows, cols):
        if names[col] is None:
            names[col] = f"{free[k][0]}.{free[k][1]}"
    if not groups:
        refuse("analyze", "every DOF is fixed or tied to a fixed DOF", "free some DOFs")
    T = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(free), len(groups)))
    return T, names


def _masses(domain, row):
    """The lumped masses of the nodal DOFs and those of them Rayleigh's ``alphaM`` acts on."""
    nf = domain.ndf
    n = nf * len(row)
    mass, damped = np.zeros(n), np.zeros(n)
    nodes, elements = (domain.damping[1], domain.damping[2]) if domain.damping else ((), ())
    for tag, values in domain.masses.items():
        mass[row[tag]:row[tag] + nf] += values
        if tag in nodes:
            damped[row[tag]:row[tag] + nf] += values
    for tag, e in domain.elements.items():
        per_length = e.mass if isinstance(e, BeamColumn) else e.rho if isinstance(e, Truss) else 0.0
        if per_length:
            L = float(np.hypot(*np.subtract(domain.nodes[e.j], domain.nodes[e.i])))
            # a truss's mass is damped by alphaM only with -doRayleigh 1 (OpenSees's Truss::getDamp)
            alpha = tag in elements and (not isinstance(e, Truss) or e.rayleigh)
            for node in (e.i, e.j):
                half = np.array([per_length * L / 2, per_length * L / 2, 0.0])
                mass[row[node]:row[node] + 3] += half
                if alpha:
                    damped[row[node]:row[node] + 3] += half
    return mass, damped


def _element_tables(domain, st, row, names, beta):
    """The beams' and springs' tables for the queries and the damped stiffness (3 nodes, 3 nodes)."""
    starts, at = {}, 0
    for e in st.elements:
        starts[e.name] = at
        at += e.E.shape[0]
    in_set = domain.damping[2] if domain.damping else frozenset()
    nf = domain.ndf
    n = nf * len(row)
    K = sp.lil_matrix((n, n))
    beams, springs = {}, {}
    for tag, e in domain.elements.items():
        factor = beta if tag in in_set else 0.0
        if isinstance(e, (BeamColumn, BeamColumn3D)):
            rows = np.r_[row[e.i]:row[e.i] + nf, row[e.j]:row[e.j] + nf]
            if isinstance(e, BeamColumn):
                Ke = beam_stiffness(domain.nodes[e.i], domain.nodes[e.j], e.A, e.E, e.I)
            else:
                Ke = beam_stiffness3d(domain, e)[0]
            beams[tag] = (rows, Ke, factor)
            if factor:
                K[np.ix_(rows, rows)] += factor * Ke
            continue
        springs[tag] = _spring_table(domain, tag, factor, (row, names, starts), K)
    return beams, springs, K.tocsr()


def _spring_table(domain, tag, factor, tables, K):
    """The materials of the zeroLength or truss ``tag`` (see :class:`Built`); their Rayleigh damping
    added to ``K``. ``tables``: the nodes' first rows, the elements' names and their first strains."""
    row, names, starts = tables
    e = domain.elements[tag]
    nf = domain.ndf
    if isinstance(e, Truss):
        material, chord = truss_material(domain, e)
        laws = [(material, np.r_[chord, np.zeros(nf - 2)])]
    else:
        laws = [(domain.materials[mat], np.eye(nf)[direction - 1]) for mat, direction in zip(e.materials, e.directions)]
    table = []
    rows = np.r_[row[e.i]:row[e.i] + nf, row[e.j]:row[e.j] + nf]
    for k, (material, vector) in enumerate(laws):
        damp = factor if e.rayleigh else 0.0
        table.append((material, vector, [(starts[name], sign) for name, sign in names[(tag, k)]], damp))
        if damp:
            t = np.r_[-vector, vector]
            K[np.ix_(rows, rows)] += damp * material.E * np.outer(t, t)
    return table
