"""Read a model file: TOML -> validated document -> cross checks -> Structure, Model and load.

:func:`load_model_file` is the entry point. Every problem is reported as a
:class:`~unilateral.modelfile.errors.ModelFileError` naming the key path; errors of the
:class:`~unilateral.structure.Frame2D` builder and of the load readers are re-raised with the key
path of the entry that caused them.
"""

from __future__ import annotations

import re
import sys
import tomllib
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp
from pydantic import ValidationError

from ..loads import (STANDARD_GRAVITY, Constant, HalfSine, LoadHistory, Ramp, Rectangular, Tabulated,
                     Triangular, force_factor, length_factor, read_record)
from ..loads.site_response import free_field
from ..loads.units import mass_factor
from ..io.files import TOML_LIMIT, InputFileError, file_problem, read_input_text
from ..model import Model
from ..structure import Frame2D, Structure
from .errors import (ModelFileError, Problems, compact_ids, did_you_mean, key_path, missing_section, toml_value,
                     translate, value_problem)
from .matrices import dof_index, read_matrix_model, read_vector
from .schema import (FILE_REF, FRAME_SECTIONS, NODE_REF, TIME_UNITS, Bar, Beam, Cable, ConstantLoad, Dashpot, Gap,
                     HalfSinePulse, Hinge, ModelFile, Node, RampLoad, RectangularPulse, Slider, Soil, Spring,
                     TableLoad, TriangularPulse, YieldLink, iter_fields)


_TOML_POSITION = re.compile(r"^(.*) \(at line (\d+), column (\d+)\)$")


@dataclass(frozen=True, eq=False)
class ModelSpec:
    """A model file read and built.

    Attributes
    ----------
    structure : Structure or None
        The frame (None for a matrix-level model).
    model : Model
        The reduced problem (``structure.to_model()`` for a frame).
    load : LoadHistory
        ``q(t) -> (n,)``, the total load in the model's force unit.
    analysis : dict
        ``dt, t_end, method, rule, lcp, initial, bilateral_reference, title``.
    units : dict
        ``length, force, time`` as declared and the derived ``mass``.
    figure : dict or None
        ``node, dof, label`` of the history drawn in the main figure.
    source : Path
        The model file.
    document : ModelFile
        The validated file.
    """

    structure: Structure | None
    model: Model
    load: LoadHistory
    analysis: dict
    units: dict
    figure: dict | None
    source: Path
    document: ModelFile


def load_model_file(path) -> ModelSpec:
    """Read, check and build the model file ``path`` (TOML; see ``docs/model-file.md``).

    Raises
    ------
    ModelFileError
        With one line ``<file>: <key path> = <value>: <problem> (<what is valid>)`` per problem.
    """
    source = Path(path)
    try:
        document = _read_document(source)
    except Problems as exc:
        raise ModelFileError(path, exc.problems) from None
    return _build_spec(document, source, path)


def build_model_spec(data: dict, source) -> ModelSpec:
    """Check and build a model file that is already parsed: ``data`` as from :func:`tomllib.load`.

    For programs that change a model file's values before building it (parameter studies).
    ``source`` is the file the data stands for: file names in ``data`` are relative to its folder,
    and error messages name it. Raises :class:`ModelFileError` as :func:`load_model_file` does.
    """
    source = Path(source)
    try:
        try:
            document = ModelFile.model_validate(data)
        except ValidationError as exc:
            raise Problems(translate(exc, data, ModelFile)) from None
    except Problems as exc:
        raise ModelFileError(source, exc.problems) from None
    return _build_spec(document, source, source)


def _build_spec(document: ModelFile, source: Path, path) -> ModelSpec:
    """Cross checks and the build of a validated document (``path``: the file as named in errors)."""
    try:
        _check(document, source.parent)
        if document.matrices is None:
            structure = _build_structure(document)
            with _at("structure"):
                model = structure.to_model()
        else:
            structure = None
            model = read_matrix_model(document.matrices, source.parent)
        load = _build_load(document, source.parent, model, structure)
    except Problems as exc:
        raise ModelFileError(path, exc.problems) from None
    units = document.units.model_dump()
    units["mass"] = f"{units['force']} {units['time']}^2/{units['length']}"
    return ModelSpec(structure=structure, model=model, load=load, analysis=document.analysis.model_dump(),
                     units=units, figure=_figure(document), source=source, document=document)


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
        raise Problems([f"{where}invalid TOML: {match[1] if match else exc}"]) from None
    except RecursionError:
        raise Problems(["invalid TOML: arrays or tables nested too deeply to be read (hundreds of levels; "
                        "a model or study file needs a few)"]) from None
    except ValueError:                                  # an integer of more digits than Python converts
        raise Problems([_long_integer_problem(text)]) from None


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


def _read_document(source: Path) -> ModelFile:
    data = read_toml(source)
    try:
        return ModelFile.model_validate(data)
    except ValidationError as exc:
        raise Problems(translate(exc, data, ModelFile)) from None


@contextmanager
def _at(where: str):
    """Re-raise a ``ValueError`` or ``TypeError`` of the library as a problem at ``where``."""
    try:
        yield
    except (ValueError, TypeError) as exc:
        raise Problems([f"{where}: {exc}"]) from None


# ---------------------------------------------------------------------- cross checks
def _check(document: ModelFile, folder: Path) -> None:
    """Raise :class:`Problems` listing every inconsistency of a validated document."""
    problems = (_mode_problems(document) + _duplicate_problems(document)
                + _reference_problems(document, folder) + _record_problems(document)
                + _foundation_problems(document) + _unilateral_problems(document))
    if problems:
        raise Problems(problems)


def _mode_problems(document: ModelFile) -> list[str]:
    """A frame and a matrix-level model take different sections and load keys."""
    loads = document.loads
    if document.matrices is None:
        problems = [] if document.nodes else [missing_section(("nodes",), Node)]
        problems += [value_problem(("loads", "nodal", k, "dof"), load.dof,
                                   "DOF loads are for matrix-level models (give node with ux, uy, rz)")
                     for k, load in enumerate(loads.nodal) if load.dof is not None]
        for k, motion in enumerate(loads.ground_motion):
            if motion.direction is None:
                problems.append(f"{key_path(('loads', 'ground_motion', k, 'direction'))}: missing key "
                                '(a frame needs direction = "ux" or "uy")')
            if motion.influence is not None:
                problems.append(value_problem(("loads", "ground_motion", k, "influence"), motion.influence,
                                              "only for matrix-level models (a frame uses direction)"))
        return problems
    needs_frame = "not allowed with [matrices] (a matrix-level model has no frame)"
    problems = [f"{name}: {needs_frame}" for name in FRAME_SECTIONS if getattr(document, name)]
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
    return problems


def _reference_problems(document: ModelFile, folder: Path) -> list[str]:
    """Nodes that are not defined and files that do not exist."""
    ids = [node.id for node in document.nodes]
    known = set(ids)
    problems = []
    for parts, value, info in iter_fields(document):
        if value is None:
            continue
        if NODE_REF in info.metadata and document.matrices is None and value not in known:
            problems.append(value_problem(parts, value, f"no node {toml_value(value)} (nodes are {compact_ids(ids)})")
                            + did_you_mean(value, ids))
        if FILE_REF in info.metadata and (problem := file_problem(folder / value)) is not None:
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


def _site_profile(document: ModelFile) -> tuple[list[dict], dict | None]:
    """``layers, base`` of ``[site]`` for :func:`~unilateral.loads.site_response.free_field`, rho in the
    consistent mass unit."""
    to_mass = _mass_factor(document.units)

    def table(t):
        values = {key: value for key, value in t.model_dump().items() if value is not None}
        return {**values, "rho": values["rho"] * to_mass}
    site = document.site
    return [table(layer) for layer in site.layers], None if site.base is None else table(site.base)


def _unilateral_problems(document: ModelFile) -> list[str]:
    """Keys of ``[[unilateral]]`` entries that go together: friction, yield forces, hinges on beams."""
    problems = []
    beams = [e.name for e in document.elements if isinstance(e, Beam)]
    hinged = {}
    for k, e in enumerate(document.unilateral):
        at = ("unilateral", k)
        if isinstance(e, Soil | Gap):
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
    return problems


def _friction_problems(at, e) -> list[str]:
    """A contact with friction needs ``kt``; ``kt`` and ``ct`` need ``mu``."""
    if e.mu is None:
        return [value_problem((*at, key), getattr(e, key), "a friction parameter: give the friction coefficient "
                              "mu too, or remove it") for key in ("kt", "ct") if getattr(e, key)]
    if e.kt is None:
        return [f"{key_path((*at, 'kt'))}: missing key (friction, mu = {toml_value(e.mu)}, needs the stick "
                "stiffness kt [F/L] > 0)"]
    return []


def _yield_force_problems(at, e) -> list[str]:
    """A yield link takes ``Fy``, or ``Fy_t`` and ``Fy_c``."""
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
    return problems


def _footing_problems(document: ModelFile, at: tuple, f) -> list[str]:
    """The problems of one footing ``f`` at key path ``at``."""
    problems = []
    ids = [node.id for node in document.nodes]
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
    soil, where = f.soil, (*at, "soil")
    m = len(f.nodes) if f.nodes is not None else (f.patches or 3)
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
    rho = soil.rho * _mass_factor(document.units)
    G = soil.G if soil.G is not None else rho * soil.Vs * soil.Vs
    vs = soil.Vs if soil.Vs is not None else float(np.sqrt(G / rho))
    area = (f.width or 1.0) * f.length
    derived = {"the shear modulus G = rho Vs^2": G, "the shear-wave speed Vs = sqrt(G/rho)": vs,
               "the footing's stiffness G sqrt(A)": G * float(np.sqrt(area)),
               "the footing's dashpot rho Vs A": rho * vs * area}
    for name, value in derived.items():
        if not 0.0 < value < np.inf:
            return [value_problem((*where, key), getattr(soil, key), f"with rho = {toml_value(soil.rho)} and the "
                                  f"footing's area A = {area:g} gives {name} = {value:g}; give values for which "
                                  "it is a finite number > 0")]
    return []


# ---------------------------------------------------------------------- the frame
def _build_structure(document: ModelFile) -> Structure:
    fr = Frame2D()
    for k, node in enumerate(document.nodes):
        with _at(key_path(("nodes", k))):
            fr.node(node.id, node.x, node.y)
    for k, support in enumerate(document.supports):
        with _at(key_path(("supports", k))):
            fr.support(support.node, ux=support.ux, uy=support.uy, rz=support.rz)
    for k, link in enumerate(document.rigid_links):
        with _at(key_path(("rigid_links", k))):
            fr.rigid_link(link.master, link.slave)
    to_mass = _mass_factor(document.units)
    for section in ("elements", "unilateral"):
        for k, element in enumerate(getattr(document, section)):
            with _at(key_path((section, k))):
                _add_element(fr, element, to_mass)
    for k, mass in enumerate(document.masses):
        with _at(key_path(("masses", k))):
            fr.mass(mass.node, mass.m * to_mass, J=mass.J * to_mass)
    for at, f in document.footings:
        soil = {key: value for key, value in f.soil.model_dump().items() if value is not None}
        if soil.get("rho") is not None:
            soil["rho"] = soil["rho"] * to_mass
        if soil.get("layers") is not None:
            soil["layers"] = [{key: value * to_mass if key == "rho" else value for key, value in layer.items()
                               if value is not None} for layer in soil["layers"]]
        with _at(key_path(at)):
            fr.foundation(f.name, f.node, width=f.width, length=f.length, soil=soil, patches=f.patches,
                          nodes=f.nodes, horizontal=f.horizontal, gap=f.gap, mass=f.mass * to_mass,
                          J=f.J * to_mass, mu=f.mu)
    rayleigh = document.damping.rayleigh if document.damping is not None else None
    if rayleigh is not None:
        with _at("damping.rayleigh"):
            if rayleigh.zeta is not None:
                fr.rayleigh_from_ratios(rayleigh.zeta, rayleigh.f1, rayleigh.f2)
            else:
                fr.rayleigh(rayleigh.a0 or 0.0, rayleigh.a1 or 0.0)
    modal = document.damping.modal if document.damping is not None else None
    if modal is not None:
        with _at("damping.modal"):
            fr.modal_damping(modal.zeta, modal.modes)
    if document.analysis.p_delta:
        gravity = document.loads.gravity
        if gravity is None:
            raise Problems(["analysis.p_delta = true: needs [loads.gravity] (the axial forces of P-Delta "
                            "are those of the gravity load)"])
        with _at("analysis.p_delta"):
            fr.p_delta(g=_gravity_value(document), direction=gravity.direction)
    with _at("structure"):
        return fr.build()


def _gravity_value(document: ModelFile) -> float:
    """``g`` of ``[loads.gravity]`` in the model's units."""
    units, g = document.units, document.loads.gravity.g
    return STANDARD_GRAVITY * TIME_UNITS[units.time] ** 2 / length_factor(units.length) if g == "standard" else g


def _mass_factor(units) -> float:
    """Factor from ``units.mass`` to the consistent mass unit force time^2/length (1 without it)."""
    if units.mass is None:
        return 1.0
    consistent_kg = force_factor(units.force) * TIME_UNITS[units.time] ** 2 / length_factor(units.length)
    return mass_factor(units.mass) / consistent_kg


def _add_element(fr: Frame2D, e, to_mass=1.0) -> None:
    match e:
        case Beam():
            fr.beam(e.name, e.node_i, e.node_j, e.E, e.A, e.I, axial_strain=e.axial_strain, curvature=e.curvature,
                    rho=None if e.rho is None else e.rho * to_mass)
        case Bar():
            fr.bar(e.name, e.node_i, e.node_j, e.E, e.A, axial_strain=e.axial_strain)
        case Spring():
            fr.spring(e.name, e.node_i, e.k, j=e.node_j, direction=e.direction)
        case Dashpot():
            fr.dashpot(e.name, e.node_i, e.c, j=e.node_j, direction=e.direction)
        case Soil():
            fr.soil(e.name, e.node, e.k, c=e.c, direction=e.direction, gap=e.gap, capacity=e.capacity, mu=e.mu,
                    kt=e.kt, ct=e.ct)
        case Gap():
            fr.gap(e.name, e.node_i, e.node_j, e.k, gap=e.gap, c=e.c, direction=e.direction, mu=e.mu, kt=e.kt,
                   ct=e.ct)
        case Cable():
            fr.cable(e.name, e.node_i, e.node_j, e.E, e.A, slack=e.slack, capacity=e.capacity)
        case YieldLink():
            fr.yield_link(e.name, e.node, e.node_j, k=e.k, Fy=e.Fy, Fy_t=e.Fy_t, Fy_c=e.Fy_c, direction=e.direction,
                          hardening=e.hardening)
        case Hinge():
            fr.hinge(e.name, e.beam, e.end, My=e.My, k=e.k, hardening=e.hardening)
        case Slider():
            fr.slider(e.name, e.node, mu=e.mu, N=e.N, k=e.k, direction=e.direction)


# ---------------------------------------------------------------------- loads
def _build_load(document: ModelFile, folder: Path, model: Model, structure: Structure | None) -> LoadHistory:
    """Gravity, nodal loads times their time functions and ground motions ``-M r a_g(t)``."""
    units = document.units
    seconds = TIME_UNITS[units.time]
    to_model = seconds ** 2 / length_factor(units.length)        # m/s^2 -> length/time^2
    constant = np.zeros(model.n)
    gravity = document.loads.gravity
    if gravity is not None:
        constant += structure.gravity(_gravity_value(document), gravity.direction)
    terms = _nodal_terms(document.loads.nodal, folder, model, structure)
    for k, load in enumerate(document.loads.distributed):
        parts = ("loads", "distributed", k)
        with _at(key_path((*parts, "beam"))):
            vector = structure.distributed_load(load.beam, wx=load.wx, wy=load.wy)
        terms.append((vector, _time_function(load.time_function, (*parts, "time_function"), folder)))
    for k, motion in enumerate(document.loads.ground_motion):
        parts = ("loads", "ground_motion", k)
        if structure is not None:
            r = np.array([1.0 if dof == motion.direction else 0.0 for _, dof in structure.dofs.free])
        else:
            r = read_vector((*parts, "influence"), motion.influence, folder, model.n)
        options = {key: getattr(motion, key) for key in ("units", "dt", "skip_header")
                   if getattr(motion, key) is not None}
        with _at(key_path((*parts, "file"))):
            record = read_record(folder / motion.file, **options)
        acceleration = record.acceleration
        if motion.at != "surface":              # the free-field surface motion of [site]
            wave = motion.wave or ("P" if motion.direction == "uy" else "S")
            layers, base = _site_profile(document)
            with _at(key_path((*parts, "at"))):
                acceleration = free_field(acceleration, record.dt / seconds, layers, base, at=motion.at,
                                          depth=motion.depth, wave=wave)
        a_g = Tabulated(record.time / seconds, acceleration * (motion.scale * to_model))
        terms.append((-np.asarray(model.M @ r).ravel(), a_g))
    return LoadHistory(constant, tuple(terms))


def _nodal_terms(loads, folder: Path, model: Model, structure: Structure | None) -> list:
    """The ``(vector, f)`` terms of ``[[loads.nodal]]``: one per distinct time function, assembled at once."""
    groups: dict = {}
    for k, load in enumerate(loads):
        groups.setdefault(load.time_function, []).append(k)
    terms = []
    for spec, indices in groups.items():
        if structure is not None:
            vector = _frame_nodal_vector(structure, loads, indices)
        else:
            rows = [dof_index(model, ("loads", "nodal", k, "dof"), loads[k].dof) for k in indices]
            vector = np.bincount(rows, weights=[loads[k].value for k in indices], minlength=model.n)
        terms.append((vector, _time_function(spec, ("loads", "nodal", indices[0], "time_function"), folder)))
    return terms


def _frame_nodal_vector(structure: Structure, loads, indices) -> np.ndarray:
    """The sum (n,) of the frame's nodal loads ``loads[k]``, ``k`` in ``indices``.

    A component on a DOF that cannot move is reported by ``Structure.nodal_load`` with its key path.
    """
    dofs = structure.dofs
    movable = np.diff(sp.csr_matrix(dofs.T).indptr) > 0
    rows, values, owners = [], [], []
    for k in indices:
        for dof in ("ux", "uy", "rz"):
            value = getattr(loads[k], dof)
            if value:
                rows.append(dofs.full_index(loads[k].node, dof))
                values.append(value)
                owners.append(k)
    stuck = [k for k, row in zip(owners, rows) if not movable[row]]
    if stuck:
        load = loads[stuck[0]]
        with _at(key_path(("loads", "nodal", stuck[0]))):
            structure.nodal_load(load.node, ux=load.ux or 0.0, uy=load.uy or 0.0, rz=load.rz or 0.0)
    return dofs.gather(np.bincount(np.asarray(rows, dtype=int), weights=values, minlength=dofs.T.shape[0]))


def _time_function(spec, parts, folder: Path):
    """The :mod:`unilateral.loads` time function (peak 1) of a ``time_function`` table."""
    with _at(key_path(parts)):
        match spec:
            case RectangularPulse():
                return Rectangular(1.0, t_start=spec.t_start, t_end=spec.t_end)
            case HalfSinePulse():
                return HalfSine(1.0, t_start=spec.t_start, duration=spec.duration)
            case TriangularPulse():
                return Triangular(1.0, t_start=spec.t_start, t_peak=spec.t_peak, t_end=spec.t_end)
            case ConstantLoad():
                return Constant(1.0)
            case RampLoad():
                return Ramp(spec.t_ramp, 1.0)
            case TableLoad():
                return Tabulated.from_csv(folder / spec.file, time_column=spec.time_column,
                                          value_column=spec.value_column, outside=spec.outside,
                                          skip_header=spec.skip_header)


def _figure(document: ModelFile) -> dict | None:
    figure = document.output.figure
    if figure is None:
        return None
    unit = "rad" if figure.dof == "rz" else document.units.length
    label = figure.label or f"{figure.dof} of node {figure.node} ({unit})"
    return {"node": figure.node, "dof": figure.dof, "label": label}
