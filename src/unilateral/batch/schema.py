"""The study-file format as pydantic models: one class per TOML table, validated strictly.

A study file names one or more model files, the ground-motion records, how they are scaled, the
parameters swept, the analysis settings, the peak quantities collected, the limit states of the
fragility curves and the figures. The format is documented in ``docs/study-file.md``; its JSON
schema, from :func:`study_file_schema`, is ``docs/study-file.schema.json``.

Like the model files, every table forbids unknown keys, takes TOML types as they are and rejects
``inf`` and ``nan``; cross references (files that exist, key paths that resolve in the model
files, quantity names) are checked after validation, in :mod:`unilateral.batch.study`.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, model_validator
from pydantic_core import PydanticCustomError

from ..modelfile import schema as _model_schema
from .footing_quantity import FOOTING_MEASURES

_MODEL_ANALYSIS = _model_schema.Analysis.model_fields
METHOD = _MODEL_ANALYSIS["method"].annotation
RULE = _MODEL_ANALYSIS["rule"].annotation
LCP = _MODEL_ANALYSIS["lcp"].annotation
INITIAL = _MODEL_ANALYSIS["initial"].annotation

MEASURES = ("factor", "pga", "sa")
"""Intensity measures of ``[scaling]``: plain factors, peak ground acceleration, Sa(T, zeta)."""

QUANTITY_TYPES = ("uplift", "contact_force", "displacement", "drift", "residual", "base_shear", "energy_error",
                  "footing")
"""Peak quantities a study can collect (``[[quantities]] type``)."""

ENVELOPES = ("saragoni-hart", "amin-ang")


class Table(BaseModel):
    """Base of the TOML tables: strict types, no unknown keys, finite numbers."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


Positive = Annotated[float, Field(gt=0)]
NonNegative = Annotated[float, Field(ge=0)]
Name = Annotated[str, Field(min_length=1)]
FileName = Annotated[str, Field(min_length=1)]
NodeId = Annotated[Union[int, str], Field()]
NodePair = Annotated[list[NodeId], Field(min_length=2, max_length=2, title="node pair")]


# ---------------------------------------------------------------------- models
class ModelEntry(Table):
    """[[models]]: a model file, with values changed by key path."""

    EXAMPLE: ClassVar[str] = '[[models]] file = "tower.toml"'
    file: FileName = Field(description="Model file (TOML), relative to the study file.")
    name: Name | None = Field(None, description="Short name in the table (default: the file stem).")
    set: dict[str, Any] = Field({}, description='Values changed in the model file, by key path, e.g. '
                                               '{ "unilateral.soil3.c" = 400.0, "loads.nodal" = [] }.')


# ---------------------------------------------------------------------- records
class Synthetic(Table):
    """Synthetic records (Kanai-Tajimi filtered noise), one per seed."""

    seeds: list[int] = Field(min_length=1, description="One record per seed.")
    duration: Positive = 10.0
    dt: Positive = 0.01
    pga: Positive = Field(1.0, description="Peak ground acceleration of the unscaled record, m/s^2.")
    f_g: Positive = 2.5
    zeta_g: Positive = 0.6
    envelope: Literal[ENVELOPES] = Field("saragoni-hart", title="envelope")


DIRECTIONS_3D = ("ux", "uy", "uz")
"""Ground motion directions of ``[records] directions`` (a 2-D frame: ux and uy only)."""


class Records(Table):
    """[records]: the ground-motion records; each replaces the ground motions of the model file."""

    folder: FileName | None = Field(None, description="Every record in this folder (.AT2, and .txt, .dat, .csv "
                                                      "with units), sorted by name.")
    files: list[FileName] = Field([], description="Record files.")
    synthetic: Synthetic | None = None
    pairs: list[list[FileName]] = Field([], description=(
        "Frames: records of two or three components, one analysis under all of them at once: "
        '[["RSN1_X.AT2", "RSN1_Y.AT2"], ...], each 2 or 3 files (x, y[, vertical]) relative to the study file; '
        "instead of folder, files and synthetic."))
    directions: list[Literal[DIRECTIONS_3D]] | None = Field(None, title="ground motion direction", description=(
        'pairs: the direction of each component (default ["ux", "uy"], or ["ux", "uy", "uz"] for 3 files; '
        "a 2-D frame: ux and uy, horizontal and vertical)."))
    angle: Union[float, Annotated[list[float], Field(min_length=1)], None] = Field(None, description=(
        "pairs, 3-D frames: the horizontal components rotated in plan by this angle [deg] (component 1 along "
        "(cos a, sin a), component 2 along (-sin a, cos a)); a list of angles: each pair at every angle "
        "(default 0)."))
    direction: Literal["ux", "uy"] | None = Field(None, title="ground motion direction", description=(
        "Frames: the direction of the ground motion (default: that of the model file's first ground motion)."))
    influence: FileName | None = Field(None, description="Matrix-level models: Matrix Market file of r (n x 1), "
                                                         "relative to the study file (default: the model's).")
    units: str | None = Field(None, description='Units of plain-text records, e.g. "g" or "cm/s2".')
    dt: Positive | None = Field(None, description="Time step of one-column text records [s].")
    skip_header: int | None = Field(None, ge=0, description=(
        "Header lines to skip at the top of plain-text records (default 0)."))

    @model_validator(mode="after")
    def _some(self):
        if self.folder is None and not self.files and self.synthetic is None and not self.pairs:
            raise PydanticCustomError("records", "give folder, files, synthetic or pairs")
        return self


# ---------------------------------------------------------------------- scaling
class Scaling(Table):
    """[scaling]: the intensity levels: factors on the records, or target intensities."""

    measure: Literal[MEASURES] = Field("factor", title="intensity measure", description=(
        "factor: values are factors on the records; pga: target peak ground accelerations; "
        "sa: target 5%-damped pseudo-spectral accelerations Sa(period, damping)."))
    values: list[Positive] = Field(min_length=1, description="Factors, or target intensities in units.")
    units: str = Field("g", description="Units of target accelerations (g, m/s2, cm/s2, ...).")
    period: Union[Positive, Literal["T1"]] = Field("T1", description=(
        'Period of Sa [s], or "T1": the first period of each model with every constraint bilateral.'))
    damping: Annotated[float, Field(gt=0, lt=1)] = Field(0.05, description="Damping ratio of Sa.")


# ---------------------------------------------------------------------- parameters
class Parameter(Table):
    """[[parameters]]: a model-file value swept over a list, by key path."""

    EXAMPLE: ClassVar[str] = '[[parameters]] key = "unilateral.soil3.k", values = [1e5, 2e5]'
    key: Name = Field(description='Key path in the model files, e.g. "unilateral.soil3.k" or "masses[0].m".')
    values: list[Any] = Field(min_length=1)
    group: Name | None = Field(None, description=(
        "Parameters of the same group are varied together (zipped, equal lengths); groups are crossed."))


# ---------------------------------------------------------------------- analysis
class StudyAnalysis(Table):
    """[analysis]: settings of every analysis (default: each model file's [analysis])."""

    dt: Positive | None = None
    t_end: Union[Positive, Literal["record"], None] = Field(None, description=(
        'End time [time of the model], or "record": the duration of each record plus t_after.'))
    t_after: NonNegative = Field(0.0, description='With t_end = "record": time after the record ends.')
    method: METHOD | None = Field(None, title="method")
    rule: RULE | None = Field(None, title="rule")
    lcp: LCP | None = Field(None, title="LCP solver")
    lcp_options: dict[str, Union[int, float, bool, str]] = Field({}, description='e.g. { max_iter = 50 }.')
    initial: INITIAL | None = Field(None, title="initial state")
    timeout: Positive | None = Field(None, description="Seconds per analysis before it is stopped and "
                                                       "recorded as timed out.")


# ---------------------------------------------------------------------- quantities
class Quantity(Table):
    """[[quantities]]: a peak quantity collected from every analysis."""

    EXAMPLE: ClassVar[str] = '[[quantities]] name = "uplift", type = "uplift"'
    name: Annotated[str, Field(min_length=1, pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")] = Field(
        description="Column name (letters, digits, _).")
    type: Literal[QUANTITY_TYPES] = Field(title="quantity type")
    elements: list[Name] | None = Field(None, description="uplift, contact_force: unilateral elements "
                                                          "(default: every contact unknown; plastic "
                                                          "multipliers, slips and shears left out); footing: "
                                                          "the footings (default: all).")
    over: Literal["max", "each"] = Field("max", title="combination", description=(
        "uplift, contact_force, footing: max over the elements (one column), or each (one column per element)."))
    measure: Literal[tuple(FOOTING_MEASURES)] | None = Field(None, description=(
        "footing: what of each footing (peak uplift, peak or residual rotation, settlement or slip, peak "
        "bearing pressure, least contact_ratio)."))
    node: NodeId | None = Field(None, description="displacement, residual: the node.")
    dof: str | None = Field(None, description=('"ux", "uy", "rz" (2-D frames), "ux" ... "rz" (3-D frames) or a DOF '
                                               'name (matrix-level models).'))
    pairs: Annotated[list[NodePair], Field(min_length=1)] | None = Field(None, description=(
        "drift: [upper, lower] node pairs, one storey each (at least one); the peak over the pairs."))
    ratio: bool = Field(True, description="drift: divided by the storey height (difference of y).")

    USES: ClassVar[dict] = {"uplift": ("elements", "over"), "contact_force": ("elements", "over"),
                            "displacement": ("node", "dof"), "residual": ("node", "dof"),
                            "drift": ("pairs", "dof", "ratio"), "base_shear": (), "energy_error": (),
                            "footing": ("measure", "elements", "over")}
    NEEDS: ClassVar[dict] = {"displacement": ("dof",), "residual": ("dof",), "drift": ("pairs",),
                             "footing": ("measure",)}


class LimitState(Table):
    """[[limit_states]]: exceeded when a quantity exceeds a threshold; a fragility curve each."""

    name: Name
    quantity: Name = Field(description="A column of the table: a quantity name (or name.element).")
    threshold: float


class Collapse(Table):
    """[collapse]: when an analysis counts as a collapse of the structure (apart from a failed one)."""

    quantity: Name | None = Field(None, description=(
        "A quantity column (e.g. a drift ratio, or a displacement with dof = \"rz\"): the structure has "
        "collapsed when it exceeds limit."))
    limit: Positive | None = Field(None, description="The collapse limit of quantity (its units).")
    mechanism: bool = Field(True, description=(
        "Also a collapse: a mechanism under gravity at the end of the run (the static tangent with P-Delta, "
        "the flowing hinges released, not positive definite)."))


class Figures(Table):
    """[figures]: what to draw."""

    ida: Name | None = Field(None, description="Quantity of the IDA curves (default: the first).")
    formats: list[Literal["png", "pdf", "svg"]] = Field(["png"], title="figure format")
    dpi: Annotated[int, Field(gt=0)] = 150


class StudyFile(Table):
    """A study: models, records, scaling, parameter sweeps, settings, quantities, limit states."""

    title: str = ""
    models: list[ModelEntry] = Field(min_length=1)
    records: Records | None = None
    scaling: Scaling | None = None
    parameters: list[Parameter] = []
    analysis: StudyAnalysis = StudyAnalysis()
    quantities: list[Quantity] = Field(min_length=1)
    limit_states: list[LimitState] = []
    collapse: Collapse | None = None
    figures: Figures = Figures()


def study_file_schema() -> dict:
    """JSON schema (draft 2020-12) of the study file, a TOML document read as JSON."""
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", **StudyFile.model_json_schema()}


def write_study_schema(path) -> Path:
    """Write :func:`study_file_schema` as indented JSON to ``path``; return the path."""
    path = Path(path)
    path.write_text(json.dumps(study_file_schema(), indent=2) + "\n", encoding="utf-8")
    return path
