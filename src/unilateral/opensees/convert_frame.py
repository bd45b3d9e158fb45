"""The structure of a recorded :class:`~.domain.Domain` as the frame tables of a model file.

Each OpenSees object becomes the model-file entry that builds the same element of the
:class:`~unilateral.structure.Frame2D` (``Frame3D``) as :mod:`.build` does, under the same name
(``e<tag>``, ``e<tag>.<k>`` for the materials of a ``zeroLength``, the parts of a composite
``e<tag>.<k>.<p>``): the materials are added to a :class:`_Recorder` by the very
:meth:`~.materials.Material.add` that adds them to the frame, and each call it records is written
as its entry (``spring``, ``dashpot``, ``gap``, ``yield``). What the model file has no key for is
refused by :func:`not_convertible`, naming the command and what is missing.
"""

from __future__ import annotations

import numpy as np

from .build import truss_material
from .elements import BeamColumn, Truss
from .elements3d import BeamColumn3D
from .materials import DIRECTIONS
from .refusals import OpenSeesRefused

__all__ = ["NotConvertible", "not_convertible", "structure_tables"]


class NotConvertible(OpenSeesRefused):
    """A command of the script that the model file cannot express (see :func:`not_convertible`)."""

    def __init__(self, what, why, instead):
        super().__init__(what, why, instead)
        self.args = (f"unilateral convert cannot write {what} as a model file: {why}. Nearest: {instead}",)

    def __str__(self) -> str:
        return self.args[0]


def not_convertible(what, why, instead):
    """Raise :class:`NotConvertible` for ``what``, with why the model file cannot say it and the nearest
    it can say."""
    raise NotConvertible(str(what), why, instead)


class _Recorder:
    """Stands for the frame in :meth:`~.materials.Material.add`: records the elements it adds."""

    def __init__(self, tag, ndf):
        self.tag, self.ndf = tag, ndf
        self.elements, self.unilateral = [], []

    @staticmethod
    def _direction(direction):
        return direction if isinstance(direction, str) else [float(x) for x in direction]

    def spring(self, name, i, k, *, j=None, direction):
        """A linear spring (an ``Elastic`` material; one of stiffness 0, a ``Steel01`` with ``b = 0``, is none)."""
        if k == 0:
            return
        self.elements.append({"type": "spring", "name": name, "node_i": i, "node_j": j, "k": float(k),
                              "direction": self._direction(direction)})

    def dashpot(self, name, i, c, *, j=None, direction):
        """A dashpot (the ``eta`` of an ``Elastic`` material)."""
        self.elements.append({"type": "dashpot", "name": name, "node_i": i, "node_j": j, "c": float(c),
                              "direction": self._direction(direction)})

    def gap(self, name, i, j, k, *, gap=0.0, direction):
        """A compression-only contact (``ENT``, ``ElasticPPGap``)."""
        self.unilateral.append({"type": "gap", "name": name, "node_i": i, "node_j": j, "k": float(k),
                                "gap": float(gap), "direction": self._direction(direction)})

    def yield_link(self, name, i, j, *, k, Fy_t, Fy_c, direction):
        """An elastic-plastic link (``ElasticPP`` and the yielding part of a composite)."""
        self.unilateral.append({"type": "yield", "name": name, "node": i, "node_j": j, "k": float(k),
                                "Fy_t": float(Fy_t), "Fy_c": float(Fy_c), "direction": self._direction(direction)})

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        not_convertible(f"the material of element {self.tag} (an ElasticPP with eps0)", "the model file's yield "
                        "link has no imposed strain", "eps0 = 0, or a [[unilateral]] yield link without it")


def structure_tables(domain) -> tuple[dict, dict]:
    """The frame tables (``nodes``, ``supports``, ..., ``damping``) of ``domain`` and the support flags
    ``{node: (0 or 1, ...)}`` of its nodes (``fix`` and the ``equalDOF`` ties to fixed DOFs).

    Raises
    ------
    NotConvertible
        For what the model file cannot express (see the module).
    """
    if not domain.nodes:
        not_convertible("the script", "it defines no nodes", "a model with nodes and elements")
    for tag, (kind, _) in domain.transforms.items():
        if kind != "Linear":
            not_convertible(f"geomTransf({kind!r}, {tag})", "the model file's p_delta is the consistent geometric "
                            "stiffness of the gravity's axial forces, not OpenSees's string stiffness of each "
                            "element's current axial force", "geomTransf('Linear', tag)")
    fixed, links, equal = _fixities(domain)
    names = ("ux", "uy", "rz") if domain.ndf == 3 else ("ux", "uy", "uz", "rx", "ry", "rz")
    tables = {"nodes": [{"id": tag, **dict(zip("xyz", map(float, xyz)))} for tag, xyz in domain.nodes.items()],
              "supports": [{"node": tag, **{n: bool(f) for n, f in zip(names, flags)}}
                           for tag, flags in fixed.items() if any(flags)],
              "rigid_links": links + [{"master": m, "slave": s[0]} for kind, m, s in domain.rigid if kind == "link"],
              "equal_dofs": equal}
    if domain.ndm == 3:
        tables["rigid_diaphragms"] = [{"master": m, "slaves": list(s)} for kind, m, s in domain.rigid
                                      if kind == "diaphragm"]
    elements, unilateral, owners = _elements(domain)
    tables.update(elements=elements, unilateral=unilateral, masses=_masses(domain, fixed))
    damping = _damping(domain, elements, owners)
    if damping:
        tables["damping"] = damping
    return {key: value for key, value in tables.items() if value != []}, fixed


def _fixities(domain):
    """The supports (fix, and equalDOF ties to a fixed DOF), the ties that are rigid links and the
    other ties (``[[equal_dofs]]``).

    A DOF tied by ``equalDOF`` to a fixed one is fixed (as :func:`.build._ties` eliminates it); a tie of
    every DOF of two nodes at one point is a rigid link; any other tie is an ``[[equal_dofs]]`` entry.
    """
    nf = domain.ndf
    fixed = {tag: list(domain.fixes.get(tag, (0,) * nf)) for tag in domain.nodes}
    changed = True
    while changed:                                   # a tie carries a fixity both ways, along chains
        changed = False
        for master, slave, dofs in domain.ties:
            for d in dofs:
                if fixed[master][d - 1] != fixed[slave][d - 1]:
                    fixed[master][d - 1] = fixed[slave][d - 1] = 1
                    changed = True
    links, between = [], []
    for master, slave, dofs in domain.ties:
        free = [d for d in dofs if not fixed[master][d - 1]]
        if not free:
            continue
        if sorted(dofs) == list(range(1, nf + 1)) and domain.nodes[master] == domain.nodes[slave]:
            links.append({"master": master, "slave": slave})
            continue
        between.append((master, slave, free))
    return {tag: tuple(flags) for tag, flags in fixed.items()}, links, _equal_dofs(domain, between, links)


def _equal_dofs(domain, between, links) -> list:
    """``[[equal_dofs]]`` of the ``equalDOF`` ties ``(master, slave, free DOFs)`` between free DOFs: each
    group of DOFs tied together follows its node defined first (whose DOF names the group, as in
    :func:`.build._ties`)."""
    names = ("ux", "uy", "rz") if domain.ndf == 3 else ("ux", "uy", "uz", "rx", "ry", "rz")
    followers = {link["slave"] for link in links} | {s for kind, _, slaves in domain.rigid for s in slaves}
    parent = {}

    def find(x):
        while parent.get(x, x) != x:
            x = parent[x]
        return x

    for master, slave, free in between:
        for node in (master, slave):
            if node in followers:
                not_convertible(f"equalDOF({master}, {slave}, {', '.join(map(str, free))})", f"node {node} also "
                                "follows a rigid link or diaphragm, and the model file ties a DOF to one master",
                                "equalDOF to the master of the rigid link")
        for d in free:
            a, b = find((master, d)), find((slave, d))
            if a != b:
                parent[b] = a
    order = {tag: k for k, tag in enumerate(domain.nodes)}
    groups = {}
    for key in {key for master, slave, free in between for node in (master, slave) for key in [(node, d) for d in free]}:
        groups.setdefault(find(key), []).append(key)
    pairs = {}
    for members in groups.values():
        root = min(members, key=lambda key: order[key[0]])
        for node, d in members:
            if node != root[0]:
                pairs.setdefault((root[0], node), []).append(d)
    return [{"master": m, "slave": s, "dofs": [names[d - 1] for d in sorted(dofs)]}
            for (m, s), dofs in sorted(pairs.items(), key=lambda item: (order[item[0][1]], order[item[0][0]]))]


def _elements(domain):
    """The ``[[elements]]`` and ``[[unilateral]]`` entries and ``{entry name: element tag}``."""
    elements, unilateral, owners = [], [], {}
    for tag, e in domain.elements.items():
        name = f"e{tag}"
        if isinstance(e, BeamColumn):
            entries = [{"type": "beam", "name": name, "node_i": e.i, "node_j": e.j, "E": float(e.E),
                        "A": float(e.A), "I": float(e.I)}]
            elements += entries
            owners[name] = tag
            continue
        if isinstance(e, BeamColumn3D):
            vecxz = [float(x) for x in domain.transforms[e.transf][1]]
            elements.append({"type": "beam", "name": name, "node_i": e.i, "node_j": e.j, "E": float(e.E),
                             "A": float(e.A), "Iy": float(e.Iy), "Iz": float(e.Iz), "G": float(e.G),
                             "J": float(e.J), "vecxz": vecxz})
            owners[name] = tag
            continue
        rec = _Recorder(tag, domain.ndf)
        if isinstance(e, Truss):
            material, chord = truss_material(domain, e)
            material.add(rec, f"{name}.0", e.i, e.j, tuple(chord))
        else:
            for k, (mat, direction) in enumerate(zip(e.materials, e.directions)):
                domain.materials[mat].add(rec, f"{name}.{k}", e.i, e.j, DIRECTIONS[domain.ndf][direction])
        for entry in rec.elements + rec.unilateral:
            if entry.get("node_j", 0) is None:
                del entry["node_j"]
            owners[entry["name"]] = tag
        elements += rec.elements
        unilateral += rec.unilateral
    return elements, unilateral, owners


def _masses(domain, fixed) -> list:
    """``[[masses]]``: the nodal masses and a truss's ``rho L / 2`` at each end, one ``m`` on the translations."""
    nd, nf = domain.ndm, domain.ndf
    values = {tag: np.array(m, dtype=float) for tag, m in domain.masses.items()}
    for tag, e in domain.elements.items():
        if isinstance(e, Truss) and e.rho:
            L = float(np.hypot(*np.subtract(domain.nodes[e.j], domain.nodes[e.i])))
            for node in (e.i, e.j):
                values.setdefault(node, np.zeros(nf))[:2] += e.rho * L / 2
    out = []
    for tag in domain.nodes:
        if tag not in values or not np.any(values[tag]):
            continue
        m = values[tag]
        free = {float(m[d]) for d in range(nd) if not fixed[tag][d]}
        if len(free) > 1:
            not_convertible(f"mass({tag}, {', '.join(f'{x:g}' for x in m)})", "a [[masses]] entry has one mass m "
                            f"on every translation, the node has {sorted(free)} on its free ones",
                            "equal translational masses (mass(tag, m, m, ...))")
        entry = {"node": tag, "m": free.pop() if free else float(m[:nd].max())}
        rotary = ("J",) if nf == 3 else ("Jx", "Jy", "Jz")
        entry.update({name: float(x) for name, x in zip(rotary, m[nd:]) if x})
        out.append(entry)
    return out


def _damping(domain, elements, owners) -> dict:
    """``[damping] rayleigh = { a0, a1 }`` of ``rayleigh(alphaM, betaK, betaKinit, betaKcomm)``, if it acts
    as the model file's ``a0 M + a1 K`` (every mass, every bilateral element: see the checks)."""
    if domain.damping is None:
        return {}
    factors, nodes, damped = domain.damping
    alpha, beta = factors[0], factors[1] + factors[2] + factors[3]
    what = f"rayleigh({', '.join(f'{x:g}' for x in factors)})"
    if alpha:
        for tag, m in domain.masses.items():
            if np.any(m) and tag not in nodes:
                not_convertible(what, f"its alphaM acts on the nodes defined before it, not on node {tag}, whose "
                                "mass the model file's a0 M damps", "rayleigh(...) after every node")
        for tag, e in domain.elements.items():
            if isinstance(e, Truss) and e.rho and not (tag in damped and e.rayleigh):
                not_convertible(what, f"the mass of truss {tag} is not damped by alphaM (OpenSees: only with "
                                "-doRayleigh 1, defined before the rayleigh call), the model file's a0 M damps it",
                                "'-doRayleigh', 1 on the truss, or its mass as nodal masses")
    if beta:
        for entry in elements:
            tag = owners[entry["name"]]
            e = domain.elements[tag]
            if entry["type"] == "dashpot":
                continue
            if tag not in damped or (entry["type"] == "spring" and not e.rayleigh):
                not_convertible(what, f"its betaK acts on element {tag} in OpenSees only if it existed at the call "
                                "(and a zeroLength or truss only with -doRayleigh 1), the model file's a1 K acts on "
                                f"every bilateral element ({entry['name']})", "rayleigh(...) after every element, "
                                "'-doRayleigh', 1 on every elastic zeroLength and truss, or betaK = 0")
    if not (alpha or beta):
        return {}
    return {"rayleigh": {"a0": float(alpha), "a1": float(beta)}}
