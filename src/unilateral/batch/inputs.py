"""What the workers need, read once on the client: the model variants' text and the record samples.

The workers of a study read no file: :func:`study_inputs` reads every model file (with the files
it refers to, and the influence vector of a matrix-level model) and every record on the client,
and the runner sends them to the workers through Dask (``client.scatter``), once per study. A
worker builds a variant from its :func:`variant_source` (``unilateral.batch.worker``), so a
cluster needs no file system shared with the client.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .study import read_study_record, sha256_json


@dataclass
class StudyInputs:
    """The inputs of the analyses to run, keyed as the analyses' payloads name them.

    Attributes
    ----------
    variants : dict
        ``variant index -> variant source`` (:func:`variant_source`).
    records : dict
        ``record samples key -> GroundMotion`` (samples in m/s^2; ``Record.samples_key``, the
        record's digest), or of a pair of components the tuple of their GroundMotions (a pair
        swept over several angles is sent once).
    errors : dict
        ``analysis key -> message``: analyses whose model file or record could not be read (they
        are recorded as errors without running).
    """

    variants: dict = field(default_factory=dict)
    records: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)


def study_inputs(analyses) -> StudyInputs:
    """Read the model variants and the records of ``analyses`` (each once).

    Parameters
    ----------
    analyses : list of Analysis
        The analyses to run (``Analysis.error`` None).

    Returns
    -------
    StudyInputs
    """
    inputs = StudyInputs()
    failed_variants, failed_records = {}, {}
    for analysis in analyses:
        variant, record = analysis.variant, analysis.record
        if variant.index not in inputs.variants and variant.index not in failed_variants:
            try:
                inputs.variants[variant.index] = variant_source(variant)
            except ValueError as exc:
                failed_variants[variant.index] = str(exc)
            except OSError as exc:
                failed_variants[variant.index] = f"cannot read the model's files: {exc}"
        samples = None if record is None else record.samples_key
        if record is not None and samples not in inputs.records and samples not in failed_records:
            try:
                inputs.records[samples] = record_samples(record)
            except (OSError, ValueError, TypeError) as exc:
                failed_records[samples] = f"cannot read the record: {type(exc).__name__}: {exc}"
        message = failed_variants.get(variant.index) or (record is not None and failed_records.get(samples))
        if message:
            inputs.errors[analysis.key] = message
    return inputs


def variant_source(variant) -> dict:
    """Everything a worker needs to build a model variant, without reading a file.

    Returns
    -------
    dict
        ``digest`` (a hash of all the rest: the key of the workers' caches), ``path`` (the model
        file, for messages and as the folder of relative names; never read by a worker), ``text``
        (the model file), ``overrides`` (``[(key path, value), ...]``), ``files`` (``{name as
        written in the model file: bytes}`` of the files the changed model refers to),
        ``ground_motion`` (``{"direction": ...}``, or ``{"influence": file name}`` with
        ``influence`` the bytes of that Matrix Market file).

    Raises
    ------
    ValueError
        The model file changed since the study was read (its hash differs).
    OSError
        A file that cannot be read.
    """
    import hashlib

    from .worker import variant_data

    raw = Path(variant.path).read_bytes()
    if hashlib.sha256(raw).hexdigest() != variant.file_digest:
        raise ValueError(f"the model file {variant.path} has changed since the study was read; start it again")
    text = raw.decode("utf-8-sig")
    files = referenced_files(variant_data(text, variant.overrides), Path(variant.path).parent)
    ground = dict(variant.ground_motion)
    influence = None
    if "influence" in ground:
        influence = Path(ground["influence"]).read_bytes()
        ground = {"influence": Path(ground["influence"]).name, "digest": ground["digest"]}
    digest = sha256_json({"text": text, "overrides": variant.overrides, "ground_motion": ground,
                          "files": {name: hashlib.sha256(data).hexdigest() for name, data in files.items()}})
    return {"digest": digest, "path": str(variant.path), "text": text, "overrides": variant.overrides,
            "files": files, "ground_motion": ground, "influence": influence}


def referenced_files(data: dict, folder: Path) -> dict:
    """``{name: bytes}`` of the files a parsed (and changed) model file ``data`` refers to.

    The names are the strings of the model file (``file`` keys and the entries of
    ``[matrices]``), relative to its ``folder``, as
    :func:`unilateral.batch.worker.localize_files` finds them again on a worker.
    """
    from .worker import file_references

    return {name: (folder / name).read_bytes() for name in file_references(data) if (folder / name).is_file()}


def record_samples(record):
    """The GroundMotion of a study record (a pair: the tuple of its components'): read when the study
    was, else read (or generated) now."""
    if record.motion is not None:
        return record.motion
    return read_study_record(record.payload())
