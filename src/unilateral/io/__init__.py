"""Saving results and reading inputs: atomic files, output folders, netCDF/xarray, CSV, summaries.

- :mod:`~unilateral.io.atomic`: write a file completely or not at all.
- :mod:`~unilateral.io.folder`: an output folder replaced as a set (staging folder, then a swap).
- :mod:`~unilateral.io.files`: read input files safely (regular files only, with a size limit).
- :mod:`~unilateral.io.results`: :class:`~unilateral.Solution` to and from :class:`xarray.Dataset`,
  netCDF-4 (h5netcdf) and CSV; :func:`open_results` checks a ``results.nc`` before reading it.
- :mod:`~unilateral.io.summary`: the key figures of a run as a JSON-ready dict and a terminal table.

Every name is imported on first use: importing the package (as :mod:`unilateral.loads` does, for
:mod:`~unilateral.io.files`, and the command line's check of a model file) imports neither numpy
nor xarray.
"""

import sys
import types
from importlib import import_module

#: Public name -> the submodule that defines it, imported on first use (:mod:`~unilateral.io.results`
#: imports xarray, :mod:`~unilateral.io.atomic` and :mod:`~unilateral.io.summary` numpy).
_EXPORTS = {
    **dict.fromkeys(("WriteError", "atomic_path", "atomic_write", "to_jsonable", "write_json_atomic",
                     "write_text_atomic"), "atomic"),
    **dict.fromkeys(("InputFileError", "file_problem", "read_input_bytes", "read_input_text"), "files"),
    **dict.fromkeys(("OutputFolder", "OutputFolderError"), "folder"),
    **dict.fromkeys(("format_summary", "summary"), "summary"),
    **dict.fromkeys(("ResultsFileError", "from_dataset", "load_netcdf", "open_results", "save_csv",
                     "save_netcdf", "to_dataset", "write_netcdf"), "results"),
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'unilateral.io' has no attribute {name!r}")
    value = getattr(import_module(f"unilateral.io.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))


class _Package(types.ModuleType):
    """The package module: ``unilateral.io.summary`` stays the function when the submodule of that name
    is imported (the import system binds the module to the package's attribute)."""

    def __setattr__(self, name, value):
        if name == "summary" and isinstance(value, types.ModuleType):
            value = value.summary
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
