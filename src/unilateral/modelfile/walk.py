"""The walk of a validated model file: :func:`iter_fields` (re-exported by
:mod:`unilateral.modelfile.schema`)."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from pydantic import BaseModel
from pydantic.fields import FieldInfo


def iter_fields(table: BaseModel, parts: tuple = ()) -> Iterator[tuple[tuple, Any, FieldInfo]]:
    """Every field of a validated document, depth first.

    Yields
    ------
    parts : tuple of str and int
        The key path, e.g. ``("elements", 3, "node_j")``.
    value : the field's value
    info : FieldInfo
        Its metadata holds :data:`NODE_REF` or :data:`FILE_REF` for references.
    """
    for name, info in type(table).model_fields.items():
        value = getattr(table, name)
        here = (*parts, name)
        yield here, value, info
        items = enumerate(value) if isinstance(value, list) else [(None, value)]
        for index, item in items:
            if isinstance(item, BaseModel):
                yield from iter_fields(item, here if index is None else (*here, index))
