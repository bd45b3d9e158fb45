"""The model-file format as pydantic models: one class per TOML table, validated strictly.

Every table forbids unknown keys, takes TOML types as they are (no ``"1.0"`` for a number) and
rejects ``inf`` and ``nan``. Numbers are in the units declared in ``[units]``; masses in
``force time^2 / length``. Cross references (nodes that exist, unique names, files that exist)
are checked after validation, in :mod:`unilateral.modelfile.checks`.

A 3-D frame (``[frame] dimensions = 3``) is validated against
:class:`~unilateral.modelfile.schema3d.ModelFile3D`, whose tables of the frame are those of
:class:`~unilateral.structure.Frame3D` (:func:`~unilateral.modelfile.dimensions.model_class`
chooses); a key of the other dimension is reported as such
(:func:`~unilateral.modelfile.dimensions.dimension_hint`).

Fields that name a node carry the marker :data:`NODE_REF` in their metadata, fields that name a
file :data:`FILE_REF`; :func:`iter_fields` walks a validated document for such checks.
"""

from __future__ import annotations

import json
from typing import Annotated, ClassVar, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, WithJsonSchema, model_validator
from pydantic_core import PydanticCustomError

from .. import _LCP_NAMES as LCP_SOLVERS, _MATRIX_METHOD_NAMES as MATRIX_METHOD_NAMES, _RULE_NAMES as RULES
from .pushover_table import PushoverTable, needs_time_step
from .rigid import rigid_tables
from .support_motion_table import support_motion_table
from .values import _direction, _dof_ref, _gravity, _node_id, _pair, _vector
from .walk import iter_fields  # noqa: F401 (the walk of a validated document, re-exported)
from .recorders import OutputRecorders

LENGTH_UNITS = ("m", "cm", "mm", "in", "ft")
FORCE_UNITS = ("N", "kN", "MN", "lbf", "kip")
TIME_UNITS = {"s": 1.0, "ms": 1e-3}                       #: Time units and their factors to seconds.
MASS_UNITS = ("kg", "t", "Mg")      #: Mass units of ``[units] mass``; without it masses are in force time^2 / length.


class _Marker:
    """Metadata marker of a field kind, found by :func:`iter_fields`."""

    def __init__(self, kind: str):
        self.kind = kind

    def __repr__(self) -> str:
        return f"<{self.kind} reference>"


NODE_REF = _Marker("node")
FILE_REF = _Marker("file")


# ---------------------------------------------------------------------- value types
_NUMBER_SCHEMA = {"type": "number"}
NodeId = Annotated[int | str, PlainValidator(_node_id), WithJsonSchema({"type": ["integer", "string"], "minLength": 1})]
NodeRef = Annotated[NodeId, NODE_REF]
FileRef = Annotated[str, Field(min_length=1), FILE_REF]
DofRef = Annotated[int | str, PlainValidator(_dof_ref),
                   WithJsonSchema({"type": ["integer", "string"], "minimum": 0, "minLength": 1})]
Vector = Annotated[tuple[float, float], PlainValidator(_vector),
                   WithJsonSchema({"type": "array", "items": _NUMBER_SCHEMA, "minItems": 2, "maxItems": 2})]
Pair = Annotated[tuple[float, float], PlainValidator(_pair),              # a point of a backbone, a polygon
                 WithJsonSchema({"type": "array", "items": _NUMBER_SCHEMA, "minItems": 2, "maxItems": 2})]
Direction = Annotated[str | tuple[float, float], PlainValidator(_direction), WithJsonSchema({"anyOf": [
    {"enum": ["ux", "uy", "rz"]}, {"type": "array", "items": _NUMBER_SCHEMA, "minItems": 2, "maxItems": 2}]})]
GravityValue = Annotated[float | str, PlainValidator(_gravity),
                    WithJsonSchema({"anyOf": [{"type": "number", "exclusiveMinimum": 0}, {"const": "standard"}]})]
Name = Annotated[str, Field(min_length=1, description="Unique element name (used in the results).")]
Positive = Annotated[float, Field(gt=0)]
NonNegative = Annotated[float, Field(ge=0)]


class Table(BaseModel):
    """Base of the TOML tables: strict types, no unknown keys, finite numbers."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True, defer_build=True)


def _toml(value) -> str:
    """A node id or number as written in TOML (strings in double quotes)."""
    return json.dumps(value) if isinstance(value, str) else f"{value:g}" if isinstance(value, float) else str(value)


class _TwoNodes(Table):
    """A table joining two nodes, ``NODES``, that must differ (the second may be absent: the ground)."""

    NODES: ClassVar[tuple[str, str]] = ("node_i", "node_j")

    @model_validator(mode="after")
    def _two_nodes(self):
        first, second = self.NODES
        node = getattr(self, first)
        if getattr(self, second) == node:
            raise PydanticCustomError("same_node", "{first} and {second} are the same node {node}: give two "
                                      "different nodes", {"first": first, "second": second, "node": _toml(node)})
        return self


def _in_order(table, earlier: str, later: str, *, strict: bool) -> None:
    """``table.later`` > (``strict``) or >= ``table.earlier``, as :mod:`unilateral.loads.pulses` requires."""
    a, b = getattr(table, earlier), getattr(table, later)
    if b < a or (strict and b == a):
        raise PydanticCustomError("order", "{later} must be {relation} {earlier}, got {later}={b} and {earlier}={a}",
                                  {"later": later, "earlier": earlier, "relation": ">" if strict else ">=",
                                   "a": repr(a), "b": repr(b)})


# ---------------------------------------------------------------------- units and geometry
class Units(Table):
    """[units]: the units of every number in the file (mass is force time^2 / length)."""

    EXAMPLE: ClassVar[str] = '[units] length = "m", force = "kN", time = "s"'
    length: Literal[LENGTH_UNITS] = Field(title="length unit")
    force: Literal[FORCE_UNITS] = Field(title="force unit")
    time: Literal[tuple(TIME_UNITS)] = Field(title="time unit")
    mass: Literal[MASS_UNITS] | None = Field(None, title="mass unit", description=(
        "Unit of the masses m [mass] and inertias J [mass length^2] in [[masses]] (t = Mg = 1000 kg); "
        "default: the consistent unit force time^2/length (kN s^2/m = t with kN, m, s)."))


class Node(Table):
    """[[nodes]]: a node and its coordinates [length]."""

    EXAMPLE: ClassVar[str] = "[[nodes]] id = 1, x = 0.0, y = 0.0; or give [matrices]"
    id: NodeId
    x: float
    y: float


class Support(Table):
    """[[supports]]: restrained DOFs of a node (true = restrained)."""

    node: NodeRef
    ux: bool = True
    uy: bool = True
    rz: bool = False

    @model_validator(mode="after")
    def _restrains_something(self):
        if not (self.ux or self.uy or self.rz):
            raise PydanticCustomError("support", "ux, uy and rz are all false: the support restrains nothing "
                                      "(set one of them true, or remove the support)")
        return self


class RigidLink(_TwoNodes):
    """[[rigid_links]]: node ``slave`` follows the rigid-body motion of node ``master``."""

    NODES: ClassVar[tuple[str, str]] = ("master", "slave")

    master: NodeRef
    slave: NodeRef


class EqualDof(_TwoNodes):
    """[[equal_dofs]]: the DOFs ``dofs`` of node ``slave`` equal the same DOFs of node ``master`` (equalDOF)."""

    NODES: ClassVar[tuple[str, str]] = ("master", "slave")

    master: NodeRef
    slave: NodeRef
    dofs: list[Literal["ux", "uy", "rz"]] = Field(min_length=1, description="The tied DOFs, each once.")


class Mass(Table):
    """[[masses]]: lumped mass m on ux and uy [mass], rotational inertia J on rz [mass length^2].

    The mass unit is ``[units] mass`` if given (``kg``, ``t``, ``Mg``), else force time^2/length.
    """

    node: NodeRef
    m: NonNegative
    J: NonNegative = 0.0


# ---------------------------------------------------------------------- elements
class Beam(_TwoNodes):
    """Euler-Bernoulli beam-column from node_i to node_j."""

    type: Literal["beam"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef
    E: Positive = Field(description="Young's modulus [force/length^2].")
    A: Positive = Field(description="Cross-section area [length^2].")
    I: Positive = Field(description="Second moment of area [length^4].")  # noqa: E741
    axial_strain: float = Field(0.0, description="Imposed (e.g. thermal) axial strain.")
    curvature: float = Field(0.0, description="Imposed curvature [1/length].")
    rho: NonNegative | None = Field(None, description=(
        "Mass density [units.mass/length^3, or force time^2/length^4]: the beam's mass rho A L, half "
        "at each end node (with [loads.gravity], its self-weight)."))


class Bar(_TwoNodes):
    """Axial bar (truss member) from node_i to node_j."""

    type: Literal["bar"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef
    E: Positive = Field(description="Young's modulus [force/length^2].")
    A: Positive = Field(description="Cross-section area [length^2].")
    axial_strain: float = Field(0.0, description="Imposed (e.g. thermal) axial strain.")
    Fy: Positive | None = Field(None, description="Axial yield force both ways [force] (none: elastic); or Fy_t, Fy_c.")
    Fy_t: Positive | None = Field(None, description="Axial yield force in tension [force].")
    Fy_c: Positive | None = Field(None, description="Axial yield force in compression [force].")
    hardening: NonNegative = Field(0.0, description="Kinematic hardening over EA/L (with a yield force).")


class Spring(_TwoNodes):
    """Linear spring from node_i to the ground (no node_j) or to node_j."""

    type: Literal["spring"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef | None = None
    k: Positive = Field(description="Stiffness [force/length] ([force length] along rz).")
    direction: Direction = "uy"


class Dashpot(_TwoNodes):
    """Linear dashpot, attached (acts in tension too), from node_i to the ground or to node_j."""

    type: Literal["dashpot"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef | None = None
    c: Positive = Field(description="Viscosity [force time/length].")
    direction: Direction = "uy"


Element = Annotated[Union[Beam, Bar, Spring, Dashpot], Field(discriminator="type", title="element type")]


class SoilBase(Table):
    """Tensionless soil under a node: spring k and dashpot c in parallel, acting only in contact."""

    type: Literal["soil"]
    name: Name
    node: NodeRef
    k: Positive = Field(description="Stiffness [force/length].")
    c: NonNegative = Field(0.0, description="Viscosity of the dashpot in parallel [force time/length].")
    direction: Direction = Field("uy", description="Direction in which the node separates from the soil.")
    gap: float = Field(0.0, description="Initial gap [length]; negative: an initial penetration.")
    capacity: NonNegative = Field(0.0, description="Tension carried before separating [force].")
    mu: NonNegative | None = Field(None, description="Coulomb friction coefficient (none: no friction).")
    kt: Positive | None = Field(None, description="Stick stiffness along the soil [force/length]; required with mu.")
    ct: NonNegative = Field(0.0, description="Viscosity in parallel with kt [force time/length].")


class Soil(SoilBase):
    """Tensionless soil under a node of a 2-D frame, which may yield in compression (bearing)."""

    bearing: Positive | None = Field(None, description="Bearing capacity of the spring: the largest compression "
                                     "[force]; beyond it the soil settles plastically (none: no limit).")


class Gap(_TwoNodes):
    """Pounding link: a compression-only contact spring between node_i and node_j."""

    type: Literal["gap"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef
    k: Positive = Field(description="Contact stiffness [force/length].")
    gap: float = Field(0.0, description="Clearance that must close before contact [length].")
    c: NonNegative = Field(0.0, description="Contact viscosity [force time/length].")
    direction: Direction | None = Field(None, description="Default: from node_i towards node_j.")
    mu: NonNegative | None = Field(None, description="Coulomb friction coefficient (none: no friction).")
    kt: Positive | None = Field(None, description="Stick stiffness across the gap [force/length]; required with mu.")
    ct: NonNegative = Field(0.0, description="Viscosity in parallel with kt [force time/length].")


class Cable(_TwoNodes):
    """Tension-only cable from node_i to node_j that goes slack in compression."""

    type: Literal["cable"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef
    E: Positive = Field(description="Young's modulus [force/length^2].")
    A: Positive = Field(description="Cross-section area [length^2].")
    slack: float = Field(0.0, description="Slack length [length]; negative: pretension.")
    capacity: NonNegative = Field(0.0, description="Compression carried before going slack [force].")


class YieldLink(_TwoNodes):
    """Zero-length elastic-plastic spring from node to the ground (no node_j) or to node_j."""

    NODES: ClassVar[tuple[str, str]] = ("node", "node_j")

    type: Literal["yield"]
    name: Name
    node: NodeRef
    node_j: NodeRef | None = None
    direction: Direction = "ux"
    k: Positive | None = Field(None, description="Elastic stiffness [force/length] ([force length] along rz); "
                               "none with a backbone.")
    Fy: Positive | None = Field(None, description="Yield force both ways [force]; or give Fy_t and Fy_c.")
    Fy_t: Positive | None = Field(None, description="Yield force in tension [force].")
    Fy_c: Positive | None = Field(None, description="Yield force in compression [force].")
    hardening: NonNegative = Field(0.0, description="Kinematic hardening modulus over k (post-yield k h/(1+h)); "
                                   "backbone: last slope/first.")
    backbone: list[Pair] | None = Field(None, min_length=1, description="Convex multi-linear backbone [[e, F], ...] "
                                        "[length, force] instead of k and Fy (e < 0: compression branch).")


class Hinge(Table):
    """Plastic hinge at an end of a beam: rigid-plastic (no k) or an elastic-plastic rotational spring."""

    type: Literal["hinge"]
    name: Name
    beam: Annotated[str, Field(min_length=1, description="Name of the beam in [[elements]].")]
    end: Literal["i", "j"] = Field(title="beam end")
    My: Positive = Field(description="Yield moment [force length].")
    k: Positive | None = Field(None, description="Rotational stiffness [force length/rad]; none: rigid-plastic.")
    hardening: NonNegative = Field(0.0, description="Kinematic hardening modulus over k (over 4EI/L without k).")


class Hinge2D(Hinge):
    """Plastic hinge at an end of a 2-D beam: elastic-plastic, multi-linear or axial force - moment."""

    My: Positive | None = Field(None, description="Yield moment [force length]; none with a backbone.")
    hardening: NonNegative = Field(0.0, description="Hardening over k (4EI/L without k); backbone: last slope/first.")
    backbone: list[Pair] | None = Field(None, min_length=1, description="Convex multi-linear backbone [[theta, M], "
                                        "...] [rad, force length] instead of My and k (theta < 0: negative branch).")
    interaction: Literal["aisc"] | list[Pair] | None = Field(None, description="Axial force - moment polygon: 'aisc' "
                                                             "(with Ny, My) or its vertices [[N, M], ...].")
    Ny: Positive | None = Field(None, description="Axial yield force [force] of interaction = 'aisc'.")


class Slider(Table):
    """Flat sliding bearing under a node: Coulomb friction mu N behind a stick spring k."""

    type: Literal["slider"]
    name: Name
    node: NodeRef
    mu: NonNegative = Field(description="Friction coefficient.")
    N: Positive = Field(description="Constant normal (compressive) force [force].")
    k: Positive = Field(description="Stick stiffness [force/length].")
    direction: Direction = Field("ux", description="Sliding direction.")


Unilateral = Annotated[Union[Soil, Gap, Cable, YieldLink, Hinge2D, Slider],
                       Field(discriminator="type", title="unilateral element type")]


class Rayleigh(Table):
    """Rayleigh damping C = a0 M + a1 K: either zeta, f1 and f2 [1/time], or a0 [1/time] and/or a1
    [time] (a missing coefficient is 0). K is that of the bilateral elements: the [[unilateral]]
    elements get no a1 damping (give contacts their dashpot c)."""

    zeta: NonNegative | None = None
    f1: Positive | None = None
    f2: Positive | None = None
    a0: NonNegative | None = None
    a1: NonNegative | None = None

    @model_validator(mode="after")
    def _one_form(self):
        ratios = [x is not None for x in (self.zeta, self.f1, self.f2)]
        coefficients = [x is not None for x in (self.a0, self.a1)]
        if not (all(ratios) and not any(coefficients) or any(coefficients) and not any(ratios)):
            raise PydanticCustomError("rayleigh", "give either zeta, f1 and f2, or a0 and/or a1")
        return self


class ModalDamping(Table):
    """Modal damping C = M Phi diag(2 zeta_i w_i) Phi^T M in the modes of the structure with its
    constraints held (massless DOFs condensed): one ratio for every mode, or one per mode."""

    zeta: NonNegative | list[NonNegative] = Field(description="Damping ratio(s), lowest mode first.")
    modes: Annotated[int, Field(ge=1)] | None = Field(None, description=(
        "Number of lowest modes damped (default: all, or as many as ratios)."))

    @model_validator(mode="after")
    def _one_ratio_per_mode(self):
        if isinstance(self.zeta, list) and not self.zeta:
            raise PydanticCustomError("modal", "zeta = []: give one ratio for every mode, or one per mode")
        if isinstance(self.zeta, list) and self.modes is not None and len(self.zeta) != self.modes:
            raise PydanticCustomError("modal", "{count} ratios for modes = {modes}: give one per mode (or one "
                                      "ratio for all)", {"count": len(self.zeta), "modes": self.modes})
        return self


class Damping(Table):
    """[damping]: structural damping (Kelvin dashpots of soil and gaps are given with them)."""

    rayleigh: Rayleigh | None = None
    modal: ModalDamping | None = None


# ---------------------------------------------------------------------- loads
class RectangularPulse(Table):
    """1 for t_start < t <= t_end, else 0."""

    type: Literal["rectangular"]
    t_start: float = 0.0
    t_end: float

    @model_validator(mode="after")
    def _ordered(self):
        _in_order(self, "t_start", "t_end", strict=True)
        return self


class HalfSinePulse(Table):
    """sin(pi (t - t_start) / duration) for t_start < t < t_start + duration, else 0."""

    type: Literal["half_sine"]
    t_start: float = 0.0
    duration: Positive


class TriangularPulse(Table):
    """0 at t_start, 1 at t_peak, 0 at t_end, linear in between, 0 outside."""

    type: Literal["triangular"]
    t_start: float = 0.0
    t_peak: float
    t_end: float

    @model_validator(mode="after")
    def _ordered(self):
        _in_order(self, "t_start", "t_end", strict=True)
        _in_order(self, "t_start", "t_peak", strict=False)
        _in_order(self, "t_peak", "t_end", strict=False)
        return self


class ConstantLoad(Table):
    """1 at all times, t = 0 included (a static load)."""

    type: Literal["constant"]


class RampLoad(Table):
    """Linear from 0 at t = 0 to 1 at t_ramp, then 1."""

    type: Literal["ramp"]
    t_ramp: Positive


class TableLoad(Table):
    """Piecewise-linear table of times and factors read from a text (CSV) file."""

    type: Literal["table"]
    file: FileRef
    time_column: int = Field(0, ge=0)
    value_column: int = Field(1, ge=0)
    outside: Literal["zero", "hold"] = Field("zero", title="value outside the table")
    skip_header: int | None = Field(None, ge=0, description=(
        "Lines to skip at the top of the file; default: the leading lines that are not all numbers."))


TimeFunction = Annotated[Union[RectangularPulse, HalfSinePulse, TriangularPulse, ConstantLoad, RampLoad, TableLoad],
                         Field(discriminator="type", title="time function type")]


class Gravity(Table):
    """[loads.gravity]: gravity on the masses, constant in time."""

    g: GravityValue = Field(description='Acceleration [length/time^2], or "standard" (9.80665 m/s^2).')
    direction: Vector = (0.0, -1.0)


class NodalLoad(Table):
    """[[loads.nodal]]: a load times a time function, at a node (frames) or a DOF (matrices)."""

    node: NodeRef | None = None
    ux: float | None = Field(None, description="Force along x [force].")
    uy: float | None = Field(None, description="Force along y [force].")
    rz: float | None = Field(None, description="Moment, counter-clockwise [force length].")
    dof: DofRef | None = Field(None, description="Matrix-level models: DOF name or 0-based index.")
    value: float | None = Field(None, description="Matrix-level models: the load on dof.")
    time_function: TimeFunction = ConstantLoad(type="constant")

    @model_validator(mode="after")
    def _node_or_dof(self):
        at_node = self.node is not None or any(x is not None for x in (self.ux, self.uy, self.rz))
        at_dof = self.dof is not None or self.value is not None
        if at_node == at_dof:
            raise PydanticCustomError("nodal_load", "give either node with ux, uy, rz, or dof with value")
        if at_node and self.node is None:
            raise PydanticCustomError("nodal_load", "ux, uy, rz need the node they act on")
        if at_dof and (self.dof is None or self.value is None):
            raise PydanticCustomError("nodal_load", "a DOF load needs both dof and value")
        return self


class DistributedLoad(Table):
    """[[loads.distributed]]: a uniform load on a beam, force per length along global x and y, as its
    fixed-end nodal forces and moments (w L/2, w L^2/12), times a time function."""

    beam: Annotated[str, Field(min_length=1, description="Name of the beam in [[elements]].")]
    wx: float = Field(0.0, description="Load along x [force/length].")
    wy: float = Field(0.0, description="Load along y [force/length].")
    time_function: TimeFunction = ConstantLoad(type="constant")


class GroundMotion(Table):
    """[[loads.ground_motion]]: an acceleration record acting as the load -M r a_g(t)."""

    file: FileRef = Field(description="PEER .AT2 or plain-text record, relative to the model file.")
    direction: Literal["ux", "uy"] | None = Field(None, title="ground motion direction",
                                                  description="Frames: the direction of the ground motion.")
    influence: FileRef | None = Field(None, description="Matrix-level models: Matrix Market file of r (n x 1).")
    scale: float = Field(1.0, description="Factor on the record.")
    units: str | None = Field(None, description="Units of a plain-text record, e.g. \"g\" or \"cm/s2\".")
    dt: Positive | None = Field(None, description="Time step of a one-column text record [s].")
    skip_header: int | None = Field(None, ge=0, description=(
        "Plain-text records: header lines to skip at the top of the file (default 0)."))
    at: Literal["surface", "outcrop", "within"] = Field("surface", title="record location", description=(
        "Where the record was taken: surface (used as it is), outcrop (at an outcrop of the [site] "
        "half-space) or within (at depth in the [site] profile); not surface: the free-field surface motion "
        "by 1D site response of [site]."))
    depth: NonNegative | None = Field(None, description="at = \"within\": depth of the record below the surface [L].")
    wave: Literal["S", "P"] | None = Field(None, title="wave type", description=(
        "Matrix-level models with at not surface: S (horizontal) or P (vertical) waves; a frame's direction "
        "sets it (ux: S, uy: P)."))


SupportMotion = support_motion_table(Table, NodeRef, TimeFunction)      # modelfile/support_motion_table.py


class Loads(Table):
    """[loads]: gravity, nodal loads and ground motions, added up."""

    gravity: Gravity | None = None
    nodal: list[NodalLoad] = []
    distributed: list[DistributedLoad] = []
    ground_motion: list[GroundMotion] = []
    support_motion: list[SupportMotion] = []


class SiteBase(Table):
    """The elastic half-space under the [site] layers."""

    G: Positive | None = Field(None, description="Shear modulus [F/L^2]; or give Vs.")
    Vs: Positive | None = Field(None, description="Shear-wave speed [L/T]; or give G.")
    nu: Annotated[float, Field(ge=0.0, lt=0.5)] | None = Field(None, description=(
        "Poisson's ratio, 0 <= nu < 0.5 (needed for P waves, vertical ground motion)."))
    rho: Positive = Field(description="Mass density [F T^2/L^4, or units.mass/L^3].")
    damping: Annotated[float, Field(ge=0.0, lt=1.0)] = Field(0.0, description="Hysteretic damping ratio.")


class SiteLayer(Table):
    """A horizontal soil layer of [site], from the surface down."""

    thickness: Positive = Field(description="Thickness [L].")
    G: Positive | None = Field(None, description="Shear modulus [F/L^2]; or give Vs.")
    Vs: Positive | None = Field(None, description="Shear-wave speed [L/T]; or give G.")
    nu: Annotated[float, Field(ge=0.0, lt=0.5)] | None = Field(None, description=(
        "Poisson's ratio, 0 <= nu < 0.5 (needed for P waves, vertical ground motion)."))
    rho: Positive = Field(description="Mass density [F T^2/L^4, or units.mass/L^3].")
    damping: Annotated[float, Field(ge=0.0, lt=1.0)] = Field(0.0, description="Hysteretic damping ratio.")


def _rigid_in_schema(schema: dict) -> None:
    """JSON schema of ``base``: the table or the string "rigid" (read as None)."""
    schema["anyOf"] = [{"const": "rigid"} if item.get("type") == "null" else item for item in schema["anyOf"]]


class Site(Table):
    """[site]: the 1D soil profile of the free field, horizontal layers over a half-space or a rigid base."""

    EXAMPLE: ClassVar[str] = ('[site] layers = [{ thickness = 20.0, Vs = 200.0, nu = 0.3, rho = 1.9, damping = 0.05 }], '
                              'base = { Vs = 800.0, nu = 0.25, rho = 2.2, damping = 0.01 }')
    layers: list[SiteLayer] = Field(description="The layers from the surface down (at least one).")
    base: SiteBase | None = Field(json_schema_extra=_rigid_in_schema, description=(
        'The elastic half-space under the layers, or "rigid" (read as None).'))

    @model_validator(mode="before")
    @classmethod
    def _rigid_base(cls, data):
        if isinstance(data, dict) and isinstance(data.get("base"), str):
            if data["base"] != "rigid":
                raise PydanticCustomError("site_base", 'base = {value}: expected "rigid" or a table of the '
                                          "half-space (G or Vs, nu, rho, damping)", {"value": json.dumps(data["base"])})
            data = {**data, "base": None}
        return data


# ---------------------------------------------------------------------- analysis and output
class Analysis(Table):
    """[analysis]: time stepping and solver settings."""

    EXAMPLE: ClassVar[str] = "[analysis] dt = 0.001, t_end = 1.0"
    type: Literal["transient", "pushover"] = Field("transient", description='pushover: see [pushover].')
    dt: Positive | None = Field(None, description='Time step [time] (type = "transient").')
    t_end: Union[Positive, Literal["record"], None] = Field(None, description='End time [time] (type = "transient"), '
                                                            'or "record": the longest ground motion plus t_after.')
    t_after: NonNegative = Field(0.0, description='With t_end = "record": free vibration after the record [time].')
    _time_step = model_validator(mode="after")(needs_time_step)
    method: Literal[MATRIX_METHOD_NAMES] = Field("auto", title="method")
    rule: Literal[tuple(RULES)] = Field("bdf2", title="rule")
    lcp: Literal[tuple(sorted(LCP_SOLVERS))] = Field("bpp", title="LCP solver")
    initial: Literal["static", "rest"] = Field("static", title="initial state")
    load_sampling: Literal["average", "point"] = Field("average", description=(
        'How the steps sample the loads: "average" (hat-function averages, second order across jumps) or '
        '"point" (the values at the step times, as OpenSees reads a Path series; not with method = "event").'))
    bilateral_reference: bool = Field(True, description="Also run with every constraint bilateral.")
    p_delta: bool = Field(False, description=(
        "Frames: add the geometric stiffness of the axial forces of [loads.gravity] (P-Delta)."))
    title: str = ""


class Figure(Table):
    """The displacement history drawn in the main figure."""

    node: NodeRef
    dof: Literal["ux", "uy", "rz"] = Field("uy", title="DOF")
    label: str | None = None


class SpectraPeriods(Table):
    """The periods of the response spectra [time], evenly spaced on a logarithmic scale."""

    min: Positive | None = Field(None, description="Shortest period [time] (default: 0.02 s).")
    max: Positive | None = Field(None, description="Longest period [time] (default: 4 s).")
    count: Annotated[int, Field(ge=2, le=2000)] = Field(100, description="Number of periods.")

    @model_validator(mode="after")
    def _increasing(self):
        if self.min is not None and self.max is not None and not self.min < self.max:
            raise PydanticCustomError("periods", "min must be < max, got min={lo} and max={hi}",
                                      {"lo": self.min, "hi": self.max})
        return self


class Output(OutputRecorders, Table):
    """[output]: what to draw and what to write (:class:`~unilateral.modelfile.recorders.OutputRecorders`)."""

    figure: Figure | None = None
    overturning_about: Annotated[list[float], Field(min_length=2, max_length=2)] | None = Field(None, description=(
        "Frames: the point [x, y] the overturning moment is taken about (default: the centre of the base, "
        "the mean x of the ground-connected nodes at the lowest level)."))
    floor_spectra: list[NodeId] = Field([], description=(
        "Frames with a ground motion: the nodes whose floor response spectra (of their absolute acceleration "
        "along the ground motion) are written to spectra.csv and spectra.png."))
    spectra_damping: Annotated[float, Field(ge=0, lt=1)] = Field(0.05, description=(
        "Damping ratio of the response spectra."))
    spectra_periods: SpectraPeriods = SpectraPeriods()


class Matrices(Table):
    """[matrices]: a matrix-level model, M u'' + C u' + K u = q + F v, psi = F^T u - H v - g."""

    format: Literal["matrix-market"] = Field("matrix-market", title="matrix format")
    M: FileRef
    K: FileRef
    F: FileRef
    H: FileRef
    C: FileRef | None = None
    F_v: FileRef | None = None
    H_v: FileRef | None = None
    g: FileRef | None = None
    dofs: FileRef | None = Field(None, description="Text file with one DOF name per line.")
    constraints: list[Annotated[str, Field(min_length=1)]] | None = None


# ---------------------------------------------------------------------- foundation on a soil medium
class FoundationSoil(Table):
    """[foundation.soil]: the soil medium under the footing and its model."""

    model: Literal["halfspace", "layered", "cones", "winkler-kelvin"] = Field(title="soil model", description=(
        "halfspace: the rigorous (visco)elastic half-space; layered: horizontal layers over it (or over a "
        "rigid base); cones: the footing's vertical cone (Wolf) spread over the patches; winkler-kelvin: a "
        "tensionless spring k and dashpot c per patch."))
    G: Positive | None = Field(None, description="Shear modulus [F/L^2] (halfspace, cones); or give Vs.")
    Vs: Positive | None = Field(None, description="Shear-wave speed [L/T] (halfspace, cones); or give G.")
    nu: Annotated[float, Field(ge=0.0, lt=0.5)] | None = Field(None, description="Poisson's ratio, 0 <= nu < 0.5.")
    rho: Positive | None = Field(None, description="Mass density [F T^2/L^4, or units.mass/L^3].")
    damping: Annotated[float, Field(ge=0.0, lt=1.0)] = Field(0.0, description=(
        "Material damping ratio of the half-space (constant Q); 0 for cones and winkler-kelvin."))
    k: Positive | list[Positive] | None = Field(None, description=(
        "winkler-kelvin: spring of each patch [F/L], one number or one per patch."))
    c: NonNegative | list[NonNegative] = Field(0.0, description=(
        "winkler-kelvin: dashpot of each patch [F T/L], one number or one per patch."))
    kx: Positive | list[Positive] | None = Field(None, description=(
        "winkler-kelvin with horizontal = \"soil\": horizontal spring of each patch [F/L] (3-D: along x and "
        "along y)."))
    cx: NonNegative | list[NonNegative] = Field(0.0, description=(
        "winkler-kelvin with horizontal = \"soil\": horizontal dashpot of each patch [F T/L] (3-D: along x and "
        "along y)."))
    layers: list[SiteLayer] | None = Field(None, description=(
        "layered: the layers from the surface down (thickness, G or Vs, nu, rho, damping); the half-space "
        "under them is G or Vs, nu, rho, damping of this table."))
    base: Literal["halfspace", "rigid"] = Field("halfspace", description=(
        "layered: what the layers rest on, the half-space of this table or a rigid base."))


class Foundation(Table):
    """[[foundations]] (or the single [foundation]): a footing resting on a soil medium through
    unilateral contacts."""

    EXAMPLE: ClassVar[str] = ('[foundation] node = 2, width = 10.0, length = 10.0, patches = 4, '
                              'soil = { model = "halfspace", Vs = 100.0, nu = 0.33, rho = 2.0 }')
    name: Name = "footing"
    node: NodeRef = Field(description="Reference node: the rigid footing's node (uy, rz); where the "
                                      "horizontal restraint acts.")
    nodes: list[NodeId] | None = Field(None, description=(
        "A flexible footing: its contact nodes, one patch each (omit for a rigid footing)."))
    width: Positive | None = Field(None, description="Width along x [L] (flexible: default the span of nodes).")
    length: Positive = Field(description="Length out of plane [L].")
    patches: Annotated[int, Field(ge=1, le=400)] | None = Field(None, description=(
        "Rigid footing: number of strips across the width (default 3)."))
    horizontal: Literal["support", "cone", "none", "soil"] = Field("support", title="horizontal restraint", description=(
        "support: ux of node supported; cone: Wolf's horizontal cone as a bilateral spring and dashpot at "
        "node; none: restrained otherwise; soil: each patch's horizontal force through the soil, limited by "
        "Coulomb friction mu (the footing slides; every footing then takes soil)."))
    mu: NonNegative | None = Field(None, description=(
        "horizontal = \"soil\": the friction coefficient of the footing on the soil."))
    gap: float = Field(0.0, description="Opening at u = 0 with the soil unloaded [L]; negative: a penetration.")
    mass: NonNegative = Field(0.0, description="Rigid footing: its own mass on ux, uy of node [M].")
    J: NonNegative = Field(0.0, description="Rigid footing: its rotary inertia on rz of node [M L^2].")
    soil: FoundationSoil


class FrameKind(Table):
    """[frame]: the kind of frame the file describes."""

    dimensions: Literal[2, 3] = Field(2, title="number of dimensions", description=(
        "2: a plane frame in x, y (DOFs ux, uy, rz; the default); 3: a space frame in x, y, z (DOFs ux, uy, "
        "uz, rx, ry, rz; z up): see \"3-D frames\" in docs/model-file.md."))


Contact, RigidBlock = rigid_tables(Table, NodeRef, Direction, Name, Positive, NonNegative,  # modelfile/rigid.py
                                   NodeId=NodeId)


class ModelFile(Table):
    """A unilateral model file: a 2-D frame (nodes, elements, ...) or matrices, loads, analysis."""

    DIMENSIONS: ClassVar[int] = 2
    units: Units
    frame: FrameKind | None = None
    nodes: list[Node] = []
    supports: list[Support] = []
    rigid_links: list[RigidLink] = []
    equal_dofs: list[EqualDof] = []
    elements: list[Element] = []
    unilateral: list[Unilateral] = []
    masses: list[Mass] = []
    contacts: list[Contact] = []
    rigid_blocks: list[RigidBlock] = []
    damping: Damping | None = None
    foundation: Foundation | None = None
    foundations: list[Foundation] = Field([], description=(
        "Several footings: on a half-space they share it (give each the same soil), elsewhere uncoupled."))
    matrices: Matrices | None = None
    loads: Loads = Loads()
    site: Site | None = None
    analysis: Analysis
    output: Output = Output()
    pushover: PushoverTable | None = None

    @model_validator(mode="after")
    def _one_way_to_give_footings(self):
        if self.foundation is not None and self.foundations:
            raise PydanticCustomError("footings", (
                "give the footings either as [foundation] (one) or as [[foundations]] (any number), not both: "
                "move [foundation] into [[foundations]]"))
        return self

    @property
    def footings(self) -> list:
        """``(key path, Foundation)`` of every footing: ``[foundation]`` or ``[[foundations]]``."""
        if self.foundation is not None:
            return [(("foundation",), self.foundation)]
        return [(("foundations", k), f) for k, f in enumerate(self.foundations)]

    @model_validator(mode="after")
    def _mass_unit_for_frames(self):
        if self.units.mass is not None and self.matrices is not None:
            raise PydanticCustomError("mass_unit", (
                "units.mass applies to the [[masses]] of a frame; the M of a matrix-level model is in "
                "force time^2/length: remove units.mass"))
        return self


FRAME_SECTIONS = ("frame", "nodes", "supports", "rigid_links", "rigid_diaphragms", "equal_dofs", "elements", "unilateral",
                  "masses", "contacts", "rigid_blocks", "damping", "foundation", "foundations")
