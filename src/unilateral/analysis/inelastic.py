"""Results of the yielding and friction elements of a frame: histories for ``results.nc``, figures
for ``summary.json``.

A yield pair (``name.plastic+``, ``name.plastic-``: a yield link or a plastic hinge) is one
*yield element* ``name``, a slip pair (``name.slip+``, ``name.slip-``: a soil or gap contact with
friction, or a slider) one *friction element* ``name`` (:mod:`unilateral.structure.elements`).
:meth:`Inelastic.histories` gives, per case:

=============================  ======================  ==============================================
variable                       dims                    content
=============================  ======================  ==============================================
``plastic_deformation``        time, yield_element     ``v+ - v-``: plastic elongation [L] (rad: a
                                                       hinge or a rotational link)
``yield_force``                time, yield_element     the force [F] of a link, the end moment [F L]
                                                       of a hinge (on the beam, counter-clockwise)
``yield_element_deformation``  time, yield_element     the total strain of the pair: a link's
                                                       elongation, the beam's end rotation relative
                                                       to its chord at a hinge (elastic and plastic)
``slip``                       time, friction_element  ``s+ - s-`` along the tangent ``t`` [L]
``friction_force``             time, friction_element  the tangential force ``T`` along ``t`` [F]
``normal_force``               time, friction_element  the compression ``N`` of ``|T| <= mu N`` [F]
``tangential_deformation``     time, friction_element  the tangential motion ``t . (u_j - u_i)`` [L]
=============================  ======================  ==============================================

with the coordinates of :meth:`Inelastic.coords` (kind, yield limits, stiffness, units, ``mu``).
:meth:`Inelastic.peaks` gives the figures of the summary: per yield element the ductility (peak
deformation ``force / k + v+ - v-`` of the link or the hinge's spring over its yield deformation
``F_y / k``; none for a rigid-plastic hinge), the peak force over the yield force (in a run with
the constraints held: the elastic demand), the peak and the permanent (last step) plastic
deformation, the number of yield excursions and the plastic work; per friction element the total
slip (the path length), the peak and the last slip and the friction work.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Relative size of a multiplier increment below which it is taken as no flow.
FLOW_TOLERANCE = 1e-10


@dataclass(frozen=True)
class Pairs:
    """Pairs of unknowns (``+``, ``-``) of one family, one element each.

    Attributes
    ----------
    names : (p,) element names (the unknowns' names without ``.plastic+`` or ``.slip+``)
    kinds : (p,) ``"hinge"`` or ``"yield link"``; ``"soil"``, ``"gap"`` or ``"slider"``
    plus, minus : (p,) int, the columns of ``v`` of the two unknowns
    limits : (p, 2) resistances ``r`` of the ``+`` and ``-`` faces [F or F L]
    k : (p,) elastic stiffness in series (NaN: rigid-plastic)
    rotational : (p,) bool, a rotation (hinge, rotational link)
    mu : (p,) friction coefficients (0 for yield)
    normal : (p,) int, the column of the contact bounding the slip (-1: a constant normal force)
    """

    names: tuple
    kinds: tuple
    plus: np.ndarray
    minus: np.ndarray
    limits: np.ndarray
    k: np.ndarray
    rotational: np.ndarray
    mu: np.ndarray
    normal: np.ndarray

    @classmethod
    def of(cls, structure, family: str) -> Pairs:
        """The pairs of ``family`` (``"yield"`` or ``"friction"``) of ``structure``, in the order of ``v``."""
        constraints = structure.constraints
        index = {u.name: k for k, (_, u) in enumerate(constraints)}
        suffix = ".plastic" if family == "yield" else ".slip"
        plus = [k for k, (_, u) in enumerate(constraints) if u.kind == family and u.name.endswith(suffix + "+")]
        names = tuple(constraints[k][1].name.removesuffix(suffix + "+") for k in plus)
        minus = [index[name + suffix + "-"] for name in names]
        elements = [constraints[k][0] for k in plus]
        first = [constraints[k][1] for k in plus]
        limits = [[constraints[i][1].r, constraints[j][1].r] for i, j in zip(plus, minus)]
        return cls(names=names, kinds=tuple(_kind(e) for e in elements), plus=np.array(plus, dtype=int),
                   minus=np.array(minus, dtype=int), limits=np.array(limits, dtype=float).reshape(-1, 2),
                   k=np.array([np.nan if u.k is None else u.k for u in first]),
                   rotational=np.array([_rotational(e) for e in elements], dtype=bool),
                   mu=np.array([u.mu for u in first]),
                   normal=np.array([-1 if u.normal is None else index[u.normal] for u in first], dtype=int))

    def __len__(self) -> int:
        return len(self.names)


def _kind(element) -> str:
    return {"beam": "hinge", "yield": "yield link"}.get(element.kind, element.kind)


def _rotational(element) -> bool:
    """A hinge, or a link along ``rz``: its deformation is a rotation."""
    return element.kind == "beam" or all(dof == "rz" for _, dof in element.dofs)


class Inelastic:
    """The yield and friction elements of a structure and their results.

    Parameters
    ----------
    structure : Structure
    units : dict of the base units (``length``, ``force``), for the attributes
    """

    def __init__(self, structure, units=None):
        units = dict(units or {})
        self.structure = structure
        self.yields = Pairs.of(structure, "yield")
        self.frictions = Pairs.of(structure, "friction")
        self.length, self.force = units.get("length", ""), units.get("force", "")

    def __bool__(self) -> bool:
        return bool(len(self.yields) or len(self.frictions))

    def coords(self) -> dict:
        """Coordinates along ``yield_element`` and ``friction_element`` (those the structure has)."""
        out = {}
        y, f = self.yields, self.frictions
        if len(y):
            moment = f"{self.force} {self.length}".strip()
            out |= {"yield_element": list(y.names), "yield_element_kind": ("yield_element", list(y.kinds)),
                    "yield_limit_positive": ("yield_element", y.limits[:, 0]),
                    "yield_limit_negative": ("yield_element", y.limits[:, 1]),
                    "yield_stiffness": ("yield_element", y.k),
                    "yield_deformation_unit": ("yield_element",
                                               ["rad" if r else self.length for r in y.rotational]),
                    "yield_force_unit": ("yield_element", [moment if r else self.force for r in y.rotational])}
        if len(f):
            out |= {"friction_element": list(f.names), "friction_element_kind": ("friction_element", list(f.kinds)),
                    "friction_coefficient": ("friction_element", f.mu)}
        return out

    def histories(self, h, e) -> dict:
        """The variables of the module's table of one case.

        Parameters
        ----------
        h : :class:`~unilateral.structure.forces.Histories`
        e : (N+1, m) total strains of the unknowns (:meth:`Structure.element_deformations`)

        Returns
        -------
        dict name -> ``(dims, (N+1, p) array, long_name, units)``
        """
        from ..structure.forces import stresses

        sigma = stresses(self.structure, h)[:, self.structure.constraint_strains]
        out = {}
        y, f, L, F = self.yields, self.frictions, self.length, self.force
        if len(y):
            plastic = h.v[:, y.plus] - h.v[:, y.minus]
            force = sigma[:, y.plus]
            dims, lengths = ("time", "yield_element"), f"{L} (yield links); rad (hinges, rotational links)"
            out["plastic_deformation"] = (dims, plastic, "plastic deformation v+ - v- of each yield pair", lengths)
            out["yield_force"] = (dims, force, "force of each yield link, end moment of each hinge (on the beam, "
                                  "counter-clockwise)", f"{F} (yield links); {F} {L} (hinges, rotational links)")
            out["yield_element_deformation"] = (dims, e[:, y.plus], "deformation of each yield element: a "
                                                "link's elongation, the beam's end rotation relative to its chord "
                                                "at a hinge (elastic and plastic)", lengths)
        if len(f):
            dims = ("time", "friction_element")
            out["slip"] = (dims, h.v[:, f.plus] - h.v[:, f.minus], "slip s+ - s- along the tangent t", L)
            out["friction_force"] = (dims, sigma[:, f.plus], "tangential (friction) force T along t", F)
            out["normal_force"] = (dims, self._normal(h, sigma), "normal force N (compression positive) of "
                                   "the Coulomb bound |T| <= mu N", F)
            out["tangential_deformation"] = (dims, e[:, f.plus], "tangential motion t . (u_j - u_i)", L)
        return out

    def _normal(self, h, sigma) -> np.ndarray:
        """``N`` (N+1, p): ``r - b sigma`` of the normal contact, or a slider's constant ``r / mu``."""
        f = self.frictions
        constraints = self.structure.constraints
        out = np.empty((len(h.t), len(f)))
        for k, c in enumerate(f.normal):
            if c >= 0:
                u = constraints[c][1]
                out[:, k] = u.r - u.b * sigma[:, c]
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
            out["yield_elements"] = {name: self._yield_peaks(t, h.v[:, [y.plus[k], y.minus[k]]], histories, k,
                                                             unknown_work)
                                     for k, name in enumerate(y.names)}
        if len(f):
            out["friction_elements"] = {name: self._friction_peaks(t, h.v[:, [f.plus[k], f.minus[k]]], histories, k,
                                                                   unknown_work)
                                        for k, name in enumerate(f.names)}
        return out

    def _yield_peaks(self, t, v, histories, k, unknown_work) -> dict:
        """Figures of yield element ``k`` with the pair's multipliers ``v`` (N+1, 2): see the module's doc."""
        y = self.yields
        plastic, force = histories["plastic_deformation"][1][:, k], histories["yield_force"][1][:, k]
        flows = _flows(v)
        out = {"kind": y.kinds[k], "unit": "rad" if y.rotational[k] else self.length, "yielded": bool(flows.any()),
               "yield_excursions": _excursions(flows), "peak_force_ratio": _ratio_peak(t, force, y.limits[k]),
               "peak_plastic_deformation": _abs_peak(t, plastic), "residual_plastic_deformation": float(plastic[-1]),
               "plastic_work": _work(unknown_work, y, k)}
        if np.isfinite(y.k[k]):
            yield_deformation = y.limits[k] / y.k[k]
            out["yield_deformation"] = yield_deformation.tolist()
            out["ductility"] = _ratio_peak(t, force / y.k[k] + plastic, yield_deformation)
        return out

    def _friction_peaks(self, t, v, histories, k, unknown_work) -> dict:
        """Figures of friction element ``k`` with the pair's multipliers ``v`` (N+1, 2): see the module's doc."""
        slip = histories["slip"][1][:, k]
        return {"kind": self.frictions.kinds[k], "unit": self.length, "slid": bool(_flows(v).any()),
                "total_slip": float(np.sum(v[-1] - v[0])), "peak_slip": _abs_peak(t, slip),
                "residual_slip": float(slip[-1]),
                "peak_friction_force": _abs_peak(t, histories["friction_force"][1][:, k]),
                "friction_work": _work(unknown_work, self.frictions, k)}


def _abs_peak(t, y) -> dict:
    i = int(np.argmax(np.abs(y)))
    return {"value": float(y[i]), "t": float(t[i])}


def _ratio_peak(t, y, limits) -> dict:
    """Peak of ``y / limits[0]`` (``y > 0``) and ``-y / limits[1]`` (``y < 0``), with its time."""
    ratio = np.maximum(y / limits[0], -y / limits[1])
    i = int(np.argmax(ratio))
    return {"value": float(ratio[i]), "t": float(t[i])}


def _flows(v) -> np.ndarray:
    """Steps (N, 2) at which each multiplier of a pair ``v`` (N+1, 2) grew."""
    dv = np.diff(v, axis=0)
    return dv > FLOW_TOLERANCE * max(float(np.abs(v).max(initial=0.0)), np.finfo(float).tiny)


def _excursions(flows) -> int:
    """Number of runs of consecutive flow steps, each multiplier on its own."""
    before = np.vstack([np.zeros((1, flows.shape[1]), dtype=bool), flows[:-1]])
    return int((flows & ~before).sum())


def _work(unknown_work, pairs, k):
    """The work on pair ``k`` (both unknowns), or None without ``unknown_work``."""
    if unknown_work is None:
        return None
    return float(unknown_work[pairs.plus[k]] + unknown_work[pairs.minus[k]])
