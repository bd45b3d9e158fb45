"""Load time functions ``f(t)``: pulses, steps and tables.

Every function is a small frozen dataclass that validates its parameters and is called with
a time in s (returns a float) or an array of times (returns an array of the same shape).
Multiply by a load vector to get a load history, e.g. ``lambda t: p * HalfSine(1.0,
duration=0.2)(t)``.

Pulses are zero at their start time and switch on just after it (``t_start < t``). A pulse
starting at t = 0 therefore has ``f(0) = 0``, so that the static equilibrium a solver starts
from at t = 0 is the unloaded one.

Every function also knows its exact piecewise form (:meth:`TimeFunction.piecewise`): its
breakpoints (jumps in value, kinks) and its one-sided values there (:meth:`TimeFunction.limits`).
That is what the event-driven reference method integrates exactly, and what
:meth:`TimeFunction.grid_samples` uses to give a time-stepping rule load samples that keep its
order of accuracy across jumps (see :mod:`unilateral.loads.piecewise`).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import KW_ONLY, dataclass

import numpy as np

from unilateral._validate import as_vector, choice, positive_float
from unilateral.loads.piecewise import Piecewise, constant, linear_table
from unilateral.loads.records import RecordFormatError, _read_only_view, read_table


#: Relative tolerance of the inclusive end of a rectangular pulse (round-off of k dt).
END_TOLERANCE = 1e-9


class TimeFunction(ABC):
    """Base of the load time functions: a scalar function of time ``f(t)``."""

    def __call__(self, t):
        """Value(s) at time(s) ``t``.

        Parameters
        ----------
        t : float or array_like
            Time(s), s.

        Returns
        -------
        float or ndarray
            ``f(t)``, same shape as ``t``.
        """
        return self._evaluate(np.asarray(t, dtype=float))[()]

    @abstractmethod
    def _evaluate(self, t: np.ndarray) -> np.ndarray:
        """Values at the float array of times ``t`` (any shape), same shape."""

    def piecewise(self) -> Piecewise | None:
        """The exact piecewise (polynomial + sinusoid) form of the function, or None.

        Subclasses defined outside the package may have none: they are then point-sampled by
        time stepping and refused by ``method="event"``.
        """
        return None

    def _form(self) -> Piecewise:
        form = self.piecewise()
        if form is None:
            raise TypeError(f"{type(self).__name__} has no piecewise form (its piecewise() returns None)")
        return form

    @property
    def breakpoints(self) -> np.ndarray:
        """Times (s) where the function jumps or has a kink, increasing."""
        return self._form().edges

    def limits(self, t) -> tuple[float, float]:
        """One-sided values ``(f(t-), f(t+))`` at time ``t``."""
        return self._form().limits(t)

    def grid_samples(self, dt: float, N: int, sampling: str = "hat") -> np.ndarray:
        """Samples at ``t_k = k dt`` (k = 0..N) that keep a rule's order across jumps.

        See :meth:`unilateral.loads.piecewise.Piecewise.grid_samples`; ``f(0-)`` (the static
        preload) is ``limits(0.0)[0]``.
        """
        return self._form().grid_samples(dt, N, sampling)


@dataclass(frozen=True)
class Rectangular(TimeFunction):
    """Rectangular pulse: ``amplitude`` for ``t_start < t <= t_end``, zero elsewhere.

    Parameters
    ----------
    amplitude : float
        Pulse value.
    t_start : float, optional, keyword-only
        Start time, s (default 0); the value at ``t_start`` itself is 0.
    t_end : float, keyword-only
        End time, s, ``> t_start``; the value at ``t_end`` is ``amplitude`` (times that exceed
        ``t_end`` by round-off only, a relative ``END_TOLERANCE``, count as ``t_end``).
    """

    amplitude: float
    _: KW_ONLY
    t_start: float = 0.0
    t_end: float

    def __post_init__(self):
        _set_finite(self, "amplitude", "t_start", "t_end")
        _check_order(self, "t_start", "t_end", strict=True)

    def _evaluate(self, t):
        # the inclusive end is widened by a relative 1e-9 so that sampled times k dt that
        # round to just above t_end (3 * 0.1 > 0.3) still see the pulse
        end = self.t_end + END_TOLERANCE * max(abs(self.t_end), abs(self.t_start), 1e-300)
        return np.where((t > self.t_start) & (t <= end), self.amplitude, 0.0)

    def piecewise(self) -> Piecewise:
        return Piecewise([self.t_start, self.t_end], [[0.0], [self.amplitude], [0.0]])


@dataclass(frozen=True)
class Triangular(TimeFunction):
    """Triangular pulse: 0 at ``t_start``, linear up to ``amplitude`` at ``t_peak``, linear
    down to 0 at ``t_end``, zero outside.

    ``t_peak == t_start`` gives the instantaneous rise of a blast load (``f(t_start) = 0`` and
    ``f`` jumps to ``amplitude`` just after); ``t_peak == t_end`` a sawtooth ending with a
    drop to 0 just after ``t_end``.

    Parameters
    ----------
    amplitude : float
        Peak value.
    t_start : float, optional, keyword-only
        Start time, s (default 0).
    t_peak : float, keyword-only
        Time of the peak, s, ``t_start <= t_peak <= t_end``.
    t_end : float, keyword-only
        End time, s, ``> t_start``.
    """

    amplitude: float
    _: KW_ONLY
    t_start: float = 0.0
    t_peak: float
    t_end: float

    def __post_init__(self):
        _set_finite(self, "amplitude", "t_start", "t_peak", "t_end")
        _check_order(self, "t_start", "t_end", strict=True)
        _check_order(self, "t_start", "t_peak", strict=False)
        _check_order(self, "t_peak", "t_end", strict=False)

    def _evaluate(self, t):
        rise = self.t_peak - self.t_start
        fall = self.t_end - self.t_peak
        up = (t - self.t_start) / rise if rise > 0 else 1.0
        down = (self.t_end - t) / fall if fall > 0 else 1.0
        on = (t > self.t_start) & (t <= self.t_end)
        return np.where(on, self.amplitude * np.minimum(up, down), 0.0)

    def piecewise(self) -> Piecewise:
        A, ts, tp, te = self.amplitude, self.t_start, self.t_peak, self.t_end
        edges, poly = [ts], [[0.0, 0.0]]
        if tp > ts:                                     # rise, from ts
            poly.append([0.0, A / (tp - ts)])
        if te > tp:                                     # fall, from tp
            if tp > ts:
                edges.append(tp)
            poly.append([A, -A / (te - tp)])
        edges.append(te)
        poly.append([0.0, 0.0])
        return Piecewise(edges, poly)


@dataclass(frozen=True)
class HalfSine(TimeFunction):
    """Half-sine pulse: ``amplitude * sin(pi (t - t_start) / duration)`` for
    ``t_start < t < t_start + duration``, zero elsewhere.

    Parameters
    ----------
    amplitude : float
        Peak value, reached at ``t_start + duration / 2``.
    t_start : float, optional, keyword-only
        Start time, s (default 0).
    duration : float, keyword-only
        Pulse duration, s, > 0.
    """

    amplitude: float
    _: KW_ONLY
    t_start: float = 0.0
    duration: float

    def __post_init__(self):
        _set_finite(self, "amplitude", "t_start")
        object.__setattr__(self, "duration", positive_float("duration", self.duration))

    def _evaluate(self, t):
        phase = (t - self.t_start) / self.duration
        return np.where((phase > 0) & (phase < 1), self.amplitude * np.sin(np.pi * phase), 0.0)

    def piecewise(self) -> Piecewise:
        return Piecewise([self.t_start, self.t_start + self.duration], np.zeros((3, 1)),
                         [[0.0, 0.0], [0.0, self.amplitude], [0.0, 0.0]], np.pi / self.duration)


@dataclass(frozen=True)
class Constant(TimeFunction):
    """Constant ``value`` at all times, t = 0 included (a static load)."""

    value: float

    def __post_init__(self):
        _set_finite(self, "value")

    def _evaluate(self, t):
        return np.full(t.shape, self.value)

    def piecewise(self) -> Piecewise:
        return constant(self.value)


@dataclass(frozen=True)
class Ramp(TimeFunction):
    """Linear ramp from 0 at t = 0 to ``value`` at ``t_ramp``, then constant; 0 for t < 0.

    Parameters
    ----------
    t_ramp : float
        Rise time, s, > 0.
    value : float
        Final value.
    """

    t_ramp: float
    value: float

    def __post_init__(self):
        object.__setattr__(self, "t_ramp", positive_float("t_ramp", self.t_ramp))
        _set_finite(self, "value")

    def _evaluate(self, t):
        return self.value * np.clip(t / self.t_ramp, 0.0, 1.0)

    def piecewise(self) -> Piecewise:
        return Piecewise([0.0, self.t_ramp], [[0.0, 0.0], [0.0, self.value / self.t_ramp], [self.value, 0.0]])


@dataclass(frozen=True, eq=False)
class Tabulated(TimeFunction):
    """Piecewise-linear interpolation of tabulated values.

    Parameters
    ----------
    t : (n,) array_like
        Strictly increasing times, s, ``n >= 2``. Stored as a float copy, exposed read-only.
    values : (n,) array_like
        Values at ``t``. Stored as a float copy, exposed read-only.
    outside : {"zero", "hold"}, optional
        Value outside ``[t[0], t[-1]]``: zero (default) or the nearest end value.

    Notes
    -----
    Instances compare and hash by identity, since they hold arrays.
    """

    t: np.ndarray
    values: np.ndarray
    outside: str = "zero"

    def __post_init__(self):
        t = as_vector("t", self.t, None)
        values = as_vector("values", self.values, t.size)
        problem = _time_problem(t)
        if problem is not None:
            raise ValueError(f"t: {problem[1]}")
        object.__setattr__(self, "_samples", (t, values))
        object.__setattr__(self, "t", _read_only_view(t))
        object.__setattr__(self, "values", _read_only_view(values))
        object.__setattr__(self, "outside", choice("outside", self.outside, ("zero", "hold")))

    @classmethod
    def from_csv(
        cls,
        path,
        *,
        time_column: int = 0,
        value_column: int = 1,
        skip_header: int | None = None,
        outside: str = "zero",
    ) -> Tabulated:
        """Read a table of times and values from a text file.

        Fields are separated by commas and/or whitespace, ``#`` starts a comment (see
        :func:`~unilateral.loads.records.read_table`).

        Parameters
        ----------
        path : str or Path
            The file.
        time_column, value_column : int, optional
            0-based columns of the times (s) and the values (default 0 and 1).
        skip_header : int or None, optional
            Lines to skip at the top; None (default) skips the leading lines that are not all
            numbers, such as a row of column names.
        outside : {"zero", "hold"}, optional
            As for :class:`Tabulated`.

        Raises
        ------
        RecordFormatError
            Unreadable file, non-numeric token, rows of unequal length, fewer than two rows or
            times that do not increase strictly; the message names the file and line.
        ValueError
            A column index out of range or an invalid ``outside``.
        """
        table = read_table(path, skip_header=skip_header)
        t = table.column(time_column, "time_column")
        values = table.column(value_column, "value_column")
        problem = _time_problem(t)
        if problem is not None:
            index, description = problem
            raise RecordFormatError(table.path, description, int(table.line_numbers[index]))
        return cls(t, values, outside)

    def _evaluate(self, t):
        fill = 0.0 if self.outside == "zero" else None
        return np.asarray(np.interp(t, *self._samples, left=fill, right=fill))

    def piecewise(self) -> Piecewise:
        t, values = self._samples
        if self.outside == "zero":
            return linear_table(t, values, 0.0, 0.0)
        return linear_table(t, values, values[0], values[-1])


def _set_finite(obj, *names: str) -> None:
    """Store the named fields of a frozen dataclass as finite floats, or raise naming them."""
    for name in names:
        value = getattr(obj, name)
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be a real number, got {value!r}") from None
        if not math.isfinite(number):
            raise ValueError(f"{name} must be finite, got {value!r}")
        object.__setattr__(obj, name, number)


def _check_order(obj, earlier: str, later: str, *, strict: bool) -> None:
    """Raise ``ValueError`` unless field ``later`` is after (or, if not strict, at) ``earlier``."""
    a, b = getattr(obj, earlier), getattr(obj, later)
    if b < a or (strict and b == a):
        relation = ">" if strict else ">="
        raise ValueError(f"{later} must be {relation} {earlier}, got {later}={b!r} and {earlier}={a!r}")


def _time_problem(t: np.ndarray) -> tuple[int, str] | None:
    """First defect of a table's times as ``(index, description)``, or None if there is none."""
    if t.size < 2:
        return 0, f"a table needs at least two times, got {t.size}"
    bad = np.flatnonzero(np.diff(t) <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        return i, f"times must increase strictly; t={float(t[i])!r} follows t={float(t[i - 1])!r}"
    return None
