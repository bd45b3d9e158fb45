"""The model-file tables of a 3-D frame (``[frame] dimensions = 3``): those of
:class:`~unilateral.structure.Frame3D` (six DOFs per node, diaphragms, 3-D beams, friction and
hinge polygons, footings in plan, loads and outputs along x, y, z) and their root :class:`ModelFile3D`.

Each extends or stands beside its 2-D table of :mod:`unilateral.modelfile.schema`, validated alike.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal, Union

from pydantic import Field, PlainValidator, WithJsonSchema, model_validator
from pydantic_core import PydanticCustomError

from .rigid import rigid_tables_3d
from .schema import (Bar, Cable, Contact, ConstantLoad, Dashpot, EqualDof, Figure, FoundationSoil, Gap, GravityValue, GroundMotion, Hinge,
                     ModelFile, Name, NodeId, NodeRef, NonNegative, Output, Positive, Slider, SoilBase, Spring,
                     SupportMotion, Table, TimeFunction, YieldLink, _NUMBER_SCHEMA, _TwoNodes)

DOFS_3D = ("ux", "uy", "uz", "rx", "ry", "rz")
"""The nodal DOFs of a 3-D frame (:class:`~unilateral.structure.Frame3D`)."""
TWO_D_ONLY_TYPES: dict[str, str] = {}
"""Unilateral element types of 2-D frames only (none: a 3-D frame takes hinges too, :class:`Hinge3D`)."""
HINGE_SHAPES = ("ellipse", "diamond", "box")
"""The interaction polygons of a 3-D hinge (those of :meth:`Frame3D.hinge <unilateral.structure.Frame3D.hinge>`)."""


def _vector3(value):
    ok = (isinstance(value, list) and len(value) == 3
          and all(isinstance(x, int | float) and not isinstance(x, bool) for x in value))
    if not ok or not all(abs(x) < float("inf") for x in value) or not any(value):
        raise PydanticCustomError("vector", "expected a nonzero vector [dx, dy, dz] of three numbers")
    return tuple(float(x) for x in value)


def _direction3(value):
    if isinstance(value, str):
        if value not in DOFS_3D:
            raise PydanticCustomError("direction", 'expected "ux", "uy", "uz", "rx", "ry", "rz" or a vector '
                                      "[dx, dy, dz]")
        return value
    return _vector3(value)


Vector3 = Annotated[tuple[float, float, float], PlainValidator(_vector3),
                    WithJsonSchema({"type": "array", "items": _NUMBER_SCHEMA, "minItems": 3, "maxItems": 3})]
Direction3 = Annotated[str | tuple[float, float, float], PlainValidator(_direction3), WithJsonSchema({"anyOf": [
    {"enum": list(DOFS_3D)}, {"type": "array", "items": _NUMBER_SCHEMA, "minItems": 3, "maxItems": 3}]})]


class Node3D(Table):
    """[[nodes]] of a 3-D frame: a node and its coordinates [length] (z up)."""

    EXAMPLE: ClassVar[str] = "[[nodes]] id = 1, x = 0.0, y = 0.0, z = 0.0"
    id: NodeId
    x: float
    y: float
    z: float


class Support3D(Table):
    """[[supports]] of a 3-D frame: restrained DOFs of a node (true = restrained; default: a pin)."""

    node: NodeRef
    ux: bool = True
    uy: bool = True
    uz: bool = True
    rx: bool = False
    ry: bool = False
    rz: bool = False

    @model_validator(mode="after")
    def _restrains_something(self):
        if not any(getattr(self, dof) for dof in DOFS_3D):
            raise PydanticCustomError("support", "ux, uy, uz, rx, ry and rz are all false: the support restrains "
                                      "nothing (set one of them true, or remove the support)")
        return self


class RigidDiaphragm(Table):
    """[[rigid_diaphragms]]: a rigid floor in the plane z = z of master: the ux, uy, rz of every slave
    follow the master's in-plane rigid motion (the slaves keep uz, rx, ry)."""

    master: NodeRef
    slaves: list[NodeId] = Field(min_length=1, description="The other nodes of the floor, at the master's z.")


class EqualDof3D(EqualDof):
    """[[equal_dofs]] of a 3-D frame: the DOFs ``dofs`` of node ``slave`` equal those of node ``master``."""

    dofs: list[Literal["ux", "uy", "uz", "rx", "ry", "rz"]] = Field(min_length=1, description="The tied DOFs, each once.")


class Mass3D(Table):
    """[[masses]] of a 3-D frame: lumped mass m on ux, uy, uz [mass], rotary inertias Jx, Jy, Jz on rx,
    ry, rz [mass length^2]."""

    node: NodeRef
    m: NonNegative
    Jx: NonNegative = 0.0
    Jy: NonNegative = 0.0
    Jz: NonNegative = 0.0


class Beam3D(_TwoNodes):
    """Elastic 3-D beam-column (Euler-Bernoulli bending about the local y' and z', St Venant torsion)."""

    type: Literal["beam"]
    name: Name
    node_i: NodeRef
    node_j: NodeRef
    E: Positive = Field(description="Young's modulus [force/length^2].")
    A: Positive = Field(description="Cross-section area [length^2].")
    Iy: Positive = Field(description="Second moment of area about the local y' axis [length^4].")
    Iz: Positive = Field(description="Second moment of area about the local z' axis [length^4].")
    G: Positive = Field(description="Shear modulus [force/length^2].")
    J: Positive = Field(description="Torsion constant [length^4].")
    vecxz: Vector3 | None = Field(None, description=(
        "A vector in the local x'-z' plane (fixes the section's orientation); default: global z, or global x "
        "for a vertical member."))
    axial_strain: float = Field(0.0, description="Imposed (e.g. thermal) axial strain.")
    rho: NonNegative | None = Field(None, description=(
        "Mass density: the beam's mass rho A L, half at each end node (with [loads.gravity], its self-weight)."))


class Spring3D(Spring):
    """Linear spring of a 3-D frame from node_i to the ground (no node_j) or to node_j."""

    k: Positive = Field(description="Stiffness [force/length] ([force length] along rx, ry, rz).")
    direction: Direction3 = "uz"


class Dashpot3D(Dashpot):
    """Linear dashpot of a 3-D frame, from node_i to the ground or to node_j."""

    direction: Direction3 = "uz"


Element3D = Annotated[Union[Beam3D, Bar, Spring3D, Dashpot3D], Field(discriminator="type", title="element type")]

_FACETS = Field(None, description=(
    "With mu: the number of facets of the friction cone (an even integer >= 4; default 4)."))


class Soil3D(SoilBase):
    """Tensionless soil under a node of a 3-D frame (default direction uz), which may yield in compression."""

    direction: Direction3 = Field("uz", description="Direction in which the node separates from the soil.")
    bearing: Positive | None = Field(None, description="Bearing capacity of the spring: the largest compression "
                                     "[force]; beyond it the soil settles plastically (none: no limit).")
    facets: Annotated[int, Field(ge=4)] | None = _FACETS


class Gap3D(Gap):
    """Pounding link of a 3-D frame between node_i and node_j."""

    direction: Direction3 | None = Field(None, description="Default: from node_i towards node_j.")
    facets: Annotated[int, Field(ge=4)] | None = _FACETS


class YieldLink3D(YieldLink):
    """Zero-length elastic-plastic spring of a 3-D frame from node to the ground or to node_j."""

    direction: Direction3 = "ux"


class Slider3D(Slider):
    """Flat sliding bearing under a node of a 3-D frame: Coulomb friction mu N behind a stick spring k."""

    direction: Direction3 = Field("ux", description="Sliding direction.")


class Hinge3D(Hinge):
    """Plastic hinge at an end of a 3-D beam, yielding under the end moments about both bending axes within a
    polygon: rigid-plastic (no k) or an elastic-plastic rotational spring on both rotations."""

    My: Positive = Field(description="Plastic moment about the beam's local y' axis [force length].")
    Mz: Positive = Field(description="Plastic moment about the beam's local z' axis [force length].")
    shape: Literal[HINGE_SHAPES] = Field("ellipse", title="hinge shape", description=(
        "ellipse: (My'/My)^2 + (Mz'/Mz)^2 <= 1, as the circumscribed polygon of facets facets; diamond: "
        "|My'|/My + |Mz'|/Mz <= 1; box: |My'| <= My and |Mz'| <= Mz, uncoupled (4 facets each)."))
    facets: Annotated[int, Field(ge=4)] | None = Field(None, description=(
        "The number of facets: for an ellipse an even integer >= 4 (default 8); a diamond or a box has 4."))
    hardening: NonNegative = Field(0.0, description=(
        "Kinematic hardening modulus over k on both axes (over 4EIy/L and 4EIz/L without k)."))


Unilateral3D = Annotated[Union[Soil3D, Gap3D, Cable, YieldLink3D, Hinge3D, Slider3D],
                         Field(discriminator="type", title="unilateral element type")]


class Foundation3D(Table):
    """[[foundations]] of a 3-D frame: a rigid rectangular footing centred on node, on an nx x ny grid of
    unilateral contact patches on a soil medium, or a flexible one (nodes: a patch under each node of a
    grid)."""

    EXAMPLE: ClassVar[str] = ('[[foundations]] node = 2, width = 2.5, length = 2.5, patches = [3, 3], '
                              'soil = { model = "halfspace", Vs = 200.0, nu = 0.33, rho = 2.0 }')
    name: Name = "footing"
    node: NodeRef | None = Field(None, description=(
        "The rigid footing's node (its centre, at the base: uz, rx, ry), required for it; a flexible "
        "footing's reference node, where horizontal = \"support\" acts (default: the grid's middle node)."))
    nodes: Annotated[list[Annotated[list[NodeId], Field(min_length=1)]], Field(min_length=1)] | None = Field(
        None, description=(
            "A flexible footing: its grid of contact nodes at one elevation, rows along x (each row at one y, "
            "each column at one x), e.g. [[1, 2, 3], [4, 5, 6]]; one patch each (omit for a rigid footing)."))
    width: Positive | None = Field(None, description=(
        "Plan dimension along x [L]; rigid: required; flexible: default the span of the columns plus one mean "
        "spacing."))
    length: Positive | None = Field(None, description=(
        "Plan dimension along y [L]; rigid: required; flexible: default the span of the rows plus one mean "
        "spacing."))
    patches: Annotated[int, Field(ge=1, le=20)] | Annotated[list[Annotated[int, Field(ge=1, le=400)]], Field(
        min_length=2, max_length=2)] | None = Field(None, description=(
            "Rigid footing: [nx, ny] patches along x and y (one integer: both; default [3, 3]; at most 400 in "
            "all)."))
    horizontal: Literal["support", "none", "soil"] = Field("support", title="horizontal restraint", description=(
        "support: ux, uy, rz of node supported; none: the frame holds the footing in plan; soil: each patch's "
        "horizontal force (fx, fy) through the soil, limited by a polygonal Coulomb cone of facets facets with "
        "mu (the footing slides and twists in plan; a flexible footing's patches act on their nodes' ux, uy; "
        "every footing then takes soil)."))
    mu: Positive | None = Field(None, description=(
        "horizontal = \"soil\": the friction coefficient of the footing on the soil."))
    facets: Annotated[int, Field(ge=4)] | None = Field(None, description=(
        "horizontal = \"soil\": the facets of each patch's friction cone in plan, an even number >= 4 "
        "(default 8; 4: the pyramid of the x and y axes)."))
    gap: float = Field(0.0, description="Opening at u = 0 with the soil unloaded [L]; negative: a penetration.")
    mass: NonNegative = Field(0.0, description="Rigid footing: its own mass on ux, uy, uz of node [M].")
    Jx: NonNegative = Field(0.0, description="Rigid footing: its rotary inertia on rx of node [M L^2].")
    Jy: NonNegative = Field(0.0, description="Rigid footing: its rotary inertia on ry of node [M L^2].")
    Jz: NonNegative = Field(0.0, description="Rigid footing: its rotary inertia on rz of node [M L^2] (its twist).")
    soil: FoundationSoil


class Gravity3D(Table):
    """[loads.gravity] of a 3-D frame: gravity on the masses, along -z by default."""

    g: GravityValue = Field(description='Acceleration [length/time^2], or "standard" (9.80665 m/s^2).')
    direction: Vector3 = (0.0, 0.0, -1.0)


class NodalLoad3D(Table):
    """[[loads.nodal]] of a 3-D frame: forces and moments at a node times a time function."""

    node: NodeRef
    ux: float | None = Field(None, description="Force along x [force].")
    uy: float | None = Field(None, description="Force along y [force].")
    uz: float | None = Field(None, description="Force along z [force].")
    rx: float | None = Field(None, description="Moment about x, right-hand positive [force length].")
    ry: float | None = Field(None, description="Moment about y [force length].")
    rz: float | None = Field(None, description="Moment about z [force length].")
    time_function: TimeFunction = ConstantLoad(type="constant")


class DistributedLoad3D(Table):
    """[[loads.distributed]] of a 3-D frame: a uniform load on a beam along global x, y, z, as its
    fixed-end nodal forces and moments, times a time function."""

    beam: Annotated[str, Field(min_length=1, description="Name of the beam in [[elements]].")]
    wx: float = Field(0.0, description="Load along x [force/length].")
    wy: float = Field(0.0, description="Load along y [force/length].")
    wz: float = Field(0.0, description="Load along z [force/length].")
    time_function: TimeFunction = ConstantLoad(type="constant")


def _ground_direction3(value):
    if isinstance(value, str):
        if value not in ("ux", "uy", "uz"):
            raise PydanticCustomError("direction", "unknown ground motion direction (valid: ux, uy, uz or a vector "
                                                   "[dx, dy, dz])")
        return value
    return _vector3(value)


GroundDirection3 = Annotated[str | tuple[float, float, float], PlainValidator(_ground_direction3), WithJsonSchema(
    {"anyOf": [{"enum": ["ux", "uy", "uz"]}, {"type": "array", "items": _NUMBER_SCHEMA, "minItems": 3,
                                             "maxItems": 3}]})]


class GroundMotion3D(GroundMotion):
    """[[loads.ground_motion]] of a 3-D frame: one component of the ground motion (give one record per
    direction for several components)."""

    direction: GroundDirection3 | None = Field(None, title="ground motion direction", description=(
        'The direction of the ground motion: "ux", "uy", "uz" or a vector [dx, dy, dz] (normalised), e.g. '
        "[cos a, sin a, 0] and [-sin a, cos a, 0] for a pair of records rotated by a in plan."))


class Loads3D(Table):
    """[loads] of a 3-D frame: gravity, nodal loads and ground motions, added up."""

    gravity: Gravity3D | None = None
    nodal: list[NodalLoad3D] = []
    distributed: list[DistributedLoad3D] = []
    ground_motion: list[GroundMotion3D] = []
    support_motion: list[SupportMotion] = []


class Figure3D(Figure):
    """The displacement history drawn in the main figure (a 3-D frame's DOF)."""

    dof: Literal[DOFS_3D] = Field("uz", title="DOF")


class Output3D(Output):
    """[output] of a 3-D frame."""

    figure: Figure3D | None = None
    overturning_about: Annotated[list[float], Field(min_length=3, max_length=3)] | None = Field(None, description=(
        "The point [x, y, z] the base moments Mx, My, Mz are taken about (default: the centre of the base)."))


Contact3D, RigidBox = rigid_tables_3d(Table, Contact, NodeRef, Name, Direction3, Positive, NonNegative, NodeId=NodeId)


class ModelFile3D(ModelFile):
    """A unilateral model file of a 3-D frame ([frame] dimensions = 3)."""

    DIMENSIONS: ClassVar[int] = 3
    nodes: list[Node3D] = []
    supports: list[Support3D] = []
    rigid_diaphragms: list[RigidDiaphragm] = []
    equal_dofs: list[EqualDof3D] = []
    elements: list[Element3D] = []
    unilateral: list[Unilateral3D] = []
    masses: list[Mass3D] = []
    contacts: list[Contact3D] = []
    rigid_blocks: list[RigidBox] = []
    foundation: Foundation3D | None = None
    foundations: list[Foundation3D] = Field([], description=(
        "Several footings: on a half-space they share it (give each the same soil), elsewhere uncoupled."))
    loads: Loads3D = Loads3D()
    output: Output3D = Output3D()
