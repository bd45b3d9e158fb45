"""Many analyses at once: studies of records, intensities and parameters on Dask.

A *study file* (TOML, ``docs/study-file.md``) names model files, ground-motion records (a folder,
a list, or synthetic ones by seed), how the records are scaled (factors, or target PGA or
Sa(T1, 5 %)), model-file values swept by key path, the analysis settings and the peak quantities
to collect. :func:`run_study` runs every analysis as a Dask task (a local cluster by default),
writes each result atomically as soon as it is done (so a study that is interrupted continues
where it stopped), and writes the study table (``study.nc``, ``study.csv``) with IDA and
fragility curves.

>>> from unilateral.batch import load_study, run_study          # doctest: +SKIP
>>> result = run_study("examples/ida.toml", "ida-out")          # doctest: +SKIP
>>> result.table["uplift"]                                       # doctest: +SKIP

Dask is imported only when a study runs on it; importing this package does not import it.
"""

from __future__ import annotations

_EXPORTS = {
    "load_study": "study", "Study": "study", "StudyFileError": "study",
    "run_study": "runner", "StudyResult": "runner", "StudyInterrupted": "runner",
    # the spectra of the records and the periods of the structure live in unilateral.analysis
    **dict.fromkeys(("response_spectrum", "first_period", "natural_periods"), "unilateral.analysis.response_spectrum"),
    "fit_fragility": "fragility", "FragilityFit": "fragility",
    "study_table": "table", "study_file_schema": "schema", "write_study_schema": "schema",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        from importlib import import_module

        where = _EXPORTS[name]
        value = getattr(import_module(where if where.startswith("unilateral.") else f"{__name__}.{where}"), name)
        globals()[name] = value         # later lookups (and pdoc) find it in the module
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
