"""Errors of model files: one message per problem, ``<file>: <key path> = <value>: <what is wrong>``.

:class:`ModelFileError` is what callers see. Inside the package, problems travel as
:class:`Problems` (a list of messages without the file name) and :func:`translate` turns a pydantic
``ValidationError`` into such messages, with TOML key paths (``elements[3].node_j``), TOML values
and, for typos, the nearest valid key or value.
"""

from __future__ import annotations

import difflib
import json
import types
from typing import Annotated, Any, Union, get_args, get_origin

from pydantic import BaseModel, ValidationError
from pydantic.fields import FieldInfo

KEY_ALIASES = {
    "stiffness": "k", "spring": "k", "damping": "c", "viscosity": "c", "dashpot": "c", "mass": "m",
    "inertia": "J", "EI": "I", "EA": "A", "i": "node_i", "j": "node_j", "start": "node_i", "end": "node_j",
    "from": "node_i", "to": "node_j", "clearance": "gap", "amplitude": "value", "record": "file",
}
"""Words people write for a key, mapped to the key, for "did you mean" suggestions."""

_ABSENT = object()


class ModelFileError(ValueError):
    """An invalid model file; the message has one line per problem, each ``<file>: <problem>``.

    Attributes
    ----------
    source : str
        The file, as given.
    problems : list of str
        The problems without the file name, e.g. ``'elements[3].node_j = 17: no node 17 (nodes
        are 1..12)'``.
    """

    def __init__(self, source, problems: list[str]):
        self.source = str(source)
        self.problems = list(problems)
        super().__init__("\n".join(f"{self.source}: {p}" for p in self.problems))


class Problems(Exception):
    """Problems found in a model file, before the file name is attached (internal)."""

    def __init__(self, problems: list[str]):
        self.problems = list(problems)
        super().__init__("\n".join(self.problems))


# ---------------------------------------------------------------------- formatting
def key_path(parts) -> str:
    """``("elements", 3, "node_j")`` -> ``"elements[3].node_j"``."""
    out = ""
    for part in parts:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def toml_value(value, limit=60) -> str:
    """A value written as in TOML (strings in double quotes, ``true``), shortened to ``limit``."""
    if isinstance(value, bool):
        text = "true" if value else "false"
    elif isinstance(value, str):
        text = json.dumps(value, ensure_ascii=False)
    elif isinstance(value, list | tuple):
        text = "[" + ", ".join(toml_value(x, limit) for x in value) + "]"
    elif isinstance(value, dict):
        text = "{" + ", ".join(f"{k} = {toml_value(v, limit)}" for k, v in value.items()) + "}"
    else:
        text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def compact_ids(ids, limit=12) -> str:
    """Node ids listed compactly: runs of consecutive integers as ranges, e.g. ``1..12, 15, "top"``."""
    ints = sorted({i for i in ids if isinstance(i, int)})
    groups = []
    for i in ints:
        if groups and i == groups[-1][1] + 1:
            groups[-1][1] = i
        else:
            groups.append([i, i])
    words = [str(a) if a == b else (f"{a}, {b}" if b == a + 1 else f"{a}..{b}") for a, b in groups]
    words += [toml_value(i) for i in ids if isinstance(i, str)]
    if not words:
        return "none"
    return ", ".join(words[:limit]) + (", ..." if len(words) > limit else "")


def suggestion(word, options, aliases: dict | None = None) -> str | None:
    """The option closest to ``word`` (or the option an alias of ``word`` stands for), or None."""
    if not isinstance(word, str):
        return None
    aliases = {a: key for a, key in (aliases or {}).items() if key in options}
    if word in aliases:
        return aliases[word]
    candidates = {str(o): o for o in options} | aliases
    same_letters = [c for c in candidates if c.lower() == word.lower()]     # "my" for "My"
    if same_letters:
        return candidates[same_letters[0]]
    match = difflib.get_close_matches(word, list(candidates), n=1)
    return candidates[match[0]] if match else None


def did_you_mean(word, options) -> str:
    """``'; did you mean "beam"?'`` if an option is close to ``word``, else ``''``."""
    best = suggestion(word, options)
    return "" if best is None else f"; did you mean {toml_value(best)}?"


def value_problem(parts, value, message: str) -> str:
    """``'<key path> = <value>: <message>'``."""
    return f"{key_path(parts)} = {toml_value(value)}: {message}"


# ---------------------------------------------------------------------- pydantic errors
def translate(exc: ValidationError, data: dict, root: type[BaseModel]) -> list[str]:
    """Messages for the errors of validating the TOML document ``data`` against ``root``.

    A missing key is not reported when an unknown key of the same table is a typo of it.
    """
    located = [(error, _locate(root, data, error["loc"])) for error in exc.errors()]
    typos = {(*site.parts[:-1], _typo_of(site)) for error, site in located if error["type"] == "extra_forbidden"}
    return [_message(error, site, root) for error, site in located
            if not (error["type"] == "missing" and tuple(site.parts) in typos)]


class _Site:
    """Where an error is: key path, raw value, the field and the table (model) holding it."""

    def __init__(self):
        self.parts: list = []
        self.value: Any = _ABSENT
        self.annotation: Any = None
        self.field: FieldInfo | None = None
        self.parent: type[BaseModel] | None = None


def _locate(root, data, loc) -> _Site:
    """Follow a pydantic error location through the annotations and the raw data.

    Tags of discriminated unions (``("elements", 0, "beam", "E")``) are dropped from the path.
    """
    site = _Site()
    site.annotation, site.value = root, data
    for key in loc:
        annotation = _unwrap(site.annotation)[0]
        members = _union_members(annotation)
        if members:
            site.annotation = members.get(key)
            continue
        site.parts.append(key)
        if isinstance(key, int):
            site.annotation = get_args(annotation)[0] if get_args(annotation) else None
            raw = site.value
            site.value = raw[key] if isinstance(raw, list) and key < len(raw) else _ABSENT
        elif isinstance(annotation, type) and issubclass(annotation, BaseModel):
            site.parent = annotation
            site.field = annotation.model_fields.get(key)
            site.annotation = None if site.field is None else site.field.annotation
            site.value = site.value.get(key, _ABSENT) if isinstance(site.value, dict) else _ABSENT
        else:
            site.annotation, site.value = None, _ABSENT
    return site


def _unwrap(annotation) -> tuple[Any, list[FieldInfo]]:
    """Strip ``Annotated`` (collecting its FieldInfo) and ``Optional``."""
    infos = []
    while True:
        if get_origin(annotation) is Annotated:
            annotation, *metadata = get_args(annotation)
            infos += [m for m in metadata if isinstance(m, FieldInfo)]
        elif get_origin(annotation) in (Union, types.UnionType) and type(None) in get_args(annotation):
            rest = [a for a in get_args(annotation) if a is not type(None)]
            annotation = rest[0] if len(rest) == 1 else Union[tuple(rest)]
        else:
            return annotation, infos


def _union_members(annotation) -> dict:
    """``{tag: model}`` of a discriminated union of tables, else ``{}``."""
    if get_origin(annotation) not in (Union, types.UnionType):
        return {}
    members = {}
    for member in get_args(annotation):
        if not (isinstance(member, type) and issubclass(member, BaseModel) and "type" in member.model_fields):
            return {}
        members[get_args(member.model_fields["type"].annotation)[0]] = member
    return members


_TYPE_MESSAGES = {
    "float_type": "expected a number", "int_type": "expected an integer", "string_type": "expected a string",
    "bool_type": "expected true or false", "finite_number": "must be finite", "list_type": "expected an array",
    "model_type": "expected a table", "model_attributes_type": "expected a table",
    "string_too_short": "must not be empty",
}
_BOUNDS = {"greater_than": ">", "greater_than_equal": ">=", "less_than": "<", "less_than_equal": "<="}


def _message(error: dict, site: _Site, root: type[BaseModel]) -> str:
    kind = error["type"]
    path = key_path(site.parts)
    value = site.value if site.value is not _ABSENT else error.get("input", _ABSENT)
    if kind == "extra_forbidden":
        return _unknown_key(site, root)
    if kind == "missing":
        return _missing(site)
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        return _bad_tag(site, error, root)
    if kind == "literal_error":
        valid = [str(v) for v in get_args(_unwrap(site.annotation)[0])]
        title = site.field.title if site.field is not None and site.field.title else "value"
        return (f"{path} = {toml_value(value)}: unknown {title} (valid: {', '.join(valid)})"
                + did_you_mean(value, valid))
    if kind in _BOUNDS:
        bound = next(iter(error["ctx"].values()))
        message = f"must be {_BOUNDS[kind]} {bound:g}"
    else:
        message = _TYPE_MESSAGES.get(kind, error["msg"])
    if isinstance(value, dict) or value is _ABSENT:
        return f"{path}: {message}"
    return f"{path} = {toml_value(value)}: {message}"


def _unknown_key(site: _Site, root: type[BaseModel]) -> str:
    key = site.parts[-1]
    path = key_path(site.parts)
    if len(site.parts) > 1 and key in root.model_fields:
        table = key_path(site.parts[:-1])
        return (f"{path}: unknown key ({key} is a top-level section, but in TOML a key after a table header "
                f"belongs to that table ({table}); move {key} = ... above the first table header, "
                f"or write [{key}] / [[{key}]])")
    from .dimensions import dimension_hint

    other = None if site.parent is None else dimension_hint(site.parent, key)
    if other is not None:
        shown = "" if site.value is _ABSENT or isinstance(site.value, dict | list) else f" = {toml_value(site.value)}"
        return f"{path}{shown}: {other}"
    what = "section" if len(site.parts) == 1 else "key"
    typo = _typo_of(site)
    hint = "" if typo is None else f"did you mean {toml_value(typo)}? "
    return f"{path}: unknown {what} ({hint}valid {what}s: {', '.join(_keys(site))})"


def _keys(site: _Site) -> list[str]:
    """The keys of the table holding the last key of ``site``."""
    return list(site.parent.model_fields) if site.parent is not None else []


def _typo_of(site: _Site) -> str | None:
    """The valid key that the unknown key at ``site`` is probably a typo of."""
    return suggestion(site.parts[-1], _keys(site), KEY_ALIASES)


def _missing(site: _Site) -> str:
    target = _unwrap(site.annotation)[0]
    if get_origin(target) is list:
        target = _unwrap(get_args(target)[0])[0]
    if hasattr(target, "EXAMPLE"):
        return missing_section(site.parts, target)
    required = [name for name, info in site.parent.model_fields.items() if info.is_required()]
    return f"{key_path(site.parts)}: missing key (required keys: {', '.join(required)})"


def _bad_tag(site: _Site, error: dict, root=None) -> str:
    annotation, infos = _unwrap(site.annotation)
    valid = sorted(_union_members(annotation))
    titles = [info.title for info in infos] + [site.field.title if site.field is not None else None]
    title = next((t for t in titles if t), "type")
    path = key_path([*site.parts, "type"])
    if error["type"] == "union_tag_not_found":
        return f"{path}: missing key (valid {title}s: {', '.join(valid)})"
    tag = error["ctx"]["tag"]
    tag = site.value.get("type", tag) if isinstance(site.value, dict) else tag
    from .schema3d import TWO_D_ONLY_TYPES

    if getattr(root, "DIMENSIONS", 2) == 3 and tag in TWO_D_ONLY_TYPES:
        return (f"{path} = {toml_value(tag)}: {TWO_D_ONLY_TYPES[tag]} are for 2-D frames only (this file declares "
                f"[frame] dimensions = 3; valid {title}s: {', '.join(valid)})")
    return f"{path} = {toml_value(tag)}: unknown {title} (valid: {', '.join(valid)})" + did_you_mean(tag, valid)


def missing_section(parts, table: type[BaseModel]) -> str:
    """``'<key path>: missing section (declare e.g. <the table's EXAMPLE>)'``."""
    return f"{key_path(parts)}: missing section (declare e.g. {table.EXAMPLE})"
