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


@dataclass(frozen=True)
class Spec:
    """The attributes of one variable of the structure's results.

    ``unit`` is a template of the base units (``{force}``, ``{length}``, ``{moment}``, ``{acc}``);
    ``requires``: the name of the unit (``"force"``, ``"acc"``) without which the variable has no unit
    at all; ``strip``: the unit without leading and trailing blanks (those of empty base units)."""

    long_name: str
    unit: str = ""
    requires: str = ""
    strip: bool = False

    def attributes(self, units: "Units") -> tuple[str, str]:
        """``(long_name, unit)`` in ``units`` (the unit ``""``: no ``units`` attribute)."""
        if self.requires and not getattr(units, self.requires):
            return self.long_name, ""
        unit = self.unit.format(force=units.force, length=units.length, moment=units.moment, acc=units.acc)
        return self.long_name, unit.strip() if self.strip else unit


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
    specs : variable name -> :class:`Spec`, of the variables whose attributes differ by dimension
    rigid_contacts : whether the pipeline handles rigid contacts itself (2-D); a 3-D frame's are
        completed by :func:`unilateral.analysis.rigid3d.structure_results_rigid_3d`
    footing_options : keywords of :func:`unilateral.analysis.footing_results.footing_histories`
    """

    name: str
    end_components: tuple
    axial_columns: tuple[int, int]
    force_components: tuple
    acceleration_directions: tuple
    point_attribute: str
    steps: tuple
    specs: dict = field(default_factory=dict)
    rigid_contacts: bool = False
    footing_options: dict = field(default_factory=dict)

    @property
    def three_d(self) -> bool:
        return self.name == "3-D"

    def attributes(self, name: str, units: Units) -> tuple[str, str]:
        """``(long_name, unit)`` of the variable ``name`` in ``units``."""
        return self.specs[name].attributes(units)


_AXIAL = Spec("element force along its axis, tension positive (moment of a rotational spring)", "{force}")

TWO_D = Dimension(
    name="2-D",
    end_components=("N_i", "V_i", "M_i", "N_j", "V_j", "M_j"),
    axial_columns=(3, 5),
    force_components=("fx", "fy", "mz"),
    acceleration_directions=("ux", "uy"),
    point_attribute="overturning_point",
    steps=("accelerations", "end_forces", "footings", "reactions", "base", "drifts", "constraints", "energy"),
    specs={
        "end_force": Spec("end forces on the element in local axes (N along i->j, V normal, M counter-clockwise)",
                          "{force} (N, V); {moment} (M)", strip=True),
        "axial_force": _AXIAL,
        "support_reaction": Spec("force of the support on the structure at node.dof", "{force} or {moment}"),
        "ground_reaction": Spec("force of the ground on the structure through the element",
                                "{force} (fx, fy); {moment} (mz)"),
    },
    rigid_contacts=True,
)

THREE_D = Dimension(
    name="3-D",
    end_components=("N_i", "Vy_i", "Vz_i", "T_i", "My_i", "Mz_i", "N_j", "Vy_j", "Vz_j", "T_j", "My_j", "Mz_j"),
    axial_columns=(6, 9),
    force_components=("Fx", "Fy", "Fz", "Mx", "My", "Mz"),
    acceleration_directions=("ux", "uy", "uz"),
    point_attribute="base_point",
    steps=("accelerations", "node_accelerations", "end_forces", "reactions", "base", "footings", "energy",
           "constraints", "drifts"),
    specs={
        "end_force": Spec("end forces and moments on the element in its local axes x' (i->j), y', z' (N, Vy, Vz "
                          "along them; T, My, Mz about them, right-hand positive)", "{force} (N, V); {moment} (T, M)",
                          strip=True),
        "axial_force": _AXIAL,
        "support_reaction": Spec("force (moment about rx, ry, rz) of the support on the structure at node.dof",
                                 "{force} or {moment}", requires="force"),
        "ground_reaction": Spec("force and moment of the ground on the structure through the element or the "
                                "footing patch, at its node", "{force} (F); {force} {length} (M)", requires="force"),
        "node_acceleration": Spec("acceleration of every node relative to the ground (of the time rule)",
                                  "{acc} (ux, uy, uz); rad/s^2 (rx, ry, rz)", requires="acc"),
        "node_absolute_acceleration": Spec("absolute acceleration of every node: relative plus the ground's",
                                           "{acc} (ux, uy, uz); rad/s^2 (rx, ry, rz)", requires="acc"),
    },
    footing_options={"three_d": True},
)


def dimension_of(structure) -> Dimension:
    """:data:`THREE_D` for a 3-D frame (six DOFs per node), else :data:`TWO_D`."""
    return THREE_D if len(getattr(structure.dofs, "dof_names", ())) == 6 else TWO_D
