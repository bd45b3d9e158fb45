"""Solutions as xarray Datasets, netCDF files and CSV tables.

Dataset layout (:func:`to_dataset`)
-----------------------------------
dimensions ``time``, ``dof``, ``constraint`` (and ``case`` for several analyses in one Dataset);
coordinates hold the times and the names; variables ``u``, ``udot`` (time, dof) and ``v``, ``psi``,
``psiL`` (time, constraint), those the solution has, each with ``long_name`` and, given the units,
``units``. Attributes: ``success`` (0/1), ``message``, ``stats`` (the statistics as JSON, for an
exact round trip), the statistics flattened (``steps``, ``time_total``, ...) for netCDF tools, and
the user's attributes, flattened alike.

With ``footings`` (a frame's :class:`~unilateral.structure.foundation.Footings`), the contact
patches of the footings get their extents as coordinates along ``constraint``
(:func:`patch_coords`): ``footing`` (the footing's name), ``patch_node`` (the node its contact
force acts on), ``patch_x`` (the patch centre's x), ``patch_width`` (along x) and ``patch_length``
(out of plane); the frame's own constraints have ``""`` and NaN there.

Several analyses on one time axis, e.g. ``{"unilateral": sol, "bilateral": bil}``, share one
Dataset with a leading ``case`` dimension. Attributes equal in all cases stay attributes; those
that differ (``success``, ``message``, ``stats``, timings, ...) become variables along ``case``, so
``from_dataset(ds.sel(case="bilateral"))`` gives back that case's Solution.

xarray is imported by the functions that need it: :mod:`unilateral.io.dataset` (the command line's
writer of ``results.nc``, without xarray) shares the helpers of this module.
"""

from __future__ import annotations

import contextlib
import csv
import errno
import io
import json
import os
import shutil
import sys
import threading
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import __version__
from ..result import Solution
from .atomic import WriteError, atomic_write, to_jsonable, write_text_atomic
from .files import file_problem, size_text

if TYPE_CHECKING:
    import xarray as xr

ENGINE = "h5netcdf"

# name: (dims, physical quantity, long_name)
_VARIABLES = {
    "u": (("time", "dof"), "length", "displacement"),
    "udot": (("time", "dof"), "velocity", "velocity"),
    "v": (("time", "constraint"), "length", "unilateral deformation (uplift, gap opening, slack)"),
    "psi": (("time", "constraint"), "force", "constraint reaction (compression negative)"),
    "psiL": (("time", "constraint"), "force", "constraint reaction with every constraint bilateral"),
}


def to_dataset(data: Solution | dict[str, Solution], *, units: dict | None = None,
               attrs: dict | None = None, footings=None) -> xr.Dataset:
    """Return a solution, or several on one time axis, as an :class:`xarray.Dataset`.

    Parameters
    ----------
    data : Solution or dict of str to Solution
        A dict gives a Dataset with a leading ``case`` dimension labelled by its keys; the
        solutions must share their time axis, DOF names and constraint names.
    units : dict, optional
        Units of the base quantities, e.g. ``{"length": "m", "force": "kN", "time": "s"}``; they
        set the ``units`` attribute of each variable (``udot`` gets ``length/time``).
    attrs : dict, optional
        Further attributes, e.g. model metadata; nested dicts are flattened to ``outer_inner``.
        An attribute may repeat a statistic (``method``, ``rule``) but not contradict it.
    footings : Footings, optional
        The footings of a frame (``structure.foundation``): adds the extents of their contact
        patches along ``constraint`` (:func:`patch_coords`).

    Returns
    -------
    xarray.Dataset
    """
    import xarray as xr

    if isinstance(data, dict):
        return _combine({label: to_dataset(sol, units=units, attrs=attrs, footings=footings)
                         for label, sol in data.items()})
    data_vars, coords, merged = dataset_parts(data, units, attrs, footings)
    return xr.Dataset(data_vars, coords=coords, attrs=merged)


def dataset_parts(data: Solution, units: dict | None, attrs: dict | None,
                  footings=None) -> tuple[dict, dict, dict]:
    """The variables, coordinates and attributes of one Solution's Dataset (:func:`to_dataset`, and
    :func:`unilateral.io.dataset.cases_dataset` without xarray); ``constraint`` and ``dof`` as lists,
    the patch extents of ``footings`` (:func:`patch_coords`) as arrays."""
    if not isinstance(data, Solution):
        raise TypeError(f"data must be a Solution or a dict of Solutions, got {type(data).__name__}")
    units = units or {}
    data_vars = {}
    for name, (dims, quantity, long_name) in _VARIABLES.items():
        values = getattr(data, name)
        if values is not None:
            data_vars[name] = (dims, np.asarray(values, dtype=float), _var_attrs(long_name, units, quantity))
    coords = {"time": ("time", np.asarray(data.t, dtype=float), _var_attrs("time", units, "time")),
              "constraint": list(data.constraint_names)}
    if "u" in data_vars or "udot" in data_vars:
        coords["dof"] = list(data.dof_names)
    if footings is not None:
        coords |= patch_coords(footings, len(data.constraint_names), units)
    meta = {"source": f"unilateral {__version__}", "success": data.success, "message": data.message,
            "stats": json.dumps(to_jsonable(data.stats))}
    merged = _flatten(meta) | _flatten(data.stats)
    for key, value in _flatten(attrs or {}).items():
        if key in merged and not _same(merged[key], value):
            raise ValueError(f"attrs[{key!r}] = {value!r} contradicts the solution's {key} = {merged[key]!r}")
        merged[key] = value
    return data_vars, coords, merged


#: The patch extents along ``constraint``: name -> (long_name, physical quantity or None for a name).
PATCH_COORDS = {
    "footing": ("footing the contact patch belongs to (empty: not a footing's patch)", None),
    "patch_node": ("node the patch's contact force acts on (a rigid footing's node, a flexible footing's "
                   "node of the patch)", None),
    "patch_x": ("x of the contact patch's centre", "length"),
    "patch_width": ("width of the contact patch along x", "length"),
    "patch_length": ("length of the contact patch out of plane", "length"),
}


def patch_coords(footings, m: int, units: dict | None = None) -> dict:
    """The extents of the footings' contact patches as coordinates along ``constraint``.

    Parameters
    ----------
    footings : Footings
        ``structure.foundation`` of a frame: ``footings`` (each with ``name``, ``m``,
        ``contact_nodes()`` and ``patches``, whose ``centres`` and ``sizes`` are ``(x, y)`` and
        ``(width, length)``) and
        ``first``, the number of the frame's own constraints, which precede the patches.
    m : int
        The number of constraint unknowns of the solution (the frame's and the patches').
    units : dict, optional
        Sets the ``units`` attribute of the lengths.

    Returns
    -------
    dict
        ``footing``, ``patch_node`` (str), ``patch_x``, ``patch_width``, ``patch_length`` (float), each
        ``("constraint", values, attrs)``: the patch of each footing contact, ``""`` and NaN for
        the frame's own constraints and for the shears and slips of footings that slide (which
        follow the contacts; ``constraint_x`` places them). A rigid footing's patch widths sum to
        its width.

    Raises
    ------
    ValueError
        The footings' patches do not end the ``m`` constraints.
    """
    first, patches = int(footings.first), sum(f.m for f in footings.footings)
    per_patch = getattr(footings, "constraints_per_patch", 4 if getattr(footings, "sliding", False) else 1)
    if first + patches * per_patch != m:
        raise ValueError(f"the footings have {patches} patches after {first} constraints of the frame, but the "
                         f"solution has {m} constraints: give the footings of the structure solved")
    name, node = np.full(m, "", dtype=object), np.full(m, "", dtype=object)
    x, width, length = (np.full(m, np.nan) for _ in range(3))
    start = first
    for footing in footings.footings:
        part = slice(start, start + footing.m)
        name[part] = str(footing.name)
        node[part] = [str(n) for n in footing.contact_nodes()]
        x[part] = footing.patches.centres[:, 0]
        width[part], length[part] = footing.patches.sizes[:, 0], footing.patches.sizes[:, 1]
        start += footing.m
    values = {"footing": np.asarray(name.tolist()), "patch_node": np.asarray(node.tolist()), "patch_x": x,
              "patch_width": width, "patch_length": length}
    return {key: ("constraint", values[key], _var_attrs(long_name, units or {}, quantity))
            for key, (long_name, quantity) in PATCH_COORDS.items()}


def from_dataset(ds: xr.Dataset) -> Solution:
    """Rebuild the :class:`~unilateral.Solution` stored by :func:`to_dataset`.

    A Dataset with several cases must be narrowed to one first: ``ds.sel(case="unilateral")``.
    """
    if "case" in ds.dims:
        raise ValueError(f"the dataset holds the cases {ds['case'].values.tolist()}; "
                         "pick one first, e.g. from_dataset(ds.sel(case=...))")

    def array(name):
        return ds[name].values.astype(float) if name in ds.data_vars else None

    def names(dim):
        return [str(x) for x in ds[dim].values] if dim in ds.coords else []

    return Solution(t=ds["time"].values.astype(float), v=array("v"), psi=array("psi"), psiL=array("psiL"),
                    u=array("u"), udot=array("udot"), success=bool(_meta(ds, "success")),
                    message=str(_meta(ds, "message")), stats=json.loads(_meta(ds, "stats")),
                    dof_names=names("dof"), constraint_names=names("constraint"))


def save_netcdf(data: Solution | dict[str, Solution] | xr.Dataset, path: str | os.PathLike, *,
                units: dict | None = None, attrs: dict | None = None) -> Path:
    """Write a solution, a dict of cases or a Dataset to a netCDF-4 file, atomically.

    Parameters
    ----------
    data : Solution, dict of str to Solution, or xarray.Dataset
        Solutions go through :func:`to_dataset` (with ``units`` and ``attrs``).
    path : str or path-like
        Target file (conventionally ``.nc``); replaced only once the new file is complete.

    Returns
    -------
    pathlib.Path
        The target path.
    """
    import xarray as xr

    if isinstance(data, xr.Dataset):
        if units is not None or attrs is not None:
            raise TypeError("units and attrs apply to Solutions; set them on the Dataset instead")
        ds = data
    else:
        ds = to_dataset(data, units=units, attrs=attrs)
    return write_netcdf(ds, path)


#: Datasets up to this size [bytes] are encoded in memory and written by Python, so that a full
#: disk is a clean :class:`~unilateral.io.atomic.WriteError`: HDF5 crashes the process
#: (segmentation fault) when the disk fills while it writes. Larger ones are written by HDF5
#: after a check of the free space.
IN_MEMORY_LIMIT = 1 << 30


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write the Dataset ``ds`` to the netCDF-4 file ``path``, atomically.

    The Dataset is encoded by xarray's own CF encoder into an h5netcdf store
    (:func:`netcdf_bytes`), so the file is the one :meth:`xarray.Dataset.to_netcdf` writes.

    Raises
    ------
    unilateral.io.atomic.WriteError
        ``could not write results.nc to DIR: No space left on device`` (or another cause); the
        previous file at ``path`` is intact and no temporary file is left.
    """
    path = Path(path)
    if ds.nbytes <= IN_MEMORY_LIMIT:
        data = netcdf_bytes(ds)
        return atomic_write(path, lambda tmp: _write_bytes(tmp, data))
    _check_free_space(path, int(ds.nbytes))
    return atomic_write(path, lambda tmp: _store(ds, tmp))


def netcdf_bytes(ds: xr.Dataset) -> bytes:
    """The netCDF-4 file of ``ds``, encoded in memory."""
    buffer = io.BytesIO()
    _store(ds, buffer)
    return buffer.getvalue()


def _store(ds: xr.Dataset, target) -> None:
    """Write ``ds`` to ``target`` (a path or a binary file object) through an h5netcdf store.

    :meth:`xarray.Dataset.to_netcdf` does the same after asking Dask which scheduler runs (it
    imports ``dask`` and ``distributed``, about 0.5 s, and under a distributed Client takes a lock
    that fails for an in-memory target). The data are in memory here, so a local lock suffices.
    """
    from xarray.backends import H5NetCDFStore

    if any(variable.chunks is not None for variable in ds.variables.values()):
        ds = ds.load()                          # Dask-backed variables: computed here, then written
    store = H5NetCDFStore.open(target, mode="w", lock=threading.Lock())
    try:
        ds.dump_to_store(store)
    finally:
        store.close()


@contextlib.contextmanager
def without_dask_arrays():
    """A block in which xarray takes Dask as absent, if this process has not imported it.

    xarray checks every new variable against ``dask.array.Array`` and imports ``dask.array`` for
    that (0.3-0.9 s); a process that has not imported Dask holds no Dask arrays, so the check can
    only say no. The command line's ``plot`` runs in this block. If Dask is imported already, or
    xarray keeps its cache of array modules otherwise, nothing changes.
    """
    try:
        from xarray.namedarray import pycompat

        cache, absent = pycompat._cached_duck_array_modules, object.__new__(pycompat.DuckArrayModule)
        absent.module, absent.version, absent.type, absent.available = None, pycompat.Version("0"), (), False
    except (ImportError, AttributeError, TypeError):
        yield
        return
    if "dask" in sys.modules or "dask" in cache:
        yield
        return
    cache["dask"] = absent
    try:
        yield
    finally:
        if cache.get("dask") is absent:
            del cache["dask"]


def _write_bytes(path: Path, data) -> None:
    with open(path, "wb") as fh:
        fh.write(data)


def _check_free_space(path: Path, nbytes: int) -> None:
    need = int(1.05 * nbytes) + (16 << 20)
    free = shutil.disk_usage(path.parent).free
    if free < need:
        raise WriteError(path, OSError(errno.ENOSPC, f"{os.strerror(errno.ENOSPC)} ({size_text(need)} needed, "
                                                     f"{size_text(free)} free)"))


def load_netcdf(path: str | os.PathLike) -> xr.Dataset:
    """Read a netCDF file written by :func:`save_netcdf` into memory (the file is closed)."""
    import xarray as xr

    return xr.load_dataset(path, engine=ENGINE, decode_times=False, decode_timedelta=False)


class ResultsFileError(ValueError):
    """A file that is not a ``results.nc`` written by unilateral (empty, truncated, foreign, ...)."""

    def __init__(self, path, problem: str):
        self.path = str(path)
        self.problem = problem
        super().__init__(f"{self.path} is not a results.nc written by unilateral: {problem}")


_HDF5 = b"\x89HDF\r\n\x1a\n"


def open_results(path: str | os.PathLike) -> xr.Dataset:
    """Check and read a ``results.nc`` written by unilateral (:func:`save_netcdf`, ``unilateral run``).

    Returns
    -------
    xarray.Dataset
        In memory; the file is closed.

    Raises
    ------
    ResultsFileError
        ``<path> is not a results.nc written by unilateral: <why>``: not a regular file, empty, not
        netCDF-4, truncated or damaged, or a netCDF file another program wrote.
    """
    path = Path(path)
    problem = file_problem(path)
    if problem is not None:
        raise ResultsFileError(path, problem)
    try:
        with open(path, "rb") as fh:
            head = fh.read(8)
    except OSError as exc:
        raise ResultsFileError(path, f"cannot read it ({exc.strerror or exc})") from None
    if not head.startswith(_HDF5):
        raise ResultsFileError(path, _not_hdf5(path, head))
    try:
        ds = load_netcdf(path)
    except Exception as exc:                    # h5py and h5netcdf raise many kinds on a damaged file
        raise ResultsFileError(path, f"it cannot be read, is it truncated or damaged? ({type(exc).__name__}: "
                                     f"{exc})") from None
    source = str(ds.attrs.get("source", ""))
    if not source.startswith("unilateral"):
        said = f"source = {source!r}" if source else "no source attribute"
        raise ResultsFileError(path, f"it is a netCDF file another program wrote ({said}; unilateral writes "
                                     "source = 'unilateral <version>')")
    selected = ds.attrs.get("output_histories", "full") != "full"     # [output]: not every history written
    missing = [name for name in (("time",) if selected else ("time", "v", "psi")) if name not in ds.variables]
    if missing:
        raise ResultsFileError(path, f"it lacks {', '.join(missing)}")
    return ds


def _not_hdf5(path: Path, head: bytes) -> str:
    if not head:
        return "the file is empty"
    if head.startswith(b"CDF"):
        return "it is a netCDF-3 file; unilateral writes netCDF-4 (HDF5)"
    if head.lstrip()[:1] in (b"{", b"["):
        return (f"it looks like JSON; give the results.nc that `unilateral run` wrote, e.g. "
                f"{path.parent / 'results.nc'}")
    return f"it is not a netCDF-4 (HDF5) file (it starts with {head!r})"


def save_csv(sol: Solution, directory: str | os.PathLike, *, prefix: str = "",
             column_units: dict | None = None, precision: str = "float64") -> list[Path]:
    """Write the histories as CSV tables with a header row, atomically and at full precision.

    Files, in ``directory`` (created if missing):

    - ``<prefix>displacements.csv``: ``time``, then one column per DOF name (if the solution has
      displacements);
    - ``<prefix>constraints.csv``: ``time``, ``v:<name>`` and ``psi:<name>`` per constraint, and
      ``psiL:<name>`` if present.

    Numbers are written as the shortest decimal that reads back to the same float (``precision =
    "float32"``: 9 significant digits, which read back to the same float32). A solution without
    ``v``, ``psi`` and ``psiL`` (None: not recorded) has no ``constraints.csv``. With
    ``column_units`` (column name -> unit), a header states its column's unit: ``time [s]``,
    ``3.ux [m]``, ``psi:soil2 [kN]``.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    tables = {}
    if sol.u is not None:
        tables["displacements.csv"] = {"time": sol.t} | dict(zip(sol.dof_names, np.asarray(sol.u).T))
    columns = {"time": sol.t}
    for name in ("v", "psi", "psiL"):
        values = getattr(sol, name)
        if values is not None:
            columns |= {f"{name}:{c}": col for c, col in zip(sol.constraint_names, np.asarray(values).T)}
    if any(getattr(sol, name) is not None for name in ("v", "psi", "psiL")):
        tables["constraints.csv"] = columns
    if column_units:
        tables = {filename: {(f"{name} [{column_units[name]}]" if column_units.get(name) else name): values
                             for name, values in table.items()} for filename, table in tables.items()}
    return [write_text_atomic(directory / f"{prefix}{filename}", csv_text(table, precision))
            for filename, table in tables.items()]


def csv_text(columns: dict[str, np.ndarray], precision: str = "float64") -> str:
    """A CSV table: a header row of the column names, then one row per sample of the columns (each (N,)).

    Each row is formatted by one ``%`` of a row format on the row's floats (no Python call per
    number): ``%r``, the shortest decimal that reads back to the same float (``precision =
    "float64"``), or ``%.9g`` (``"float32"``: reads back to the same float32).
    """
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow(columns)
    if not columns:
        return buffer.getvalue()
    rows = np.column_stack([np.asarray(c, dtype=float) for c in columns.values()]).tolist()
    fmt = ",".join(["%r" if precision == "float64" else "%.9g"] * len(columns))
    body = "\n".join([fmt % tuple(row) for row in rows])
    return buffer.getvalue() + body + ("\n" if rows else "")


def _var_attrs(long_name: str, units: dict, quantity: str | None) -> dict:
    if quantity == "velocity":
        unit = f"{units['length']}/{units['time']}" if "length" in units and "time" in units else None
    else:
        unit = units.get(quantity)
    return {"long_name": long_name} | ({"units": unit} if unit else {})


def _flatten(mapping: dict, prefix: str = "") -> dict:
    """netCDF attributes from a nested dict: keys joined by ``_``, None dropped, bools as 0/1."""
    out = {}
    for key, value in mapping.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out |= _flatten(value, f"{name}_")
        elif value is not None:
            out[name] = _attribute(name, value)
    return out


def _attribute(name: str, value):
    if isinstance(value, (bool, np.bool_)):
        return int(value)
    if isinstance(value, (str, int, float, np.integer, np.floating)):
        return value
    if isinstance(value, (list, tuple, np.ndarray)):
        array = np.asarray(value)
        if array.dtype.kind in "biuf":
            return array.astype(np.int8) if array.dtype.kind == "b" else array
        return json.dumps(to_jsonable(value))
    raise TypeError(f"attribute {name!r} has type {type(value).__name__}; "
                    "netCDF attributes must be str, numbers, arrays or lists of them")


def _same(a, b) -> bool:
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return bool(np.array_equal(a, b))


def _meta(ds: xr.Dataset, key: str):
    """A solution's metadata: an attribute, or a 0-d variable after selecting one case."""
    if key in ds.attrs:
        return ds.attrs[key]
    if key in ds.data_vars and ds[key].ndim == 0:
        return ds[key].item()
    raise KeyError(f"the dataset has no {key!r} attribute; was it written by unilateral.io.to_dataset?")


def check_common_time(cases: dict) -> None:
    """Raise unless every case (a Dataset each) has the first case's time axis."""
    (first_label, first), *rest = cases.items()
    for label, ds in rest:
        if not np.array_equal(ds["time"].values, first["time"].values):
            raise ValueError(
                f"case {label!r} has {ds.sizes['time']} times in [{ds['time'].values[0]:g}, "
                f"{ds['time'].values[-1]:g}], case {first_label!r} has {first.sizes['time']} in "
                f"[{first['time'].values[0]:g}, {first['time'].values[-1]:g}]; cases share a Dataset only "
                "on a common time axis (did one analysis stop early?): store them separately")


def _combine(cases: dict[str, xr.Dataset]) -> xr.Dataset:
    """One Dataset with a leading ``case`` dimension; differing attributes become variables."""
    if not cases:
        raise ValueError("no cases to combine: the dict is empty")
    check_common_time(cases)
    import xarray as xr

    datasets = list(cases.values())
    common, per_case = {}, {}
    for key in dict.fromkeys(key for ds in datasets for key in ds.attrs):
        values = [ds.attrs.get(key) for ds in datasets]
        if all(value is not None and _same(value, values[0]) for value in values):
            common[key] = values[0]
        else:
            per_case[key] = ("case", _case_column(values))
    combined = xr.concat(datasets, dim="case", data_vars="all", coords="minimal", compat="equals",
                         join="exact", combine_attrs="override")     # variables keep their attributes
    combined.attrs = common
    return combined.assign_coords(case=list(cases)).assign(per_case)


def _case_column(values: list) -> np.ndarray:
    """Per-case values of one attribute (None where a case lacks it) as a 1-d array."""
    present = [value for value in values if value is not None]
    if all(isinstance(value, (int, float, np.integer, np.floating)) for value in present):
        return np.array([np.nan if value is None else value for value in values])
    return np.array([_text(value) for value in values])


def _text(value) -> str:
    if value is None:
        return ""
    return value if isinstance(value, str) else json.dumps(to_jsonable(value))
