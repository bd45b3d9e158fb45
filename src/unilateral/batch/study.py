"""Read a study file: TOML -> validated document -> checks -> the list of analyses.

:func:`load_study` is the entry point. It reads and validates the study file, reads every model
file once, applies the changed values and the parameter sweeps (by key path) and builds every
model variant (which checks it, and gives its first period ``T1``), lists the records, works out
the scale factor of every record at every intensity level, and names every analysis by a hash of
everything its result depends on. Every problem is reported as a :class:`StudyFileError` with
one line ``<file>: <key path> = <value>: <what is wrong> (<what is valid>)`` per problem, as for
model files.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from pydantic import ValidationError

from ..modelfile import ModelFileError, build_model_spec
from ..modelfile.build import read_toml
from ..modelfile.errors import Problems, key_path, toml_value, translate, value_problem
from .checks import PAIR_DIRECTIONS, check_quantities, lcp_option_problems, quantity_columns, static_problems
from .estimate import RECORD_SUFFIXES, combinations, size_problems, study_size
from .keypath import KeyPathError, PlainErrors, set_key_path
from .keys import AnalysisKeys
from .schema import StudyFile

TIME_UNITS = {"s": 1.0, "ms": 1e-3}
HORIZONTAL = {2: ("ux",), 3: ("ux", "uy")}
"""The horizontal ground motion directions of a 2-D and of a 3-D frame (the others are vertical)."""


class StudyFileError(ModelFileError):
    """An invalid study file; one line ``<file>: <problem>`` per problem (a ``ValueError``)."""


def package_version() -> str:
    from .. import __version__

    return __version__


def sha256_file(path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def sha256_json(obj) -> str:
    text = json.dumps(obj, sort_keys=True, separators=(",", ":"), default=str, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()


# ---------------------------------------------------------------------- the pieces of a study
@dataclass
class Record:
    """A ground-motion record of the study (a file, synthetic by seed, or a pair of files).

    A pair (``kind = "pair"``, from ``[records] pairs``) is one record of the study made of 2 or 3
    components, each a file applied along its direction (``directions``), the horizontal ones
    rotated in plan by ``angle`` (degrees); its ``motion`` is the tuple of their GroundMotions.
    """

    name: str
    kind: str                         # "file", "synthetic" or "pair"
    path: Path | None
    options: dict                     # reader options (files) or generator arguments (synthetic)
    digest: str                       # content hash (of a pair: its components, directions and angle)
    motion: object = None             # the GroundMotion (a pair: a tuple of them), when read on the client
    error: str | None = None          # why it cannot be read (its analyses fail without running)
    components: list = field(default_factory=list)   # pair: [{"file", "path", "digest"}, ...]
    directions: tuple = ()            # pair: the direction of each component
    angle: float = 0.0                # pair: the plan rotation of the horizontal components [deg]

    def payload(self) -> dict:
        out = {"name": self.name, "kind": self.kind, "path": None if self.path is None else str(self.path),
               "options": self.options, "digest": self.digest}
        if self.kind == "pair":
            out.update(components=self.components, directions=list(self.directions), angle=self.angle)
        return out

    @property
    def samples_key(self) -> str:
        """The key of the record's samples among the inputs sent to the workers: the digest, or of a
        pair the digest of its components alone (the pair at several angles is sent once)."""
        if self.kind != "pair":
            return self.digest
        return sha256_json({"pair": [c["digest"] for c in self.components]})

    def ground(self) -> dict | None:
        """How a pair's components enter the model (``{"directions", "angle"}``), None for a record."""
        return {"directions": list(self.directions), "angle": self.angle} if self.kind == "pair" else None


@dataclass
class Variant:
    """A model file with its changed values and one combination of the swept parameters."""

    index: int
    model: str                        # the model's name
    model_index: int
    path: Path
    overrides: list                   # [(key path, value), ...], applied in order
    parameters: dict                  # swept key path -> value
    digest: str                       # model file and the files it references
    file_digest: str                  # the model file alone (checked again when its analyses start)
    ground_motion: dict               # {"direction": ...} or {"influence": path, "digest": ...}
    settings: dict                    # dt, t_end, method, rule, lcp, initial
    T1: float = math.nan              # first period with every constraint bilateral [s]
    constraint_names: list = field(default_factory=list)
    spec: object = field(default=None, repr=False)    # the built ModelSpec (client side)


@dataclass
class Analysis:
    """One analysis: a variant, a record and an intensity level."""

    key: str
    index: int
    variant: Variant
    record: Record | None
    level: int
    intensity: float
    scale: float
    record_intensity: float           # intensity measure of the unscaled record (units of [scaling])
    settings: dict
    payload: dict
    error: str | None = None

    def inputs(self) -> dict:
        """The inputs of the analysis as a flat dict (one row of the study table)."""
        row = {"key": self.key, "model": self.variant.model, "variant": self.variant.index,
               "record": "" if self.record is None else self.record.name}
        if self.record is not None and self.record.kind == "pair":
            row.update(record_files="; ".join(c["file"] for c in self.record.components),
                       directions=" ".join(self.record.directions), angle=self.record.angle)
        row.update({"level": self.level, "intensity": self.intensity, "scale": self.scale,
                    "record_intensity": self.record_intensity, "T1": self.variant.T1, "dt": self.settings["dt"],
                    "t_end": self.settings["t_end"], "method": self.settings["method"]})
        for name, value in self.variant.parameters.items():
            row[f"param.{name}"] = value
        return row


@dataclass
class Study:
    """A study file read and expanded: its variants, records and analyses."""

    source: Path
    document: StudyFile
    variants: list
    records: list
    analyses: list
    quantity_columns: list
    intensity_label: str
    size: object = None               # the StudySize counted before the study was expanded

    @property
    def title(self) -> str:
        return self.document.title


# ---------------------------------------------------------------------- reading
def read_study_document(source: Path) -> tuple[StudyFile, dict]:
    data = read_toml(source)
    try:
        return StudyFile.model_validate(data), data
    except ValidationError as exc:
        raise Problems(translate(PlainErrors(exc, data), data, StudyFile)) from None


def load_study(path, *, announce=None) -> Study:
    """Read, check and expand the study file ``path`` (TOML; see ``docs/study-file.md``).

    The analyses are counted first (:func:`unilateral.batch.estimate.study_size`, from the file
    alone) and a study whose reading would not fit in memory is refused before anything is built;
    ``announce(size)``, if given, is called with that :class:`~unilateral.batch.estimate.StudySize`
    before the variants are built (``unilateral batch`` prints :meth:`StudySize.describe`).

    Raises
    ------
    StudyFileError
        One line ``<file>: <key path> = <value>: <problem> (<what is valid>)`` per problem.
    """
    source = Path(path)
    try:
        document, _ = read_study_document(source)
        return _expand(document, source, announce)
    except Problems as exc:
        raise StudyFileError(path, exc.problems) from None


def _expand(doc: StudyFile, source: Path, announce=None) -> Study:
    folder = source.parent
    problems = static_problems(doc, folder)
    size = study_size(doc, folder)
    problems = problems or size_problems(size)       # counted, nothing built: refused before any allocation
    if problems:
        raise Problems(problems)
    if announce is not None:
        announce(size)
    records = _records(doc, folder)
    variants = _variants(doc, folder)
    problems = lcp_option_problems(doc, variants)
    if problems:
        raise Problems(problems)
    check_quantities(doc, variants)
    scaling = doc.scaling
    need_motion = doc.records is not None and (
        (scaling is not None and scaling.measure != "factor") or doc.analysis.t_end == "record")
    if need_motion:
        _read_records(records, doc)
    levels = list(scaling.values) if scaling is not None else [1.0]
    analyses = []
    quantities = [q.model_dump() for q in doc.quantities]       # one list shared by every payload
    for variant in variants:
        keys = AnalysisKeys(variant.digest, variant.overrides, variant.ground_motion, quantities, package_version())
        for record in records or [None]:
            for level, value in enumerate(levels):
                analyses.append(_analysis(len(analyses), doc, (variant, keys, quantities), record, level, value))
    return Study(source=source, document=doc, variants=variants, records=records, analyses=analyses,
                 quantity_columns=quantity_columns(doc, variants), intensity_label=_intensity_label(doc), size=size)


def _intensity_label(doc: StudyFile) -> str:
    scaling = doc.scaling
    if scaling is None or scaling.measure == "factor":
        return "scale factor"
    if scaling.measure == "pga":
        return f"PGA [{scaling.units}]"
    period = "T1" if scaling.period == "T1" else f"{scaling.period:g} s"
    return f"Sa({period}, {100 * scaling.damping:g}%) [{scaling.units}]"


def pair_directions(rec, count: int) -> tuple:
    """The directions of the components of a pair of ``count`` files: ``[records] directions`` or the default."""
    return tuple(rec.directions) if rec.directions is not None else PAIR_DIRECTIONS[count]


# ---------------------------------------------------------------------- records
def _records(doc: StudyFile, folder: Path) -> list[Record]:
    rec = doc.records
    if rec is None:
        return []
    files = []
    if rec.folder is not None:
        files += sorted(p for p in (folder / rec.folder).iterdir()
                        if p.is_file() and p.suffix.lower() in RECORD_SUFFIXES and not p.name.startswith("."))
        if not files:
            raise Problems([value_problem(("records", "folder"), rec.folder,
                                           f"no records in the folder (files ending in "
                                           f"{', '.join(s.upper() if s == '.at2' else s for s in RECORD_SUFFIXES)})")])
    files += [folder / name for name in rec.files]
    problems = []
    out = []
    names = {}
    for path in files:
        options = _reader_options(rec, path, problems)
        name = path.stem
        if name in names:
            name = f"{path.stem}{path.suffix}"
        names[name] = path
        digest = sha256_json({"file": sha256_file(path), "options": options})
        out.append(Record(name=name, kind="file", path=path.resolve(), options=options, digest=digest))
    out += _pair_records(rec, folder, problems)
    if rec.synthetic is not None:
        syn = rec.synthetic
        for seed in syn.seeds:
            options = {"duration": syn.duration, "dt": syn.dt, "pga": syn.pga, "seed": seed, "f_g": syn.f_g,
                       "zeta_g": syn.zeta_g, "envelope": syn.envelope}
            out.append(Record(name=f"synthetic-{seed}", kind="synthetic", path=None, options=options,
                              digest=sha256_json({"synthetic": options})))
    seen = {}
    for k, record in enumerate(out):
        if record.name in seen:
            problems.append(f"records: two records named {toml_value(record.name)} (every record needs a "
                            "different name: file stems, synthetic-<seed> and the first file stems of pairs)")
        seen.setdefault(record.name, k)
    if problems:
        raise Problems(problems)
    return out


def _reader_options(rec, path: Path, problems: list) -> dict:
    """The reader options of the record file ``path`` (none for .AT2); a missing ``units`` into ``problems``."""
    if path.suffix.lower() == ".at2":
        return {}
    if rec.units is None:
        problems.append(f"records.units: missing key (the plain-text record {path.name} needs the units of "
                        'its values, e.g. units = "g" or "cm/s2")')
    return {k: v for k, v in (("units", rec.units), ("dt", rec.dt), ("skip_header", rec.skip_header)) if v is not None}


def _pair_records(rec, folder: Path, problems: list) -> list[Record]:
    """The records of ``[records] pairs``: one per pair and angle, named by the first file's stem (both
    stems joined if two pairs start with files of the same stem; ``@<angle>`` with several angles)."""
    angles = rec.angle if isinstance(rec.angle, list) else [0.0 if rec.angle is None else rec.angle]
    firsts = [Path(pair[0]).stem for pair in rec.pairs]
    out = []
    for pair in rec.pairs:
        paths = [folder / name for name in pair]
        components = []
        for name, path in zip(pair, paths):
            options = _reader_options(rec, path, problems)
            components.append({"file": name, "path": str(path.resolve()), "options": options,
                               "digest": sha256_json({"file": sha256_file(path), "options": options})})
        stem = paths[0].stem
        name = stem if firsts.count(stem) == 1 else "+".join(p.stem for p in paths)
        directions = pair_directions(rec, len(pair))
        for angle in angles:
            angle = float(angle)
            digest = sha256_json({"pair": [c["digest"] for c in components], "directions": directions,
                                  "angle": angle})
            out.append(Record(name=name if len(angles) == 1 else f"{name}@{angle:g}", kind="pair", path=None,
                              options={}, digest=digest, components=components, directions=directions,
                              angle=angle))
    return out


def read_study_record(payload: dict):
    """The GroundMotion of a record payload (``Record.payload()``), in m/s^2; of a pair the tuple of
    its components' GroundMotions."""
    from ..loads import read_record, synthetic_accelerogram

    if payload["kind"] == "synthetic":
        return synthetic_accelerogram(**payload["options"])
    if payload["kind"] == "pair":
        return tuple(read_record(c["path"], **c["options"]) for c in payload["components"])
    return read_record(payload["path"], **payload["options"])


def _read_records(records: list[Record], doc: StudyFile) -> None:
    read = {}                                       # samples_key -> motion or error (a pair at several angles)
    for record in records:
        if record.samples_key not in read:
            try:
                read[record.samples_key] = (read_study_record(record.payload()), None)
            except (ValueError, OSError, TypeError) as exc:
                read[record.samples_key] = (None, f"cannot read the record: {exc}")
        record.motion, record.error = read[record.samples_key]


# ---------------------------------------------------------------------- model variants
def _parameter_site(doc: StudyFile, key: str, value) -> tuple:
    for k, parameter in enumerate(doc.parameters):
        if parameter.key == key:
            for j, v in enumerate(parameter.values):
                if v == value:
                    return ("parameters", k, "values", j)
            return ("parameters", k, "values")
    return ("parameters",)


def _variants(doc: StudyFile, folder: Path) -> list[Variant]:
    problems = []
    variants = []
    combos = combinations(doc)
    for k, entry in enumerate(doc.models):
        path = (folder / entry.file)
        name = entry.name or Path(entry.file).stem
        try:
            base = read_toml(path)
        except Problems as exc:
            problems.append(value_problem(("models", k, "file"), entry.file,
                                          f"cannot read the model file ({'; '.join(exc.problems)})"))
            continue
        ground = _ground_motion(doc, base, folder, path, k)
        if isinstance(ground, (str, list)):
            problems += [ground] if isinstance(ground, str) else ground
            continue
        study_settings = [(f"analysis.{key}", value) for key, value in
                          doc.analysis.model_dump(include={"dt", "method", "rule", "lcp", "initial"}).items()
                          if value is not None]
        if isinstance(doc.analysis.t_end, float):
            study_settings.append(("analysis.t_end", doc.analysis.t_end))
        head = [("loads.ground_motion", [])] if doc.records is not None else []
        model_sets = list(entry.set.items())
        prefix = copy.deepcopy(base)
        base_problem = False
        for j, (key, value) in enumerate(head + study_settings + model_sets):
            try:
                set_key_path(prefix, key, value)
            except KeyPathError as exc:
                problems.append(f'{key_path(("models", k, "set"))}."{key}": {exc}'
                                if j >= len(head) + len(study_settings) else f"models[{k}] ({entry.file}): {exc}")
                base_problem = True
        if base_problem:
            continue
        file_digest = sha256_file(path)
        for combo in combos:
            data = copy.deepcopy(prefix)
            overrides = head + study_settings + model_sets + list(combo.items())
            bad = False
            for key, value in combo.items():       # the sweep wins over the model's set
                try:
                    set_key_path(data, key, value)
                except KeyPathError as exc:
                    site = _parameter_site(doc, key, value)[:2] + ("key",)
                    problems.append(f"{key_path(site)} = {toml_value(key)}: in model {name} ({entry.file}): {exc}")
                    bad = True
            if bad:
                continue
            try:
                spec = build_model_spec(data, path)
            except ModelFileError as exc:
                if len(combo) == 1:
                    (key, value), = combo.items()
                    where = f"{key_path(_parameter_site(doc, key, value))} = {toml_value(value)}: "
                else:
                    where = "".join(f"with {', '.join(f'{k} = {toml_value(v)}' for k, v in combo.items())}: "
                                    for _ in [0] if combo)
                problems += [f"{where}models[{k}] ({entry.file}): {p}" for p in exc.problems]
                continue
            settings = {key: spec.analysis[key] for key in ("dt", "t_end", "method", "rule", "lcp", "initial")}
            seconds = TIME_UNITS[spec.units["time"]]
            try:
                from ..analysis.response_spectrum import first_period

                T1 = first_period(spec.model) * seconds
            except Exception:                                   # noqa: BLE001 - T1 is informative only
                T1 = math.nan
            digest = sha256_json({"file": file_digest, "refs": _referenced_digests(data, path.parent)})
            variants.append(Variant(index=len(variants), model=name, model_index=k, path=path.resolve(),
                                    overrides=overrides, parameters=dict(combo), digest=digest,
                                    file_digest=file_digest, ground_motion=ground, settings=settings, T1=T1,
                                    constraint_names=list(spec.model.constraint_names), spec=spec))
    if problems:
        raise Problems(list(dict.fromkeys(problems)))
    return variants


def _ground_motion(doc: StudyFile, base: dict, folder: Path, model_path: Path, k: int):
    """How the study's records enter model ``k``: a direction (frames) or an influence vector."""
    if doc.records is None:
        return {}
    frame = "matrices" not in base
    if doc.records.pairs:
        return _pair_ground(doc.records, base, model_path) if frame else [value_problem(
            ("records", "pairs"), doc.records.pairs, f"the matrix-level model {model_path.name} has no directions to "
            "apply the components of a pair along (pairs are for frames; give files with influence)")]
    motions = (base.get("loads") or {}).get("ground_motion") or []
    first = motions[0] if motions and isinstance(motions[0], dict) else {}
    if frame:
        direction = doc.records.direction or first.get("direction")
        if direction not in ("ux", "uy"):
            return (f"records.direction: missing key (model {model_path.name} has no ground motion to take the "
                    'direction from; give direction = "ux" or "uy")')
        return {"direction": direction}
    if doc.records.influence is not None:
        influence = (folder / doc.records.influence).resolve()
    elif first.get("influence"):
        influence = (model_path.parent / first["influence"]).resolve()
    else:
        return (f"records.influence: missing key (the matrix-level model {model_path.name} has no ground motion "
                "to take the influence vector r from)")
    if not influence.is_file():
        return f"models[{k}]: influence file not found (looked for {influence})"
    return {"influence": str(influence), "digest": sha256_file(influence)}


def _pair_ground(rec, base: dict, model_path: Path):
    """``{"pairs": dimensions}`` of a frame under the pairs of ``rec``, or the problems of the pairs'
    directions and angle with it (a 2-D frame: directions ux and uy, no angle)."""
    frame = base.get("frame")
    dimensions = 3 if isinstance(frame, dict) and frame.get("dimensions") == 3 else 2
    valid = PAIR_DIRECTIONS[dimensions]
    problems = []
    what = f"model {model_path.name} is a {dimensions}-D frame"
    if rec.directions is not None:
        bad = [d for d in rec.directions if d not in valid]
        if bad:
            problems.append(value_problem(("records", "directions"), rec.directions,
                                          f"{toml_value(bad[0])} is not a ground motion direction of a 2-D frame "
                                          f"({what}; valid: {', '.join(valid)}: horizontal and vertical)"))
    else:
        for k, pair in enumerate(rec.pairs):
            if len(pair) > len(valid):
                problems.append(value_problem(("records", "pairs", k), pair,
                                              f"{len(pair)} files, but {what} with {len(valid)} ground motion "
                                              f"directions ({', '.join(valid)}): give {len(valid)} files"))
    if rec.angle is not None and dimensions == 2:
        problems.append(value_problem(("records", "angle"), rec.angle,
                                      f"a rotation in plan needs a 3-D frame ({what}: its pair is horizontal ux "
                                      "and vertical uy; leave angle out)"))
    return problems or {"pairs": dimensions}


def _referenced_digests(data, folder: Path) -> dict:
    """Hashes of the files a (changed) model file refers to: tables and matrices."""
    from .worker import file_references

    return {name: sha256_file(folder / name) for name in file_references(data) if (folder / name).is_file()}


# ---------------------------------------------------------------------- analyses
def _analysis(index: int, doc: StudyFile, shared: tuple, record: Record | None, level: int, value: float):
    """The analysis of ``record`` at level ``value``; ``shared``: ``(variant, its AnalysisKeys, the
    quantities)``, the parts common to the variant's analyses (encoded, and held, once)."""
    from ..loads import acceleration_factor

    variant, keys, quantities = shared
    scaling = doc.scaling
    t_end = variant.settings["t_end"]
    error = None if record is None else record.error
    record_im = math.nan
    scale = 1.0
    if scaling is None:
        intensity = 1.0
    elif scaling.measure == "factor":
        scale = intensity = float(value)
    else:
        intensity = float(value)
        if record.motion is not None:
            unit = acceleration_factor(scaling.units)
            if scaling.measure == "pga":
                record_im = _pga(record, variant) / unit
            else:
                period = variant.T1 if scaling.period == "T1" else scaling.period
                if math.isfinite(period):
                    record_im = _sa(record, variant, period, scaling.damping) / unit
                else:
                    error = error or "no first period T1 for Sa(T1) (the model has no mode with mass)"
            if math.isfinite(record_im) and record_im > 0:
                scale = intensity / record_im
            elif error is None:
                error = f"the record's intensity is {record_im:g}: it cannot be scaled to {intensity:g}"
    if doc.analysis.t_end == "record" and record is not None:
        if record.motion is not None:
            seconds = TIME_UNITS[variant.spec.units["time"]]
            duration = max(m.duration for m in _components(record))       # a pair: its longest component
            t_end = (duration + doc.analysis.t_after) / seconds
        else:
            t_end = math.nan
    base = dict(variant.settings, lcp_options=dict(doc.analysis.lcp_options), timeout=doc.analysis.timeout)
    settings, text = keys.settings(base, t_end)
    key = keys.key(None if record is None else record.digest, scale, text)     # sha256_json of the ident
    payload = {"key": key, "variant": variant.index, "record": None if record is None else record.samples_key,
               "scale": scale, "settings": settings, "quantities": quantities}
    if record is not None and record.kind == "pair":
        payload["ground"] = record.ground()
    return Analysis(key=key, index=index, variant=variant, record=record, level=level, intensity=intensity,
                    scale=scale, record_intensity=record_im, settings=settings, payload=payload, error=error)


_SA_CACHE: dict = {}


def _components(record: Record) -> list:
    """``[GroundMotion]`` of a record read on the client: its motion, or the components of a pair."""
    return list(record.motion) if record.kind == "pair" else [record.motion]


def _horizontal(record: Record, variant: Variant) -> list:
    """``[(digest, GroundMotion)]`` of the components of ``record`` that scale it: the record itself, or
    the components of a pair along a horizontal direction of the variant's frame (ux, uy in 3-D; ux in
    2-D), as recorded (whatever the pair's angle)."""
    if record.kind != "pair":
        return [(record.digest, record.motion)]
    horizontal = HORIZONTAL[variant.ground_motion["pairs"]]
    return [(c["digest"], motion) for c, motion, direction in zip(record.components, record.motion,
                                                                 record.directions) if direction in horizontal]


def _pga(record: Record, variant: Variant) -> float:
    """PGA of a record [m/s^2]; of a pair the larger PGA of its horizontal components."""
    return max(motion.pga for _, motion in _horizontal(record, variant))


def _sa(record: Record, variant: Variant, period: float, zeta: float) -> float:
    """Sa(period, zeta) of a record [m/s^2]; of a pair the geometric mean of its horizontal components'
    (Sa_GM, e.g. Baker & Cornell 2006)."""
    values = [_sa_cached(digest, motion, period, zeta) for digest, motion in _horizontal(record, variant)]
    return values[0] if len(values) == 1 else math.sqrt(values[0] * values[1])


def _sa_cached(digest: str, motion, period: float, zeta: float) -> float:
    from ..analysis.response_spectrum import response_spectrum

    key = (digest, float(period), float(zeta))
    if key not in _SA_CACHE:
        _SA_CACHE[key] = response_spectrum(motion, period, zeta)
    return _SA_CACHE[key]
