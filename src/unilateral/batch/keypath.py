"""Key paths into a parsed model file: ``"unilateral.soil3.k"``, ``"masses[0].m"``, ``"analysis.dt"``.

A key path is a dotted list of segments. On a table a segment is a key; on an array of tables
``[k]`` is the entry with 0-based index ``k`` and a bare segment is the entry whose ``name``,
``id`` or ``node`` equals it (``unilateral.soil3``, ``nodes.3``, ``masses.1``). ``elements.<name>``
also finds the unilateral elements (names are unique over both sections). Setting a key that a
table does not hold yet adds it (e.g. a default value); missing tables on the way are created, and
the model file's validation then reports keys that do not exist.
"""

from __future__ import annotations

import re

from ..modelfile.errors import compact_ids, did_you_mean, toml_value

_PIECE = re.compile(r"([^\[\]]+)((?:\[\d+\])*)")
_SELECTORS = ("name", "id", "node")


class KeyPathError(ValueError):
    """A key path that does not resolve in a model file."""


def parse_key_path(text: str) -> list:
    """``"masses[0].m"`` -> ``["masses", 0, "m"]``."""
    parts = []
    for piece in str(text).split("."):
        match = _PIECE.fullmatch(piece)
        if match is None:
            raise KeyPathError(f"cannot read the key path {toml_value(text)} "
                               '(write e.g. "unilateral.soil3.k", "masses[0].m" or "analysis.dt")')
        parts.append(match[1])
        parts += [int(i) for i in re.findall(r"\[(\d+)\]", match[2])]
    return parts


def _show(parts) -> str:
    out = ""
    for part in parts:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _select(items: list, segment: str, where: list) -> int:
    """Index of the entry of an array of tables that ``segment`` names."""
    for field in _SELECTORS:
        values = [item.get(field) if isinstance(item, dict) else None for item in items]
        if not any(v is not None for v in values):
            continue
        hits = [k for k, v in enumerate(values) if v is not None and str(v) == segment]
        if len(hits) > 1:
            raise KeyPathError(f"{_show(where)}: {len(hits)} entries have {field} = {segment} "
                               f"(entries {', '.join(str(h) for h in hits)}); select one by index, "
                               f"e.g. {_show(where)}[{hits[0]}]")
        if hits:
            return hits[0]
    for field in _SELECTORS:
        values = [item.get(field) for item in items if isinstance(item, dict) and item.get(field) is not None]
        if values:
            what = "ids" if field == "id" else f"{field}s"
            return _fail(f"{_show(where)}: no entry with {field} {toml_value(segment)} "
                         f"({what}: {compact_ids(values)})" + did_you_mean(segment, [str(v) for v in values]))
    return _fail(f"{_show(where)}: select an entry by index, e.g. {_show(where)}[0] "
                 f"(the array has {len(items)} entries)")


def _fail(message):
    raise KeyPathError(message)


def set_key_path(data: dict, text: str, value) -> None:
    """Set the value at key path ``text`` of the parsed TOML document ``data`` (in place)."""
    parts = parse_key_path(text)
    node = data
    where: list = []
    for i, part in enumerate(parts):
        last = i == len(parts) - 1
        if i == 1 and parts[0] in ("elements", "unilateral") and isinstance(part, str):
            node, where = _element_section(data, parts[0], part)
        if isinstance(node, dict):
            if isinstance(part, int):
                raise KeyPathError(f"{_show(where) or 'the file'} is a table, not an array ([{part}] selects an "
                                   "entry of an array)")
            if last:
                node[part] = value
                return
            node = node.setdefault(part, {})
            where.append(part)
        elif isinstance(node, list):
            index = part if isinstance(part, int) else _select(node, part, where)
            if index >= len(node):
                raise KeyPathError(f"{_show(where)}[{index}]: no such entry (the array has {len(node)} entries)")
            where.append(index)
            if last:
                node[index] = value
                return
            node = node[index]
        else:
            raise KeyPathError(f"{_show(where)} is a value ({toml_value(node)}), not a table")


def _element_section(data: dict, section: str, name: str):
    """The array (elements or unilateral) that holds the element ``name``."""
    for candidate in (section, "unilateral" if section == "elements" else "elements"):
        items = data.get(candidate)
        if isinstance(items, list) and any(isinstance(e, dict) and e.get("name") == name for e in items):
            return items, [candidate]
    names = [e.get("name") for s in ("elements", "unilateral") for e in data.get(s, []) or []
             if isinstance(e, dict) and e.get("name") is not None]
    raise KeyPathError(f"{section}: no element named {toml_value(name)} (names: {', '.join(names) or 'none'})"
                       + did_you_mean(name, names))


def get_key_path(data: dict, text: str, default=None):
    """The value at key path ``text``, or ``default`` if a key on the way is missing."""
    parts = parse_key_path(text)
    node = data
    for i, part in enumerate(parts):
        if i == 1 and parts[0] in ("elements", "unilateral") and isinstance(part, str):
            try:
                node, _ = _element_section(data, parts[0], part)
            except KeyPathError:
                return default
        if isinstance(node, dict) and isinstance(part, str) and part in node:
            node = node[part]
        elif isinstance(node, list):
            try:
                index = part if isinstance(part, int) else _select(node, part, [])
            except KeyPathError:
                return default
            if index >= len(node):
                return default
            node = node[index]
        else:
            return default
    return node


# ---------------------------------------------------------------------- validation errors
_SCALAR_TAGS = {"float": (int, float), "int": (int,), "str": (str,), "bool": (bool,)}


def _branch_tag(key) -> bool:
    """Whether ``key`` of a pydantic error location names a member of a plain union (``float``,
    ``list[float]``, ``constrained-float``, ``literal['T1']``), not a key of the file."""
    return isinstance(key, str) and (key in _SCALAR_TAGS or "[" in key or key.startswith("constrained-")
                                     or key.startswith(("function-", "lax-", "json-or-python")))


def _fits(tag: str, value) -> bool:
    """Whether the union member ``tag`` is the one meant for ``value`` (by the value's TOML type)."""
    if tag.startswith("literal[") or tag == "str" or tag.startswith("constrained-str"):
        return isinstance(value, str)
    if tag.startswith(("list[", "tuple[", "set[")):
        return isinstance(value, list)
    if tag.startswith("dict["):
        return isinstance(value, dict)
    number = isinstance(value, int | float) and not isinstance(value, bool)
    if tag in ("float", "int") or tag.startswith(("constrained-float", "constrained-int")):
        return number
    return True


class PlainErrors:
    """The errors of a pydantic ``ValidationError`` located by the file's keys only: the members of
    a plain union are dropped from the locations (``records.angle.list[float][0]`` ->
    ``records.angle[0]``), and of a union's members only the errors of the one meant for the
    value's type are kept (a list, a number, a string), the others when none is.

    Parameters
    ----------
    exc : pydantic.ValidationError
    data : dict
        The document validated.
    """

    def __init__(self, exc, data):
        self.exc, self.data = exc, data

    def errors(self) -> list[dict]:
        groups: dict = {}
        for error in self.exc.errors():
            loc = tuple(error["loc"])
            at = next((k for k, key in enumerate(loc) if _branch_tag(key)), None)
            if at is None:
                groups.setdefault((loc, None), []).append((True, error))
                continue
            value = _value_at(self.data, loc[:at])
            plain = tuple(key for key in loc if not _branch_tag(key))
            groups.setdefault((loc[:at], "union"), []).append((_fits(loc[at], value), {**error, "loc": plain}))
        out, seen = [], set()
        for members in groups.values():
            members = [(fits, _plain_message(error)) for fits, error in members]
            kept = [error for fits, error in members if fits] or [error for _, error in members]
            for error in kept:
                if (error["loc"], error["msg"]) not in seen:
                    seen.add((error["loc"], error["msg"]))
                    out.append(error)
        return out


def _value_at(data, loc):
    """The raw value at the location ``loc`` of ``data`` (None where there is none)."""
    value = data
    for key in loc:
        if isinstance(key, int) and isinstance(value, list) and key < len(value):
            value = value[key]
        elif isinstance(value, dict) and key in value:
            value = value[key]
        elif not _branch_tag(key):
            return None
    return value


def _plain_message(error: dict) -> dict:
    """``error`` with pydantic's wording of a list's length ("List should have at least 1 item after
    validation, not 0") said plainly."""
    ctx = error.get("ctx") or {}
    if error["type"] == "too_short" and "min_length" in ctx:
        return {**error, "msg": f"needs at least {ctx['min_length']} item(s), got {ctx.get('actual_length', 0)}"}
    if error["type"] == "too_long" and "max_length" in ctx:
        return {**error, "msg": f"takes at most {ctx['max_length']} item(s), got {ctx.get('actual_length')}"}
    return error
