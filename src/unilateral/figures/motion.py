"""Pictures of the motion of a 2-D frame from its ``results.nc``: the deformed shape at chosen
instants (:func:`deformed_shape_figure`, the instant of the peak drift by default) and an animation
of the run (:func:`animate`, a GIF through Pillow).

The shape is drawn from the model drawing that ``results.nc`` carries (attribute
``model_drawing``: the nodes and members) and the node displacements of one case (variable
``node_displacement``, ``(case, time, node, component)``): a beam is drawn with the cubic of its
end displacements and rotations (its exact elastic shape without span loads), other members as
straight lines between their displaced ends. Marked at each instant: contacts that are open
(``v > 0``: a footing lifted off, a gap open, a cable slack), yield elements that yield in that step (their plastic
deformation grows) and slips that slide. Displacements are magnified so that the largest at the
instants drawn is a tenth of the structure's size; the title gives the factor.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import FigureDataError

#: The largest displacement drawn, as a fraction of the structure's size (the magnification).
DRAWN_FRACTION = 0.1
#: Points of a beam's cubic.
BEAM_POINTS = 21
#: A step's change of a plastic deformation or slip counts as yielding or sliding above this
#: fraction of the largest value of the run (round-off below it is not drawn).
ACTIVE_TOLERANCE = 1e-9
#: Where a mark sits from its node, as a fraction of the structure's size (marks at one node apart).
MARK_OFFSET = {"open": np.array([0.0, -0.02]), "yield": np.zeros(2), "slip": np.array([0.0, 0.02])}
#: Resolution of the animation's frames (dots per inch; the figures' own is higher).
ANIMATION_DPI = 72
#: Marks: what they show, their marker and colour.
MARKS = {"open": ("open: lifted, gap open, cable slack", "v", "tab:red"), "yield": ("yielding", "o", "tab:orange"),
         "slip": ("sliding", "s", "tab:purple")}


@dataclass
class Motion:
    """The data of the pictures of one case of a 2-D run.

    Attributes
    ----------
    case : str;  title : str;  length_unit : str
    t : (N+1,) times [s]
    nodes : list of str, the node names;  xy : (nodes, 2) their coordinates
    d : (N+1, nodes, 3) their displacements ``ux, uy, rz``
    members : list of ``(kind, name, i, j)`` with node indices (rigid links as ``"link"``)
    marks : dict, kind of mark -> (N+1, constraints) bool
    mark_node : (constraints,) int, the node nearest each constraint (where its mark moves with)
    """

    case: str
    title: str
    length_unit: str
    t: np.ndarray
    nodes: list
    xy: np.ndarray
    d: np.ndarray
    members: list
    marks: dict
    mark_node: np.ndarray

    @classmethod
    def of(cls, ds, case: str = "unilateral") -> Motion:
        """The motion of ``case`` in the Dataset ``ds`` of a 2-D ``results.nc``.

        Raises
        ------
        unilateral.figures.FigureDataError
            If ``ds`` has no 2-D model drawing, no node displacements or no such case.
        """
        if "model_drawing" not in ds.attrs or "node_displacement" not in ds:
            raise FigureDataError("the motion needs the model drawing and node_displacement of a 2-D frame's "
                                  "results.nc (a model given as matrices has no shape to draw)")
        drawing = json.loads(ds.attrs["model_drawing"])
        if any(len(xy) != 2 for xy in drawing["coords"].values()):
            raise FigureDataError("the motion is drawn for 2-D frames; this results.nc is of a 3-D one")
        cases = [str(c) for c in ds["case"].values]
        if case not in cases:
            raise FigureDataError(f"case={case!r} is not in this results.nc; valid: {', '.join(cases)}")
        nd = ds["node_displacement"].sel(case=case).transpose("time", "node", "component")
        nodes = [str(n) for n in ds["node"].values]
        missing = sorted(set(drawing["coords"]) - set(nodes))
        if missing:
            raise FigureDataError(f"node_displacement has no rows for nodes {missing[:5]} of the model drawing")
        index = {name: k for k, name in enumerate(nodes)}
        xy = np.array([drawing["coords"].get(name, [np.nan, np.nan]) for name in nodes], dtype=float)
        members = [(kind, name, index[i], index[j]) for kind, name, i, j in drawing["members"]
                   if i in index and j in index]
        members += [("link", "", index[i], index[j]) for i, j in drawing.get("links", [])
                    if i in index and j in index]
        components = [str(c) for c in ds["component"].values]
        d = np.stack([nd.sel(component=c).values if c in components else np.zeros(nd.shape[:2])
                      for c in ("ux", "uy", "rz")], axis=-1)
        marks, mark_xy = _marks(ds, case)
        near = np.nan_to_num(np.linalg.norm(mark_xy[:, None, :] - xy[None, :, :], axis=2), nan=np.inf)
        return cls(case, str(ds.attrs.get("title", "")), str(drawing.get("length_unit", "m")),
                   np.asarray(ds["time"].values, dtype=float), nodes, xy, np.nan_to_num(d), members, marks,
                   np.argmin(near, axis=1) if near.size else np.zeros(0, dtype=int))

    @property
    def size(self) -> float:
        """The structure's size: the larger side of the box of its nodes (at least 1e-300)."""
        box = np.nanmax(self.xy, axis=0) - np.nanmin(self.xy, axis=0)
        return float(max(np.nanmax(box), 1e-300))

    def peak_instant(self) -> int:
        """The step of the largest horizontal displacement of a node relative to the base (the
        lowest nodes): the peak drift of the structure."""
        base = self.xy[:, 1] <= np.nanmin(self.xy[:, 1]) + 1e-9 * self.size
        relative = self.d[:, :, 0] - self.d[:, base, 0].mean(axis=1, keepdims=True)
        return int(np.argmax(np.max(np.abs(relative), axis=1)))

    def scale(self, steps) -> float:
        """The magnification that draws the largest displacement of ``steps`` at
        :data:`DRAWN_FRACTION` of the structure's size (1 if nothing moves)."""
        peak = float(np.max(np.abs(self.d[np.asarray(steps)][..., :2]), initial=0.0))
        return DRAWN_FRACTION * self.size / peak if peak > 0 else 1.0

    def shape(self, k: int, scale: float) -> list[np.ndarray]:
        """The members at step ``k`` magnified by ``scale``: one (points, 2) line each."""
        lines = []
        for kind, _, i, j in self.members:
            if kind == "beam":
                lines.append(_beam_line(self.xy[i], self.xy[j], self.d[k, i], self.d[k, j], scale))
            else:
                lines.append(np.array([self.xy[i] + scale * self.d[k, i, :2], self.xy[j] + scale * self.d[k, j, :2]]))
        return lines


def _beam_line(a, b, da, db, scale) -> np.ndarray:
    """The displaced beam from ``a`` to ``b`` (ends displaced by ``da``, ``db``: ux, uy, rz) as the
    cubic of its transverse end displacements and rotations, the axial part linear."""
    chord = b - a
    L = float(np.hypot(*chord))
    if L == 0.0:
        return np.array([a, b])
    c, s = chord / L
    x = np.linspace(0.0, 1.0, BEAM_POINTS)
    ua, ub = c * da[0] + s * da[1], c * db[0] + s * db[1]            # axial
    wa, wb = -s * da[0] + c * da[1], -s * db[0] + c * db[1]          # transverse
    n1, n2 = 1 - 3 * x**2 + 2 * x**3, L * (x - 2 * x**2 + x**3)
    n3, n4 = 3 * x**2 - 2 * x**3, L * (-x**2 + x**3)
    u = (1 - x) * ua + x * ub
    w = n1 * wa + n2 * da[2] + n3 * wb + n4 * db[2]
    along = x * L + scale * u
    across = scale * w
    return np.column_stack([a[0] + c * along - s * across, a[1] + s * along + c * across])


def _marks(ds, case):
    """Which constraints are open, yield or slide at each step: kind -> (N+1, m) bool."""
    if "constraint_kind" not in ds.coords or "v" not in ds:
        return {}, np.zeros((0, 2))
    kinds = np.array([str(k) for k in ds["constraint_kind"].values])
    v = np.nan_to_num(ds["v"].sel(case=case).transpose("time", "constraint").values)
    xy = np.column_stack([ds[c].values if c in ds.coords else np.full(kinds.size, np.nan)
                          for c in ("constraint_x", "constraint_y")])
    scale = max(float(np.max(np.abs(v), initial=0.0)), 1e-300)
    growing = np.vstack([np.zeros((1, v.shape[1]), dtype=bool), np.diff(v, axis=0) > ACTIVE_TOLERANCE * scale])
    contact = ~np.isin(kinds, ("yield", "friction"))     # a contact's kind is its element's: soil, gap, cable ...
    marks = {"open": (v > ACTIVE_TOLERANCE * scale) & contact,
             "yield": growing & (kinds == "yield"), "slip": growing & (kinds == "friction")}
    return {k: m for k, m in marks.items() if m.any()}, xy


def _draw(ax, motion: Motion, k: int, scale: float) -> list:
    """Draw step ``k`` on ``ax``: the undeformed frame in grey, the deformed one, the marks."""
    artists = []
    for kind, _, i, j in motion.members:
        ax.plot(*motion.xy[[i, j]].T, color="0.8", lw=0.8, zorder=1)
    for (kind, *_), line in zip(motion.members, motion.shape(k, scale)):
        artists += ax.plot(*line.T, color="0.3" if kind == "link" else "tab:blue", lw=2.4 if kind == "link" else 1.6,
                           zorder=2)
    for kind, active in motion.marks.items():
        label, marker, color = MARKS[kind]
        at = motion.mark_node[active[k]]
        where = motion.xy[at] + scale * motion.d[k, at, :2] + MARK_OFFSET[kind] * motion.size
        artists.append(ax.scatter(where[:, 0], where[:, 1], marker=marker, s=36, color=color, zorder=3,
                                  label=f"{label} ({int(active[k].sum())})"))
    return artists


def _axes(motion: Motion):
    from .plots import _figure

    fig, ax = _figure((7.0, 6.5), margins=(0.9, 0.3, 0.6, 0.7))
    ax.set_aspect("equal")
    pad = (DRAWN_FRACTION + 0.08) * motion.size
    lo, hi = np.nanmin(motion.xy, axis=0) - pad, np.nanmax(motion.xy, axis=0) + pad
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_xlabel(f"x [{motion.length_unit}]")
    ax.set_ylabel(f"y [{motion.length_unit}]")
    return fig, ax


def _title(motion: Motion, k: int, scale: float) -> str:
    head = f"{motion.title}\n" if motion.title else ""
    return f"{head}case {motion.case}, t = {motion.t[k]:.3f} s, displacements x {scale:.3g}"


def deformed_shape_figure(ds, case: str = "unilateral", time: float | None = None):
    """The deformed shape of ``case`` at ``time`` (s; the grid time nearest it; default: the
    instant of the peak drift), with the open contacts, yielding hinges and sliding slips marked.

    Returns
    -------
    matplotlib.figure.Figure
    """
    motion = Motion.of(ds, case)
    k = motion.peak_instant() if time is None else _step_of(motion, time)
    scale = motion.scale([k])
    fig, ax = _axes(motion)
    _draw(ax, motion, k, scale)
    ax.set_title(_title(motion, k, scale), fontsize=9)
    if motion.marks:
        ax.legend(loc="upper right", fontsize=8)
    return fig


def _step_of(motion: Motion, time) -> int:
    t = float(time)
    if not (np.isfinite(t) and motion.t[0] <= t <= motion.t[-1]):
        raise ValueError(f"time = {time!r} s is not in the run: valid {motion.t[0]:g} <= time <= {motion.t[-1]:g}")
    return int(np.argmin(np.abs(motion.t - t)))


def animate(ds, path, *, case: str = "unilateral", frames: int = 60, fps: int = 10) -> Path:
    """An animation of ``case`` as a GIF at ``path`` (written atomically): ``frames`` instants
    evenly spaced over the run, one magnification for all (:meth:`Motion.scale`).

    Parameters
    ----------
    ds : xarray.Dataset of a 2-D ``results.nc``;  path : str or path-like, ending in ``.gif``
    case : str;  frames : int >= 2;  fps : int >= 1
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    from ..io.atomic import atomic_write

    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise ValueError(f"path = {str(path)!r}: the animation is written as a GIF (a name ending in .gif)")
    for name, value, low in (("frames", frames, 2), ("fps", fps, 1)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise ValueError(f"{name} must be an integer >= {low}, got {value!r}")
    motion = Motion.of(ds, case)
    steps = np.unique(np.linspace(0, motion.t.size - 1, int(frames)).round().astype(int))
    scale = motion.scale(steps)
    fig, ax = _axes(motion)
    drawn = []

    def frame(n):
        for artist in drawn:
            artist.remove()
        drawn[:] = _draw(ax, motion, int(steps[n]), scale)
        ax.set_title(_title(motion, int(steps[n]), scale), fontsize=9)
        return drawn

    movie = FuncAnimation(fig, frame, frames=len(steps), blit=False)
    atomic_write(path, lambda tmp: movie.save(tmp, writer=PillowWriter(fps=int(fps)), dpi=ANIMATION_DPI))
    return path
