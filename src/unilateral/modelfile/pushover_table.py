"""The ``[pushover]`` table of a model file (``[analysis] type = "pushover"``) and its cross checks.

Pydantic only (the command line checks a file before numpy loads). The analysis itself is
:func:`unilateral.pushover.pushover`, run from a model file by
:func:`unilateral.pushover.files.run_file`.

.. code-block:: toml

    [analysis]
    type = "pushover"

    [pushover]
    pattern = "triangular"      # or "uniform", "mode", or [{ node = 2, ux = 1.0 }, ...]
    node = 2                    # the control node
    dof = "ux"
    target = 0.10               # or cycles = [0.05, -0.05, 0.10, -0.10]
"""

from __future__ import annotations

import json
from typing import Annotated, ClassVar, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator
from pydantic_core import PydanticCustomError

#: The named load patterns (those of :data:`unilateral.pushover.PATTERNS`).
PATTERN_NAMES = ("uniform", "triangular", "mode")


class _Table(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class PatternForce(_Table):
    """One nodal force of a pushover pattern given as loads (its magnitude per unit load factor)."""

    node: int | str = Field(description="The node.")
    ux: float = Field(0.0, description="Force along x [force].")
    uy: float = Field(0.0, description="Force along y [force].")
    rz: float = Field(0.0, description="Moment about z [force length] (2-D: counter-clockwise).")
    uz: float = Field(0.0, description="3-D frames: force along z [force].")
    rx: float = Field(0.0, description="3-D frames: moment about x [force length].")
    ry: float = Field(0.0, description="3-D frames: moment about y [force length].")

    @property
    def components(self) -> dict:
        """The nonzero components ``{dof: value}``."""
        return {dof: getattr(self, dof) for dof in ("ux", "uy", "uz", "rx", "ry", "rz") if getattr(self, dof)}


class PushoverTable(_Table):
    """[pushover]: a static pushover, event by event (``[analysis] type = "pushover"``)."""

    EXAMPLE: ClassVar[str] = '[pushover] pattern = "triangular", node = 2, dof = "ux", target = 0.1'
    pattern: Literal[PATTERN_NAMES] | Annotated[list[PatternForce], Field(min_length=1)] = Field(description=(
        'The lateral pattern: "uniform" (the masses), "triangular" (masses times height), "mode" (the first '
        "mode times the masses), each scaled so that the load factor is the base shear per unit mass; or "
        "nodal forces [{ node, ux, uy, rz }] per unit load factor."))
    node: int | str = Field(description="The control node.")
    dof: Literal["ux", "uy", "rz", "uz", "rx", "ry"] = Field("ux", description=(
        "The control DOF of node (3-D frames also uz, rx, ry), and the direction of a named pattern and of the "
        "base shear."))
    target: float | None = Field(None, description=(
        'The control DOF\'s displacement to reach [length] (control = "load": the load factor). Or give cycles.'))
    cycles: Annotated[list[float], Field(min_length=1)] | None = Field(None, description=(
        "A cyclic pushover: the control DOF's displacements (or load factors) to reach in turn, reversing at "
        "each."))
    control: Literal["displacement", "load"] = Field("displacement", description=(
        "displacement: the load factor is free (plateaus and softening are followed); load: the load factor "
        "is the parameter and the path stops at a mechanism."))
    gravity: bool = Field(True, description="Start from the static state under [loads.gravity].")
    p_delta: Literal["none", "consistent", "string"] | None = Field(None, description=(
        'The geometric stiffness of the gravity\'s axial forces: "consistent" (the beams\' cubic, as [analysis] '
        'p_delta), "string" (N/L on the chords) or "none"; default: as [analysis] p_delta.'))
    max_events: Annotated[int, Field(ge=1, le=100000)] = Field(200, description=(
        "The most events followed before the path stops."))

    @model_validator(mode="after")
    def _one_target(self):
        if (self.target is None) == (self.cycles is None):
            raise PydanticCustomError("pushover_target", "give either target (one) or cycles (a history), not "
                                      + ("both" if self.target is not None else "neither"))
        return self

    @property
    def targets(self) -> list[float]:
        """The targets in turn: ``[target]`` or ``cycles``."""
        return [self.target] if self.cycles is None else list(self.cycles)


def needs_time_step(analysis):
    """The model validator of ``[analysis]``: ``dt`` and ``t_end`` for a transient analysis."""
    if analysis.type == "transient":
        missing = [key for key in ("dt", "t_end") if getattr(analysis, key) is None]
        if missing:
            raise PydanticCustomError("time_step", "missing key {keys}: a transient analysis needs dt and t_end "
                                      '(or set type = "pushover" with a [pushover] table)',
                                      {"keys": " and ".join(missing)})
    return analysis


def pushover_problems(document) -> list[str]:
    """The cross checks of ``[analysis] type`` and ``[pushover]`` (nodes that exist, a frame)."""
    table, kind = getattr(document, "pushover", None), document.analysis.type
    if kind != "pushover":
        return [] if table is None else ['pushover: a [pushover] table needs [analysis] type = "pushover" (or '
                                         "remove it)"]
    if table is None:
        return [f"pushover: missing section (declare e.g. {PushoverTable.EXAMPLE})"]
    if document.matrices is not None:
        return ['analysis.type = "pushover": needs a frame (nodes, elements); a matrix-level model is pushed '
                "from Python (unilateral.pushover.pushover on its Model)"]
    ids = [node.id for node in document.nodes]
    known, problems = set(ids), []
    listed = ", ".join(json.dumps(n) for n in ids[:12]) + (" ..." if len(ids) > 12 else "")
    if table.node not in known:
        problems.append(f"pushover.node = {json.dumps(table.node)}: no such node (nodes: {listed})")
    if not isinstance(table.pattern, str):
        problems += [f"pushover.pattern[{k}].node = {json.dumps(f.node)}: no such node (nodes: {listed})"
                     for k, f in enumerate(table.pattern) if f.node not in known]
        problems += [f"pushover.pattern[{k}]: a zero force; give ux, uy or rz" for k, f in enumerate(table.pattern)
                     if not f.components]
    plane = getattr(document, "DIMENSIONS", 2) == 2
    if plane:
        problems += [f"pushover.pattern[{k}].{dof} = {value!r}: a plane frame's nodes have ux, uy, rz only"
                     for k, f in enumerate(table.pattern if not isinstance(table.pattern, str) else ())
                     for dof, value in f.components.items() if dof not in ("ux", "uy", "rz")]
        if table.dof not in ("ux", "uy", "rz"):
            problems.append(f'pushover.dof = "{table.dof}": a plane frame\'s DOFs are ux, uy, rz')
    if table.gravity is False and table.p_delta in ("consistent", "string"):
        problems.append(f'pushover.p_delta = "{table.p_delta}": needs the gravity\'s axial forces (gravity = true '
                        "and [loads.gravity])")
    return problems
