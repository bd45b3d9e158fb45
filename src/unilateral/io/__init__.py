"""Saving results: atomic files, netCDF/xarray, CSV tables and run summaries.

- :mod:`~unilateral.io.atomic`: write a file completely or not at all.
- :mod:`~unilateral.io.results`: :class:`~unilateral.Solution` to and from :class:`xarray.Dataset`,
  netCDF-4 (h5netcdf) and CSV.
- :mod:`~unilateral.io.summary`: the key figures of a run as a JSON-ready dict and a terminal table.
"""

from unilateral.io.atomic import atomic_path, atomic_write, to_jsonable, write_json_atomic, write_text_atomic
from unilateral.io.results import from_dataset, load_netcdf, save_csv, save_netcdf, to_dataset
from unilateral.io.summary import format_summary, summary

__all__ = [
    "atomic_path",
    "atomic_write",
    "format_summary",
    "from_dataset",
    "load_netcdf",
    "save_csv",
    "save_netcdf",
    "summary",
    "to_dataset",
    "to_jsonable",
    "write_json_atomic",
    "write_text_atomic",
]
