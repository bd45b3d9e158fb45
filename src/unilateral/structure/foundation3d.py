"""Rigid and flexible footings in plan for :class:`~unilateral.structure.Frame3D`: rocking, sliding and twisting.

A rigid rectangular footing (``width`` along x, ``length`` along y, centred on its reference node)
rests on the soil through an ``nx x ny`` grid of patches (:func:`unilateral.soil.patches.grid`),
each a unilateral contact. The footing's node carries its vertical displacement ``uz`` and its
rotations ``rx``, ``ry`` (right-handed), so the upward displacement of the patch at ``(x, y)`` is

    z_j = uz + rx (y_j - y_0) - ry (x_j - x_0)

and the soil's compressive force ``c_j`` at the patch loads the node with ``fz = c_j``,
``mx = (y_j - y_0) c_j``, ``my = -(x_j - x_0) c_j``. All footings on one half-space (or layered
soil) share it: every patch of every footing is coupled to every other through the ground, in
plan. The footing is held horizontally and in twist (``ux``, ``uy``, ``rz`` of its node supported:
``horizontal="support"``), left to the frame (``"none"``), or rests on the soil horizontally too
and **slides in plan** (``"soil"``, with ``mu`` and ``facets``): each patch carries a horizontal
force ``(fx, fy)`` through the soil's x-y-z flexibility (the half-space's or layered soil's Green's
tensor, ``components="xyz"``; Wolf's horizontal cone spread over the patches by area for
``"cones"``; springs ``kx`` and dashpots ``cx`` along x and along y per patch for
``"winkler-kelvin"``), limited by a polygonal Coulomb cone of ``facets`` facets (facet ``k`` of
unit normal ``d_k`` keeps ``d_k . f <= mu c``, :func:`unilateral.soil.flexibility.facet_normals`).
The footing's horizontal displacement at a patch includes its twist ``rz`` about its node (its base
is at the node's elevation, as in 2-D, so rocking does not move it horizontally):

    x_j = ux - (y_j - y_0) rz,        y_j = uy + (x_j - x_0) rz

so sway, rocking and torsion of the footing couple through the ground. The same
:class:`~unilateral.soil.FoundationModel` as in 2-D solves it, with ``Tx``, ``Ty`` and ``facets``.

A **flexible** footing in plan (``nodes=``, a grid of nodes at one elevation: rows along x, each at
one y; columns at one x) has one patch per node, its contact acting on that node's ``uz`` alone
(``T[:, j] = e_uz`` of node ``j``); the structure the user builds on the nodes (a grillage of beams,
plates of links, ...) is the footing's stiffness, the footing adds none. Along x and along y the
patches follow the rule of the 2-D flexible footing: the footing spans ``c +- width/2`` (``c`` the
middle of the end columns; default ``width``: the columns' span plus one mean spacing), each
column's strip reaches halfway to its neighbours and, at the ends, to the edge, and its patches are
centred on it, twice as wide as the nearer end of the strip; likewise ``length`` along y. Equally
spaced nodes with the default extents get equal patches covering the footing (the rigid footing's
patches of the same grid). Sliding in plan, each patch's shears act on its own node's ``ux``, ``uy``
(no twist term: each node moves on its own).
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from .foundation import (Footings, Foundation, _concat_patches, _positive, _rows_matrix, patch_gaps, shared_medium,
                         soil_flexibility)

#: Horizontal restraint of a 3-D footing.
HORIZONTAL_3D = ("support", "none", "soil")
#: The facets of a footing's friction cone in plan unless given.
DEFAULT_FACETS = 8


@dataclass(frozen=True, eq=False)
class Footing3D(Foundation):
    """A rigid footing in plan (see the module). ``patches`` holds absolute plan centres ``(x, y)``;
    ``y`` (inherited) is the elevation ``z`` of the footing's base; ``origin`` the plan position of
    its node; ``facets`` the facets of its friction cone (``horizontal="soil"``)."""

    facets: int | None = None
    origin: tuple = (0.0, 0.0)

    def moved_rows(self, coords) -> list[tuple]:
        """Per contact: ``[(node, dof, factor), ...]`` with ``z_j = sum factor * u(node, dof)``."""
        if not self.rigid:
            return [[(node, "uz", 1.0)] for node in self.nodes]
        x0, y0 = (float(a) for a in coords[self.node][:2])
        return [[(self.node, "uz", 1.0), (self.node, "rx", float(y) - y0), (self.node, "ry", -(float(x) - x0))]
                for x, y in self.patches.centres]

    def shear_rows(self) -> list[tuple]:
        """Per contact: the footing's displacement along x at the patch, ``ux - (y_j - y_0) rz`` (rigid),
        ``ux`` of the patch's node (flexible)."""
        if not self.rigid:
            return [[(node, "ux", 1.0)] for node in self.nodes]
        y0 = float(self.origin[1])
        return [[(self.node, "ux", 1.0), (self.node, "rz", -(float(y) - y0))] for y in self.patches.centres[:, 1]]

    def shear_rows_y(self) -> list[tuple]:
        """Per contact: the footing's displacement along y at the patch, ``uy + (x_j - x_0) rz`` (rigid),
        ``uy`` of the patch's node (flexible)."""
        if not self.rigid:
            return [[(node, "uy", 1.0)] for node in self.nodes]
        x0 = float(self.origin[0])
        return [[(self.node, "uy", 1.0), (self.node, "rz", float(x) - x0)] for x in self.patches.centres[:, 0]]

    def Ty(self, dofs) -> np.ndarray:
        """``Ty`` (n, m): displacement along y of the footing at each patch, ``y_f = Ty^T u``."""
        return _rows_matrix(dofs, self.shear_rows_y(), self.m)

    def constraint_coords(self) -> dict:
        """Plan coordinates, kind and gap of each patch along ``constraint``."""
        x, y = self.patches.centres.T
        return {"constraint_x": ("constraint", [float(a) for a in x]),
                "constraint_y": ("constraint", [float(a) for a in y]),
                "constraint_kind": ("constraint", ["foundation"] * self.m),
                "constraint_gap": ("constraint", [float(g) for g in self.gap])}

    def ground_reactions(self, structure, c, h=None) -> tuple[dict, dict]:
        """The soil's forces per contact on the node it acts on (the rigid footing's node, the flexible
        footing's node of the patch): ``(fx, fy, fz, mx, my, mz)`` (N+1, 6), with the moments of the
        patch centre's offset from that node (none for a flexible footing's centred patches).

        ``h`` (N+1, m, 2): the soil's horizontal forces on the footing (sliding in plan), or None."""
        forces, at = {}, {}
        for j, ((x, y), node) in enumerate(zip(self.patches.centres, self.contact_nodes())):
            x0, y0 = (float(a) for a in structure.coords[node][:2])
            f = np.zeros((c.shape[0], 6))
            f[:, 2] = c[:, j]
            f[:, 3] = (float(y) - y0) * c[:, j]
            f[:, 4] = -(float(x) - x0) * c[:, j]
            if h is not None:
                f[:, 0], f[:, 1] = h[:, j, 0], h[:, j, 1]
                f[:, 5] = (float(x) - x0) * h[:, j, 1] - (float(y) - y0) * h[:, j, 0]
            forces[self.contact_names[j]] = f
            at[self.contact_names[j]] = node
        return forces, at


def build_footing(*, name, node, width, length, soil, patches, horizontal, gap, coords, mu=None,
                  facets=None, nodes=None) -> Footing3D:
    """Check the arguments of :meth:`Frame3D.foundation <unilateral.structure.Frame3D.foundation>`
    and make the :class:`Footing3D` (rigid; flexible with ``nodes``, a grid from :func:`grid_nodes`)."""
    from ..soil.patches import RectangularPatches, grid

    where = f"foundation {name!r}"
    if not isinstance(horizontal, str) or horizontal not in HORIZONTAL_3D:
        raise ValueError(f"{where}: horizontal={horizontal!r} is not valid for a 3-D footing; valid: "
                         f"{', '.join(map(repr, HORIZONTAL_3D))}")
    mu, facets = _friction(where, horizontal, mu, facets)
    if nodes is not None:
        return _flexible_footing(where, name=name, node=node, nodes=nodes, width=width, length=length, soil=soil,
                                 horizontal=horizontal, gap=gap, coords=coords, mu=mu, facets=facets)
    width = _positive(where, "width", width)
    length = _positive(where, "length", length)
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
    flex, spec = _footing_soil(soil, pts, where, horizontal)
    return Footing3D(name=name, node=node, nodes=None, width=width, length=length, patches=pts, soil=flex,
                     spec=spec, horizontal=horizontal, gap=patch_gaps(where, gap, pts.m),
                     contact_names=tuple(f"{name}.{j + 1}" for j in range(pts.m)), y=z0, mu=mu, facets=facets,
                     origin=(x0, y0))


def _footing_soil(soil, patches, where, horizontal):
    if horizontal == "soil":
        return plan_soil(soil, patches, f"{where}: soil")
    return soil_flexibility(soil, patches, f"{where}: soil", "z")


def grid_nodes(where, nodes) -> list[list]:
    """``nodes`` of a flexible footing checked as a grid: a non-empty list of rows (along x), each a
    non-empty list of node ids, all rows as long, at least two nodes, none twice."""
    def is_list(a):
        return isinstance(a, (list, tuple))

    if not is_list(nodes) or not nodes or not all(is_list(row) and row for row in nodes):
        raise ValueError(f"{where}: nodes={nodes!r} is not valid; give a grid of node ids, a list of rows (each "
                         "row the nodes at one y, along x), e.g. [[1, 2, 3], [4, 5, 6]] (one row: [[1, 2, 3]])")
    rows = [list(row) for row in nodes]
    if len({len(row) for row in rows}) > 1:
        raise ValueError(f"{where}: nodes={nodes!r}: the rows have {[len(row) for row in rows]} nodes; every row "
                         "of the grid needs the same number of nodes (one per column)")
    flat = [n for row in rows for n in row]
    if len(flat) < 2:
        raise ValueError(f"{where}: nodes={nodes!r}: a flexible footing needs at least two nodes (one patch each); "
                         "give node only for a rigid footing")
    seen = {}
    for i, row in enumerate(rows):
        for j, n in enumerate(row):
            if repr(n) in seen:
                raise ValueError(f"{where}: nodes[{i}][{j}]={n!r} is given twice (also nodes{seen[repr(n)]}); "
                                 "give each node of the grid once")
            seen[repr(n)] = f"[{i}][{j}]"
    return rows


def _flexible_footing(where, *, name, node, nodes, width, length, soil, horizontal, gap, coords, mu, facets):
    """The flexible :class:`Footing3D` on the grid ``nodes`` (see :meth:`Frame3D.foundation`)."""
    from ..soil.patches import RectangularPatches

    rows = grid_nodes(where, nodes)
    xyz = np.array([[coords[n] for n in row] for row in rows], dtype=float)        # (ny, nx, 3)
    scale = max(1.0, float(np.abs(xyz).max()))
    tol = 1e-9 * scale
    z = xyz[..., 2]
    if np.ptp(z) > tol:
        i, j = np.unravel_index(np.argmax(np.abs(z - z[0, 0])), z.shape)
        raise ValueError(f"{where}: nodes[{i}][{j}]={rows[i][j]!r} is at z={z[i, j]:g}, nodes[0][0]={rows[0][0]!r} "
                         f"at z={z[0, 0]:g}; a footing's nodes lie at one elevation (on the ground surface)")
    for axis, label, key in ((0, "x", "column"), (1, "y", "row")):
        values = xyz[..., axis]
        # x is constant down each column (along the rows' index), y along each row
        ref = values[0:1, :] if axis == 0 else values[:, 0:1]
        bad = np.abs(values - ref) > tol
        if np.any(bad):
            i, j = np.argwhere(bad)[0]
            i0, j0 = (0, j) if axis == 0 else (i, 0)
            raise ValueError(f"{where}: nodes[{i}][{j}]={rows[i][j]!r} is at {label}={values[i, j]:g}, but "
                             f"nodes[{i0}][{j0}]={rows[i0][j0]!r} of its {key} at {label}={values[i0, j0]:g}; the "
                             f"nodes must lie on a rectilinear grid in plan: each row (nodes[i]) at one y, each "
                             f"column (nodes[.][j]) at one x")
    xs, ys = xyz[0, :, 0], xyz[:, 0, 1]
    for values, label, what in ((xs, "x", "columns"), (ys, "y", "rows")):
        if len(values) > 1 and np.min(np.abs(np.diff(np.sort(values)))) <= tol:
            raise ValueError(f"{where}: nodes={nodes!r}: two {what} are at the same {label} "
                             f"({label} = {sorted(values.tolist())}); give each {what[:-1]} its own {label}")
    ox, oy = np.argsort(xs), np.argsort(ys)
    rows = [[rows[i][j] for j in ox] for i in oy]
    xs, ys = xs[ox], ys[oy]
    width, wx = _tributary(where, "width", "x", xs, width)
    length, wy = _tributary(where, "length", "y", ys, length)
    X, Y = np.meshgrid(xs, ys)                                   # x fastest, then y
    W, L = np.meshgrid(wx, wy)
    pts = RectangularPatches(np.column_stack([X.ravel(), Y.ravel()]), np.column_stack([W.ravel(), L.ravel()]))
    flat = tuple(n for row in rows for n in row)
    if node is None:
        node = rows[(len(rows) - 1) // 2][(len(rows[0]) - 1) // 2]
    flex, spec = _footing_soil(soil, pts, where, horizontal)
    x0, y0 = (float(a) for a in coords[node][:2])
    return Footing3D(name=name, node=node, nodes=flat, width=width, length=length, patches=pts, soil=flex,
                     spec=spec, horizontal=horizontal, gap=patch_gaps(where, gap, pts.m),
                     contact_names=tuple(f"{name}.{n}" for n in flat), y=float(z[0, 0]), mu=mu, facets=facets,
                     origin=(x0, y0))


def _tributary(where, arg, axis, xs, extent) -> tuple[float, np.ndarray]:
    """The footing's extent along ``axis`` and its patches' sizes there, as the 2-D flexible footing's
    (:func:`~unilateral.structure.foundation.build_foundation`): the footing spans ``c +- extent/2``,
    ``c`` the middle of the end nodes (default ``extent``: their span plus one mean spacing; one node:
    required); each node's strip reaches halfway to its neighbours and to the edge; its patch is
    centred on it, twice as wide as the nearer end of the strip."""
    n, span = len(xs), float(xs[-1] - xs[0])
    if extent is None:
        if n == 1:
            raise ValueError(f"{where}: the nodes form one line along {'x' if axis == 'y' else 'y'}: give {arg}, "
                             f"the footing's extent along {axis} (no node spacing to take it from)")
        extent = span * n / (n - 1)
    extent = _positive(where, arg, extent)
    if extent <= span * (1 + 1e-12):
        raise ValueError(f"{where}: {arg}={extent!r} is not larger than the span of the nodes along {axis} "
                         f"({span:g}); give a {arg} larger than the span, or omit it (the span plus one mean "
                         "node spacing)")
    centre = 0.5 * (xs[0] + xs[-1])
    edges = np.concatenate([[centre - 0.5 * extent], 0.5 * (xs[1:] + xs[:-1]), [centre + 0.5 * extent]])
    half = np.minimum(xs - edges[:-1], edges[1:] - xs)
    return float(extent), 2.0 * half


def _friction(where, horizontal, mu, facets):
    """``(mu, facets)`` of a footing that slides in plan, checked; ``(None, None)`` otherwise."""
    if horizontal != "soil":
        for arg, value in (("mu", mu), ("facets", facets)):
            if value is not None:
                raise ValueError(f"{where}: {arg}={value!r} is for a footing that slides on the soil; give "
                                 f"horizontal='soil' (now {horizontal!r}) or remove {arg}")
        return None, None
    if isinstance(mu, bool) or not isinstance(mu, numbers.Real) or not (np.isfinite(mu) and mu > 0):
        raise ValueError(f"{where}: horizontal='soil' needs mu, the friction coefficient of the footing on the "
                         f"soil (a finite number > 0; a large one for a footing that does not slide), got mu={mu!r}")
    if facets is None:
        facets = DEFAULT_FACETS
    if isinstance(facets, bool) or not isinstance(facets, numbers.Integral) or facets < 4 or facets % 2:
        raise ValueError(f"{where}: facets={facets!r} is not valid; give the facets of the friction cone in plan, "
                         "an even int >= 4 (opposite facets in pairs; 4: the pyramid of the x and y axes)")
    return float(mu), int(facets)


def plan_soil(soil, patches, where):
    """The x-y-z :class:`~unilateral.soil.SoilFlexibility` (3 m rows: x, y, z) of ``patches`` for a
    footing that slides in plan, and its :class:`~unilateral.structure.foundation.SoilSpec` (or None).

    A SoilFlexibility is taken as it is (3 m rows). A spec is checked as the 2-D footing that slides
    checks it (``components="xz"``), then: the half-space's or layered soil's ``components="xyz"``;
    Wolf's horizontal cone of the footing's area spread over the patches by area along x and along
    y, its vertical cone along z; Kelvin springs ``kx``, dashpots ``cx`` along x and along y.
    """
    from ..soil.flexibility import SoilFlexibility

    if isinstance(soil, SoilFlexibility):
        if soil.m != 3 * patches.m:
            raise ValueError(f"{where}: the SoilFlexibility has m = {soil.m} rows but the footing has {patches.m} "
                             f"patches and slides in plan (x, y then z rows: 3 per patch, {3 * patches.m}); build "
                             "it for these patches with components='xyz'")
        return soil, None
    flex, spec = soil_flexibility(soil, patches, where, "xz")           # checks the spec
    if spec.model == "winkler-kelvin":
        m = patches.m
        k, c = flex.kelvin
        return SoilFlexibility.kelvin(np.concatenate([k[:m], k[:m], k[m:]]),
                                      np.concatenate([c[:m], c[:m], c[m:]])), spec
    if spec.model == "cones":
        from ..soil.cones import Cone, cone

        G, nu = spec.shear_modulus(where), spec.poisson(where)
        share = patches.areas / patches.areas.sum()
        r0 = float(np.sqrt(patches.areas.sum() / np.pi))
        cones = []
        for motion in ("horizontal", "horizontal", "vertical"):
            whole = cone(motion, G, nu, spec.rho, r0)
            cones += [Cone(motion, whole.K * w, whole.C * w, whole.dM * w, 0.0, whole.z0, whole.c) for w in share]
        out = SoilFlexibility.impedances(cones)
        out.description = (f"the footing's horizontal (x and y) and vertical cones (G={G:g}, nu={nu:g}, "
                           f"rho={spec.rho:g}) over {patches.m} patches by area")
        return out, spec
    if spec.model == "layered":
        from .foundation import layered_soil

        return SoilFlexibility.halfspace(layered_soil(spec, where), patches, components="xyz"), spec
    from ..soil.halfspace import HalfSpace

    medium = HalfSpace(spec.shear_modulus(where), spec.poisson(where), float(spec.rho), float(spec.damping))
    return SoilFlexibility.halfspace(medium, patches, components="xyz"), spec


class Footings3D(Footings):
    """The footings of a :class:`~unilateral.structure.Frame3D` on one soil (see
    :class:`~unilateral.structure.foundation.Footings`); footings that slide in plan add the
    maps ``Tx``, ``Ty``, the facets of their friction cones, and their results in plan.

    The constraints of the soil after the frame's own: the contacts (``m``), the shears along x
    (``m``), along y (``m``), then the ``facets`` slip multipliers of each patch.
    """

    def __init__(self, footings, first=0):
        footings = tuple(footings)
        self.facets = None
        if not any(f.sliding for f in footings):
            super().__init__(footings, first)
            return
        self.footings, self.first, self.sliding = footings, int(first), True
        names = ", ".join(repr(f.name) for f in footings)
        if not all(f.sliding for f in footings):
            raise ValueError(f"foundations {names}: footings that slide (horizontal='soil') and footings held "
                             "otherwise cannot be mixed in one frame; give every footing horizontal='soil', or none")
        if len({f.facets for f in footings}) > 1:
            raise ValueError(f"foundations {names}: footings that slide in plan share one friction cone; give them "
                             f"the same facets, got {[f.facets for f in footings]}")
        self.facets = footings[0].facets
        self.mu = np.concatenate([np.full(f.m, f.mu) for f in footings])
        self.soil = _plan_group_soil(footings)
        self.patches = _concat_patches([f.patches for f in footings])
        self.gap = np.concatenate([f.gap for f in footings])
        self.contact_names = tuple(name for f in footings for name in f.contact_names)

    @property
    def constraints_per_patch(self) -> int:
        """The soil's constraints per patch: 1 (a contact), or sliding in plan ``3 + facets``."""
        return 3 + self.facets if self.sliding else 1

    def Ty(self, dofs) -> np.ndarray:
        """``Ty`` (n, m) of all patches (footings that slide in plan)."""
        return np.hstack([f.Ty(dofs) for f in self.footings])

    def constraint_coords(self) -> dict:
        """x, y, kind and gap along ``constraint``: the contacts; sliding: the shears along x and along
        y (kind ``"foundation_shear"``) and the facets (``"foundation_slip"``), each at its patch."""
        if not self.sliding:
            return super().constraint_coords()
        parts = [f.constraint_coords() for f in self.footings]
        out = {key: [x for p in parts for x in p[key][1]] for key in parts[0]}
        x, y, gap, n = out["constraint_x"], out["constraint_y"], out["constraint_gap"], self.facets
        out = {"constraint_x": x + x + x + [a for a in x for _ in range(n)],
               "constraint_y": y + y + y + [a for a in y for _ in range(n)],
               "constraint_kind": out["constraint_kind"] + ["foundation_shear"] * (2 * self.m)
               + ["foundation_slip"] * (n * self.m),
               "constraint_gap": gap + [0.0] * ((2 + n) * self.m)}
        return {key: ("constraint", value) for key, value in out.items()}

    def shear_forces(self, sol) -> np.ndarray | None:
        """The soil's horizontal forces on the footings (N+1, m, 2) (force; x, y), or None."""
        if not self.sliding:
            return None
        psi = np.asarray(sol.psi, dtype=float)[:, self.first + self.m:self.first + 3 * self.m]
        return np.stack([psi[:, :self.m], psi[:, self.m:]], axis=-1)

    def slips(self, sol) -> np.ndarray | None:
        """The net slip ``sum_k lambda_k d_k`` (N+1, m, 2) of each patch on the soil (length; x, y), or None."""
        if not self.sliding:
            return None
        v = np.asarray(sol.v, dtype=float)[:, self.first + self.m:self.first + 3 * self.m]
        return np.stack([v[:, :self.m], v[:, self.m:]], axis=-1)

    def facet_slips(self, sol) -> np.ndarray | None:
        """The slip multipliers ``lambda_k`` (N+1, m, facets) of each patch (length), or None."""
        if not self.sliding:
            return None
        v = np.asarray(sol.v, dtype=float)[:, self.first + 3 * self.m:self.first + (3 + self.facets) * self.m]
        return v.reshape(v.shape[0], self.m, self.facets)

    def contact_load(self, structure, sol) -> np.ndarray:
        """``T c + Tx hx + Ty hy`` (N+1, n): the load of the soil's forces on the structure."""
        out = self.contact_forces(sol) @ self.T(structure.dofs, structure.coords).T
        if self.sliding:
            h = self.shear_forces(sol)
            out = out + h[..., 0] @ self.Tx(structure.dofs).T + h[..., 1] @ self.Ty(structure.dofs).T
        return out


def _plan_group_soil(footings):
    """One x-y-z flexibility of all the footings' patches: all x rows, all y rows, then all z rows."""
    from ..soil.flexibility import SoilFlexibility

    if len(footings) == 1:
        return footings[0].soil
    specs = [f.spec for f in footings]
    if shared_medium(footings, "z"):
        return plan_soil(specs[0], _concat_patches([f.patches for f in footings]),
                         f"foundation {footings[0].name!r}: soil")[0]
    soil = SoilFlexibility.block_diagonal([f.soil for f in footings])
    starts = np.cumsum([0] + [3 * f.m for f in footings])
    order = [a + b * f.m + j for b in range(3) for a, f in zip(starts, footings) for j in range(f.m)]
    return soil.permuted(order)


def to_plan_model(structure):
    """The :class:`~unilateral.soil.FoundationModel` of a 3-D frame whose footings slide in plan
    (``Tx``, ``Ty``, ``mu``, ``facets``), as :func:`~unilateral.structure.foundation.to_foundation_model`
    makes that of other footings: the frame's own constraints first (if any), then the soil's."""
    from ..model import Model
    from ..soil.foundation_model import FoundationModel

    fnd = structure.foundation
    T, Tx, Ty = fnd.T(structure.dofs, structure.coords), fnd.Tx(structure.dofs), fnd.Ty(structure.dofs)
    big = structure.n > 2000
    if big:
        T, Tx, Ty = sp.csr_matrix(T), sp.csr_matrix(Tx), sp.csr_matrix(Ty)
    slide = dict(Tx=Tx, Ty=Ty, mu=fnd.mu, facets=fnd.facets, gap=fnd.gap, contact_names=list(fnd.contact_names))
    nat = structure.natural
    if structure.m:
        model = Model.from_natural(nat.G, nat.E, nat.B, M=structure.M, A=nat.A, r=nat.r, theta=nat.theta(0.0),
                                   C=structure.C, E_v=nat.E_v, dof_names=structure.dofs.names,
                                   constraint_names=list(structure.constraint_names), families=structure.families(),
                                   on_soil=True)
        if structure.geometric is not None:        # P-Delta: as Structure.to_model adds it
            model.K = (model.K + structure.geometric).tocsr()
            model.natural = replace(model.natural, K_geometric=structure.geometric)
        return FoundationModel.on(model, T, fnd.soil, **slide)
    if np.any(nat.theta(0.0)):
        raise ValueError("the frame has imposed strains (axial_strain, curvature) and a foundation on a soil "
                         "medium: give them as loads")
    K = (nat.G @ nat.E @ nat.G.T).tocsr()
    if structure.geometric is not None:            # P-Delta: the gravity's axial forces on the soil's springs
        K = (K + structure.geometric).tocsr()
    M, C = structure.M, structure.C
    if not big:
        K, M = K.toarray(), M.toarray()
        C = None if C is None else C.toarray()
    return FoundationModel(M, K, T, fnd.soil, C=C, dof_names=structure.dofs.names,
                           K_geometric=structure.geometric, **slide)


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
