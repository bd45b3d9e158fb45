"""What the structure's results of a 2-D and of a 3-D frame differ in, as data: :class:`Dimension`.

:func:`unilateral.analysis.results.structure_results` computes the results of both with one
pipeline; a :class:`Dimension` (:func:`dimension_of` a structure: :data:`TWO_D` or :data:`THREE_D`)
gives it the names and units of the components (end forces ``N, V, M`` or ``N, Vy, Vz, T, My, Mz``
at each end; the ground's forces ``fx, fy, mz`` or ``Fx ... Mz``), the directions of the ground's
translations, the attribute that names the base point, the variable specs that differ (long name
and unit, :class:`Spec`) and the steps of a case's results, in the order they are written (the
order of the variables in ``results.nc`` and of the columns of ``base.csv``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..structure import forces, forces3d


@dataclass(frozen=True)
class Spec:
    """One variable of the structure's results: its dimensions, long name and unit.

    ``long_name`` may hold fields (``{x0:g}``) that the step fills in; ``unit`` is a template of the
    base units (``{force}``, ``{length}``, ``{moment}``, ``{acc}``); ``requires``: the name of the
    unit (``"force"``, ``"acc"``) without which the variable has no unit at all; ``strip``: the unit
    without leading and trailing blanks (those of empty base units)."""

    dims: tuple
    long_name: str
    unit: str = ""
    requires: str = ""
    strip: bool = False

    def attributes(self, units: "Units", **fields) -> tuple[str, str]:
        """``(long_name, unit)`` in ``units`` (the unit ``""``: no ``units`` attribute), the long
        name's ``fields`` filled in."""
        long_name = self.long_name.format(**fields) if fields else self.long_name
        if self.requires and not getattr(units, self.requires):
            return long_name, ""
        unit = self.unit.format(force=units.force, length=units.length, moment=units.moment, acc=units.acc)
        return long_name, unit.strip() if self.strip else unit


@dataclass(frozen=True)
class Units:
    """The base units of a run (``force``, ``length``, ``time``) and the derived ``moment`` and ``acc``."""

    force: str = ""
    length: str = ""
    time: str = ""

    @classmethod
    def of(cls, units) -> "Units":
        """The :class:`Units` of a dict ``{"force": ..., "length": ..., "time": ...}`` (or None)."""
        units = dict(units or {})
        return cls(units.get("force", ""), units.get("length", ""), units.get("time", ""))

    @property
    def moment(self) -> str:
        return f"{self.force} {self.length}".strip()

    @property
    def acc(self) -> str:
        return f"{self.length}/{self.time}^2" if self.length and self.time else ""


@dataclass(frozen=True)
class Dimension:
    """The dimension-specific data of the structure's results (see the module).

    Attributes
    ----------
    name : ``"2-D"`` or ``"3-D"``
    end_components : the components of ``end_force`` (the coordinate ``end_component``)
    axial_columns : the columns of ``end_force`` read as ``axial_force``: the first where the
        element has it (``N_j``), else the second (a rotational spring's moment)
    force_components : the components of ``ground_reaction`` (the coordinate ``force_component``)
    acceleration_directions : the DOF names whose peak absolute accelerations the summary gives
    point_attribute : the dataset attribute (and summary entry) that holds the base point
    steps : the steps of a case's results, in the order they write their variables
    specs : variable name -> :class:`Spec` (dims, long name, unit) of the variables the steps write
        (the accelerations, footings' and inelastic histories and energies have theirs in
        :mod:`unilateral.analysis.result_parts`, :mod:`unilateral.analysis.footing_results`,
        :mod:`unilateral.analysis.inelastic`, :mod:`unilateral.analysis.energy`)
    forces : the module of the frame's forces (:mod:`unilateral.structure.forces` or
        :mod:`unilateral.structure.forces3d`): its ``end_forces``, ``base_point``, ...
    rigid_contacts : whether the pipeline handles rigid contacts itself (2-D); a 3-D frame's are
        completed by :func:`unilateral.analysis.rigid3d.structure_results_rigid_3d`
    footing_options : keywords of :func:`unilateral.analysis.footing_results.footing_histories`
    constraint_deformation : whether ``constraint_deformation`` is written (and the strains computed
        without yield or friction elements)
    frame_periods : whether the summary gives the periods of each separate frame (pounding buildings)
    contact_at_start : whether the footings' contact forces at ``t = 0`` enter the initial
        acceleration of a run without a load (3-D; a plane frame's have no initial acceleration then)
    """

    name: str
    end_components: tuple
    axial_columns: tuple[int, int]
    force_components: tuple
    acceleration_directions: tuple
    point_attribute: str
    steps: tuple
    specs: dict = field(default_factory=dict)
    forces: object = forces
    rigid_contacts: bool = False
    footing_options: dict = field(default_factory=dict)
    constraint_deformation: bool = False
    frame_periods: bool = False
    contact_at_start: bool = False

    @property
    def three_d(self) -> bool:
        return self.name == "3-D"

    def spec(self, name: str) -> Spec:
        """The :class:`Spec` of the variable ``name`` of this dimension's results."""
        return self.specs[name]


#: The variables of the structure's results whose specs are those of both dimensions.
SHARED = {
    "axial_force": Spec(("time", "element"), "element force along its axis, tension positive (moment of a "
                        "rotational spring)", "{force}"),
}

#: The variables of a plane frame's results (:data:`TWO_D`).
SPECS_2D = SHARED | {
    "end_force": Spec(("time", "element", "end_component"), "end forces on the element in local axes (N along "
                      "i->j, V normal, M counter-clockwise)", "{force} (N, V); {moment} (M)", strip=True),
    "support_reaction": Spec(("time", "support"), "force of the support on the structure at node.dof",
                             "{force} or {moment}"),
    "ground_reaction": Spec(("time", "ground_element", "force_component"),
                            "force of the ground on the structure through the element",
                            "{force} (fx, fy); {moment} (mz)"),
    "frame_base_shear": Spec(("time", "frame"), "base shear of each separate frame: sum of the x forces of the "
                             "ground on it", "{force}"),
    "base_shear": Spec(("time",), "base shear: sum of the x forces of the ground", "{force}"),
    "base_vertical": Spec(("time",), "sum of the y forces of the ground", "{force}"),
    "overturning_moment": Spec(("time",), "overturning moment of the ground forces about ({x0:g}, {y0:g}), "
                               "counter-clockwise", "{moment}"),
    "storey_drift": Spec(("time", "storey"), "interstorey drift ux(upper) - ux(lower)", "{length}"),
    "drift_ratio": Spec(("time", "storey"), "interstorey drift ratio", "1"),
    "constraint_deformation": Spec(("time", "constraint"), (
        "total strain the constraint acts on (soil, gap: opening positive; cable, yield link: elongation; "
        "slip: tangential motion; hinge: end rotation in rad; footing patch: its upward motion "
        "plus the gap; its shear and slips: its horizontal motion)"), "{length}"),
}

#: The long names of the 3-D base forces (``base_Fx`` ... ``base_Mz``).
BASE_WORDS = {"Fx": "base shear along x", "Fy": "base shear along y", "Fz": "vertical force of the ground (up)",
              "Mx": "base moment about x", "My": "base moment about y", "Mz": "base torque about z"}
_NODES = ("time", "node", "component")

#: The variables of a 3-D frame's results (:data:`THREE_D`).
SPECS_3D = SHARED | {
    "end_force": Spec(("time", "element", "end_component"), "end forces and moments on the element in its local "
                      "axes x' (i->j), y', z' (N, Vy, Vz along them; T, My, Mz about them, right-hand positive)",
                      "{force} (N, V); {moment} (T, M)", strip=True),
    "support_reaction": Spec(("time", "support"), "force (moment about rx, ry, rz) of the support on the "
                             "structure at node.dof", "{force} or {moment}", requires="force"),
    "ground_reaction": Spec(("time", "ground_element", "force_component"), "force and moment of the ground on the "
                            "structure through the element or the footing patch, at its node",
                            "{force} (F); {force} {length} (M)", requires="force"),
    "node_acceleration": Spec(_NODES, "acceleration of every node relative to the ground (of the time rule)",
                              "{acc} (ux, uy, uz); rad/s^2 (rx, ry, rz)", requires="acc"),
    "node_absolute_acceleration": Spec(_NODES, "absolute acceleration of every node: relative plus the ground's",
                                       "{acc} (ux, uy, uz); rad/s^2 (rx, ry, rz)", requires="acc"),
    **{f"base_{key}": Spec(("time",), f"{words}, the resultant of the ground's forces on the structure"
                           + ("" if key.startswith("F") else " about base_point"),
                           "{force}" if key.startswith("F") else "{moment}") for key, words in BASE_WORDS.items()},
    **{f"drift_ratio_{axis}": Spec(("time", "storey"), f"interstorey drift ratio along {axis}, the largest over the "
                                   "plan's corners", "1") for axis in "xy"},
}

TWO_D = Dimension(
    name="2-D",
    end_components=("N_i", "V_i", "M_i", "N_j", "V_j", "M_j"),
    axial_columns=(3, 5),
    force_components=("fx", "fy", "mz"),
    acceleration_directions=("ux", "uy"),
    point_attribute="overturning_point",
    steps=("accelerations", "end_forces", "footings", "reactions_2d", "base_2d", "drifts_2d", "constraints", "energy"),
    specs=SPECS_2D,
    forces=forces,
    rigid_contacts=True,
    constraint_deformation=True,
    frame_periods=True,
)

THREE_D = Dimension(
    name="3-D",
    end_components=("N_i", "Vy_i", "Vz_i", "T_i", "My_i", "Mz_i", "N_j", "Vy_j", "Vz_j", "T_j", "My_j", "Mz_j"),
    axial_columns=(6, 9),
    force_components=("Fx", "Fy", "Fz", "Mx", "My", "Mz"),
    acceleration_directions=("ux", "uy", "uz"),
    point_attribute="base_point",
    steps=("accelerations", "node_accelerations", "end_forces", "reactions_3d", "base_3d", "footings", "energy",
           "constraints", "drifts_3d"),
    specs=SPECS_3D,
    forces=forces3d,
    footing_options={"three_d": True},
    contact_at_start=True,
)


def dimension_of(structure) -> Dimension:
    """:data:`THREE_D` for a 3-D frame (six DOFs per node), else :data:`TWO_D`."""
    return THREE_D if len(getattr(structure.dofs, "dof_names", ())) == 6 else TWO_D
