"""The model figure ``model.png``: the structure with the names of its parts, and its first modes.

:func:`model_drawing` reads a built frame (:class:`unilateral.structure.Structure`) into a
:class:`ModelDrawing`, plain data (no matplotlib is imported) that ``results.nc`` keeps as JSON in its
attribute ``model_drawing``, so that ``unilateral plot`` redraws the figure; :func:`model_figure`
draws it:

* the nodes (their ids in grey), the elements (beams, bars, rigid links, springs, dashpots) and
  the unilateral elements (gaps, cables, soil springs, yielding links, sliders; plastic hinges as
  open circles near their beam end), each named, every kind in its own style with a legend;
  elements to the ground are drawn from their node away along their direction, to a ground line;
  rotational springs and links between coincident nodes as a diamond at the node;
* supports (a triangle: pinned, a square: fixed against rotation too, hollow: one direction only),
  lumped masses (black dots, area proportional to the mass) and footings (a grey strip across
  their width, cut into their contact patches, each patch numbered: the patch ``k`` of footing
  ``A`` is the contact ``A.k``);
* below, the first mode shapes of the bilateral structure (:mod:`unilateral.structure.modes`:
  every constraint held), the translations scaled to a tenth of the structure's size.

Names are placed where they overlap the fewest names already placed (the unilateral elements
first, then the elements, the footings and the nodes), trying a few offsets around their anchor.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from .styles import GROUND_SYMBOL, KIND_STYLES

#: The kinds of ``[[unilateral]]`` elements (and ``"hinge"``).
UNILATERAL_KINDS = ("gap", "cable", "soil", "yield", "slider", "hinge")
#: How many mode shapes are drawn.
MODE_COUNT = 3
#: Font size of the names, points.
NAME_SIZE = 6.0


@dataclass
class Footing:
    """A footing as drawn: its name, extent ``x0 .. x1`` at elevation ``y`` [length] and patches."""

    name: str
    x0: float
    x1: float
    y: float
    patch_x: tuple          # (m,) patch centres [length]
    patch_width: tuple      # (m,) patch widths along x [length]
    patch_names: tuple      # (m,) contact names, "<footing>.<k>"


@dataclass
class ModelDrawing:
    """A frame as drawn by :func:`model_figure`; plain data (picklable, no matplotlib).

    Attributes
    ----------
    coords : dict str -> (x, y)
        Node id (as text) -> coordinates [length].
    members : list of (kind, name, node_i, node_j)
        Elements between two nodes (``kind`` a key of :data:`KIND_STYLES`).
    grounded : list of (kind, name, node, (dx, dy))
        Elements from a node to the ground, the ground along the unit ``(dx, dy)`` from the node;
        ``(0, 0)``: a rotational element.
    hinges : list of (name, node, other)
        Plastic hinges at ``node`` on the beam towards node ``other``.
    supports : list of (node, restrained)
        ``restrained``: the restrained DOFs of the node, a tuple of ``"ux"``, ``"uy"``, ``"rz"``.
    masses : list of (node, m)
        Lumped translational masses [model mass unit].
    links : list of (master, slave)
        Rigid links (to the end of a chain of links).
    footings : list of Footing
    modes : list of (period, dict node -> (dx, dy))
        The first mode shapes: node translations (largest component of the shape 1).
    length_unit, time_unit, title : str
    """

    coords: dict
    members: list = field(default_factory=list)
    grounded: list = field(default_factory=list)
    hinges: list = field(default_factory=list)
    supports: list = field(default_factory=list)
    masses: list = field(default_factory=list)
    links: list = field(default_factory=list)
    footings: list = field(default_factory=list)
    modes: list = field(default_factory=list)
    length_unit: str = ""
    time_unit: str = ""
    title: str = ""

    def to_json(self) -> str:
        """The drawing as JSON (the attribute ``model_drawing`` of ``results.nc``)."""
        return json.dumps(asdict(self), separators=(",", ":"))

    @classmethod
    def from_json(cls, text: str) -> ModelDrawing:
        """The drawing of :meth:`to_json`.

        Raises
        ------
        ValueError, TypeError, KeyError
            ``text`` is not such JSON.
        """
        data = json.loads(text)
        if not isinstance(data, dict):
            raise TypeError(f"expected a JSON object, got {type(data).__name__}")
        data["coords"] = {str(node): (float(x), float(y)) for node, (x, y) in data["coords"].items()}
        data["footings"] = [Footing(**footing) for footing in data.get("footings", ())]
        data["modes"] = [(float(period), {str(node): tuple(d) for node, d in shape.items()})
                         for period, shape in data.get("modes", ())]
        return cls(**data)

    def figure(self):
        """The figure of :func:`model_figure`."""
        return model_figure(self)

    @property
    def unilateral_names(self) -> list[str]:
        """The names of the unilateral elements drawn (hinges included; footing patches not)."""
        return ([name for kind, name, *_ in self.members + self.grounded if kind in UNILATERAL_KINDS]
                + [name for name, *_ in self.hinges])


# ---------------------------------------------------------------------- from a structure
def model_drawing(structure, *, shapes=None, periods=None, units=None, title="") -> ModelDrawing:
    """Read a built frame into a :class:`ModelDrawing`.

    Parameters
    ----------
    structure : unilateral.structure.Structure
    shapes : (k, n) array_like, optional
        Mode shapes over the free DOFs (``mode_shape`` of :func:`unilateral.structure.modes.modes`);
        the first :data:`MODE_COUNT` are drawn. None: no modes.
    periods : (k,) array_like, optional
        Their periods [time].
    units : dict, optional
        ``length`` and ``time`` units, for the axis labels and the periods.
    title : str
    """
    units = units or {}
    coords = {str(node): (float(x), float(y)) for node, (x, y) in structure.coords.items()}
    drawing = ModelDrawing(coords=coords, length_unit=units.get("length", ""), time_unit=units.get("time", ""),
                           title=title)
    for element in (*structure.elements, *structure.dashpots):
        _add_element(drawing, element)
    drawing.supports = _supports(structure)
    drawing.links = [(str(master), str(slave)) for slave, master in structure.dofs.masters.items()]
    drawing.masses = [(str(node), float(m)) for node, m in zip(structure.dofs.nodes, structure.nodal_mass[:, 0])
                      if m > 0]
    footings = getattr(structure, "foundation", None)
    drawing.footings = [_footing(f) for f in (footings.footings if footings is not None else ())]
    if shapes is not None and periods is not None:
        nodal = structure.dofs.nodal(np.asarray(shapes, dtype=float)[:MODE_COUNT])
        drawing.modes = [(float(T), {str(node): (float(d[0]), float(d[1])) for node, d in zip(structure.dofs.nodes, u)})
                         for T, u in zip(periods, nodal)]
    return drawing


def _element_nodes(element) -> list:
    """The nodes of an element, in the order of its DOFs."""
    return list(dict.fromkeys(node for node, _ in element.dofs))


def _add_element(drawing: ModelDrawing, element) -> None:
    """Add a natural-form element (and the hinges of a beam) to ``drawing``."""
    nodes = _element_nodes(element)
    kind = element.kind
    if kind == "beam":
        for unknown in element.unknowns:
            if unknown.kind == "yield" and unknown.name.endswith(".plastic+"):
                node = unknown.node
                other = nodes[1] if node == nodes[0] else nodes[0]
                drawing.hinges.append((unknown.name[: -len(".plastic+")], str(node), str(other)))
    if len(nodes) == 2 and kind in KIND_STYLES:
        drawing.members.append((kind, element.name, str(nodes[0]), str(nodes[1])))
    elif len(nodes) == 1 and kind in KIND_STYLES:
        drawing.grounded.append((kind, element.name, str(nodes[0]), _ground_direction(element)))


def _ground_direction(element) -> tuple[float, float]:
    """The unit vector from the node of an element to the ground towards its ground end, or ``(0, 0)``
    for a rotation. Its strain (row 0 of ``a``) is ``+d . u`` with the ground at end ``i`` and
    ``-d . u`` with the ground at end ``j``: either way the ground end lies along ``-a``."""
    row = {dof: float(element.a[0, k]) for k, (_, dof) in enumerate(element.dofs)}
    vector = -np.array([row.get("ux", 0.0), row.get("uy", 0.0)])
    length = float(np.hypot(*vector))
    return (0.0, 0.0) if length == 0 else (float(vector[0] / length), float(vector[1] / length))


def _supports(structure) -> list:
    """``(node, restrained DOFs)`` of the supported nodes: a translation that is no free DOF of a
    node that is no slave; a rotation that is no free DOF of a node an element rotates."""
    dofs = structure.dofs
    free = set(dofs.free)
    rotated = {node for e in (*structure.elements, *structure.dashpots) for node, dof in e.dofs if dof == "rz"}
    out = []
    for node in dofs.nodes:
        if node in dofs.masters:
            continue
        restrained = tuple(dof for dof in ("ux", "uy") if (node, dof) not in free)
        if restrained and node in rotated and (node, "rz") not in free:
            restrained += ("rz",)
        if restrained:
            out.append((str(node), restrained))
    return out


def _footing(f) -> Footing:
    """A :class:`~unilateral.structure.foundation.Foundation` as drawn."""
    x = np.asarray(f.patches.centres[:, 0], dtype=float)
    width = np.asarray(f.patches.sizes[:, 0], dtype=float)
    return Footing(name=str(f.name), x0=float(np.min(x - width / 2)), x1=float(np.max(x + width / 2)),
                   y=float(f.y), patch_x=tuple(x.tolist()), patch_width=tuple(width.tolist()),
                   patch_names=tuple(str(name) for name in f.contact_names))


def model_file_drawing(path):
    """The :class:`ModelDrawing` of a model file, with the modes of its bilateral structure; for a
    3-D frame its :class:`~unilateral.figures.model3d.ModelDrawing3D`.

    Raises
    ------
    unilateral.modelfile.ModelFileError
        The file is invalid or is a matrix-level model (no frame to draw).
    """
    from ..structure.modes import modes
    from ..modelfile import ModelFileError, load_model_file

    spec = load_model_file(path)
    if spec.structure is None:
        raise ModelFileError(path, ["[matrices]: a matrix-level model has no frame to draw (the model figure "
                                    "needs nodes and elements)"])
    if spec.document.DIMENSIONS == 3:                 # in perspective, without the modes
        from .model3d import model_drawing_3d

        return model_drawing_3d(spec.structure, units=spec.units,
                                title=spec.analysis.get("title") or Path(path).stem)
    model = spec.model
    if spec.structure.foundation is not None:       # the footings on the soil's static springs
        try:
            model = model.static_model()
        except ValueError:                          # a soil without static flexibility: no modes
            model = None
    info = modes(model, count=MODE_COUNT) if model is not None else None
    return model_drawing(spec.structure, shapes=None if info is None else info["shape"],
                         periods=None if info is None else info["period"], units=spec.units,
                         title=spec.analysis.get("title") or Path(path).stem)


# ---------------------------------------------------------------------- drawing
def draw_model(drawing, out_dir, formats=("png",)) -> list[Path]:
    """Draw ``drawing`` (a :class:`ModelDrawing` or a 3-D one) as ``model.<format>`` into ``out_dir``;
    return the files written."""
    from .plots import save_figure

    if not formats:
        return []
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return save_figure(drawing.figure(), out / "model", formats)


def model_figure(drawing: ModelDrawing):
    """The model figure of ``drawing``: a :class:`matplotlib.figure.Figure` on an Agg canvas."""
    from .plots import _styled

    return _styled(_model_figure)(drawing)


def _model_figure(drawing: ModelDrawing):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from .plots import DPI, PAGE_WIDTH, math_unit, plain_text

    xy = np.array(list(drawing.coords.values()) or [(0.0, 0.0)])
    size = max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1e-9)
    aspect = (float(np.ptp(xy[:, 1])) + 0.3 * size) / (float(np.ptp(xy[:, 0])) + 0.3 * size)
    main_w = PAGE_WIDTH - 1.0
    main_h = float(np.clip(main_w * aspect, 2.2, 5.5))
    kinds = _kinds_drawn(drawing)
    legend_rows = -(-len(kinds) // 3)
    legend_h = 0.2 * legend_rows + 0.15
    modes_h = 1.9 if drawing.modes else 0.0
    top, gap = 0.35, 0.5
    height = top + main_h + gap + legend_h + modes_h
    fig = Figure(figsize=(PAGE_WIDTH, height), dpi=DPI)
    FigureCanvasAgg(fig)
    ax = fig.add_axes(_rect(fig, 0.75, top, main_w, main_h))
    _draw_structure(ax, drawing, size)
    ax.set_aspect("equal", adjustable="datalim")
    ax.margins(0.08)
    unit = math_unit(drawing.length_unit) if drawing.length_unit else ""
    ax.set_xlabel(f"$x$ [{unit}]" if unit else "$x$")
    ax.set_ylabel(f"$y$ [{unit}]" if unit else "$y$")
    if drawing.title:
        ax.set_title(plain_text(str(drawing.title)[:200]))
    handles = [_legend_handle(kind) for kind in kinds]
    fig.legend(handles=handles, loc="upper center", ncol=3, frameon=False, fontsize=7,
               bbox_to_anchor=(0.5, 1.0 - (top + main_h + gap - 0.05) / height))
    _draw_modes(fig, drawing, size, bottom=0.15, height=modes_h - 0.45)
    _place_names(fig, ax)
    return fig


def _rect(fig, left, top, width, height) -> list[float]:
    """An axes rectangle in figure fractions from inches measured from the top-left corner."""
    w, h = fig.get_figwidth(), fig.get_figheight()
    return [left / w, 1.0 - (top + height) / h, width / w, height / h]


def _kinds_drawn(drawing: ModelDrawing) -> list[str]:
    """The legend entries of the drawing, in a fixed order."""
    present = {kind for kind, *_ in drawing.members + drawing.grounded}
    if drawing.links:
        present.add("rigid_link")
    out = [kind for kind in KIND_STYLES if kind in present]
    out += [extra for extra, shown in (("hinge", drawing.hinges), ("support", drawing.supports),
                                       ("mass", drawing.masses), ("footing", drawing.footings)) if shown]
    return out


def _legend_handle(kind: str):
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if kind in KIND_STYLES:
        label, color, style, width = KIND_STYLES[kind]
        return Line2D([], [], color=color, linestyle=style, linewidth=width, label=label)
    if kind == "footing":
        return Patch(facecolor="0.85", edgecolor="0.3", label="footing (numbered contact patches)")
    marker = {"hinge": ("o", "white", "C6", "plastic hinge"), "support": ("^", "0.5", "0.2", "support"),
              "mass": ("o", "black", "black", "mass")}[kind]
    return Line2D([], [], linestyle="", marker=marker[0], markerfacecolor=marker[1], markeredgecolor=marker[2],
                  markersize=5, label=marker[3])


def _name(ax, text, xy, offset, category, *, color="black", size=NAME_SIZE, **kw):
    """A name annotated at ``xy`` (data) shifted by ``offset`` points; ``gid`` ``"<category>:<text>"``."""
    return ax.annotate(str(text), xy, xytext=offset, textcoords="offset points", fontsize=size, color=color,
                       ha=kw.pop("ha", "center"), va=kw.pop("va", "center"), gid=f"{category}:{text}",
                       annotation_clip=False, bbox={"boxstyle": "square,pad=0.1", "facecolor": "white",
                                                    "edgecolor": "none", "alpha": 0.75}, zorder=6, **kw)


def _draw_structure(ax, drawing: ModelDrawing, size: float) -> None:
    """Everything of ``drawing`` but the modes on ``ax``, each part named (the names placed later)."""
    c = {node: np.asarray(xy) for node, xy in drawing.coords.items()}
    _draw_members(ax, drawing, c)
    for kind, name, node, direction in drawing.grounded:
        _draw_grounded(ax, kind, name, c[node], np.asarray(direction), size)
    for name, node, other in drawing.hinges:
        at = c[node] + 0.08 * (c[other] - c[node])
        ax.plot(*at, marker="o", markersize=4.5, markerfacecolor="white", markeredgecolor="C6", linestyle="",
                zorder=5)
        _name(ax, name, at, (0, 7), "unilateral", color="C6")
    _draw_supports_and_masses(ax, drawing, c)
    for footing in drawing.footings:
        _draw_footing(ax, footing, size)
    xy = np.array(list(c.values()))
    ax.plot(xy[:, 0], xy[:, 1], linestyle="", marker="o", markersize=2, color="0.3", zorder=4)
    for node, p in c.items():
        _name(ax, node, p, (5, 5), "node", color="0.45", ha="left", style="italic")


def _draw_members(ax, drawing: ModelDrawing, c: dict) -> None:
    """Rigid links and the elements between two nodes (a diamond where both are at one point)."""
    for master, slave in drawing.links:
        _, color, style, width = KIND_STYLES["rigid_link"]
        ax.plot(*np.column_stack([c[master], c[slave]]), color=color, linestyle=style, linewidth=width,
                solid_capstyle="round", zorder=1)
    for kind, name, i, j in drawing.members:
        _, color, style, width = KIND_STYLES[kind]
        if np.allclose(c[i], c[j]):
            ax.plot(*c[i], marker="D", color=color, markersize=4, linestyle="", zorder=4)
            _name(ax, name, c[i], (0, 8), _category(kind))
            continue
        ax.plot(*np.column_stack([c[i], c[j]]), color=color, linestyle=style, linewidth=width, zorder=2)
        _name(ax, name, 0.5 * (c[i] + c[j]), (0, 0), _category(kind), color=color if kind != "beam" else "0.1")


def _draw_supports_and_masses(ax, drawing: ModelDrawing, c: dict) -> None:
    """Supports (a square: rotation restrained too; a triangle: pinned, hollow: one direction only, ``>``
    for ``ux``) and masses (black dots, area growing with the mass)."""
    for node, restrained in drawing.supports:
        both = "ux" in restrained and "uy" in restrained
        marker = "s" if "rz" in restrained else ("^" if both or "uy" in restrained else ">")
        ax.plot(c[node][0], c[node][1], marker=marker, markersize=7, markerfacecolor="0.5" if both else "white",
                markeredgecolor="0.2", linestyle="", zorder=3)
    if drawing.masses:
        m = np.array([mass for _, mass in drawing.masses])
        xy = np.array([c[node] for node, _ in drawing.masses])
        ax.scatter(xy[:, 0], xy[:, 1], s=12 + 50 * m / m.max(), color="black", zorder=4)


def _category(kind: str) -> str:
    return "unilateral" if kind in UNILATERAL_KINDS else "element"


def _draw_grounded(ax, kind, name, at, direction, size) -> None:
    """An element from ``at`` to the ground along ``direction`` (a diamond for a rotation)."""
    _, color, style, width = KIND_STYLES[kind]
    if not direction.any():
        ax.plot(*at, marker="D", color=color, markersize=4, linestyle="", zorder=4)
        _name(ax, name, at, (0, -9), _category(kind), color=color)
        return
    end = at + GROUND_SYMBOL * size * direction
    ax.plot(*np.column_stack([at, end]), color=color, linestyle=style, linewidth=width, zorder=2)
    across = 0.4 * GROUND_SYMBOL * size * np.array([-direction[1], direction[0]])
    ax.plot(*np.column_stack([end - across, end + across]), color="0.2", linewidth=1.0, zorder=2)
    offset = 9 * direction
    _name(ax, name, end, (float(offset[0]), float(offset[1])), _category(kind), color=color)


def _draw_footing(ax, footing: Footing, size: float) -> None:
    """The footing as a strip under its elevation, cut at its patches, each numbered below."""
    from matplotlib.patches import Rectangle

    depth = 0.5 * GROUND_SYMBOL * size
    ax.add_patch(Rectangle((footing.x0, footing.y - depth), footing.x1 - footing.x0, depth, facecolor="0.85",
                           edgecolor="0.3", linewidth=0.8, zorder=1))
    for x, w, name in zip(footing.patch_x, footing.patch_width, footing.patch_names):
        for edge in (x - w / 2, x + w / 2):
            ax.plot([edge, edge], [footing.y - depth, footing.y], color="0.45", linewidth=0.5, zorder=1)
        _name(ax, name.rpartition(".")[2] or name, (x, footing.y - depth), (0, -6), "patch", color="0.3",
              size=NAME_SIZE - 1)
    _name(ax, footing.name, (footing.x0, footing.y - depth / 2), (-5, 0), "footing", ha="right", weight="bold")


def _draw_modes(fig, drawing: ModelDrawing, size: float, *, bottom: float, height: float) -> None:
    """A row of panels, one per mode: the undeformed lines in grey, the mode shape over them."""
    count = len(drawing.modes)
    if not count:
        return
    c = {node: np.asarray(xy) for node, xy in drawing.coords.items()}
    lines = [(i, j) for _, _, i, j in drawing.members] + list(drawing.links)
    width = (fig.get_figwidth() - 0.5 - 0.3 * (count - 1)) / count
    for k, (period, shape) in enumerate(drawing.modes):
        ax = fig.add_axes(_rect(fig, 0.25 + k * (width + 0.3), fig.get_figheight() - bottom - height, width, height))
        peak = max((float(np.hypot(*d)) for d in shape.values()), default=0.0)
        scale = 0.1 * size / peak if peak > 0 else 0.0
        moved = {node: c[node] + scale * np.asarray(shape.get(node, (0.0, 0.0))) for node in c}
        ax.plot(*_segments(c, lines), color="0.75", linewidth=0.8)          # one line each: fewer artists
        ax.plot(*_segments(moved, lines), color="C0", linewidth=1.3)
        ax.set_aspect("equal", adjustable="datalim")
        ax.margins(0.1)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
        unit = f" {drawing.time_unit}" if drawing.time_unit else ""
        ax.set_title(f"mode {k + 1}: T = {period:.3g}{unit}", fontsize=8)


def _segments(xy: dict, lines: list) -> tuple:
    """``x, y`` of the segments ``lines`` (pairs of nodes of ``xy``) in one line, NaN between them."""
    out = np.full((3 * len(lines), 2), np.nan)
    for k, (i, j) in enumerate(lines):
        out[3 * k], out[3 * k + 1] = xy[i], xy[j]
    return out[:, 0], out[:, 1]


# ---------------------------------------------------------------------- names without overlaps
#: Offsets tried for a name, in points, added to its own offset: where it is, then around it.
_TRIES = [(0.0, 0.0)] + [(r * np.cos(a), r * np.sin(a)) for r in (7.0, 13.0, 20.0)
                         for a in np.linspace(0.0, 2 * np.pi, 8, endpoint=False)]
#: The order names are placed in: the first keep their place.
_PRIORITY = ("unilateral", "footing", "element", "patch", "node")


def _place_names(fig, ax) -> None:
    """Move each name to the offset of :data:`_TRIES` where it overlaps the names placed before it
    least (no overlap: the first such offset)."""
    ax.apply_aspect()                               # the limits of the equal aspect, as drawing sets them
    renderer = fig.canvas.get_renderer()
    names = [t for t in ax.texts if str(t.get_gid() or "").partition(":")[0] in _PRIORITY]
    names.sort(key=lambda t: _PRIORITY.index(t.get_gid().partition(":")[0]))
    placed = np.empty((len(names) + len(ax.texts), 4))      # (x0, y0, x1, y1) of the boxes placed
    count = 0
    for box in _node_boxes(ax, [t.xy for t in names if t.get_gid().startswith("node:")]):
        placed[count], count = box.extents, count + 1
    for text in names:
        base = tuple(text.xyann)
        best, best_overlap = base, None
        for dx, dy in _TRIES:
            text.xyann = (base[0] + dx, base[1] + dy)
            overlap = _overlap_sum(text.get_window_extent(renderer), placed[:count])
            if best_overlap is None or overlap < best_overlap:
                best, best_overlap = text.xyann, overlap
            if overlap == 0.0:
                break
        text.xyann = best
        placed[count], count = text.get_window_extent(renderer).extents, count + 1


def _node_boxes(ax, points, radius: float = 4.0) -> list:
    """Boxes (display units) ``radius`` points around the nodes at ``points`` (data): names avoid them."""
    from matplotlib.transforms import Bbox

    pixels = radius * ax.figure.dpi / 72.0
    return [Bbox.from_extents(x - pixels, y - pixels, x + pixels, y + pixels)
            for x, y in ax.transData.transform(np.asarray(points, dtype=float).reshape(-1, 2))]


def _overlap_sum(box, others: np.ndarray) -> float:
    """The sum of the areas ``box`` shares with each of ``others`` (k, 4) ``(x0, y0, x1, y1)`` (display
    units), added in their order (the same float as adding them one by one)."""
    w = np.minimum(box.x1, others[:, 2]) - np.maximum(box.x0, others[:, 0])
    h = np.minimum(box.y1, others[:, 3]) - np.maximum(box.y0, others[:, 1])
    shared = (w > 0) & (h > 0)
    return sum((w[shared] * h[shared]).tolist())
