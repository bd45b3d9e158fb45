"""A structural analysis from start to finish: the unilateral and bilateral cases, and every output.

:func:`run_model_file` and :func:`run_example` are the command line's ``run`` and ``example`` from
Python; :func:`run` (also ``unilateral.run``) analyses a model file in memory, an :class:`Analysis`
(:mod:`unilateral.analysis.memory`); :func:`run_cases` solves the cases; :func:`write_outputs`
writes ``results.nc``, CSV tables, ``summary.json`` and the figures atomically; :func:`report` is
the terminal summary. The structure's results (end forces, reactions, base shear, drifts,
accelerations) are in :mod:`unilateral.analysis.results`, the energy balance in
:mod:`unilateral.analysis.energy`, periods and mode shapes in :mod:`unilateral.structure.modes`.
"""

from importlib import import_module

# Exported lazily: importing ``unilateral.analysis.energy`` (a batch worker does) does not import
# the writers of results.nc (xarray) and the figures.
_EXPORTS = {"report": "outputs", "run_cases": "outputs", "write_outputs": "outputs",
            "analyse": "run", "run_example": "run", "run_model_file": "run",
            "Analysis": "memory", "results_dataset": "memory", "run": "memory"}


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(import_module(f"{__name__}.{_EXPORTS[name]}"), name)
        globals()[name] = value         # later lookups (and pdoc) find it in the module
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["Analysis", "analyse", "report", "results_dataset", "run", "run_cases", "run_example", "run_model_file",
           "write_outputs"]
