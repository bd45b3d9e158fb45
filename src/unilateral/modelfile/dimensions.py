"""The two root tables of a model file, :class:`~unilateral.modelfile.schema.ModelFile` (a 2-D frame
or matrices) and :class:`~unilateral.modelfile.schema3d.ModelFile3D`: choosing one for a parsed file
(:func:`model_class`), naming a key of the other dimension (:func:`dimension_hint`), and the JSON
schema of both (:func:`model_file_schema`, :func:`write_schema`).
"""

from __future__ import annotations

import json
from pathlib import Path

from .schema import (Beam, Dashpot, DistributedLoad, Figure, Foundation, Gap, Gravity, Hinge2D, Loads, Mass, ModelFile,
                     NodalLoad, Node, Output, Soil, Spring, Support)
from .schema3d import (Beam3D, Dashpot3D, DistributedLoad3D, Figure3D, Foundation3D, Gap3D, Gravity3D, GroundMotion3D,
                       Hinge3D, Loads3D, Mass3D, ModelFile3D, NodalLoad3D, Node3D, Output3D, RigidDiaphragm, Soil3D,
                       Spring3D, Support3D)


#: The table of a 2-D frame and that of a 3-D frame in the same place (both ways).
COUNTERPARTS = {Node: Node3D, Support: Support3D, Mass: Mass3D, Beam: Beam3D, Spring: Spring3D, Dashpot: Dashpot3D,
                Soil: Soil3D, Gap: Gap3D, Hinge2D: Hinge3D, Foundation: Foundation3D, Gravity: Gravity3D,
                NodalLoad: NodalLoad3D, DistributedLoad: DistributedLoad3D, Loads: Loads3D, Figure: Figure3D,
                Output: Output3D, ModelFile: ModelFile3D}
COUNTERPARTS |= {three: two for two, three in COUNTERPARTS.items()}
THREE_D_TABLES = frozenset({
    Node3D, Support3D, Mass3D, Beam3D, Spring3D, Dashpot3D, Soil3D, Gap3D, Hinge3D, Foundation3D, Gravity3D,
    NodalLoad3D, DistributedLoad3D, Loads3D, Figure3D, Output3D, ModelFile3D, RigidDiaphragm, GroundMotion3D})


def model_class(data) -> type[ModelFile]:
    """The root table of a parsed model file: :class:`ModelFile3D` for ``[frame] dimensions = 3``, else
    :class:`ModelFile` (which reports a bad ``[frame]``)."""
    frame = data.get("frame") if isinstance(data, dict) else None
    dimensions = frame.get("dimensions") if isinstance(frame, dict) else None
    three = isinstance(dimensions, int | float) and not isinstance(dimensions, bool) and dimensions == 3
    return ModelFile3D if three else ModelFile


def dimension_hint(table, key: str) -> str | None:
    """What is wrong with the unknown ``key`` of ``table`` if it is a key of the same table in the other
    dimension (a 2-D key in a 3-D frame, or the reverse), else None."""
    other = COUNTERPARTS.get(table)
    if other is None or key not in other.model_fields or key in table.model_fields:
        return None
    valid = ", ".join(table.model_fields)
    if table in THREE_D_TABLES:
        return f"a key of 2-D frames only (this file declares [frame] dimensions = 3; valid keys here: {valid})"
    return f"a key of 3-D frames only (declare [frame] dimensions = 3; valid keys of a 2-D frame here: {valid})"


def model_file_schema() -> dict:
    """JSON schema (draft 2020-12) of the model file, a TOML document read as JSON: a 2-D frame or
    matrices (:class:`ModelFile`), or a 3-D frame (:class:`ModelFile3D`, ``[frame] dimensions = 3``)."""
    from pydantic.json_schema import models_json_schema

    refs, defs = models_json_schema([(ModelFile, "validation"), (ModelFile3D, "validation")])
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "unilateral model file",
            "anyOf": [refs[(ModelFile, "validation")], refs[(ModelFile3D, "validation")]], **defs}


def write_schema(path) -> Path:
    """Write :func:`model_file_schema` as indented JSON to ``path``; return the path."""
    path = Path(path)
    path.write_text(json.dumps(model_file_schema(), indent=2) + "\n", encoding="utf-8")
    return path
