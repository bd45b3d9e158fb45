"""``[output]``'s keys of what a run writes (:mod:`unilateral.io.recorders`), and their cross checks.

:class:`OutputRecorders` is the base of :class:`unilateral.modelfile.schema.Output`; the nodes and
elements it names are checked against the document by :func:`recorder_problems` (called by
:mod:`unilateral.modelfile.checks`).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, WithJsonSchema, field_validator
from pydantic_core import PydanticCustomError

from ..io.recorders import HISTORIES, HISTORY_VARIABLES, PRECISIONS, variable_problem


def _node_id(value):
    if isinstance(value, bool) or not isinstance(value, int | str) or value == "":
        raise PydanticCustomError("node_id", "expected an integer or a non-empty string")
    return value


NodeId = Annotated[int | str, PlainValidator(_node_id), WithJsonSchema({"type": ["integer", "string"], "minLength": 1})]


class OutputRecorders(BaseModel):
    """What is written to ``results.nc`` and the CSV tables (the summary and figures are of every result)."""

    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)

    histories: Literal[HISTORIES] = Field("auto", description=(
        "auto: every history when they take at most 20 MB, else the key ones; key: base forces, drifts, energies, "
        "the ground motion and the figure node's displacement; full: every DOF, constraint, element and node."))
    variables: list[str] = Field([], description=(
        f"Histories to write beside the key ones ({', '.join(HISTORY_VARIABLES)}, energy_...)."))
    nodes: list[NodeId] | None = Field(None, description="Frames: the nodes whose histories are written (only them).")
    elements: list[Annotated[str, Field(min_length=1)]] | None = Field(None, description=(
        "Frames: the elements (beams, hinges, contacts, ...) whose histories are written (only them)."))
    every: Annotated[int, Field(ge=1)] | None = Field(None, description=(
        "Write every k-th step (1: every step; default 1, or what keeps a very long run's histories under 40 MB)."))
    precision: Literal[PRECISIONS] = Field("float64", description=(
        "float64, or float32: histories in results.nc as float32, CSV numbers with 9 significant digits."))
    csv: bool = Field(True, description="Write the CSV tables (results.nc and summary.json always).")

    @field_validator("variables")
    @classmethod
    def _known(cls, value):
        for name in value:
            problem = variable_problem(name)
            if problem:
                raise PydanticCustomError("variable", problem)
        return value


def recorder_problems(document) -> list[str]:
    """``[output] nodes`` and ``elements``: names of the document's nodes and elements."""
    output = document.output
    problems = []
    if document.matrices is not None:
        return [f"output.{key}: needs a frame (a matrix-level model has no nodes or elements)"
                for key in ("nodes", "elements") if getattr(output, key) is not None]
    ids = [node.id for node in document.nodes]
    for k, node in enumerate(output.nodes or ()):
        if node not in ids:
            problems.append(f"output.nodes[{k}] = {node!r}: no such node (nodes: "
                            f"{', '.join(map(str, ids[:20]))}{' ...' if len(ids) > 20 else ''})")
    names = [e.name for e in [*document.elements, *document.unilateral] if getattr(e, "name", None)]
    names += [f.name for _, f in document.footings]
    for k, name in enumerate(output.elements or ()):
        if name not in names:
            problems.append(f"output.elements[{k}] = {name!r}: no such element (elements: "
                            f"{', '.join(names[:20])}{' ...' if len(names) > 20 else ''})")
    return problems
