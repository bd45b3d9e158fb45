"""A small Dataset in memory and its netCDF-4 writer, without xarray.

``unilateral run`` and ``example`` build ``results.nc`` with :class:`Dataset`: xarray imports
pandas (0.3-0.5 s), and Dask too as it checks each new variable for Dask arrays, which a run
that writes one file and exits does not need. :class:`Dataset` has the few parts of
:class:`xarray.Dataset` that :mod:`unilateral.analysis.outputs` uses (``ds[name].values``,
``dims``, ``sizes``, ``coords``, ``data_vars``, ``attrs``, ``assign``, ``assign_coords``,
``sel``, ``isel``), :meth:`Dataset.to_xarray` gives the equal :class:`xarray.Dataset` (the
figures are drawn from it), and :func:`write_netcdf` writes the file xarray writes for it (the
same variables, dimensions, coordinates, attributes and ``_FillValue``), through h5netcdf.

:func:`cases_dataset` is :func:`unilateral.io.results.to_dataset` for this Dataset, and
:func:`save_netcdf` its :func:`~unilateral.io.results.save_netcdf`.
"""

from __future__ import annotations

import io
import os
import sys
from pathlib import Path

import numpy as np

from ..result import Solution
from . import results as _results
from .atomic import atomic_write
from .results import _case_column, _same, check_common_time, dataset_parts


class Variable:
    """An array with named dimensions and attributes (``dims``, ``values``, ``attrs``)."""

    __slots__ = ("dims", "values", "attrs")

    def __init__(self, dims, values, attrs=None):
        dims = (dims,) if isinstance(dims, str) else tuple(dims)
        values = np.asarray(values)
        if values.ndim != len(dims):
            raise ValueError(f"values of shape {values.shape} do not match the dimensions {dims}")
        self.dims, self.values, self.attrs = dims, values, dict(attrs or {})

    @property
    def ndim(self) -> int:
        return self.values.ndim

    @property
    def shape(self) -> tuple:
        return self.values.shape

    @property
    def size(self) -> int:
        return self.values.size

    @property
    def dtype(self):
        return self.values.dtype

    def __len__(self) -> int:
        return len(self.values)

    def __array__(self, dtype=None, copy=None):
        return self.values if dtype is None else self.values.astype(dtype)

    @property
    def sizes(self) -> dict:
        return dict(zip(self.dims, self.values.shape))

    def item(self):
        return self.values.item()

    def transpose(self, *dims) -> Variable:
        """The variable with ``dims`` first, in that order (``...``: the others, as they are)."""
        if ... in dims:
            head = [d for d in dims if d is not ...]
            dims = (*head, *(d for d in self.dims if d not in head))
        return Variable(dims, np.transpose(self.values, [self.dims.index(d) for d in dims]), self.attrs)


class DataArray(Variable):
    """A variable of a :class:`Dataset` with the coordinates along its dimensions: ``da["node"]``,
    ``da.coords``, ``da.sel(node="3", component="uy")`` as in xarray."""

    __slots__ = ("coords",)

    def __init__(self, variable: Variable, coords: dict):
        super().__init__(variable.dims, variable.values, variable.attrs)
        self.coords = coords

    def __getitem__(self, name) -> Variable:
        return self.coords[name]

    def sel(self, **labels) -> DataArray:
        """Labels of dimension coordinates, one per dimension; the dimensions selected are dropped."""
        index = {dim: _position(self.coords, dim, label) for dim, label in labels.items()}
        values = self.values[tuple(index.get(d, slice(None)) for d in self.dims)]
        dims = tuple(d for d in self.dims if d not in index)
        coords = {name: var for name, var in self.coords.items() if set(var.dims) <= set(dims)}
        return DataArray(Variable(dims, values, self.attrs), coords)


def _position(coords: dict, dim: str, label) -> int:
    """The position of ``label`` along the dimension coordinate ``dim`` (KeyError if absent, as xarray)."""
    if dim not in coords:
        raise KeyError(f"no index found for coordinate {dim!r}")
    found = np.flatnonzero(coords[dim].values == label)
    if not found.size:
        raise KeyError(f"{label!r} is not in the coordinate {dim!r}")
    return int(found[0])


class Dataset:
    """Variables sharing named dimensions, some of them coordinates, and global attributes.

    ``Dataset(data_vars, coords, attrs)`` as :class:`xarray.Dataset`: each value is a
    :class:`Variable`, a tuple ``(dims, values[, attrs])`` or, for a coordinate, the values of the
    dimension of its name. The variables keep xarray's order (the data variables, then the
    coordinates, then what is assigned, in turn), and the dimensions are numbered in the file by
    their first appearance in it, as xarray does.
    """

    def __init__(self, data_vars=None, coords=None, attrs=None):
        self.variables: dict[str, Variable] = {}
        self._coord_names: list[str] = []
        self.attrs = dict(attrs or {})
        self._set(data_vars or {}, coord=False)     # in xarray's order: the files list them alike
        self._set(coords or {}, coord=True)

    # ------------------------------------------------------------------ access
    @property
    def sizes(self) -> dict:
        sizes = {}
        for var in self.variables.values():
            sizes.update(zip(var.dims, var.values.shape))
        return sizes

    dims = sizes

    @property
    def coords(self) -> dict:
        return {name: self.variables[name] for name in self._coord_names}

    @property
    def data_vars(self) -> dict:
        return {name: var for name, var in self.variables.items() if name not in self._coord_names}

    @property
    def nbytes(self) -> int:
        return sum(var.values.nbytes for var in self.variables.values())

    def __contains__(self, name) -> bool:
        return name in self.variables

    def __getitem__(self, name) -> DataArray:
        var = self.variables[name]
        return DataArray(var, {c: self.variables[c] for c in self._coord_names
                               if set(self.variables[c].dims) <= set(var.dims)})

    # ------------------------------------------------------------------ new datasets
    def copy(self) -> Dataset:
        out = Dataset(attrs=self.attrs)
        out.variables = dict(self.variables)
        out._coord_names = list(self._coord_names)
        return out

    def assign(self, variables=None, **more) -> Dataset:
        out = self.copy()
        out._set({**(variables or {}), **more}, coord=False)
        return out

    def assign_coords(self, coords=None, **more) -> Dataset:
        out = self.copy()
        out._set({**(coords or {}), **more}, coord=True)
        return out

    def isel(self, **indexers) -> Dataset:
        """Positions along dimensions: an integer drops the dimension, a slice keeps it."""
        out = Dataset(attrs=self.attrs)
        for name, var in self.variables.items():
            index = tuple(indexers.get(d, slice(None)) for d in var.dims)
            dims = tuple(d for d in var.dims if not isinstance(indexers.get(d), (int, np.integer)))
            out.variables[name] = Variable(dims, var.values[index], var.attrs)
        out._coord_names = list(self._coord_names)
        return out

    def sel(self, **labels) -> Dataset:
        """Labels of dimension coordinates, one per dimension (``ds.sel(case="bilateral")``)."""
        return self.isel(**{dim: _position(self.coords, dim, label) for dim, label in labels.items()})

    def _set(self, mapping: dict, *, coord: bool) -> None:
        for name, value in mapping.items():
            if isinstance(value, Variable):             # a DataArray too: its coordinates are the Dataset's
                var = Variable(value.dims, value.values, value.attrs)
            elif isinstance(value, tuple):
                var = Variable(*value)
            else:
                var = Variable((name,), value)
            self.variables[name] = var
            if coord and name not in self._coord_names:
                self._coord_names.append(name)
            elif not coord and name in self._coord_names:
                self._coord_names.remove(name)

    # ------------------------------------------------------------------ xarray
    def to_xarray(self):
        """The equal :class:`xarray.Dataset`, its variables in the same order (imports xarray)."""
        import xarray as xr

        ds = xr.Dataset({name: (var.dims, var.values, var.attrs) for name, var in self.variables.items()},
                        attrs=self.attrs)
        return ds.set_coords([name for name in self._coord_names if name not in ds.coords])


def cases_dataset(data: Solution | dict[str, Solution], *, units: dict | None = None,
                  attrs: dict | None = None, footings=None) -> Dataset:
    """:func:`unilateral.io.results.to_dataset` as a :class:`Dataset` (the same variables, coordinates
    and attributes, the patch extents of ``footings`` included; ``cases_dataset(...).to_xarray()``
    equals ``to_dataset(...)``)."""
    if isinstance(data, dict):
        return _combine({label: cases_dataset(sol, units=units, attrs=attrs, footings=footings)
                         for label, sol in data.items()})
    data_vars, coords, merged = dataset_parts(data, units, attrs, footings)
    for dim in ("constraint", "dof"):
        if dim in coords:
            coords[dim] = (dim, _labels(coords[dim]))
    return Dataset(data_vars, coords=coords, attrs=merged)


def _equal(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal shapes and values, NaN equal to NaN (as xarray compares coordinates)."""
    if a.dtype.kind == "f" and b.dtype.kind == "f":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


def _labels(names) -> np.ndarray:
    """Names as a coordinate, as xarray stores a list (``<U``; float64 when empty)."""
    return np.asarray(list(names)) if len(names) else np.array([], dtype=float)


def _combine(cases: dict[str, Dataset]) -> Dataset:
    """:func:`unilateral.io.results._combine`: one Dataset with a leading ``case`` dimension."""
    if not cases:
        raise ValueError("no cases to combine: the dict is empty")
    check_common_time(cases)
    first, *rest = cases.values()
    for ds in rest:
        for name, var in first.coords.items():
            other = ds.coords.get(name)
            if other is None or other.dims != var.dims or not _equal(other.values, var.values):
                raise ValueError(f"the cases differ in the coordinate {name!r}: store them separately")
        if set(ds.data_vars) != set(first.data_vars):
            raise ValueError(f"the cases hold different variables ({sorted(ds.data_vars)} and "
                             f"{sorted(first.data_vars)}): store them separately")
    datasets = list(cases.values())
    common, per_case = {}, {}
    for key in dict.fromkeys(key for ds in datasets for key in ds.attrs):
        values = [ds.attrs.get(key) for ds in datasets]
        if all(value is not None and _same(value, values[0]) for value in values):
            common[key] = values[0]
        else:
            per_case[key] = ("case", _case_column(values))
    data_vars = {name: Variable(("case", *var.dims), np.stack([ds[name].values for ds in datasets]), var.attrs)
                 for name, var in first.data_vars.items()}
    combined = Dataset(data_vars, coords=first.coords, attrs=common)
    return combined.assign_coords(case=np.asarray(list(cases))).assign(per_case)


# ---------------------------------------------------------------------- netCDF
def save_netcdf(ds: Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to the netCDF-4 file ``path``, atomically: by :func:`write_netcdf`, or, in a process
    that has imported xarray already (a notebook, the tests), by xarray's encoder
    (:func:`unilateral.io.results.write_netcdf` of ``ds.to_xarray()``); the file is the same."""
    if "xarray" in sys.modules:
        return _results.write_netcdf(ds.to_xarray(), path)
    return write_netcdf(ds, path)


def write_netcdf(ds: Dataset, path: str | os.PathLike) -> Path:
    """Write ``ds`` to the netCDF-4 file ``path``, atomically, as
    :func:`unilateral.io.results.write_netcdf` writes ``ds.to_xarray()`` (the same file, read back
    by xarray; a full disk is a :class:`~unilateral.io.atomic.WriteError`)."""
    path = Path(path)
    if ds.nbytes <= _results.IN_MEMORY_LIMIT:
        buffer = io.BytesIO()
        _store(ds, buffer)
        data = buffer.getvalue()
        return atomic_write(path, lambda tmp: _results._write_bytes(tmp, data))
    _results._check_free_space(path, int(ds.nbytes))
    return atomic_write(path, lambda tmp: _store(ds, tmp))


def _store(ds: Dataset, target) -> None:
    """The encoding of xarray's h5netcdf backend: strings as variable-length UTF-8, booleans as int8
    with ``dtype = "bool"``, ``_FillValue = NaN`` on floats, the non-dimension coordinates named
    in the ``coordinates`` attribute of the variables that span their dimensions (the others in
    the global one)."""
    import h5netcdf
    import h5py

    coords = ds.coords
    non_dim = [name for name, var in coords.items() if var.dims != (name,)]
    attached = set()
    with h5netcdf.File(target, "w") as f:
        sizes = {}
        for var in ds.variables.values():
            for dim, size in zip(var.dims, var.values.shape):
                sizes.setdefault(dim, size)
        f.dimensions = sizes
        for key, value in ds.attrs.items():
            f.attrs[key] = value
        for name, var in ds.variables.items():
            values, attrs = var.values, dict(var.attrs)
            if values.dtype.kind == "b":
                values, attrs["dtype"] = values.astype(np.int8), "bool"
            if values.dtype.kind in "UO":
                dtype, fill = h5py.string_dtype(), None
                values = values.astype(object)
            elif values.dtype.kind in "iuf":
                dtype, fill = values.dtype, (np.nan if values.dtype.kind == "f" else None)
            else:
                raise ValueError(f"variable {name!r}: unsupported dtype {values.dtype} for netCDF-4")
            if name not in coords:
                mine = sorted(c for c in non_dim if set(coords[c].dims) <= set(var.dims))
                if mine and "coordinates" not in attrs:
                    attrs["coordinates"] = " ".join(mine)
                    attached.update(mine)
            created = f.create_variable(name, dimensions=var.dims, dtype=dtype, fillvalue=fill,
                                        data=values if values.size else None)
            for key, value in attrs.items():
                created.attrs[key] = value
        unattached = sorted(set(non_dim) - attached)
        if unattached and "coordinates" not in ds.attrs:
            f.attrs["coordinates"] = " ".join(unattached)
