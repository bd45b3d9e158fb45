"""The model figure of a 3-D frame (:class:`~unilateral.structure.Frame3D`): ``model.png`` in perspective.

:func:`model_drawing_3d` reads a built 3-D frame into a :class:`ModelDrawing3D` (plain data, no
matplotlib); :meth:`ModelDrawing3D.figure` draws it on 3-D axes (x, y horizontal, z up, equal scales):

* the nodes (grey dots), the elements between two nodes (beams, bars, springs, dashpots, gaps,
  cables), each kind in the style of the 2-D figure (:data:`unilateral.figures.styles.KIND_STYLES`),
  with a legend;
* the elements to the ground (soil springs, springs, dashpots on one node) as a short segment from
  their node along minus their direction (a soil spring along ``uz`` hangs below its node);
* rigid links and the ties of rigid diaphragms (thin grey dashes from the master to each slave);
* supports (a triangle: translations held; a square: rotations held too), lumped masses (black
  dots, area proportional to the mass);
* footings: their contact patches as rectangles in plan at the footing's elevation, the footing's
  name beside it.

Used by ``unilateral plot --model`` for a 3-D model file.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .styles import GROUND_SYMBOL, KIND_STYLES

#: The translations and rotations of a 3-D node.
TRANSLATIONS, ROTATIONS = ("ux", "uy", "uz"), ("rx", "ry", "rz")


@dataclass
class ModelDrawing3D:
    """A 3-D frame as drawn by :meth:`figure`; plain data.

    Attributes
    ----------
    coords : dict str -> (x, y, z)
        Node id (as text) -> coordinates [length].
    members : list of (kind, name, node_i, node_j)
    grounded : list of (kind, name, node, (dx, dy, dz))
        Elements from a node to the ground, along the unit translation ``(dx, dy, dz)`` of the element
        (``(0, 0, 0)``: a rotational element).
    ties : list of (master, slave)
        Rigid links and slaves of rigid diaphragms.
    supports : list of (node, restrained)
        The restrained DOFs of the node (names among ``ux`` ... ``rz``).
    masses : list of (node, m)
    footings : list of (name, z, centres, sizes)
        Each footing's elevation and its patches: centres (m, 2) and sizes (m, 2) in plan [length].
    length_unit, title : str
    """

    coords: dict
    members: list = field(default_factory=list)
    grounded: list = field(default_factory=list)
    ties: list = field(default_factory=list)
    supports: list = field(default_factory=list)
    masses: list = field(default_factory=list)
    footings: list = field(default_factory=list)
    length_unit: str = ""
    title: str = ""

    def figure(self):
        """The figure: a :class:`matplotlib.figure.Figure` on an Agg canvas."""
        from .plots import _styled

        return _styled(_figure)(self)


def model_drawing_3d(structure, *, units=None, title="") -> ModelDrawing3D:
    """The :class:`ModelDrawing3D` of a built 3-D frame (``Structure3D``)."""
    dofs = structure.dofs
    coords = {str(node): tuple(float(c) for c in xyz) for node, xyz in structure.coords.items()}
    drawing = ModelDrawing3D(coords=coords, length_unit=(units or {}).get("length", ""), title=str(title))
    for e in list(structure.elements) + list(structure.dashpots):
        nodes = list(dict.fromkeys(node for node, _ in e.dofs))
        kind = e.kind if e.kind in KIND_STYLES else ("beam" if e.kind.startswith("beam") else "spring")
        if len(nodes) >= 2:
            drawing.members.append((kind, e.name, str(nodes[0]), str(nodes[1])))
        else:
            drawing.grounded.append((kind, e.name, str(nodes[0]), _direction(e)))
    drawing.ties = [(str(master), str(slave)) for slave, (master, _) in getattr(dofs, "ties", {}).items()]
    held = {}
    for node, dof in dofs._restrained:
        held.setdefault(str(node), []).append(dof)
    drawing.supports = [(node, tuple(sorted(d, key=(TRANSLATIONS + ROTATIONS).index))) for node, d in held.items()]
    drawing.masses = [(str(node), float(mass[0])) for node, mass in zip(dofs.nodes, structure.nodal_mass) if mass[0] > 0]
    if structure.foundation is not None:
        drawing.footings = [(str(f.name), float(f.y), np.asarray(f.patches.centres, dtype=float).tolist(),
                             np.broadcast_to(f.patches.sizes, f.patches.centres.shape).astype(float).tolist())
                            for f in structure.foundation.footings]
    return drawing


def _direction(element) -> tuple[float, float, float]:
    """The unit translation of a one-node element (its strain's row over ux, uy, uz), or zeros."""
    row = dict(zip((dof for _, dof in element.dofs), np.asarray(element.a, dtype=float)[0]))
    d = np.array([row.get(dof, 0.0) for dof in TRANSLATIONS])
    norm = float(np.linalg.norm(d))
    return tuple((d / norm).tolist()) if norm else (0.0, 0.0, 0.0)


def _figure(drawing: ModelDrawing3D):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    from .plots import DPI, PAGE_WIDTH, math_unit, plain_text

    xyz = np.array(list(drawing.coords.values()) or [(0.0, 0.0, 0.0)], dtype=float)
    size = max(float(np.ptp(xyz, axis=0).max()), 1e-9)
    fig = Figure(figsize=(PAGE_WIDTH, 0.85 * PAGE_WIDTH), dpi=DPI)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    at = lambda node: np.asarray(drawing.coords[node], dtype=float)   # noqa: E731
    kinds = []
    for kind, _, i, j in drawing.members:
        label, colour, style, width = KIND_STYLES[kind]
        (a, b) = at(i), at(j)
        ax.plot(*np.column_stack([a, b]), color=colour, linestyle=style, linewidth=width)
        kinds.append(kind)
    for kind, _, node, direction in drawing.grounded:
        label, colour, style, width = KIND_STYLES[kind]
        a = at(node)
        d = np.asarray(direction, dtype=float)
        b = a - GROUND_SYMBOL * size * (d if d.any() else np.array([0.0, 0.0, 1.0]))
        ax.plot(*np.column_stack([a, b]), color=colour, linestyle=style, linewidth=width)
        kinds.append(kind)
    for master, slave in drawing.ties:
        ax.plot(*np.column_stack([at(master), at(slave)]), color="0.65", linestyle=(0, (2, 2)), linewidth=0.7)
    for name, z, centres, sizes in drawing.footings:
        for (x, y), (w, h) in zip(centres, sizes):
            corners = np.array([[x - w / 2, y - h / 2], [x + w / 2, y - h / 2], [x + w / 2, y + h / 2],
                                [x - w / 2, y + h / 2], [x - w / 2, y - h / 2]])
            ax.plot(corners[:, 0], corners[:, 1], np.full(5, z), color="0.45", linewidth=0.6)
        c = np.mean(np.asarray(centres, dtype=float), axis=0)
        ax.text(c[0], c[1], z - 0.04 * size, name, fontsize=6, color="0.3")
    for node, held in drawing.supports:
        marker = "s" if any(dof in ROTATIONS for dof in held) else "^"
        ax.scatter(*at(node), marker=marker, s=30, color="0.2", depthshade=False)
    ax.scatter(*xyz.T, s=4, color="0.5", depthshade=False)
    if drawing.masses:
        m = np.array([mass for _, mass in drawing.masses])
        points = np.array([at(node) for node, _ in drawing.masses])
        ax.scatter(*points.T, s=8 + 40 * m / m.max(), color="black", depthshade=False)
    lo, hi = xyz.min(axis=0), xyz.max(axis=0)
    centre, half = 0.5 * (lo + hi), 0.55 * size
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    unit = math_unit(drawing.length_unit) if drawing.length_unit else ""
    for setter, axis in zip((ax.set_xlabel, ax.set_ylabel, ax.set_zlabel), "xyz"):
        setter(f"${axis}$ [{unit}]" if unit else f"${axis}$")
    if drawing.title:
        ax.set_title(plain_text(str(drawing.title)[:200]))
    handles = [Line2D([], [], color=KIND_STYLES[k][1], linestyle=KIND_STYLES[k][2], linewidth=KIND_STYLES[k][3],
                      label=KIND_STYLES[k][0]) for k in dict.fromkeys(kinds)]
    if drawing.ties:
        handles.append(Line2D([], [], color="0.65", linestyle=(0, (2, 2)), label="rigid link / diaphragm"))
    if drawing.footings:
        handles.append(Line2D([], [], color="0.45", label="footing patches"))
    fig.legend(handles=handles, loc="lower center", ncol=3, frameon=False, fontsize=7)
    return fig
