"""A small TOML writer for the model files :mod:`.convert` writes.

The subset written: top-level keys whose values are scalars, inline tables or arrays (an array of
tables is written inline, one table per line), then ``[tables]`` of such keys. Strings are TOML
basic strings (JSON's escapes are TOML's), floats are written with Python's shortest repr that
reads back to the same double, integers and booleans as TOML writes them. Non-finite floats are
refused: a model file has none. ``tomli-w`` is not a dependency of the package; the subset here
is checked by reading every file back with :mod:`tomllib` (``tests/test_opensees_convert.py``).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np

__all__ = ["dumps", "value"]

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(name) -> str:
    name = str(name)
    return name if _BARE_KEY.match(name) else json.dumps(name)


def value(x) -> str:
    """A Python value (str, bool, int, float, list, tuple, dict; numpy scalars) as a TOML value.

    Raises
    ------
    ValueError
        For a non-finite float or a type TOML has no value for (None among them).
    """
    if isinstance(x, np.generic):
        x = x.item()
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        if not math.isfinite(x):
            raise ValueError(f"a model file holds finite numbers only, got {x!r}")
        text = repr(x)
        return text if any(c in text for c in ".e") else text + ".0"
    if isinstance(x, str):
        return json.dumps(x)
    if isinstance(x, (list, tuple, np.ndarray)):
        return "[" + ", ".join(value(item) for item in x) + "]"
    if isinstance(x, dict):
        return "{ " + ", ".join(f"{_key(k)} = {value(v)}" for k, v in x.items()) + " }" if x else "{}"
    raise ValueError(f"TOML has no value for {x!r} ({type(x).__name__})")


def _entry(key, x) -> str:
    if isinstance(x, list) and x and all(isinstance(item, dict) for item in x):
        lines = ",\n".join("    " + value(item) for item in x)
        return f"{_key(key)} = [\n{lines},\n]"
    return f"{_key(key)} = {value(x)}"


def dumps(document: dict, header: str = "") -> str:
    """The TOML text of ``document``: its non-table keys first, then one ``[table]`` per dict value.

    Parameters
    ----------
    document : dict
        ``{key: value}``; a dict value becomes a ``[key]`` table (its own dict values inline tables),
        any other value a key of the top level.
    header : str
        Comment lines put first (each prefixed with ``# ``).
    """
    lines = [f"# {line}".rstrip() for line in header.splitlines()]
    tables = {k: v for k, v in document.items() if isinstance(v, dict) and k != "units"}
    for key, x in document.items():
        if key not in tables:
            lines.append(_entry(key, x))
    for key, table in tables.items():
        lines += ["", f"[{_key(key)}]"] + [_entry(k, v) for k, v in table.items()]
    return "\n".join(lines) + "\n"
