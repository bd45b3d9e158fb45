"""Check a model file without building it: read the TOML, validate it, cross-check the document.

Everything here needs the parsed file only (pydantic, the standard library and :mod:`unilateral.io.files`;
no numpy, scipy or structure code, except for the unit factors of ``[units] mass``: see
:func:`consistent_mass_factor`), so that the command line reports every mistake it can find in
a model file at once, before the heavy imports: a TOML syntax error (with its line and column), a
wrong key or value, and the cross checks of the document (nodes that do not exist, duplicate names
and ids, files that do not exist, keys that go together). :mod:`unilateral.modelfile.build` calls
the same functions (:func:`read_document`, :func:`check_document`) before building the structure,
so each check is in one place and both say the same words.

>>> check_file("examples/liolios1990.toml")             # doctest: +SKIP
"""

from __future__ import annotations

import math
import re
import sys
import tomllib
import types
from pathlib import Path
from typing import Annotated, Union, get_args, get_origin

from pydantic import ValidationError
from pydantic.fields import FieldInfo

from ..io.files import TOML_LIMIT, InputFileError, file_problem, read_input_text
from .dimensions import model_class
from .errors import (ModelFileError, Problems, compact_ids, did_you_mean, key_path, missing_section, toml_value,
                     translate, value_problem)
from .pushover_table import pushover_problems
from .recorders import recorder_problems
from .schema import (FILE_REF, FRAME_SECTIONS, NODE_REF, TIME_UNITS, Beam, Gap, Hinge, ModelFile, Node, SoilBase, YieldLink,
                     iter_fields)
from .schema3d import DOFS_3D, Beam3D, Node3D

_TOML_POSITION = re.compile(r"^(.*) \(at line (\d+), column (\d+)\)$")


def check_file(path) -> ModelFile:
    """Read, validate and cross-check the model file ``path``; return the validated document.

    Raises
    ------
    ModelFileError
        The problems that :func:`~unilateral.modelfile.load_model_file` reports for the file before it
        builds anything, in the same words: it calls the same checks.
    """
    source = Path(path)
    try:
        document = read_document(source)
        check_document(document, source.parent)
    except Problems as exc:
        raise ModelFileError(path, exc.problems) from None
    return document


# ---------------------------------------------------------------------- reading
def read_toml(source: Path) -> dict:
    """The TOML document at ``source`` as a dict; unreadable files and syntax errors raise :class:`Problems`."""
    problem = file_problem(source)              # before opening: a FIFO would block
    if problem is not None:
        raise Problems([problem])
    try:
        text = read_input_text(source, limit=TOML_LIMIT)
    except InputFileError as exc:
        raise Problems([exc.problem]) from None
    except FileNotFoundError:
        raise Problems(["file not found"]) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise Problems([f"cannot read the file ({exc})"]) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        match = _TOML_POSITION.match(str(exc))
        where = f"line {match[2]}, column {match[3]}: " if match else ""
        shown = _shown_line(text, int(match[2]), match[1]) if match else ""
        raise Problems([f"{where}invalid TOML: {match[1] if match else exc}{shown}"]) from None
    except RecursionError:
        raise Problems(["invalid TOML: arrays or tables nested too deeply to be read (hundreds of levels; "
                        "a model or study file needs a few)"]) from None
    except ValueError:                                  # an integer of more digits than Python converts
        raise Problems([_long_integer_problem(text)]) from None


def _shown_line(text: str, number: int, message: str, limit: int = 70) -> str:
    """``'; the line reads: <line number of text>'`` (shortened to ``limit``), or ``''`` past the end or if blank.

    A line break in a string (tomllib's ``message`` ``Illegal character '\\n'``) on a line with an odd
    number of double quotes gets a hint: the string is not closed.
    """
    lines = text.split("\n")                          # as tomllib counts them
    line = lines[number - 1].strip() if 0 < number <= len(lines) else ""
    if not line:
        return ""
    hint = ""
    if message == "Illegal character '\\n'" and line.count('"') % 2 == 1:
        hint = ' (a string not closed: end it with " on the same line, or use """ for several lines)'
    return f"; the line reads: {line if len(line) <= limit else line[:limit - 3] + '...'}{hint}"


_LONG_INTEGER = re.compile(r"[+-]?\d[\d_]{%d,}" % (sys.get_int_max_str_digits() - 1))


def _long_integer_problem(text: str) -> str:
    """Where ``text`` has an integer too long for Python to read: its key path, or its line."""
    match = _LONG_INTEGER.search(text)
    if match is None:
        return "invalid TOML: a number that cannot be read"
    digits = sum(c.isdigit() for c in match[0])
    what = (f"{match[0][:20]}... ({digits} digits): an integer too large to be read (at most "
            f"{sys.get_int_max_str_digits()} digits; a model value is at most about 1.8e308)")
    sentinel = next(n for n in range(10 ** 17, 10 ** 18) if str(n) not in text)
    try:
        data = tomllib.loads(_LONG_INTEGER.sub(str(sentinel), text))
    except ValueError:
        data = {}
    parts = _path_of(data, sentinel)
    if parts is None:
        line = text.count("\n", 0, match.start()) + 1
        column = match.start() - text.rfind("\n", 0, match.start())
        return f"line {line}, column {column}: {what}"
    return f"{key_path(parts)} = {what}"


def _path_of(node, value, parts=()) -> tuple | None:
    """The key path of the first integer ``value`` in nested dicts and lists, or None."""
    if isinstance(node, int) and not isinstance(node, bool) and node == value:
        return parts
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, item in items:
        found = _path_of(item, value, (*parts, key))
        if found is not None:
            return found
    return None


def read_document(source: Path) -> ModelFile:
    """The validated document of the model file ``source``; every problem of the file raises :class:`Problems`."""
    return validate_document(read_toml(source))


def validate_document(data: dict) -> ModelFile:
    """The validated document of the parsed model file ``data``: a :class:`~.schema3d.ModelFile3D` for
    ``[frame] dimensions = 3``, else a :class:`ModelFile`; its problems raise :class:`Problems`."""
    root = model_class(data)
    try:
        return root.model_validate(data)
    except ValidationError as exc:
        raise Problems(translate(exc, data, root)) from None


def is_3d(document: ModelFile) -> bool:
    """Whether ``document`` describes a 3-D frame (``[frame] dimensions = 3``)."""
    return document.DIMENSIONS == 3


def frame_dofs(document: ModelFile) -> tuple[str, ...]:
    """The nodal DOFs of the document's frame."""
    return DOFS_3D if is_3d(document) else ("ux", "uy", "rz")


# ---------------------------------------------------------------------- cross checks
def check_document(document: ModelFile, folder: Path) -> None:
    """Raise :class:`Problems` listing every inconsistency of a validated document.

    ``folder`` is the model file's folder, the one its file names are relative to.
    """
    problems = (_mode_problems(document) + _duplicate_problems(document)
                + _reference_problems(document, folder) + _record_problems(document)
                + _foundation_problems(document) + _unilateral_problems(document)
                + _link_problems(document) + _beam_load_problems(document) + _analysis_problems(document)
                + _output_problems(document) + _diaphragm_problems(document) + pushover_problems(document))
    if problems:
        raise Problems(problems)


def _mode_problems(document: ModelFile) -> list[str]:
    """A frame and a matrix-level model take different sections and load keys."""
    loads = document.loads
    if document.matrices is None:
        problems = [] if document.nodes else [missing_section(("nodes",), Node3D if is_3d(document) else Node)]
        problems += [value_problem(("loads", "nodal", k, "dof"), load.dof,
                                   "DOF loads are for matrix-level models (give node with ux, uy, rz)")
                     for k, load in enumerate(loads.nodal) if getattr(load, "dof", None) is not None]
        for k, motion in enumerate(loads.ground_motion):
            if motion.direction is None:
                problems.append(f"{key_path(('loads', 'ground_motion', k, 'direction'))}: missing key "
                                + ('(a 3-D frame needs direction = "ux", "uy" or "uz")' if is_3d(document)
                                   else '(a frame needs direction = "ux" or "uy")'))
            if motion.influence is not None:
                problems.append(value_problem(("loads", "ground_motion", k, "influence"), motion.influence,
                                              "only for matrix-level models (a frame uses direction)"))
            if isinstance(motion.direction, tuple) and motion.at != "surface":
                problems.append(value_problem(("loads", "ground_motion", k, "direction"), list(motion.direction),
                                              f'a vector with at = "{motion.at}": the site response takes S waves '
                                              'along "ux" or "uy" and P waves along "uz"; give one record per '
                                              "direction"))
        return problems
    needs_frame = "not allowed with [matrices] (a matrix-level model has no frame)"
    problems = [f"{name}: {needs_frame}" for name in FRAME_SECTIONS if getattr(document, name, None)]
    if loads.gravity is not None:
        problems.append("loads.gravity: needs a frame (give the weight of a matrix-level model as a "
                        "constant [[loads.nodal]] load)")
    if loads.distributed:
        problems.append("loads.distributed: needs a frame (a matrix-level model has no beams)")
    if document.output.overturning_about is not None:
        problems.append("output.overturning_about: needs a frame (a matrix-level model has no base)")
    if document.output.figure is not None:
        problems.append("output.figure: needs a frame (a matrix-level model has no nodes)")
    problems += [value_problem(("loads", "nodal", k, "node"), load.node,
                               "a matrix-level model has no nodes (give dof and value)")
                 for k, load in enumerate(loads.nodal) if load.node is not None]
    for k, motion in enumerate(loads.ground_motion):
        if motion.direction is not None:
            problems.append(value_problem(("loads", "ground_motion", k, "direction"), motion.direction,
                                          'a matrix-level model needs influence = "<file>.mtx" instead'))
        elif motion.influence is None:
            problems.append(f"{key_path(('loads', 'ground_motion', k, 'influence'))}: missing key "
                            "(a matrix-level model needs the influence vector r)")
    return problems


def _duplicate_problems(document: ModelFile) -> list[str]:
    problems = []
    first_node = {}
    for k, node in enumerate(document.nodes):
        if node.id in first_node:
            problems.append(value_problem(("nodes", k, "id"), node.id,
                                          f"duplicate node id (also {key_path(first_node[node.id])})"))
        first_node.setdefault(node.id, ("nodes", k, "id"))
    first_name = {}
    for section in ("elements", "unilateral"):
        for k, element in enumerate(getattr(document, section)):
            if element.name in first_name:
                problems.append(value_problem((section, k, "name"), element.name,
                                              f"duplicate element name (also {key_path(first_name[element.name])})"))
            first_name.setdefault(element.name, (section, k, "name"))
    for at, footing in document.footings:
        if footing.name in first_name:
            default = "" if "name" in footing.model_fields_set else "; the default name, give each footing its own"
            problems.append(value_problem((*at, "name"), footing.name, "duplicate element name (also "
                                          f"{key_path(first_name[footing.name])}{default})"))
        first_name.setdefault(footing.name, (*at, "name"))
    return problems


def _reference_problems(document: ModelFile, folder: Path) -> list[str]:
    """Nodes that are not defined and files that do not exist."""
    ids = [node.id for node in document.nodes]
    known = set(ids)
    problems = []
    frame = document.matrices is None
    for parts, value, info in iter_fields(document):
        if value is None:
            continue
        markers = _markers(info)
        if NODE_REF in markers and frame and value not in known:
            problems.append(value_problem(parts, value, f"no node {toml_value(value)} (nodes are {compact_ids(ids)})")
                            + did_you_mean(value, ids))
        if frame and parts[-1] == "influence":          # reported by _mode_problems: only for matrices
            continue
        if FILE_REF in markers and (problem := file_problem(folder / value)) is not None:
            problems.append(value_problem(parts, value, f"{problem} (looked for {folder / value})"))
    return problems


def _record_problems(document: ModelFile) -> list[str]:
    """An .AT2 record has its time step, a plain-text record needs its units."""
    problems = []
    for k, motion in enumerate(document.loads.ground_motion):
        at2 = Path(motion.file).suffix.lower() == ".at2"
        if at2 and motion.dt is not None:
            problems.append(value_problem(("loads", "ground_motion", k, "dt"), motion.dt,
                                          "only for plain-text records (an .AT2 file gives DT in its header)"))
        if not at2 and motion.units is None:
            problems.append(f"{key_path(('loads', 'ground_motion', k, 'units'))}: missing key (a plain-text "
                            'record needs the units of its values, e.g. units = "g" or "cm/s2")')
    return problems + _site_problems(document)


_SITE_KEYS = ("layers = [{thickness, Vs or G, nu, rho, damping}, ...] and base = {Vs or G, nu, rho, damping} "
              'or "rigid"')


def _site_problems(document: ModelFile) -> list[str]:
    """``[site]`` and the keys ``at``, ``depth``, ``wave`` of the ground motions that use it."""
    site, problems = document.site, []
    tables = []
    if site is not None:
        if not site.layers:
            problems.append(value_problem(("site", "layers"), [], "give at least one layer, from the surface down "
                                          "({thickness, Vs or G, nu, rho, damping})"))
        tables = [(("site", "layers", j), layer) for j, layer in enumerate(site.layers)]
        tables += [] if site.base is None else [(("site", "base"), site.base)]
        for where, table in tables:
            if table.G is None and table.Vs is None:
                problems.append(f"{key_path((*where, 'G'))}: missing key (give G [F/L^2] or Vs [L/T])")
            elif table.G is not None and table.Vs is not None:
                problems.append(value_problem((*where, "Vs"), table.Vs, "give either G or Vs, not both"))
    frame = document.matrices is None
    vertical = None
    for k, motion in enumerate(document.loads.ground_motion):
        parts = ("loads", "ground_motion", k)
        if motion.depth is not None and motion.at != "within":
            problems.append(value_problem((*parts, "depth"), motion.depth, 'only for at = "within" (a record taken '
                                          "at depth)"))
        if motion.wave is not None and frame:
            problems.append(value_problem((*parts, "wave"), motion.wave, "only for matrix-level models (a frame's "
                                          'direction sets the waves: "ux" S waves, "uy" P waves): remove it'))
        if motion.at == "surface":
            continue
        if site is None:
            problems.append(value_problem((*parts, "at"), motion.at, f"needs the [site] table with the soil profile "
                                          f"under the record ({_SITE_KEYS})"))
            continue
        total = sum(layer.thickness for layer in site.layers)
        if motion.at == "outcrop" and site.base is None:
            problems.append(value_problem((*parts, "at"), motion.at, 'a rigid base (site.base = "rigid") has no '
                                          'outcrop motion: give the motion of the base with at = "within", depth = '
                                          f"{total:g}, or an elastic site.base"))
        if motion.at == "within" and motion.depth is None:
            problems.append(f"{key_path((*parts, 'depth'))}: missing key (at = \"within\" needs the depth [L] of "
                            "the record below the surface)")
        elif motion.at == "within" and motion.depth > total * (1.0 + 1e-12):
            problems.append(value_problem((*parts, "depth"), motion.depth, f"below the [site] profile: give 0 <= "
                                          f"depth <= {total:g} (the thickness of the layers, the top of the base)"))
        if not frame and motion.wave is None:
            problems.append(f"{key_path((*parts, 'wave'))}: missing key (a matrix-level model with at = "
                            f'{toml_value(motion.at)} needs wave = "S" (horizontal motion) or "P" (vertical))')
        if vertical is None and (motion.direction == "uy" if frame else motion.wave == "P"):
            vertical = k
    if vertical is not None:
        for where, table in tables:
            if table.nu is None:
                problems.append(f"{key_path((*where, 'nu'))}: missing key (loads.ground_motion[{vertical}] is "
                                "vertical: P waves, which need Poisson's ratio, 0 <= nu < 0.5)")
    return problems

def _unilateral_problems(document: ModelFile) -> list[str]:
    """Keys of ``[[unilateral]]`` entries that go together: friction, yield forces, hinges on beams."""
    problems = []
    beams = [e.name for e in document.elements if isinstance(e, Beam | Beam3D)]
    hinged = {}
    for k, e in enumerate(document.unilateral):
        at = ("unilateral", k)
        if isinstance(e, SoilBase | Gap):               # (their 3-D forms are subclasses)
            problems += _friction_problems(at, e)
        elif isinstance(e, YieldLink):
            problems += _yield_force_problems(at, e)
        elif isinstance(e, Hinge):
            if e.beam not in beams:
                problems.append(value_problem((*at, "beam"), e.beam, f"no beam {toml_value(e.beam)} in [[elements]] "
                                              f"(beams are {compact_ids(beams)})") + did_you_mean(e.beam, beams))
            elif (e.beam, e.end) in hinged:
                problems.append(value_problem((*at, "end"), e.end, f"beam {toml_value(e.beam)} already has a hinge "
                                              f"at this end ({key_path(hinged[(e.beam, e.end)])}); one per end"))
            hinged.setdefault((e.beam, e.end), (*at, "end"))
            problems += _hinge_facets_problems(at, e)
    return problems


def _hinge_facets_problems(at, e) -> list[str]:
    """A 3-D hinge's facets: an even number for an ellipse, 4 for a diamond or a box."""
    facets = getattr(e, "facets", None)
    if facets is None:
        return []
    if e.shape != "ellipse" and facets != 4:
        return [value_problem((*at, "facets"), facets, f"a {e.shape} has exactly 4 facets: give facets = 4 or "
                              'remove it (or use shape = "ellipse")')]
    if facets % 2:
        return [value_problem((*at, "facets"), facets, "must be even (the facets of the hinge's polygon come in "
                              "opposite pairs)")]
    return []


def _friction_problems(at, e) -> list[str]:
    """A contact with friction needs ``kt``; ``kt`` and ``ct`` need ``mu``."""
    if e.mu is None:
        keys = ("kt", "ct", "facets") if hasattr(e, "facets") else ("kt", "ct")
        return [value_problem((*at, key), getattr(e, key), "a friction parameter: give the friction coefficient "
                              "mu too, or remove it") for key in keys if getattr(e, key)]
    if e.kt is None:
        return [f"{key_path((*at, 'kt'))}: missing key (friction, mu = {toml_value(e.mu)}, needs the stick "
                "stiffness kt [F/L] > 0)"]
    return []


def _yield_force_problems(at, e) -> list[str]:
    """A yield link takes ``k`` and ``Fy``, or ``Fy_t`` and ``Fy_c``; or a ``backbone`` alone."""
    if e.backbone is not None:
        return [value_problem((*at, key), getattr(e, key), "cannot go with a backbone, which gives the link's "
                              "stiffness and strengths") for key in ("k", "Fy", "Fy_t", "Fy_c") if getattr(e, key) is not None]
    if e.k is None:
        return [f"{key_path((*at, 'k'))}: missing key (give the elastic stiffness k [F/L] > 0, or a backbone)"]
    if e.Fy is not None:
        return [value_problem((*at, key), getattr(e, key), "give either Fy (both ways) or Fy_t and Fy_c, not both")
                for key in ("Fy_t", "Fy_c") if getattr(e, key) is not None]
    if e.Fy_t is None and e.Fy_c is None:
        return [f"{key_path((*at, 'Fy'))}: missing key (give the yield force Fy [F], or Fy_t and Fy_c)"]
    return [f"{key_path((*at, key))}: missing key (Fy_t and Fy_c go together; or give Fy for both)"
            for key in ("Fy_t", "Fy_c") if getattr(e, key) is None]


def _foundation_problems(document: ModelFile) -> list[str]:
    """The keys of every footing that go together (soil model and its parameters, nodes)."""
    if document.matrices is not None:
        return []
    problems = []
    for at, f in document.footings:
        problems += _footing_problems(document, at, f)
    if is_3d(document):
        problems += _shared_node_problems(document)
    return problems


def _shared_node_problems(document: ModelFile) -> list[str]:
    """Nodes of a 3-D frame's footings that rest on two footings (a rigid footing's node or a flexible
    footing's grid node)."""
    problems, first = [], {}
    for at, f in document.footings:
        if f.nodes is None:
            places = [((*at, "node"), f.node)] if f.node is not None else []
        else:
            places = [((*at, "nodes", i, j), node) for i, row in enumerate(f.nodes) for j, node in enumerate(row)]
        mine = set()
        for parts, node in places:
            if node in first and node not in mine:
                problems.append(value_problem(parts, node, f"the node already rests on another footing (also in "
                                              f"{key_path(first[node])}); give each footing its own nodes"))
            first.setdefault(node, parts)
            mine.add(node)
    return problems


def _footing_problems(document: ModelFile, at: tuple, f) -> list[str]:
    """The problems of one footing ``f`` at key path ``at``."""
    problems = []
    ids = [node.id for node in document.nodes]
    if is_3d(document):
        count = _patch_count_3d(f.patches) if f.nodes is None else sum(len(row) for row in f.nodes)
        return (problems + _footing_3d_problems(document, at, f) + _sliding_3d_problems(at, f)
                + _soil_problems(document, at, f, count))
    for k, node in enumerate(f.nodes or ()):
        if node not in set(ids):
            problems.append(value_problem((*at, "nodes", k), node, f"no node {toml_value(node)} (nodes are "
                                          f"{compact_ids(ids)})") + did_you_mean(node, ids))
    if f.nodes is not None and f.patches is not None:
        problems.append(value_problem((*at, "patches"), f.patches, "only for a rigid footing (a flexible footing, "
                                      "with nodes, has one patch per node): remove patches or nodes"))
    if f.nodes is not None and len(f.nodes) < 2:
        problems.append(value_problem((*at, "nodes"), f.nodes, "a flexible footing needs at least two nodes; "
                                      "omit nodes for a rigid footing"))
    if f.nodes is None and f.width is None:
        problems.append(f"{key_path((*at, 'width'))}: missing key (a rigid footing needs its width along x)")
    if f.nodes is not None and (f.mass or f.J):
        problems.append(value_problem((*at, "mass" if f.mass else "J"), f.mass or f.J, "only for a rigid footing "
                                      "(give a flexible footing's masses to its nodes in [[masses]])"))
    if f.horizontal == "soil" and f.mu is None:
        problems.append(f"{key_path((*at, 'mu'))}: missing key (horizontal = \"soil\" needs the friction "
                        "coefficient of the footing on the soil, a number >= 0)")
    if f.horizontal != "soil" and f.mu is not None:
        problems.append(value_problem((*at, "mu"), f.mu, f'only for horizontal = "soil" (now '
                                      f'{toml_value(f.horizontal)}): remove it, or let the footing slide'))
    return problems + _soil_problems(document, at, f, len(f.nodes) if f.nodes is not None else (f.patches or 3))


def _footing_3d_problems(document: ModelFile, at: tuple, f) -> list[str]:
    """A 3-D footing's keys: a rigid footing's node, width and length; a flexible footing's grid of
    nodes (defined, each once, rows as long, one elevation, a rectilinear grid in plan) and no keys of
    a rigid footing."""
    if f.nodes is None:
        return [f"{key_path((*at, key))}: missing key (a rigid footing needs {what}; or give nodes, the grid of a "
                "flexible footing)" for key, what in (("node", "its node, at its centre"),
                                                      ("width", "its width along x"),
                                                      ("length", "its length along y"))
                if getattr(f, key) is None]
    problems = [value_problem((*at, key), getattr(f, key), "only for a rigid footing (a flexible footing, with "
                              "nodes, has one patch per node" + ("" if key == "patches" else " and its masses in "
                                                                  "[[masses]]") + "): remove it")
                for key in ("patches", "mass", "Jx", "Jy", "Jz") if getattr(f, key)]
    if len({len(row) for row in f.nodes}) > 1:
        return problems + [value_problem((*at, "nodes"), f.nodes, "the rows have "
                                         f"{', '.join(str(len(row)) for row in f.nodes)} nodes; every row of the "
                                         "grid needs the same number of nodes (one per column)")]
    if sum(len(row) for row in f.nodes) < 2:
        return problems + [value_problem((*at, "nodes"), f.nodes, "a flexible footing needs at least two nodes; "
                                         "omit nodes for a rigid footing")]
    ids = [node.id for node in document.nodes]
    where = {node.id: (node.x, node.y, node.z) for node in document.nodes}
    seen, bad = {}, False
    for i, row in enumerate(f.nodes):
        for j, node in enumerate(row):
            parts = (*at, "nodes", i, j)
            if node not in where:
                problems.append(value_problem(parts, node, f"no node {toml_value(node)} (nodes are "
                                              f"{compact_ids(ids)})") + did_you_mean(node, ids))
                bad = True
            elif node in seen:
                problems.append(value_problem(parts, node, f"given twice (also {key_path(seen[node])}); give each "
                                              "node of the grid once"))
                bad = True
            seen.setdefault(node, parts)
    return problems if bad else problems + _grid_plan_problems(at, f.nodes, where)


def _grid_plan_problems(at: tuple, grid: list, where: dict) -> list[str]:
    """The first node of a flexible footing's grid off its elevation, or off the rectilinear grid."""
    xyz = [[where[node] for node in row] for row in grid]
    scale = max(1.0, *(abs(a) for row in xyz for point in row for a in point))
    tol = 1e-9 * scale

    def off(i, j, axis, i0, j0, rule):
        a, b = xyz[i][j][axis], xyz[i0][j0][axis]
        if abs(a - b) <= tol:
            return None
        label = "xyz"[axis]
        return value_problem((*at, "nodes", i, j), grid[i][j], f"at {label} = {a!r}, but "
                             f"{key_path(('nodes', i0, j0))} = {toml_value(grid[i0][j0])} at {label} = {b!r}; {rule}")

    elevation = "a footing's nodes lie at one elevation (on the ground surface)"
    rectilinear = ("the nodes must lie on a rectilinear grid in plan: each row (nodes[i]) at one y, each column "
                   "(nodes[i][j] of every row) at one x")
    for i, row in enumerate(grid):
        for j in range(len(row)):
            problem = (off(i, j, 2, 0, 0, elevation) or off(i, j, 0, 0, j, rectilinear)
                       or off(i, j, 1, i, 0, rectilinear))
            if problem:
                return [problem]
    return []


def _sliding_3d_problems(at: tuple, f) -> list[str]:
    """``mu`` and ``facets`` of a 3-D footing: both for horizontal = "soil" only, ``mu`` needed there,
    ``facets`` even."""
    problems = []
    if f.horizontal == "soil" and f.mu is None:
        problems.append(f"{key_path((*at, 'mu'))}: missing key (horizontal = \"soil\" needs the friction "
                        "coefficient of the footing on the soil, a number > 0)")
    for key in ("mu", "facets"):
        if f.horizontal != "soil" and getattr(f, key) is not None:
            problems.append(value_problem((*at, key), getattr(f, key), f'only for horizontal = "soil" (now '
                                          f'{toml_value(f.horizontal)}): remove it, or let the footing slide'))
    if f.facets is not None and f.facets % 2:
        problems.append(value_problem((*at, "facets"), f.facets, "give an even number >= 4 (the facets of the "
                                      "friction cone in plan come in opposite pairs)"))
    return problems


def _patch_count_3d(patches) -> int:
    """The number of patches of a 3-D footing's ``patches`` (``[nx, ny]``, one integer for both, default 3 x 3)."""
    if patches is None:
        return 9
    return patches * patches if isinstance(patches, int) else patches[0] * patches[1]


def _soil_problems(document: ModelFile, at: tuple, f, m: int) -> list[str]:
    """The keys of the soil of the footing ``f`` (at ``at``, ``m`` patches) that go together."""
    problems = []
    soil, where = f.soil, (*at, "soil")
    if soil.model != "layered" and (soil.layers is not None or soil.base != "halfspace"):
        problems.append(value_problem((*where, "layers" if soil.layers is not None else "base"),
                                      soil.layers if soil.layers is not None else soil.base,
                                      f'only for model = "layered" (model = {toml_value(soil.model)})'))
    if soil.model == "layered":
        if not soil.layers:
            problems.append(f"{key_path((*where, 'layers'))}: missing key (model = \"layered\" needs the layers "
                            "from the surface down: [{ thickness = ..., Vs = ..., nu = ..., rho = ... }])")
        if soil.base == "rigid":
            return problems + [value_problem((*where, key), getattr(soil, key), 'not used with base = "rigid": '
                                             "remove it") for key in ("G", "Vs", "nu", "rho")
                               if getattr(soil, key) is not None]
    if soil.model == "winkler-kelvin":
        for key in ("G", "Vs", "nu", "rho"):
            if getattr(soil, key) is not None:
                problems.append(value_problem((*where, key), getattr(soil, key), 'not used by model = '
                                              '"winkler-kelvin" (give k and c per patch): remove it'))
        if soil.damping:
            problems.append(value_problem((*where, "damping"), soil.damping, 'not used by model = "winkler-kelvin" '
                                          "(give c): remove it"))
        if soil.k is None:
            problems.append(f"{key_path((*where, 'k'))}: missing key (model = \"winkler-kelvin\" needs the spring "
                            "of each patch [F/L], one number or a list of one per patch)")
        if f.horizontal == "soil" and soil.kx is None:
            problems.append(f"{key_path((*where, 'kx'))}: missing key (a footing with horizontal = \"soil\" on "
                            "model = \"winkler-kelvin\" needs the horizontal spring of each patch [F/L])")
        if f.horizontal != "soil" and (soil.kx is not None or soil.cx != 0.0):
            key = "kx" if soil.kx is not None else "cx"
            problems.append(value_problem((*where, key), getattr(soil, key), 'only for horizontal = "soil" (a '
                                          "footing that slides): remove it"))
        for key in ("k", "c", "kx", "cx"):
            value = getattr(soil, key)
            if isinstance(value, list) and len(value) != m:
                problems.append(value_problem((*where, key), value, f"give one number or a list of {m} numbers "
                                              f"(one per patch; the footing has {m})"))
        return problems
    if soil.G is None and soil.Vs is None:
        problems.append(f"{key_path((*where, 'G'))}: missing key (model = {toml_value(soil.model)} needs G or Vs)")
    elif soil.G is not None and soil.Vs is not None:
        problems.append(value_problem((*where, "Vs"), soil.Vs, "give either G or Vs, not both"))
    for key in ("nu", "rho"):
        if getattr(soil, key) is None:
            problems.append(f"{key_path((*where, key))}: missing key (model = {toml_value(soil.model)} needs it)")
    for key in ("k", "c", "kx", "cx"):
        value = getattr(soil, key)
        if value is not None and value != 0.0:
            problems.append(value_problem((*where, key), value, f'only for model = "winkler-kelvin" (model = '
                                          f"{toml_value(soil.model)} takes G or Vs, nu, rho)"))
    problems += _soil_scale_problems(document, f, where)
    if soil.model == "cones" and soil.damping:
        problems.append(value_problem((*where, "damping"), soil.damping, 'the cones have no material damping; '
                                      'use damping = 0 or model = "halfspace"'))
    if f.horizontal == "cone" and soil.model == "winkler-kelvin":
        problems.append(value_problem((*at, "horizontal"), f.horizontal, 'needs the soil\'s G or Vs, nu, rho '
                                      '(model = "halfspace" or "cones")'))
    return problems


def _soil_scale_problems(document: ModelFile, f, where: tuple) -> list[str]:
    """Moduli derived from the soil's ``G`` or ``Vs``, ``rho`` and the footing's area that overflow or vanish.

    ``G = rho Vs^2``, ``Vs = sqrt(G / rho)`` and the footing's stiffness ``G sqrt(A)`` and dashpot
    ``rho Vs A`` (``A = width length``) must be finite numbers > 0.
    """
    soil = f.soil
    if soil.rho is None or (soil.G is None) == (soil.Vs is None):
        return []
    key = "G" if soil.G is not None else "Vs"
    rho = soil.rho * consistent_mass_factor(document.units)
    G = soil.G if soil.G is not None else rho * soil.Vs * soil.Vs
    vs = soil.Vs if soil.Vs is not None else math.sqrt(G / rho)
    area = (f.width or 1.0) * (f.length or 1.0)         # a flexible footing without them: of order 1
    derived = {"the shear modulus G = rho Vs^2": G, "the shear-wave speed Vs = sqrt(G/rho)": vs,
               "the footing's stiffness G sqrt(A)": G * math.sqrt(area),
               "the footing's dashpot rho Vs A": rho * vs * area}
    for name, value in derived.items():
        if not 0.0 < value < math.inf:
            return [value_problem((*where, key), getattr(soil, key), f"with rho = {toml_value(soil.rho)} and the "
                                  f"footing's area A = {area:g} gives {name} = {value:g}; give values for which "
                                  "it is a finite number > 0")]
    return []


def _markers(info: FieldInfo) -> list:
    """The metadata of a field, with that of an optional annotated type (``NodeRef | None``)."""
    found, stack = list(info.metadata), [info.annotation]
    while stack:
        annotation = stack.pop()
        if get_origin(annotation) is Annotated:
            base, *metadata = get_args(annotation)
            found += metadata
            stack.append(base)
        elif get_origin(annotation) in (Union, types.UnionType):
            stack += get_args(annotation)
    return found


def _link_problems(document: ModelFile) -> list[str]:
    """Rigid links: a slave follows one master, is not supported, and the links form no loop."""
    if document.matrices is not None:
        return []
    supported = {}                                      # node -> (its restrained DOFs, the first support)
    for k, support in enumerate(document.supports):
        dofs, first = supported.get(support.node, (set(), ("supports", k)))
        supported[support.node] = (dofs | {dof for dof in frame_dofs(document) if getattr(support, dof)}, first)
    problems, master_of, ids = [], {}, {node.id for node in document.nodes}
    for k, link in enumerate(document.rigid_links):
        at = ("rigid_links", k, "slave")
        if link.slave == link.master or not {link.master, link.slave} <= ids:    # said by the schema, the references
            continue
        if link.slave in master_of:
            first, j = master_of[link.slave]
            problems.append(value_problem(at, link.slave, f"node {toml_value(link.slave)} is already a slave of node "
                                          f"{toml_value(first)} (rigid_links[{j}]); a node follows one master"))
            continue
        if link.slave in supported:                     # in the words of Frame2D.rigid_link
            dofs, first = supported[link.slave]
            problems.append(f"{key_path(at[:2])}: rigid_link({link.master!r}, {link.slave!r}): slave node "
                            f"{link.slave!r} is supported ({', '.join(d for d in frame_dofs(document) if d in dofs)}) "
                            f"by {key_path(first)}; support the master node instead")
        root = link.master
        while root in master_of and root != link.slave:
            root = master_of[root][0]
        if root == link.slave:
            problems.append(value_problem(at, link.slave, "the link would close a loop of rigid links through node "
                                          f"{toml_value(link.slave)}"))
            continue
        master_of[link.slave] = (link.master, k)
    return problems


def _output_problems(document: ModelFile) -> list[str]:
    """``[output] floor_spectra``: nodes of the frame, each once."""
    spectra = document.output.floor_spectra
    if document.matrices is not None:
        return ["output.floor_spectra: needs a frame (a matrix-level model has no nodes)"] if spectra else []
    ids = [node.id for node in document.nodes]
    problems = []
    for k, node in enumerate(spectra):
        if node not in ids:
            problems.append(value_problem(("output", "floor_spectra", k), node,
                                          f"no node {toml_value(node)} (nodes are {compact_ids(ids)})")
                            + did_you_mean(node, ids))
        elif node in spectra[:k]:
            problems.append(value_problem(("output", "floor_spectra", k), node, "node given twice"))
    return problems + _overturning_problems(document) + recorder_problems(document)


#: How far ``[output] overturning_about`` may lie from the nodes, in sizes of the structure.
OVERTURNING_REACH = 1e6


def _overturning_problems(document: ModelFile) -> list[str]:
    """``[output] overturning_about`` within 1e6 sizes of the structure of its nodes.

    Farther, the overturning moment is the base shear times the distance (no information), and
    near ``1e308`` it overflows to ``inf``.
    """
    about = document.output.overturning_about
    if about is None or not document.nodes:
        return []
    axes = ("x", "y", "z")[: len(about)]
    lo = [min(float(getattr(node, axis, 0.0)) for node in document.nodes) for axis in axes]
    hi = [max(float(getattr(node, axis, 0.0)) for node in document.nodes) for axis in axes]
    size = max([b - a for a, b in zip(lo, hi)] + [1.0])
    reach = OVERTURNING_REACH * size
    far = [axis for axis, x, a, b in zip(axes, about, lo, hi) if not a - reach <= x <= b + reach]
    if not far:
        return []
    valid = ", ".join(f"{axis} in [{a - reach:g}, {b + reach:g}]" for axis, a, b in zip(axes, lo, hi))
    return [value_problem(("output", "overturning_about"), list(about),
                          f"{' and '.join(far)} more than {OVERTURNING_REACH:g} times the structure's size ({size:g}) "
                          "from its nodes: the overturning moment would be the base shear times that arm (inf "
                          f"near 1e308); give a point with {valid}")]


def _beam_load_problems(document: ModelFile) -> list[str]:
    """``[[loads.distributed]]`` on a beam of ``[[elements]]``."""
    if document.matrices is not None:
        return []
    beams = [e.name for e in document.elements if isinstance(e, Beam | Beam3D)]
    return [value_problem(("loads", "distributed", k, "beam"), load.beam, f"no beam {toml_value(load.beam)} in "
                          f"[[elements]] (beams are {compact_ids(beams)})") + did_you_mean(load.beam, beams)
            for k, load in enumerate(document.loads.distributed) if load.beam not in beams]


def _analysis_problems(document: ModelFile) -> list[str]:
    """``[analysis]`` keys that need other sections."""
    if document.analysis.load_sampling == "point" and document.analysis.method == "event":
        return ['analysis.load_sampling = "point": method = "event" integrates the loads exactly between events '
                'and cannot sample them at points; use load_sampling = "average" or another method']
    if document.matrices is None and document.analysis.p_delta and document.loads.gravity is None:
        return ["analysis.p_delta = true: needs [loads.gravity] (the axial forces of P-Delta are those of the "
                "gravity load)"]
    return []


def _diaphragm_problems(document: ModelFile) -> list[str]:
    """``[[rigid_diaphragms]]`` of a 3-D frame: slaves that are nodes, other than the master."""
    ids = [node.id for node in document.nodes]
    known, problems = set(ids), []
    for k, diaphragm in enumerate(getattr(document, "rigid_diaphragms", ())):
        for j, slave in enumerate(diaphragm.slaves):
            at = ("rigid_diaphragms", k, "slaves", j)
            if slave not in known:
                problems.append(value_problem(at, slave, f"no node {toml_value(slave)} (nodes are {compact_ids(ids)})")
                                + did_you_mean(slave, ids))
            elif slave == diaphragm.master:
                problems.append(value_problem(at, slave, "the master node itself: give the other nodes of the floor"))
    return problems


def consistent_mass_factor(units) -> float:
    """Factor from ``units.mass`` to the consistent mass unit force time^2/length (1 without it).

    With ``units.mass`` it imports :mod:`unilateral.loads` (numpy, scipy) for the unit factors.
    """
    if units.mass is None:
        return 1.0
    from ..loads.units import force_factor, length_factor, mass_factor

    consistent_kg = force_factor(units.force) * TIME_UNITS[units.time] ** 2 / length_factor(units.length)
    return mass_factor(units.mass) / consistent_kg
