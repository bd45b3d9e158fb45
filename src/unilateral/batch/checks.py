"""The checks of a study document: those that need no model (the files, key paths, sweeps,
scaling and quantities of the document) and those against the model variants once built (the
options of their LCP solvers, the elements, nodes and DOFs the quantities name).

Each problem is one line ``<key path> = <value>: <what is wrong> (<what is valid>)``, collected
for :class:`~unilateral.batch.study.StudyFileError`.
"""

from __future__ import annotations

from pathlib import Path

from ..modelfile.errors import Problems, did_you_mean, key_path, toml_value, value_problem
from .collapse import collapse_problems
from .footing_quantity import footing_names, footing_problems
from .keypath import KeyPathError, parse_key_path
from .schema import StudyFile

MAX_RECORD_SAMPLES = 10_000_000
"""Most samples (duration / dt) of a synthetic record."""
MAX_ACCELERATION_G = 100.0
"""Largest target intensity (PGA or Sa) of ``[scaling]``, in g: beyond it a study is a typo."""
MAX_SCALE_FACTOR = 1e4
"""Largest scale factor of ``[scaling] measure = "factor"``."""
PAIR_DIRECTIONS = {2: ("ux", "uy"), 3: ("ux", "uy", "uz")}
"""Default ``[records] directions`` of a pair of 2 and of 3 files (x, y[, vertical])."""


# ---------------------------------------------------------------------- checks without the models
def static_problems(doc: StudyFile, folder: Path) -> list[str]:
    """The problems of the document ``doc`` found without building a model: its model files and
    their ``set`` keys, its records and scaling, its parameter sweeps and its quantities (the
    files looked for in ``folder``, the study file's)."""
    return (_model_file_problems(doc, folder) + _record_problems(doc, folder) + _parameter_problems(doc)
            + _quantity_problems(doc))


def _model_file_problems(doc: StudyFile, folder: Path) -> list[str]:
    """``[[models]]``: files not found, names given twice, ``set`` keys that are no key paths."""
    problems = []
    names = {}
    for k, entry in enumerate(doc.models):
        if not (folder / entry.file).is_file():
            problems.append(value_problem(("models", k, "file"), entry.file,
                                          f"file not found (looked for {folder / entry.file})"))
        name = entry.name or Path(entry.file).stem
        if name in names:
            problems.append(value_problem(("models", k, "name"), name,
                                          f"duplicate model name (also models[{names[name]}]; give name = ...)"))
        names.setdefault(name, k)
        for key in entry.set:
            try:
                parse_key_path(key)
            except KeyPathError as exc:
                problems.append(f'{key_path(("models", k, "set"))}."{key}": {exc}')
    return problems


def _record_problems(doc: StudyFile, folder: Path) -> list[str]:
    """``[records]`` (files and folder, units, influence, pairs, a synthetic record), ``[scaling]``
    and ``t_end = "record"``."""
    from ..loads import acceleration_factor

    problems = []
    rec = doc.records
    if rec is not None:
        if rec.folder is not None and not (folder / rec.folder).is_dir():
            problems.append(value_problem(("records", "folder"), rec.folder,
                                          f"folder not found (looked for {folder / rec.folder})"))
        for k, name in enumerate(rec.files):
            if not (folder / name).is_file():
                problems.append(value_problem(("records", "files", k), name,
                                              f"file not found (looked for {folder / name})"))
        if rec.units is not None:
            try:
                acceleration_factor(rec.units)
            except ValueError as exc:
                problems.append(value_problem(("records", "units"), rec.units, str(exc)))
        if rec.influence is not None and not (folder / rec.influence).is_file():
            problems.append(value_problem(("records", "influence"), rec.influence,
                                          f"file not found (looked for {folder / rec.influence})"))
        problems += _pair_problems(rec, folder)
    if rec is not None and rec.synthetic is not None:
        problems += _synthetic_problems(rec.synthetic)
    if doc.scaling is not None:
        if rec is None:
            problems.append("scaling: needs [records] (the levels scale the records)")
        try:
            acceleration_factor(doc.scaling.units)
        except ValueError as exc:
            problems.append(value_problem(("scaling", "units"), doc.scaling.units, str(exc)))
        else:
            problems += _intensity_problems(doc.scaling)
    if doc.analysis.t_end == "record" and rec is None:
        problems.append(value_problem(("analysis", "t_end"), "record", 'needs [records] (or give a number)'))
    return problems


def _parameter_problems(doc: StudyFile) -> list[str]:
    """``[[parameters]]``: keys that are no key paths or swept twice, groups of unequal lengths."""
    problems = []
    groups = {}
    for k, parameter in enumerate(doc.parameters):
        try:
            parse_key_path(parameter.key)
        except KeyPathError as exc:
            problems.append(value_problem(("parameters", k, "key"), parameter.key, str(exc)))
        group = parameter.group or f"#{k}"
        if group in groups and len(doc.parameters[groups[group]].values) != len(parameter.values):
            first = groups[group]
            problems.append(f"{key_path(('parameters', k, 'values'))}: {len(parameter.values)} values, but "
                            f"parameters[{first}] of the same group {toml_value(parameter.group)} has "
                            f"{len(doc.parameters[first].values)} (a group is varied together: equal lengths)")
        groups.setdefault(group, k)
        keys = [p.key for p in doc.parameters[:k]]
        if parameter.key in keys:
            problems.append(value_problem(("parameters", k, "key"), parameter.key,
                                          f"swept twice (also parameters[{keys.index(parameter.key)}])"))
    return problems


def _quantity_problems(doc: StudyFile) -> list[str]:
    """``[[quantities]]``: names given twice, keys missing or not used by the quantity's type,
    drift storeys of one node."""
    problems = []
    seen = {}
    for k, quantity in enumerate(doc.quantities):
        if quantity.name in seen:
            problems.append(value_problem(("quantities", k, "name"), quantity.name,
                                          f"duplicate quantity name (also quantities[{seen[quantity.name]}])"))
        seen.setdefault(quantity.name, k)
        for key in quantity.NEEDS.get(quantity.type, ()):
            if getattr(quantity, key) is None:
                problems.append(f"{key_path(('quantities', k, key))}: missing key ({_article(quantity.type)} "
                                f"{quantity.type} quantity needs {' and '.join(quantity.NEEDS[quantity.type])}"
                                f"{', and node for a frame' if key == 'dof' and quantity.type != 'drift' else ''})")
        for key in ("elements", "node", "dof", "pairs", "measure"):
            if getattr(quantity, key) is not None and key not in quantity.USES[quantity.type]:
                uses = ", ".join(quantity.USES[quantity.type]) or "no other key"
                problems.append(value_problem(("quantities", k, key), getattr(quantity, key),
                                              f"not used by {_article(quantity.type)} {quantity.type} quantity "
                                              f"(it uses: {uses})"))
        if quantity.type == "drift" and quantity.pairs is not None:
            for j, (upper, lower) in enumerate(quantity.pairs):
                if upper == lower:
                    problems.append(value_problem(("quantities", k, "pairs", j), [upper, lower],
                                                  "the two nodes of a storey must differ"))
    return problems


def _pair_problems(rec, folder: Path) -> list[str]:
    """``[records] pairs`` and the keys that go with them (directions, angle): counts, files, directions."""
    problems = []
    if not rec.pairs:
        for key in ("directions", "angle"):
            if getattr(rec, key) is not None:
                problems.append(value_problem(("records", key), getattr(rec, key),
                                              "only with pairs (records of two or three components); a record "
                                              "of files, folder or synthetic takes direction"))
        return problems
    only = "a study of pairs takes its records from pairs only: put every record in a pair, or make two studies"
    why = {"direction": "give the direction of each component with directions = [...]",
           "influence": "pairs are for frames; a matrix-level model takes single records (files) with influence"}
    for key in ("folder", "files", "synthetic", "direction", "influence"):
        value = getattr(rec, key)
        if value is None or value == []:
            continue
        head = key_path(("records", key))
        if key != "synthetic":
            head += f" = {toml_value(value)}"
        problems.append(f"{head}: not with pairs ({why.get(key, only)})")
    for k, pair in enumerate(rec.pairs):
        if len(pair) not in PAIR_DIRECTIONS:
            problems.append(value_problem(("records", "pairs", k), pair, f"{len(pair)} file{'s' * (len(pair) != 1)}: "
                                          "a pair holds 2 or 3 files (x, y[, vertical])"))
            continue
        for j, name in enumerate(pair):
            if not (folder / name).is_file():
                problems.append(value_problem(("records", "pairs", k, j), name,
                                              f"file not found (looked for {folder / name})"))
        if len(set(pair)) < len(pair):
            problems.append(value_problem(("records", "pairs", k), pair, "the same file twice (each component "
                                          "of a pair is a file of its own)"))
    directions = rec.directions
    if directions is not None:
        repeated = [d for d in dict.fromkeys(directions) if directions.count(d) > 1]
        if repeated:
            problems.append(value_problem(("records", "directions"), directions,
                                          f"{toml_value(repeated[0])} twice (each component along a direction of "
                                          "its own: ux, uy, uz)"))
        for k, pair in enumerate(rec.pairs):
            if len(pair) in PAIR_DIRECTIONS and len(pair) != len(directions):
                problems.append(value_problem(("records", "directions"), directions,
                                              f"{len(directions)} direction{'s' * (len(directions) != 1)} for "
                                              f"the {len(pair)} files of pairs[{k}] "
                                              "(one direction per file, in the order of the files)"))
                break
    if isinstance(rec.angle, list) and len(set(rec.angle)) < len(rec.angle):
        problems.append(value_problem(("records", "angle"), rec.angle, "an angle twice (each angle once)"))
    return problems


def _synthetic_problems(syn) -> list[str]:
    """A synthetic record of more than ``MAX_RECORD_SAMPLES`` samples, refused before it is generated."""
    samples = syn.duration / syn.dt
    if samples <= MAX_RECORD_SAMPLES:
        return []
    gib = 8 * samples / 1024 ** 3
    return [value_problem(("records", "synthetic", "duration"), syn.duration,
                          f"with dt = {toml_value(syn.dt)} a record of {samples:.3g} samples (at least "
                          f"{gib:.3g} GiB per array of it): more than the {MAX_RECORD_SAMPLES:,} samples "
                          "allowed; shorten the duration or increase dt")]


def _intensity_problems(scaling) -> list[str]:
    """Intensity levels beyond ``MAX_ACCELERATION_G`` (targets) or ``MAX_SCALE_FACTOR`` (factors)."""
    from ..loads import STANDARD_GRAVITY, acceleration_factor

    if scaling.measure == "factor":
        limit, what = MAX_SCALE_FACTOR, f"a scale factor above {MAX_SCALE_FACTOR:g}"
    else:
        limit = MAX_ACCELERATION_G * STANDARD_GRAVITY / acceleration_factor(scaling.units)
        what = f"an acceleration above {MAX_ACCELERATION_G:g} g ({limit:g} {scaling.units})"
    return [value_problem(("scaling", "values", k), value, f"{what} is not a ground motion of this world; "
                          "check the value and scaling.units")
            for k, value in enumerate(scaling.values) if value > limit]


# ---------------------------------------------------------------------- checks against the model variants
def lcp_option_problems(doc: StudyFile, variants) -> list[str]:
    """``[analysis] lcp_options`` that the LCP solver of a model variant does not take."""
    from ..lcp import get_lcp_solver

    options = dict(doc.analysis.lcp_options)
    if not options:
        return []
    problems = []
    for lcp in dict.fromkeys(variant.settings["lcp"] for variant in variants):
        try:
            get_lcp_solver(lcp, **options)
        except (ValueError, TypeError) as exc:
            problems.append(value_problem(("analysis", "lcp_options"), options,
                                          f"not options of the LCP solver {toml_value(lcp)} ({exc})"))
    return problems


def quantity_columns(doc: StudyFile, variants) -> list[str]:
    """Names of the quantity columns of the table, in order."""
    columns = []
    for quantity in doc.quantities:
        if quantity.type in ("uplift", "contact_force", "footing") and quantity.over == "each":
            names = quantity.elements
            if names is None and quantity.type == "footing":
                names = list(dict.fromkeys(n for variant in variants for n in footing_names(variant.spec.structure)))
            elif names is None:                   # the contacts (plastic multipliers and slips left out)
                from .worker import contact_names

                names = []
                for variant in variants:
                    contacts = contact_names(getattr(variant.spec, "model", None), variant.constraint_names)
                    names += [n for n in contacts if n not in names]
            columns += [f"{quantity.name}.{n}" for n in names]
        else:
            columns.append(quantity.name)
    return columns


def check_quantities(doc: StudyFile, variants) -> None:
    """Raise :class:`~unilateral.modelfile.errors.Problems` for the quantities, limit states, collapse
    and IDA figure of ``doc`` that name an element, node, DOF or quantity no model variant has."""
    problems = []
    for variant in variants:
        spec = variant.spec
        where = f"in model {variant.model} ({variant.path.name})"
        ids = [node.id for node in spec.document.nodes]
        ys = {node.id: getattr(node, "z", node.y) for node in spec.document.nodes}      # elevations
        for k, q in enumerate(doc.quantities):
            if q.type == "footing":
                problems += footing_problems(k, q.elements, spec.structure, where)
                continue
            for j, name in enumerate(q.elements or []):
                if name not in variant.constraint_names:
                    problems.append(value_problem(("quantities", k, "elements", j), name,
                                                  f"no unilateral element {toml_value(name)} {where} (valid: "
                                                  f"{', '.join(variant.constraint_names) or 'none'})")
                                    + did_you_mean(name, variant.constraint_names))
            nodes = [("node", q.node)] if q.node is not None else []
            nodes += [(("pairs", j, i), n) for j, pair in enumerate(q.pairs or []) for i, n in enumerate(pair)]
            if spec.structure is None:
                if nodes:
                    problems.append(f"{key_path(('quantities', k, 'node'))}: {where}: a matrix-level model has no "
                                    "nodes (give dof = a DOF name)")
                elif q.dof is not None and q.dof not in spec.model.dof_names:
                    problems.append(value_problem(("quantities", k, "dof"), q.dof, f"no DOF {toml_value(q.dof)} "
                                                  f"{where}") + did_you_mean(q.dof, spec.model.dof_names))
                continue
            for part, node in nodes:
                parts = ("quantities", k, *(part if isinstance(part, tuple) else (part,)))
                if node not in ids:
                    from ..modelfile.errors import compact_ids

                    problems.append(value_problem(parts, node, f"no node {toml_value(node)} {where} (nodes are "
                                                  f"{compact_ids(ids)})"))
            if q.type in ("displacement", "residual") and q.node is None and q.dof is not None:
                problems.append(f"{key_path(('quantities', k, 'node'))}: missing key (a frame needs the node of "
                                f"dof {toml_value(q.dof)})")
            node_dofs = list(spec.structure.dofs.dof_names)
            if q.dof is not None and q.dof not in node_dofs:
                problems.append(value_problem(("quantities", k, "dof"), q.dof, 'unknown DOF of a frame node '
                                              f'(valid: {", ".join(node_dofs)})') + did_you_mean(q.dof, node_dofs))
            for j, pair in enumerate(q.pairs or []):
                if q.ratio and all(n in ys for n in pair) and ys[pair[0]] == ys[pair[1]]:
                    axis = "z" if len(node_dofs) == 6 else "y"
                    problems.append(value_problem(("quantities", k, "pairs", j), pair, f"both nodes at {axis} = "
                                                  f"{ys[pair[0]]:g} {where}: no storey height for the drift ratio "
                                                  "(give ratio = false for the drift itself)"))
    columns = quantity_columns(doc, variants)
    for k, limit in enumerate(doc.limit_states):
        if limit.quantity not in columns:
            problems.append(value_problem(("limit_states", k, "quantity"), limit.quantity,
                                          f"no such quantity (valid: {', '.join(columns)})")
                            + did_you_mean(limit.quantity, columns))
    problems += collapse_problems(doc, columns)
    ida = doc.figures.ida
    if ida is not None and ida not in columns:
        problems.append(value_problem(("figures", "ida"), ida, f"no such quantity (valid: {', '.join(columns)})")
                        + did_you_mean(ida, columns))
    if problems:
        raise Problems(list(dict.fromkeys(problems)))


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiou" else "a"
