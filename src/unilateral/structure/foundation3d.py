"""Rigid footings in plan for :class:`~unilateral.structure.Frame3D`: rocking about both axes.

A rigid rectangular footing (``width`` along x, ``length`` along y, centred on its reference node)
rests on the soil through an ``nx x ny`` grid of patches (:func:`unilateral.soil.patches.grid`),
each a unilateral contact. The footing's node carries its vertical displacement ``uz`` and its
rotations ``rx``, ``ry`` (right-handed), so the upward displacement of the patch at ``(x, y)`` is

    z_j = uz + rx (y_j - y_0) - ry (x_j - x_0)

and the soil's compressive force ``c_j`` at the patch loads the node with ``fz = c_j``,
``mx = (y_j - y_0) c_j``, ``my = -(x_j - x_0) c_j``. All footings on one half-space (or layered
soil) share it: every patch of every footing is coupled to every other through the ground, in
plan. The footing is held horizontally and in twist (``ux``, ``uy``, ``rz`` of its node supported:
``horizontal="support"``) or left to the frame (``"none"``); sliding in plan is not available.
The same :class:`~unilateral.structure.foundation.Footings` and
:class:`~unilateral.soil.FoundationModel` as in 2-D solve it.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from .foundation import Foundation, _positive, patch_gaps, soil_flexibility

#: Horizontal restraint of a 3-D footing.
HORIZONTAL_3D = ("support", "none")


@dataclass(frozen=True, eq=False)
class Footing3D(Foundation):
    """A rigid footing in plan (see the module). ``patches`` holds absolute plan centres ``(x, y)``;
    ``y`` (inherited) is the elevation ``z`` of the footing's base."""

    def moved_rows(self, coords) -> list[tuple]:
        """Per contact: ``[(node, dof, factor), ...]`` with ``z_j = sum factor * u(node, dof)``."""
        x0, y0 = (float(a) for a in coords[self.node][:2])
        return [[(self.node, "uz", 1.0), (self.node, "rx", float(y) - y0), (self.node, "ry", -(float(x) - x0))]
                for x, y in self.patches.centres]

    def constraint_coords(self) -> dict:
        """Plan coordinates, kind and gap of each patch along ``constraint``."""
        x, y = self.patches.centres.T
        return {"constraint_x": ("constraint", [float(a) for a in x]),
                "constraint_y": ("constraint", [float(a) for a in y]),
                "constraint_kind": ("constraint", ["foundation"] * self.m),
                "constraint_gap": ("constraint", [float(g) for g in self.gap])}

    def ground_reactions(self, structure, c, h=None) -> tuple[dict, dict]:
        """The soil's forces on the footing's node per contact: ``(fx, fy, fz, mx, my, mz)`` (N+1, 6)."""
        x0, y0 = (float(a) for a in structure.coords[self.node][:2])
        forces, at = {}, {}
        for j, (x, y) in enumerate(self.patches.centres):
            f = np.zeros((c.shape[0], 6))
            f[:, 2] = c[:, j]
            f[:, 3] = (float(y) - y0) * c[:, j]
            f[:, 4] = -(float(x) - x0) * c[:, j]
            forces[self.contact_names[j]] = f
            at[self.contact_names[j]] = self.node
        return forces, at


def build_footing(*, name, node, width, length, soil, patches, horizontal, gap, coords) -> Footing3D:
    """Check the arguments of :meth:`Frame3D.foundation <unilateral.structure.Frame3D.foundation>`
    and make the :class:`Footing3D`."""
    from ..soil.patches import RectangularPatches, grid

    where = f"foundation {name!r}"
    width = _positive(where, "width", width)
    length = _positive(where, "length", length)
    if horizontal not in HORIZONTAL_3D:
        raise ValueError(f"{where}: horizontal={horizontal!r} is not valid for a 3-D footing; valid: "
                         f"{', '.join(map(repr, HORIZONTAL_3D))} (sliding in plan is not available)")
    counts = (patches, patches) if isinstance(patches, numbers.Integral) and not isinstance(patches, bool) \
        else patches
    ok = (isinstance(counts, (tuple, list)) and len(counts) == 2
          and all(isinstance(k, numbers.Integral) and not isinstance(k, bool) and k >= 1 for k in counts))
    if not ok or counts[0] * counts[1] > 400:
        raise ValueError(f"{where}: patches={patches!r} is not valid; give the patches along x and y, (nx, ny) "
                         "with nx, ny >= 1 and nx ny <= 400 (or one integer for both)")
    x0, y0, z0 = (float(a) for a in coords[node])
    local = grid(width, length, int(counts[0]), int(counts[1]))
    pts = RectangularPatches(local.centres + np.array([x0, y0]), local.sizes)
    flex, spec = soil_flexibility(soil, pts, f"{where}: soil", "z")
    return Footing3D(name=name, node=node, nodes=None, width=width, length=length, patches=pts, soil=flex,
                     spec=spec, horizontal=horizontal, gap=patch_gaps(where, gap, pts.m),
                     contact_names=tuple(f"{name}.{j + 1}" for j in range(pts.m)), y=z0)


def check_plan_overlap(footings, new, where) -> None:
    """Raise if the new footing's plan rectangle overlaps one already attached at the same elevation."""
    def box(f):
        lo = f.patches.centres - 0.5 * f.patches.sizes
        hi = f.patches.centres + 0.5 * f.patches.sizes
        return lo.min(axis=0), hi.max(axis=0)

    lo, hi = box(new)
    for other in footings:
        if abs(other.y - new.y) > 1e-9 * max(1.0, abs(new.y)):
            continue
        olo, ohi = box(other)
        overlap = np.minimum(hi, ohi) - np.maximum(lo, olo)
        if np.all(overlap > 1e-9 * max(new.width, new.length, other.width, other.length)):
            raise ValueError(f"{where}: the footing (x from {lo[0]:g} to {hi[0]:g}, y from {lo[1]:g} to {hi[1]:g}) "
                             f"overlaps footing {other.name!r} (x from {olo[0]:g} to {ohi[0]:g}, y from {olo[1]:g} "
                             f"to {ohi[1]:g}); footings on the ground must not overlap")
