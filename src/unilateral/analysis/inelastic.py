"""Results of the yielding and friction elements of a frame (2-D or 3-D): histories for ``results.nc``,
figures for ``summary.json``.

Every yield or friction element is a *polygon*: the unknowns of one element (its *facets*) on its
one or two strains (its *components*), each facet ``k`` a multiplier ``v_k >= 0`` whose column of
``B`` is its unit outward normal ``n_k`` on the components (:attr:`Unknown.entries
<unilateral.structure.elements.Unknown.entries>`) with the resistance ``r_k``: ``n_k . s <= r_k``
bounds the element's force ``s`` on its components, and its plastic deformation (or slip) is
``sum_k v_k n_k``. The elements (:class:`Polygons`), named after the unknowns without their
suffix:

- a two-sided pair on one strain (``name.plastic+``, ``name.plastic-``: a yield link or a 2-D
  plastic hinge; ``name.slip+``, ``name.slip-``: a 2-D soil or gap contact with friction, a
  slider): two facets, ``n = +1`` and ``-1``; its plastic deformation is ``v+ - v-``;
- a 3-D plastic hinge (``name.facet<k>``, :meth:`Frame3D.hinge <unilateral.structure.Frame3D.hinge>`):
  the facets of its interaction polygon on the end rotations ``roty``, ``rotz`` (force: the end
  moments ``M_y'``, ``M_z'``);
- the friction cone of a 3-D contact (``name.slip+``, ``name.slip-``, ``name.slip2+``,
  ``name.slip2-``, or ``name.facet<k>`` with more than 4 facets, :func:`~unilateral.structure.elements3d.frictional`):
  its facets on the tangential strains ``t1``, ``t2`` (force: the tangential force ``T``).

A *yield element* is an element of the ``"yield"`` family, a *friction element* one of the
``"friction"`` family. When every element of a family has one component (every 2-D frame; a 3-D
frame with yield links and sliders alone) its variables are the 2-D ones, without a component
dimension. :meth:`Inelastic.histories` gives, per case:

=============================  ======================  ==============================================
variable                       dims                    content
=============================  ======================  ==============================================
``plastic_deformation``        time, yield_element     ``sum_k v_k n_k``: ``v+ - v-`` of a pair, the
                               [, yield_component]     plastic elongation [L] (rad: a hinge or a
                                                       rotational link); a 3-D hinge's plastic
                                                       rotations about ``y'``, ``z'``
``yield_force``                time, yield_element     the force [F] of a link, the end moment(s)
                               [, yield_component]     [F L] of a hinge (on the beam; 2-D:
                                                       counter-clockwise)
``yield_total_deformation``    time, yield_element     ``force / k + plastic``: the total deformation
                               [, yield_component]     of the spring, a hinge spring's total rotation
                                                       (rad; the plastic part for a rigid-plastic
                                                       hinge), a link's elongation [L]
``yield_element_deformation``  time, yield_element     the total strain(s): a link's elongation, the
                               [, yield_component]     beam's end rotation(s) relative to its chord
                                                       at a hinge (elastic and plastic)
``yield_ratio``                time, yield_element     with components only: ``max_k n_k . s / r_k``,
                                                       the force over the polygon (1 on it without
                                                       hardening; 2-D: ``max(F / F_y+, -F / F_y-)``)
``slip``                       time, friction_element  ``sum_k v_k n_k``: ``s+ - s-`` along the
                               [, friction_component]  tangent ``t`` [L]; a cone's along ``t1``, ``t2``
``friction_force``             time, friction_element  the tangential force ``T`` [F]
                               [, friction_component]
``normal_force``               time, friction_element  the compression ``N`` of ``|T| <= mu N`` [F]
``tangential_deformation``     time, friction_element  the tangential motion ``t . (u_j - u_i)`` [L]
                               [, friction_component]
``slip_path``                  time, friction_element  with components only: the length of the slip's
                                                       path so far, ``sum |s_n - s_{n-1}|`` [L]
=============================  ======================  ==============================================

with the coordinates of :meth:`Inelastic.coords` (kind, yield limits, stiffness, units, ``mu``; with
components: ``yield_component`` (1, 2), ``yield_component_name`` (element, component: ``roty``,
``rotz``; ``t1``, ``t2``; ``d``, the direction of a one-strain element, and ``""`` for no second
component, whose values are NaN), ``yield_facets``, and their ``friction_`` counterparts).
:meth:`Inelastic.peaks` gives the figures of the summary: per yield element the ductility (peak
deformation ``force / k + plastic`` of the link or the hinge's spring over its yield deformation
``r / k``, in the polygon's gauge ``max_k k n_k . d / r_k``; none for a rigid-plastic hinge), the
peak force over the yield force (in a run with the constraints held: the elastic demand), the peak
and the permanent (last step) plastic deformation, the number of yield excursions (runs of flow of
each facet) and the plastic work ``int s . d(plastic deformation)``; per friction element the
total slip (the path length), the peak and the last slip, the peak friction force and the friction
work ``int T . d(slip)``. An element with one component has the 2-D figures (signed peaks, numbers);
one with two has vectors: each peak is the largest magnitude with its time and ``vector``, the
residuals are lists over ``components``.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass

import numpy as np

#: Relative size of a multiplier increment below which it is taken as no flow.
FLOW_TOLERANCE = 1e-10
#: The suffixes of the facets of a yield or friction element (``name.plastic+``, ``name.slip2-``, ``name.facet3``).
FACET_SUFFIX = re.compile(r"\.(plastic\d*[+-]|slip2?[+-]|facet\d+)$")
#: The component of a 3-D beam's strain row (:func:`unilateral.structure.elements3d.beam`) and of a
#: 3-D friction contact's (:func:`unilateral.structure.elements3d.frictional`).
BEAM3D_COMPONENTS = {4: "roty", 2: "rotz", 5: "roty", 3: "rotz"}
CONE_COMPONENTS = {1: "t1", 2: "t2"}
#: The components of a 2-D beam's strain rows: a hinge's axial force - moment polygon.
BEAM_COMPONENTS = {0: "axial", 1: "rot_i", 2: "rot_j"}


@dataclass(frozen=True)
class Polygons:
    """The yield or the friction elements of a structure, each the facets of a polygon on its one or
    two strains (see the module's doc); the arrays of the elements' facets are padded to the
    largest number ``F`` of facets (a padding facet: the element's first column, normal 0,
    resistance inf).

    Attributes
    ----------
    names : (p,) element names (the unknowns' names without ``.plastic+``, ``.slip-``, ``.facet3``)
    kinds : (p,) ``"hinge"`` or ``"yield link"``; ``"soil"``, ``"gap"`` or ``"slider"``
    columns : (p, F) int, the columns of ``v`` of the facets, in the order of ``v``
    normals : (p, F, c) the facets' unit normals on the components (``c``: 1 or 2)
    limits : (p, F) resistances ``r_k`` [F or F L]
    counts : (p,) int, the number of facets
    rows : (p, c) int, the strain (row of ``sigma``) of each component, -1: none
    components : (p, c) names of the components (``""``: none)
    k : (p,) elastic stiffness in series (NaN: rigid-plastic)
    rotational : (p,) bool, a rotation (hinge, rotational link)
    mu : (p,) friction coefficients (0 for yield)
    normal : (p,) int, the column of the contact bounding the slip (-1: a constant normal force)
    """

    names: tuple
    kinds: tuple
    columns: np.ndarray
    normals: np.ndarray
    limits: np.ndarray
    counts: np.ndarray
    rows: np.ndarray
    components: np.ndarray
    k: np.ndarray
    rotational: np.ndarray
    mu: np.ndarray
    normal: np.ndarray

    @classmethod
    def of(cls, structure, family: str) -> Polygons:
        """The elements of ``family`` (``"yield"`` or ``"friction"``) of ``structure``, in the order of
        their first unknown in ``v``."""
        constraints = structure.constraints
        index = {u.name: k for k, (_, u) in enumerate(constraints)}
        groups: dict = {}
        for col, (element, u) in enumerate(constraints):
            match = FACET_SUFFIX.search(u.name) if u.kind == family else None
            if match:
                groups.setdefault((id(element), u.name[: match.start()]), (element, []))[1].append(col)
        strains = np.asarray(structure.constraint_strains, dtype=int)
        facets = [(name, element, cols, _local_rows(element, [constraints[c][1] for c in cols]))
                  for (_, name), (element, cols) in groups.items()]
        p = len(facets)
        width = max((len(local) for *_, local in facets), default=1)
        F = max((len(cols) for _, _, cols, _ in facets), default=2)
        columns, normals = np.zeros((p, F), dtype=int), np.zeros((p, F, width))
        limits, rows = np.full((p, F), np.inf), np.full((p, width), -1, dtype=int)
        components = np.full((p, width), "", dtype=object)
        for g, (_, element, cols, local) in enumerate(facets):
            first = constraints[cols[0]][1]
            offset = strains[cols[0]] - first.row               # the element's first strain
            columns[g] = cols[0]
            columns[g, :len(cols)] = cols
            for f, col in enumerate(cols):
                u = constraints[col][1]
                limits[g, f] = u.r
                for row, b in u.entries:
                    normals[g, f, local.index(row)] = b
            rows[g, :len(local)] = [offset + row for row in local]
            components[g, :len(local)] = _component_names(element, local, family)
        first = [constraints[cols[0]][1] for _, _, cols, _ in facets]
        return cls(names=tuple(name for name, *_ in facets), kinds=tuple(_kind(e) for _, e, _, _ in facets),
                   columns=columns, normals=normals, limits=limits,
                   counts=np.array([len(cols) for _, _, cols, _ in facets], dtype=int), rows=rows,
                   components=components, k=np.array([np.nan if u.k is None else u.k for u in first]),
                   rotational=np.array([_rotational(e) for _, e, _, _ in facets], dtype=bool),
                   mu=np.array([u.mu for u in first]),
                   normal=np.array([-1 if u.normal is None else index[u.normal] for u in first], dtype=int))

    def __len__(self) -> int:
        return len(self.names)

    @property
    def width(self) -> int:
        """The number of components of the family's variables: 2 if an element has two, else 1."""
        return self.rows.shape[1]

    def facets(self, g) -> np.ndarray:
        """The columns of ``v`` of element ``g``'s facets."""
        return self.columns[g, :self.counts[g]]

    def ncomponents(self, g) -> int:
        return int(np.count_nonzero(self.rows[g] >= 0))

    def axis_limits(self) -> np.ndarray:
        """(p, c, 2): the resistance along ``+`` and ``-`` each component's axis, ``min r_k / |n_k|``
        over the facets facing it (a pair's ``r+`` and ``r-``; a hinge's ``My`` and ``Mz`` on its
        polygon's axes); NaN for no component. Computed once (the peaks of each element read it)."""
        return self._axis_limits

    @functools.cached_property
    def _axis_limits(self) -> np.ndarray:
        out = np.full((len(self), self.width, 2), np.nan)
        for g in range(len(self)):
            n, r = self.normals[g, :self.counts[g]], self.limits[g, :self.counts[g]]
            for j in range(self.ncomponents(g)):
                for side, sign in enumerate((1.0, -1.0)):
                    facing = sign * n[:, j] > 0
                    if facing.any():
                        out[g, j, side] = np.min(r[facing] / (sign * n[facing, j]))
        out.flags.writeable = False
        return out

    def vectors(self, v) -> np.ndarray:
        """``sum_k v_k n_k`` (N+1, p, c) of the multipliers ``v`` (N+1, m): each element's plastic
        deformation or slip on its components (NaN where it has none)."""
        out = v[:, self.columns[:, 0], None] * self.normals[None, :, 0]
        for f in range(1, self.columns.shape[1]):
            out = out + v[:, self.columns[:, f], None] * self.normals[None, :, f]
        out[:, self.rows < 0] = np.nan
        return out

    def gauge(self, s) -> np.ndarray:
        """``max_k n_k . s / r_k`` (N+1, p) of vectors ``s`` (N+1, p, c) on the components: 1 on the
        polygon (2-D: ``max(s / r+, -s / r-)``)."""
        s = np.where(self.rows[None] >= 0, s, 0.0)
        out = np.full(s.shape[:2], -np.inf)
        for f in range(self.columns.shape[1]):
            out = np.maximum(out, (s * self.normals[None, :, f]).sum(axis=2) / self.limits[:, f])
        return out


def _local_rows(element, unknowns) -> list:
    """The strain rows of the element that the ``unknowns`` enter: a 3-D beam's ``(roty, rotz)`` of
    its end, else in ascending order."""
    rows = sorted({row for u in unknowns for row, _ in u.entries})
    if element.kind == "beam3d" and len(rows) == 2:
        rows.sort(key=lambda row: BEAM3D_COMPONENTS.get(row, ""))
    return rows


def _component_names(element, rows, family) -> list:
    """``roty``, ``rotz`` (a 3-D hinge), ``axial``, ``rot_i``/``rot_j`` (a 2-D axial force - moment hinge),
    ``t1``, ``t2`` (a 3-D friction cone), ``d`` (one strain)."""
    if len(rows) == 1:
        return ["d"]
    names = {"beam3d": BEAM3D_COMPONENTS, "beam": BEAM_COMPONENTS}.get(
        element.kind, CONE_COMPONENTS if family == "friction" else {})
    return [names.get(row, f"strain{row}") for row in rows]


def _kind(element) -> str:
    return {"beam": "hinge", "beam3d": "hinge", "yield": "yield link"}.get(element.kind, element.kind)


def _rotational(element) -> bool:
    """A hinge (on a 2-D or 3-D beam), or a link along a rotation: its deformation is a rotation."""
    return element.kind in ("beam", "beam3d") or all(dof in ("rx", "ry", "rz") for _, dof in element.dofs)


def rotational_unknowns(structure) -> set:
    """The names of the unknowns of ``structure`` whose multipliers are rotations (rad): those of
    hinges (the facets of a 3-D hinge's polygon too) and of links along a rotation."""
    return {u.name for element, u in getattr(structure, "constraints", ()) if _rotational(element)}


class Inelastic:
    """The yield and friction elements of a structure and their results.

    Parameters
    ----------
    structure : Structure (2-D or 3-D)
    units : dict of the base units (``length``, ``force``), for the attributes
    """

    def __init__(self, structure, units=None):
        units = dict(units or {})
        self.structure = structure
        self.yields = Polygons.of(structure, "yield")
        self.frictions = Polygons.of(structure, "friction")
        self.length, self.force = units.get("length", ""), units.get("force", "")

    def __bool__(self) -> bool:
        return bool(len(self.yields) or len(self.frictions))

    def coords(self) -> dict:
        """Coordinates along ``yield_element`` and ``friction_element`` (those the structure has)."""
        out = {}
        y, f = self.yields, self.frictions
        if len(y):
            moment = f"{self.force} {self.length}".strip()
            limits = y.axis_limits()
            wide = y.width > 1
            dims = ("yield_element", "yield_component") if wide else "yield_element"
            out |= {"yield_element": list(y.names), "yield_element_kind": ("yield_element", list(y.kinds)),
                    "yield_limit_positive": (dims, limits[..., 0] if wide else limits[:, 0, 0]),
                    "yield_limit_negative": (dims, limits[..., 1] if wide else limits[:, 0, 1]),
                    "yield_stiffness": ("yield_element", y.k),
                    "yield_deformation_unit": ("yield_element",
                                               ["rad" if r else self.length for r in y.rotational]),
                    "yield_force_unit": ("yield_element", [moment if r else self.force for r in y.rotational])}
            if wide:
                out |= _component_coords("yield", y)
        if len(f):
            out |= {"friction_element": list(f.names), "friction_element_kind": ("friction_element", list(f.kinds)),
                    "friction_coefficient": ("friction_element", f.mu)}
            if f.width > 1:
                out |= _component_coords("friction", f)
        return out

    def histories(self, h, e) -> dict:
        """The variables of the module's table of one case.

        Parameters
        ----------
        h : :class:`~unilateral.structure.forces.Histories`
        e : (N+1, m) total strains of the unknowns (:meth:`Structure.element_deformations`)

        Returns
        -------
        dict name -> ``(dims, (N+1, p) or (N+1, p, 2) array, long_name, units)``
        """
        from ..structure.forces import stresses

        sigma = stresses(self.structure, h)
        out = {}
        y, f, L, F = self.yields, self.frictions, self.length, self.force
        if len(y):
            dims, lengths = _dims("yield", y), f"{L} (yield links); rad (hinges, rotational links)"
            force = _on_rows(sigma, y.rows)
            wide = y.width > 1
            out["plastic_deformation"] = (dims, _squeezed(y.vectors(h.v)), "plastic deformation sum_k v_k n_k of "
                                          "each yield element: v+ - v- of a pair, the plastic rotations about y', "
                                          "z' of a 3-D hinge" if wide else
                                          "plastic deformation v+ - v- of each yield pair", lengths)
            out["yield_force"] = (dims, _squeezed(force), "force of each yield link, end moments M_y', M_z' of each "
                                  "hinge (on the beam)" if wide else "force of each yield link, end moment of each "
                                  "hinge (on the beam, counter-clockwise)",
                                  f"{F} (yield links); {F} {L} (hinges, rotational links)")
            out["yield_total_deformation"] = (dims, _squeezed(_total(force, y.vectors(h.v), y.k)), "total "
                                              "deformation force / k + plastic of each yield element's spring "
                                              "(elastic and plastic): a hinge spring's total rotation, a link's "
                                              "elongation; the plastic part alone for a rigid-plastic hinge", lengths)
            out["yield_element_deformation"] = (dims, _squeezed(self._deformations(h, e, y)), "deformation of "
                                                "each yield element: a link's elongation, the beam's end rotation "
                                                "relative to its chord at a hinge (elastic and plastic)", lengths)
            if y.width > 1:
                out["yield_ratio"] = (dims[:2], y.gauge(force), "force over the yield polygon, max_k n_k . force / "
                                      "r_k (1 on the polygon without hardening)", "1")
        if len(f):
            dims = _dims("friction", f)
            slip = f.vectors(h.v)
            wide = f.width > 1
            out["slip"] = (dims, _squeezed(slip), "slip sum_k v_k n_k: s+ - s- along the tangent t of a pair, "
                           "along the tangent axes t1, t2 of a 3-D contact" if wide else
                           "slip s+ - s- along the tangent t", L)
            out["friction_force"] = (dims, _squeezed(_on_rows(sigma, f.rows)), "tangential (friction) force T "
                                     "along t, or along t1, t2" if wide else "tangential (friction) force T along t",
                                     F)
            out["normal_force"] = (dims[:2], self._normal(h, sigma), "normal force N (compression positive) of "
                                   "the Coulomb bound |T| <= mu N", F)
            out["tangential_deformation"] = (dims, _squeezed(self._deformations(h, e, f)),
                                             "tangential motion t . (u_j - u_i)", L)
            if wide:
                out["slip_path"] = (dims[:2], _path(slip), "length of the slip's path so far, sum |s_n - s_{n-1}|",
                                    L)
        return out

    def _deformations(self, h, e, family) -> np.ndarray:
        """The total strains (N+1, p, c) on the components: ``e`` of the first facet entering a
        component's strain as its primary, else ``G^T u`` on the strain; NaN for no component."""
        strains = np.asarray(self.structure.constraint_strains, dtype=int)
        out = np.full((len(h.t), *family.rows.shape), np.nan)
        missing = []
        for g in range(len(family)):
            cols = family.facets(g)
            for j, row in enumerate(family.rows[g]):
                primary = cols[strains[cols] == row]
                if row < 0:
                    continue
                if primary.size:
                    out[:, g, j] = e[:, primary[0]]
                else:
                    missing.append((g, j, row))
        if missing:
            G = self.structure.natural.G[:, [row for *_, row in missing]]
            values = np.asarray(G.T @ np.asarray(h.u).T).T
            for k, (g, j, _) in enumerate(missing):
                out[:, g, j] = values[:, k]
        return out

    def _normal(self, h, sigma) -> np.ndarray:
        """``N`` (N+1, p): ``r - b sigma`` of the normal contact, or a slider's constant ``r / mu``."""
        f = self.frictions
        constraints, strains = self.structure.constraints, self.structure.constraint_strains
        out = np.empty((len(h.t), len(f)))
        for k, c in enumerate(f.normal):
            if c >= 0:
                u = constraints[c][1]
                out[:, k] = u.r - u.b * sigma[:, strains[c]]
            else:
                out[:, k] = f.limits[k, 0] / f.mu[k] if f.mu[k] > 0 else np.nan
        return out

    def peaks(self, t, h, histories, unknown_work=None) -> dict:
        """Summary figures of one case: ``yield_elements`` and ``friction_elements``, dicts by name.

        Parameters
        ----------
        t : (N+1,) times;  h : Histories (the multipliers ``v``)
        histories : :meth:`histories` of the case
        unknown_work : (m,) work on each unknown over the run (``unknown_work`` of
            :func:`~unilateral.analysis.energy.energy_balance`), optional
        """
        out = {}
        y, f = self.yields, self.frictions
        if len(y):
            out["yield_elements"] = {name: self._yield_peaks(t, h.v, histories, k, unknown_work)
                                     for k, name in enumerate(y.names)}
        if len(f):
            out["friction_elements"] = {name: self._friction_peaks(t, h.v, histories, k, unknown_work)
                                        for k, name in enumerate(f.names)}
        return out

    def _yield_peaks(self, t, v, histories, k, unknown_work) -> dict:
        """Figures of yield element ``k`` with the multipliers ``v`` (N+1, m): see the module's doc."""
        y = self.yields
        plastic, force = _element(histories, "plastic_deformation", k), _element(histories, "yield_force", k)
        cols = y.facets(k)
        flows = _flows(v[:, cols])
        out = {"kind": y.kinds[k], "unit": "rad" if y.rotational[k] else self.length, "yielded": bool(flows.any()),
               "yield_excursions": _excursions(flows)}
        if y.ncomponents(k) == 1:                       # a pair: the 2-D figures
            limits = y.axis_limits()[k, 0]
            plastic, force = plastic[:, 0], force[:, 0]
            out |= {"peak_force_ratio": _ratio_peak(t, force, limits),
                    "peak_plastic_deformation": _abs_peak(t, plastic),
                    "residual_plastic_deformation": float(plastic[-1]), "plastic_work": _work(unknown_work, cols)}
            if np.isfinite(y.k[k]):
                yield_deformation = limits / y.k[k]
                out["yield_deformation"] = yield_deformation.tolist()
                out["ductility"] = _ratio_peak(t, force / y.k[k] + plastic, yield_deformation)
            return out
        n, r = y.normals[k, :len(cols)], y.limits[k, :len(cols)]
        out |= {"components": list(y.components[k]), "facets": len(cols),
                "peak_force_ratio": _peak(t, _gauge(force, n, r)),
                "peak_plastic_deformation": _vector_peak(t, plastic),
                "residual_plastic_deformation": plastic[-1].tolist(), "plastic_work": _work(unknown_work, cols)}
        if np.isfinite(y.k[k]):
            out["yield_deformation"] = (r / y.k[k]).tolist()
            out["ductility"] = _peak(t, _gauge(force / y.k[k] + plastic, n, r / y.k[k]))
        return out

    def _friction_peaks(self, t, v, histories, k, unknown_work) -> dict:
        """Figures of friction element ``k`` with the multipliers ``v`` (N+1, m): see the module's doc."""
        f = self.frictions
        cols = f.facets(k)
        slip, force = _element(histories, "slip", k), _element(histories, "friction_force", k)
        out = {"kind": f.kinds[k], "unit": self.length, "slid": bool(_flows(v[:, cols]).any())}
        if f.ncomponents(k) == 1:                       # a pair: the 2-D figures
            return out | {"total_slip": float(np.sum(v[-1, cols] - v[0, cols])), "peak_slip": _abs_peak(t, slip[:, 0]),
                          "residual_slip": float(slip[-1, 0]), "peak_friction_force": _abs_peak(t, force[:, 0]),
                          "friction_work": _work(unknown_work, cols)}
        return out | {"components": list(f.components[k]), "facets": len(cols),
                      "total_slip": float(_path(slip[:, None])[-1, 0]), "peak_slip": _vector_peak(t, slip),
                      "residual_slip": slip[-1].tolist(), "peak_friction_force": _vector_peak(t, force),
                      "friction_work": _work(unknown_work, cols)}


def _dims(family: str, polygons) -> tuple:
    """``("time", "<family>_element"[, "<family>_component"])``."""
    return ("time", f"{family}_element", f"{family}_component")[:2 + (polygons.width > 1)]


def _component_coords(family: str, polygons) -> dict:
    """The coordinates of the components of a family with two: their numbers (1, 2), names and the
    elements' numbers of facets."""
    element = f"{family}_element"
    return {f"{family}_component": np.arange(1, polygons.width + 1),
            f"{family}_component_name": ((element, f"{family}_component"), polygons.components.astype(str)),
            f"{family}_facets": (element, polygons.counts)}


def _total(force, plastic, k) -> np.ndarray:
    """``force / k + plastic`` (N+1, p, c) of the yield elements (stiffness ``k`` (p,); NaN: rigid-plastic,
    whose elastic part is 0)."""
    k = np.asarray(k, dtype=float)[None, :, None]
    elastic = np.divide(force, k, out=np.zeros_like(force), where=np.isfinite(k) & (k != 0))
    return plastic + elastic


def _squeezed(values) -> np.ndarray:
    """(N+1, p, c) -> (N+1, p) with one component (the 2-D variables)."""
    return values[:, :, 0] if values.shape[2] == 1 else values


def _element(histories, name, k) -> np.ndarray:
    """Element ``k``'s values (N+1, c) of the variable ``name`` of :meth:`Inelastic.histories`."""
    values = histories[name][1]
    return values[:, k, None] if values.ndim == 2 else values[:, k, :]


def _on_rows(sigma, rows) -> np.ndarray:
    """``sigma`` (N+1, ne) on the components' strains ``rows`` (p, c): (N+1, p, c), NaN for -1."""
    out = sigma[:, np.where(rows >= 0, rows, 0)]
    out[:, rows < 0] = np.nan
    return out


def _path(vectors) -> np.ndarray:
    """The path length so far (N+1, p) of vectors (N+1, p, c) (NaN components left out)."""
    steps = np.sqrt(np.nansum(np.diff(vectors, axis=0) ** 2, axis=2))
    return np.vstack([np.zeros((1, vectors.shape[1])), np.cumsum(steps, axis=0)])


def _gauge(s, n, r) -> np.ndarray:
    """``max_k n_k . s / r_k`` (N+1,) of one element's vectors ``s`` (N+1, c), normals ``n`` (F, c)."""
    return np.max((s @ n.T) / r, axis=1)


def _abs_peak(t, y) -> dict:
    i = int(np.argmax(np.abs(y)))
    return {"value": float(y[i]), "t": float(t[i])}


def _peak(t, y) -> dict:
    i = int(np.argmax(y))
    return {"value": float(y[i]), "t": float(t[i])}


def _vector_peak(t, s) -> dict:
    """The largest magnitude of vectors ``s`` (N+1, c): ``value``, ``t`` and the ``vector`` then."""
    magnitude = np.linalg.norm(s, axis=1)
    i = int(np.argmax(magnitude))
    return {"value": float(magnitude[i]), "t": float(t[i]), "vector": s[i].tolist()}


def _ratio_peak(t, y, limits) -> dict:
    """Peak of ``y / limits[0]`` (``y > 0``) and ``-y / limits[1]`` (``y < 0``), with its time; a side
    without a limit (NaN: the tension side of a soil spring's bearing capacity) left out."""
    ratio = np.fmax(y / limits[0], -y / limits[1])
    i = int(np.argmax(ratio))
    return {"value": float(ratio[i]), "t": float(t[i])}


def _flows(v) -> np.ndarray:
    """Steps (N, F) at which each multiplier of an element's facets ``v`` (N+1, F) grew."""
    dv = np.diff(v, axis=0)
    return dv > FLOW_TOLERANCE * max(float(np.abs(v).max(initial=0.0)), np.finfo(float).tiny)


def _excursions(flows) -> int:
    """Number of runs of consecutive flow steps, each multiplier on its own."""
    before = np.vstack([np.zeros((1, flows.shape[1]), dtype=bool), flows[:-1]])
    return int((flows & ~before).sum())


def _work(unknown_work, cols):
    """The work on the facets ``cols`` of an element, or None without ``unknown_work``."""
    if unknown_work is None:
        return None
    return float(sum(unknown_work[c] for c in cols))
