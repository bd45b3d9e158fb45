"""The validators of the model file's value types (:mod:`unilateral.modelfile.schema`): a node id, a
DOF reference, a 2-D vector, a pair of numbers, a direction and the gravity's ``g``; each raises a
``PydanticCustomError`` with the expected form.
"""

from __future__ import annotations

from pydantic_core import PydanticCustomError


def _node_id(value):
    if isinstance(value, bool) or not isinstance(value, int | str) or value == "":
        raise PydanticCustomError("node_id", "expected an integer or a non-empty string")
    return value


def _dof_ref(value):
    if isinstance(value, bool) or not isinstance(value, int | str) or value == "" or (
            isinstance(value, int) and value < 0):
        raise PydanticCustomError("dof_ref", "expected a DOF name or a 0-based index >= 0")
    return value


def _vector(value):
    ok = (isinstance(value, list) and len(value) == 2
          and all(isinstance(x, int | float) and not isinstance(x, bool) for x in value))
    if not ok or not all(abs(x) < float("inf") for x in value) or not any(value):
        raise PydanticCustomError("vector", "expected a nonzero vector [dx, dy] of two numbers")
    return (float(value[0]), float(value[1]))


def _pair(value):
    if not (isinstance(value, list) and len(value) == 2 and all(isinstance(x, int | float) and not isinstance(x, bool)
                                                                and abs(x) < float("inf") for x in value)):
        raise PydanticCustomError("pair", "expected a pair [x, y] of two finite numbers")
    return (float(value[0]), float(value[1]))


def _direction(value):
    if isinstance(value, str):
        if value not in ("ux", "uy", "rz"):
            raise PydanticCustomError("direction", 'expected "ux", "uy", "rz" or a vector [dx, dy]')
        return value
    return _vector(value)


def _gravity(value):
    if value == "standard":
        return value
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0 < value < float("inf"):
        raise PydanticCustomError("gravity", 'expected a number > 0 or "standard"')
    return float(value)
