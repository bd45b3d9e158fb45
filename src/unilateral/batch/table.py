"""The study table: one row per analysis, its inputs and its peak quantities.

Besides ``status`` (``failed``: the LCP of a step failed) each row says whether the structure
collapsed (``collapse``, ``collapse_reason``: :mod:`unilateral.batch.collapse`); the two are apart.

:func:`study_table` gathers the results written by the analyses into an :class:`xarray.Dataset`
along the dimension ``analysis``; :func:`write_table` writes it as ``study.nc`` (netCDF-4 via
h5netcdf) and ``study.csv``, both atomically. Analyses without a result yet are ``"pending"``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..io.atomic import atomic_path, to_jsonable, write_json_atomic
from ..modelfile.errors import toml_value
from .collapse import collapse_of
from .footing_quantity import measure_unit

STATUSES = ("ok", "failed", "error", "timeout", "pending")


def result_path(results: str | Path, key: str) -> Path:
    """``<results>/<key>.json``: the file of the result of analysis ``key``."""
    return Path(results) / f"{key}.json"


def write_result(path: Path, result: dict, *, fsync: bool = False) -> None:
    """Write a result atomically: a temporary file in the same folder, renamed over ``path``.

    A process killed half-way leaves the previous state (no file, or the old one) and at most a
    stale temporary file (removed by the next run). With ``fsync`` the file and the rename are
    also flushed to disk (:func:`unilateral.io.atomic.write_json_atomic`), which survives a crash
    of the operating system too but costs about 8 ms per result on an ordinary disk; without it a
    crash of the machine can leave a truncated file, which the next run finds unreadable and runs
    again, so nothing is lost either way.
    """
    import os
    import secrets

    if fsync:
        write_json_atomic(path, result)
        return
    text = json.dumps(to_jsonable(result), indent=1) + "\n"
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp{path.suffix}")
    try:
        with open(tmp, "x", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def read_result(results: Path, key: str) -> dict | None:
    """The result of analysis ``key``, or None if it has none (or an unreadable one)."""
    path = result_path(results, key)
    try:
        return json.loads(path.read_text())
    except FileNotFoundError:
        return None
    except (OSError, ValueError):
        return None


def _column(values) -> np.ndarray:
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=np.int64)
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=float)
    return np.array([v if isinstance(v, str) else toml_value(v) for v in values], dtype=str)


def study_rows(study, results: Path) -> list[dict]:
    """The table as a list of dicts (one per analysis, in the study's order)."""
    rows = []
    for analysis in study.analyses:
        row = analysis.inputs()
        result = read_result(results, analysis.key)
        values = {} if result is None else result.get("values", {})
        for column in study.quantity_columns:
            value = values.get(column)
            row[column] = math.nan if value is None else float(value)
        stats = {} if result is None else result.get("stats", {})
        row.update({
            "status": "pending" if result is None else result["status"],
            "message": "" if result is None else result.get("message", ""),
            "notes": "" if result is None else "; ".join(result.get("notes", [])),
            "solve_time": math.nan if result is None else float(result.get("solve_time", math.nan)),
            "task_time": math.nan if result is None else float(result.get("task_time", math.nan)),
            "steps": float(stats.get("steps", math.nan)),
            "method_used": str(stats.get("method", "")),
            "max_lcp_error": float(stats.get("max_lcp_error", math.nan)),
            "contact_changes": float(stats.get("contact_changes", math.nan)),
            "run_id": "" if result is None else str(result.get("run_id", "")),
        })
        row["collapse"], row["collapse_reason"] = collapse_of(result, study.document.collapse)
        rows.append(row)
    return rows


def study_table(study, results) -> "xarray.Dataset":  # noqa: F821 - xarray imported lazily
    """The study table as an :class:`xarray.Dataset` (dimension ``analysis``)."""
    import xarray as xr

    from .study import package_version

    rows = study_rows(study, Path(results))
    columns = list(dict.fromkeys(k for row in rows for k in row))
    data = {}
    for column in columns:
        values = [row.get(column, math.nan) for row in rows]
        data[column] = ("analysis", _column(values))
    ds = xr.Dataset(data, coords={"analysis": np.arange(len(rows))})
    doc = study.document
    counts = {s: int(np.sum(ds["status"].values == s)) for s in STATUSES} if rows else {}
    if rows:
        counts["collapse"] = int(np.sum(ds["collapse"].values == 1))
    ds.attrs.update({
        "title": doc.title, "study_file": str(study.source), "unilateral_version": package_version(),
        "intensity": study.intensity_label,
        "measure": "none" if doc.scaling is None else doc.scaling.measure,
        "quantities": json.dumps([q.model_dump() for q in doc.quantities]),
        "quantity_columns": json.dumps(study.quantity_columns),
        "counts": json.dumps(counts),
    })
    units = quantity_units(study)
    for column in study.quantity_columns:
        ds[column].attrs["long_name"] = f"peak quantity {column}"
        if units.get(column):
            ds[column].attrs["units"] = units[column]
    ds["intensity"].attrs["long_name"] = study.intensity_label
    ds["T1"].attrs.update(long_name="first period with every constraint bilateral", units="s")
    if rows:
        ds["collapse"].attrs.update(long_name="the structure collapsed (1), not (0), pending (-1); apart from status",
                                    flag_values="-1 0 1")
    return ds


def quantity_units(study) -> dict:
    """``{column: unit}`` of the quantity columns, in the units of the (first) model."""
    spec = study.variants[0].spec if study.variants else None
    if spec is None:
        return {}
    length, force = spec.units["length"], spec.units["force"]
    kinds = {"uplift": length, "contact_force": force, "displacement": length, "residual": length,
             "base_shear": force, "energy_error": ""}
    out = {}
    for q in study.document.quantities:
        unit = kinds.get(q.type, "") if q.type != "footing" else measure_unit(q.measure, spec.units)
        if q.type in ("displacement", "residual", "drift") and q.dof == "rz":
            unit = "rad"
        elif q.type == "drift":
            unit = "1" if q.ratio else length
        for column in study.quantity_columns:
            if column == q.name or column.startswith(q.name + "."):
                out[column] = unit
    return out


def write_table(study, results, out) -> "xarray.Dataset":  # noqa: F821
    """Write ``study.nc`` and ``study.csv`` to ``out`` atomically; return the dataset."""
    out = Path(out)
    from ..io.results import write_netcdf

    ds = study_table(study, results)
    write_netcdf(ds, out / "study.nc")          # a full disk is a clean WriteError, not a crash of HDF5
    frame = ds.to_dataframe()
    with atomic_path(out / "study.csv") as tmp:
        frame.to_csv(tmp)
    return ds
