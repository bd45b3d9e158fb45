"""Earthquake ground-motion records: the :class:`GroundMotion` container and its readers.

Readers
-------
:func:`read_at2`
    PEER NGA ``.AT2`` files (all known variants of the NPTS/DT header line).
:func:`read_text_record`
    Plain text: one column of values with a given time step, or time and value columns.
:func:`read_record`
    Either of the above, chosen by the file suffix.
:func:`read_table`
    The numeric-table reader underneath :func:`read_text_record` (also used for tabulated
    loads).

Every reader returns accelerations in m/s^2 and raises :class:`RecordFormatError` (a
``ValueError``) naming the file, the line and the problem when a file cannot be read.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass, replace
from functools import cached_property
from pathlib import Path

import numpy as np

from unilateral._validate import as_vector, positive_float
from unilateral.io.files import TABLE_LIMIT, read_input_text
from unilateral.loads.units import acceleration_factor

UNIFORM_STEP_RTOL = 1e-6
"""Relative tolerance on the time steps of a time column for it to count as uniform."""

AT2_HEADER_LINES = 4
"""Number of header lines of a PEER ``.AT2`` file; the last one holds NPTS and DT."""
_AT2_UNITS_LINE = 3

# A decimal number, with an optional Fortran E or D exponent: 1, -.5, 0.1234E-02, 1.0D-03.
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?")
_D_EXPONENT = str.maketrans("Dd", "Ee")
_FIELD_SEPARATOR = re.compile(r"[\s,]+")
# Old PEER header line with the values first: "3930  .00500  NPTS, DT".
_VALUES_FIRST = re.compile(r"\s*(\S+?)[\s,]+(\S+?)[\s,]+NPTS\b(?!\s*=)", re.IGNORECASE)
_UNITS = re.compile(r"UNITS\s+OF\s+([^\s,;]+)", re.IGNORECASE)
_NPTS_DT_EXAMPLES = "'NPTS=  1999, DT=   .0100 SEC' or '1999  .0100  NPTS, DT'"


class RecordFormatError(ValueError):
    """A record or table file that cannot be read.

    Attributes
    ----------
    path : str
        The file.
    line : int or None
        1-based line number of the problem, if it has one.
    """

    def __init__(self, path, problem: str, line: int | None = None):
        self.path = str(path)
        self.line = line
        where = self.path if line is None else f"{self.path}, line {line}"
        super().__init__(f"{where}: {problem}")


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """A uniformly sampled ground acceleration record.

    Calling a record, ``gm(t)``, interpolates the acceleration linearly at the time(s) ``t``
    and gives zero outside ``[0, duration]`` (the ground is at rest before and after the
    record), so a record is usable wherever a load time function is expected.

    Parameters
    ----------
    dt : float
        Time step, s.
    acceleration : (npts,) array_like
        Ground acceleration in m/s^2; sample ``k`` is at time ``k * dt``. Stored as a float
        copy, exposed read-only.
    name : str, optional
        Short name, e.g. the file stem.
    source : str, optional
        Where the record came from, e.g. the file path.
    header : tuple of str, optional
        Header lines of the file.
    units : str, optional
        Units the file was written in, for information only (``acceleration`` is always
        m/s^2).

    Notes
    -----
    Instances compare and hash by identity, since they hold an array.
    """

    dt: float
    acceleration: np.ndarray
    name: str = ""
    source: str = ""
    header: tuple[str, ...] = ()
    units: str = "m/s2"

    def __post_init__(self):
        acceleration = as_vector("acceleration", self.acceleration, None)
        if acceleration.size == 0:
            raise ValueError("acceleration must hold at least one sample, got an empty array")
        object.__setattr__(self, "dt", positive_float("dt", self.dt))
        object.__setattr__(self, "_samples", acceleration)
        object.__setattr__(self, "acceleration", _read_only_view(acceleration))
        object.__setattr__(self, "header", tuple(self.header))

    @property
    def npts(self) -> int:
        """Number of samples."""
        return self.acceleration.size

    @property
    def duration(self) -> float:
        """Time of the last sample, ``(npts - 1) * dt``, s."""
        return (self.npts - 1) * self.dt

    @property
    def time(self) -> np.ndarray:
        """(npts,) read-only array of sample times ``k * dt``, s."""
        return _read_only_view(self._times)

    @cached_property
    def _times(self) -> np.ndarray:
        return np.arange(self.npts) * self.dt

    @property
    def pga(self) -> float:
        """Peak ground acceleration, ``max |acceleration|``, m/s^2."""
        return float(np.max(np.abs(self.acceleration)))

    def __call__(self, t):
        """Acceleration at time(s) ``t``, m/s^2.

        Parameters
        ----------
        t : float or array_like
            Time(s), s.

        Returns
        -------
        float or ndarray
            Linearly interpolated acceleration, same shape as ``t``; zero for ``t < 0`` and
            ``t > duration``.
        """
        return np.interp(t, self._times, self._samples, left=0.0, right=0.0)

    def piecewise(self):
        """Exact piecewise-linear form: linear between samples, zero before 0 and after the end.

        A record whose first (last) sample is not zero jumps at t = 0 (at its end).
        """
        from unilateral.loads.piecewise import linear_table

        return linear_table(self._times, self._samples, 0.0, 0.0)

    @property
    def breakpoints(self) -> np.ndarray:
        """Times of the samples (kinks of the interpolation; jumps at the ends if nonzero)."""
        return self.piecewise().edges

    def limits(self, t) -> tuple[float, float]:
        """One-sided values ``(a(t-), a(t+))``."""
        return self.piecewise().limits(t)

    def grid_samples(self, dt: float, N: int, sampling: str = "hat") -> np.ndarray:
        """Samples at ``k dt`` that keep a rule's order (see :mod:`unilateral.loads.piecewise`)."""
        return self.piecewise().grid_samples(dt, N, sampling)

    def scaled(self, factor: float) -> GroundMotion:
        """Copy with the acceleration multiplied by ``factor`` (finite, may be negative)."""
        factor = float(factor)
        if not math.isfinite(factor):
            raise ValueError(f"factor must be finite, got {factor!r}")
        return replace(self, acceleration=self.acceleration * factor)

    def resampled(self, dt: float) -> GroundMotion:
        """Copy sampled at the time step ``dt`` (s) by linear interpolation.

        The new record keeps the samples ``k * dt`` that lie within the original duration
        (to a relative 1e-9 of ``dt``), so its duration may be shorter by less than ``dt``.
        """
        dt = positive_float("dt", dt)
        npts = math.floor(self.duration / dt + 1e-9) + 1
        acceleration = np.interp(np.arange(npts) * dt, self._times, self._samples)
        return replace(self, dt=dt, acceleration=acceleration)


@dataclass(frozen=True, eq=False)
class Table:
    """Numeric table read from a text file by :func:`read_table`.

    Attributes
    ----------
    path : Path
        The file.
    values : (nrows, ncols) ndarray
        The numbers, row by row.
    line_numbers : (nrows,) ndarray of int
        1-based file line of each row, for error messages.
    header : tuple of str
        Non-blank lines before the first data row (skipped header lines and comments).
    """

    path: Path
    values: np.ndarray
    line_numbers: np.ndarray
    header: tuple[str, ...]

    def column(self, index: int, name: str) -> np.ndarray:
        """Column ``index`` as an (nrows,) array; ``name`` is the argument named in errors."""
        ncols = self.values.shape[1]
        if isinstance(index, bool) or not isinstance(index, int) or not 0 <= index < ncols:
            raise ValueError(f"{name}={index!r} is out of range: {self.path} has {ncols} column(s)")
        return self.values[:, index]


def read_at2(path, *, units: str | None = None) -> GroundMotion:
    """Read a PEER NGA ``.AT2`` acceleration record.

    The file has four header lines: a title, the event/station/component, a line such as
    ``ACCELERATION TIME SERIES IN UNITS OF G`` and the NPTS/DT line, which comes in several
    variants, all accepted (any case, any leading spaces)::

        NPTS=  1999, DT=   .0100 SEC      (optionally followed by more text)
        NPTS=3309,    DT=0.0050SEC
        NPTS= 1999 DT= 0.01 SEC
        3930 0.00500 NPTS, DT             (old PEER format)

    The values follow, any number per line, separated by spaces, as plain or Fortran E/D
    format numbers (``-.1234E-02``, ``1.0D-03``).

    Parameters
    ----------
    path : str or Path
        The file.
    units : str, optional
        Units of the values (see :func:`~unilateral.loads.units.acceleration_factor`). Needed
        only if line 3 does not declare them (``... UNITS OF G``); the default is then g. If
        both are given they must agree.

    Returns
    -------
    GroundMotion
        Acceleration in m/s^2, named after the file stem, with the four header lines.

    Raises
    ------
    RecordFormatError
        Empty file, fewer than four lines, missing or invalid NPTS or DT, unknown units in
        the header, a token that is not a number, or fewer values than NPTS.
    ValueError
        If ``units`` is unknown or disagrees with the units declared in the file.

    Warns
    -----
    UserWarning
        If there are more values than NPTS; the first NPTS are used.
    """
    path = Path(path)
    lines = _read_lines(path)
    if len(lines) < AT2_HEADER_LINES:
        raise RecordFormatError(
            path, f"only {len(lines)} line(s); a PEER .AT2 file starts with {AT2_HEADER_LINES} header lines"
        )
    label, factor = _at2_units(path, lines[_AT2_UNITS_LINE - 1], units)
    npts, dt = _at2_npts_dt(path, lines[AT2_HEADER_LINES - 1])
    values = [
        value
        for lineno, line in enumerate(lines[AT2_HEADER_LINES:], start=AT2_HEADER_LINES + 1)
        for value in _parse_row(path, line, lineno)
    ]
    if len(values) < npts:
        raise RecordFormatError(path, f"found {len(values)} values after the header, expected NPTS={npts}")
    if len(values) > npts:
        warnings.warn(
            f"{path}: found {len(values)} values after the header but NPTS={npts}; using the first {npts}",
            stacklevel=2,
        )
    return GroundMotion(
        dt,
        np.array(values[:npts]) * factor,
        name=path.stem,
        source=str(path),
        header=tuple(line.strip() for line in lines[:AT2_HEADER_LINES]),
        units=label,
    )


def read_text_record(
    path,
    *,
    dt: float | None = None,
    units: str | None = None,
    columns: int | None = None,
    skip_header: int | None = 0,
    time_column: int = 0,
    value_column: int = 1,
) -> GroundMotion:
    """Read an acceleration record from a plain text file.

    Values are separated by commas and/or whitespace; ``#`` starts a comment. A file with
    one column holds the values and needs ``dt``. A file with several columns has the times
    in ``time_column`` and the values in ``value_column``; the time step is inferred and
    must be uniform: every step must equal the median step to a relative
    :data:`UNIFORM_STEP_RTOL`, otherwise resample the record before reading it. The first
    sample is taken to be at t = 0 (with a warning if the time column starts elsewhere).

    Parameters
    ----------
    path : str or Path
        The file.
    dt : float, optional
        Time step, s. Required for one column; checked against the time column otherwise.
    units : str
        Units of the values, e.g. ``"g"`` or ``"cm/s2"``. Required: a file of bare numbers
        does not say its units.
    columns : int, optional
        Expected number of columns per row; by default that of the first data row. Rows with
        another count raise.
    skip_header : int or None, optional
        Lines to skip at the top of the file; None skips the leading lines that are not
        all numbers. Default 0.
    time_column, value_column : int, optional
        0-based columns of time and acceleration in a multi-column file (default 0 and 1).

    Returns
    -------
    GroundMotion
        Acceleration in m/s^2, named after the file stem.

    Raises
    ------
    RecordFormatError
        No data, a token that is not a number, a row with the wrong column count, a
        non-uniform or non-increasing time column.
    ValueError
        Missing ``units``, missing ``dt`` for one column, ``dt`` disagreeing with the time
        column, or a column index out of range.
    """
    path = Path(path)
    if units is None:
        raise ValueError(
            f"{path}: units is required for a text record (a file of bare numbers does not say "
            "its units); pass e.g. units='g' or units='cm/s2'"
        )
    factor = acceleration_factor(units)
    table = read_table(path, skip_header=skip_header, columns=columns)
    if table.values.shape[1] == 1:
        if dt is None:
            raise ValueError(f"{path}: a one-column record needs dt, the time step in s")
        step = positive_float("dt", dt)
        values = table.values[:, 0]
    else:
        if time_column == value_column:
            raise ValueError(f"time_column and value_column must differ, both are {time_column!r}")
        step = _uniform_step(table, table.column(time_column, "time_column"))
        values = table.column(value_column, "value_column")
        if dt is not None and not math.isclose(positive_float("dt", dt), step, rel_tol=UNIFORM_STEP_RTOL):
            raise ValueError(f"{path}: dt={dt!r} disagrees with the time step {step!r} s of the time column")
    return GroundMotion(
        step, values * factor, name=path.stem, source=str(path), header=table.header, units=units
    )


def read_record(path, **kwargs) -> GroundMotion:
    """Read a record, choosing the reader by the file suffix.

    ``.at2`` (any case) is read by :func:`read_at2`, anything else by
    :func:`read_text_record`; ``kwargs`` are passed on to the reader. An ``.AT2`` file takes
    only ``units``: other options (``dt``, ``skip_header``, ...) raise ``ValueError``.
    """
    if Path(path).suffix.lower() != ".at2":
        return read_text_record(path, **kwargs)
    text_only = sorted(set(kwargs) - {"units"})
    if text_only:
        raise ValueError(
            f"{path}: {', '.join(text_only)} {'is' if len(text_only) == 1 else 'are'} for plain-text records "
            f"only; a PEER .AT2 file has "
            f"{AT2_HEADER_LINES} header lines that give NPTS and DT (only units may be given, to check its header)"
        )
    return read_at2(path, **kwargs)


def read_table(path, *, skip_header: int | None = 0, columns: int | None = None) -> Table:
    """Read a table of numbers separated by commas and/or whitespace.

    ``#`` starts a comment; blank and comment lines are ignored. Numbers may use Fortran E or
    D exponents; ``nan`` and ``inf`` are rejected.

    Parameters
    ----------
    path : str or Path
        The file.
    skip_header : int or None, optional
        Lines to skip at the top; None skips the leading lines that are not all numbers
        (e.g. a row of column names). Default 0.
    columns : int, optional
        Expected number of columns; by default that of the first data row.

    Returns
    -------
    Table

    Raises
    ------
    RecordFormatError
        Empty file, no data rows, a token that is not a number or a row with another number
        of columns.
    """
    path = Path(path)
    _check_count("skip_header", skip_header, minimum=0)
    _check_count("columns", columns, minimum=1)
    skip = skip_header or 0
    ncols = columns
    header, rows, line_numbers = [], [], []
    for lineno, line in enumerate(_read_lines(path), start=1):
        text = line.split("#", 1)[0].strip()
        if not rows and (not text or lineno <= skip or (skip_header is None and not _is_numeric(text))):
            if line.strip():
                header.append(line.strip())
            continue
        if not text:
            continue
        if not rows and not _is_numeric(text):
            raise RecordFormatError(path, _header_hint(text, lineno, skip), lineno)
        row = _parse_row(path, text, lineno)
        ncols = len(row) if ncols is None else ncols
        if len(row) != ncols:
            raise RecordFormatError(path, f"{len(row)} column(s), expected {ncols}", lineno)
        rows.append(row)
        line_numbers.append(lineno)
    if not rows:
        raise RecordFormatError(path, "no data rows")
    return Table(path, np.array(rows), np.array(line_numbers), tuple(header))


def _header_hint(text: str, lineno: int, skip: int) -> str:
    """Message for a first data line that is not all numbers: most likely a header."""
    token = next(field for field in _fields(text) if not _NUMBER.fullmatch(field))
    shown = text if len(text) <= 60 else text[:57] + "..."
    told = f" (after skipping {skip} line(s))" if skip else ""
    return (f"{token!r} is not a number: is {shown!r}{told} a header? Skip it with skip_header={lineno} "
            f"(in a model file: skip_header = {lineno}), or with skip_header=None every leading line that "
            "is not all numbers")


def _read_only_view(array: np.ndarray) -> np.ndarray:
    """Read-only view of ``array``.

    Classes holding arrays expose such views and keep the writeable arrays privately for
    ``np.interp``, which copies read-only inputs on every call.
    """
    view = array.view()
    view.flags.writeable = False
    return view


def _read_lines(path: Path) -> list[str]:
    text = read_input_text(path, limit=TABLE_LIMIT, errors="replace")   # regular files only (a FIFO blocks)
    if not text.strip():
        raise RecordFormatError(path, "empty file")
    return text.splitlines()


def _check_count(name: str, value, *, minimum: int) -> None:
    """Raise ``ValueError`` unless ``value`` is None or an integer >= ``minimum``."""
    if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < minimum):
        raise ValueError(f"{name} must be None or an integer >= {minimum}, got {value!r}")


def _fields(text: str) -> list[str]:
    return [field for field in _FIELD_SEPARATOR.split(text.strip()) if field]


def _is_numeric(text: str) -> bool:
    return all(_NUMBER.fullmatch(field) for field in _fields(text))


def _parse_row(path: Path, text: str, lineno: int) -> list[float]:
    return [_parse_number(path, field, lineno) for field in _fields(text)]


def _parse_number(path: Path, token: str, lineno: int) -> float:
    if not _NUMBER.fullmatch(token):
        raise RecordFormatError(path, f"{token!r} is not a number", lineno)
    return float(token.translate(_D_EXPONENT))


def _at2_units(path: Path, line: str, units: str | None) -> tuple[str, float]:
    """Units label and factor to m/s^2 from the units line of an AT2 file and the ``units`` argument."""
    match = _UNITS.search(line)
    if match is None:
        label = "g" if units is None else units
        return label, acceleration_factor(label)
    declared = match.group(1).rstrip(".")
    try:
        factor = acceleration_factor(declared)
    except ValueError as exc:
        raise RecordFormatError(path, f"units in the header: {exc}", _AT2_UNITS_LINE) from None
    if units is not None and acceleration_factor(units) != factor:
        raise ValueError(
            f"{path}: units={units!r} disagrees with the units {declared!r} declared on line "
            f"{_AT2_UNITS_LINE} of the file"
        )
    return declared, factor


def _at2_npts_dt(path: Path, line: str) -> tuple[int, float]:
    """NPTS and DT from the last header line of an AT2 file."""
    lineno = AT2_HEADER_LINES
    match = _VALUES_FIRST.match(line)
    if match:
        npts_text, dt_text = match.groups()
    else:
        npts_text = _at2_keyword(path, line, "NPTS")
        dt_text = _at2_keyword(path, line, "DT")
    npts = _parse_number(path, npts_text, lineno)
    dt = _parse_number(path, dt_text, lineno)
    if npts < 1 or npts != int(npts):
        raise RecordFormatError(path, f"NPTS must be a positive integer, got {npts_text!r}", lineno)
    if dt <= 0:
        raise RecordFormatError(path, f"DT must be positive, got {dt_text!r}", lineno)
    return int(npts), dt


def _at2_keyword(path: Path, line: str, keyword: str) -> str:
    """The number after ``keyword=`` on the NPTS/DT line."""
    match = re.search(rf"\b{keyword}\s*=\s*", line, re.IGNORECASE)
    if match is None:
        raise RecordFormatError(
            path,
            f"missing {keyword} in {line.strip()!r}; expected e.g. {_NPTS_DT_EXAMPLES}",
            AT2_HEADER_LINES,
        )
    number = _NUMBER.match(line, match.end())
    if number is None:
        rest = line[match.end():].split(",")[0].strip()
        raise RecordFormatError(path, f"{keyword}= is followed by {rest!r}, not a number", AT2_HEADER_LINES)
    return number.group()


def _uniform_step(table: Table, times: np.ndarray) -> float:
    """Time step of a uniform, increasing time column (see :func:`read_text_record`)."""
    if times.size < 2:
        raise RecordFormatError(table.path, "a time column needs at least two rows to give the time step")
    steps = np.diff(times)
    reference = float(np.median(steps))
    off = np.flatnonzero(~(np.abs(steps - reference) <= UNIFORM_STEP_RTOL * abs(reference)))
    if reference <= 0 or off.size:
        i = int(off[0]) if off.size else 0
        raise RecordFormatError(
            table.path,
            f"time {float(times[i + 1])!r} follows {float(times[i])!r}: the time column must increase "
            f"with a uniform step (median step {reference:.6g} s, relative tolerance {UNIFORM_STEP_RTOL:g}); "
            "resample the record to a uniform step",
            int(table.line_numbers[i + 1]),
        )
    step = float(times[-1] - times[0]) / (times.size - 1)
    if abs(times[0]) > UNIFORM_STEP_RTOL * step:
        warnings.warn(
            f"{table.path}: the time column starts at t={float(times[0])!r} s; "
            "the record is taken to start at t = 0",
            stacklevel=3,
        )
    return step
