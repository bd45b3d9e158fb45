"""Saving results and reading inputs: atomic files, output folders, netCDF/xarray, CSV, summaries.

- :mod:`~unilateral.io.atomic`: write a file completely or not at all.
- :mod:`~unilateral.io.folder`: an output folder replaced as a set (staging folder, then a swap).
- :mod:`~unilateral.io.files`: read input files safely (regular files only, with a size limit).
- :mod:`~unilateral.io.results`: :class:`~unilateral.Solution` to and from :class:`xarray.Dataset`,
  netCDF-4 (h5netcdf) and CSV; :func:`open_results` checks a ``results.nc`` before reading it.
- :mod:`~unilateral.io.summary`: the key figures of a run as a JSON-ready dict and a terminal table.

The names of :mod:`~unilateral.io.results` are imported on first use: importing the package (as
:mod:`unilateral.loads` does, for :mod:`~unilateral.io.files`) does not import xarray.
"""

from importlib import import_module

from unilateral.io.atomic import (WriteError, atomic_path, atomic_write, to_jsonable, write_json_atomic,
                                  write_text_atomic)
from unilateral.io.files import InputFileError, file_problem, read_input_bytes, read_input_text
from unilateral.io.folder import OutputFolder, OutputFolderError
from unilateral.io.summary import format_summary, summary

#: Names of :mod:`unilateral.io.results` (imports xarray), imported on first use.
_EXPORTS = dict.fromkeys(("ResultsFileError", "from_dataset", "load_netcdf", "open_results", "save_csv",
                          "save_netcdf", "to_dataset", "write_netcdf"), "results")

__all__ = sorted([*_EXPORTS, "InputFileError", "OutputFolder", "OutputFolderError", "WriteError", "atomic_path",
                  "atomic_write", "file_problem", "format_summary", "read_input_bytes", "read_input_text",
                  "summary", "to_jsonable", "write_json_atomic", "write_text_atomic"])


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'unilateral.io' has no attribute {name!r}")
    value = getattr(import_module(f"unilateral.io.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
