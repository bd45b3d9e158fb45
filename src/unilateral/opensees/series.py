"""OpenSees time series (``Constant``, ``Linear``, ``Path``) and load patterns (``Plain``,
``UniformExcitation``), evaluated as OpenSees evaluates them.

A ``Path`` given with ``-dt`` is zero from the time of its last sample on (its interval index
reaches the end; ``-useLast`` keeps the last value), a ``Path`` given with ``-time`` is zero before
its first and after its last time; both are linear between samples and scaled by ``-factor``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .refusals import refuse

__all__ = ["Series", "Pattern", "parse_series", "parse_pattern"]


@dataclass
class Series:
    """A time series: ``kind`` ``"Constant"``, ``"Linear"`` or ``"Path"``.

    Attributes
    ----------
    kind : str
    factor : float, the ``-factor`` (cFactor)
    dt : float or None, the sample interval of a ``-dt`` path
    values : (k,) ndarray or None, the samples of a path
    times : (k,) ndarray or None, the times of a ``-time`` path
    start : float, ``-startTime`` of a ``-dt`` path
    use_last : bool, ``-useLast``
    """

    kind: str
    factor: float = 1.0
    dt: float | None = None
    values: np.ndarray | None = None
    times: np.ndarray | None = None
    start: float = 0.0
    use_last: bool = False

    def __call__(self, t) -> np.ndarray:
        """The factor of the series at times ``t``.

        Parameters
        ----------
        t : array_like, times (s)

        Returns
        -------
        ndarray, the shape of ``t``
        """
        t = np.asarray(t, dtype=float)
        if self.kind == "Constant":
            return np.full(t.shape, self.factor)
        if self.kind == "Linear":
            return self.factor * t
        values = self.values
        last = self.factor * values[-1] if self.use_last else 0.0
        if self.times is None:
            incr = (t - self.start) / self.dt
            k1 = np.floor(incr).astype(np.int64)
            inside = (k1 >= 0) & (k1 + 1 < values.size)
            k = np.clip(k1, 0, max(values.size - 2, 0))
            v1, v2 = values[k], values[np.minimum(k + 1, values.size - 1)]
            out = self.factor * (v1 + (v2 - v1) * (incr - k))
            return np.where(inside, out, np.where(k1 < 0, 0.0, last))
        times = self.times
        k = np.clip(np.searchsorted(times, t, side="right") - 1, 0, max(times.size - 2, 0))
        t1, t2 = times[k], times[np.minimum(k + 1, times.size - 1)]
        v1, v2 = values[k], values[np.minimum(k + 1, values.size - 1)]
        with np.errstate(invalid="ignore", divide="ignore"):
            out = np.where(t2 > t1, self.factor * (v1 + (v2 - v1) * (t - t1) / (t2 - t1)), self.factor * v1)
        return np.where(t < times[0], 0.0, np.where(t > times[-1], last, out))

    def end(self) -> float:
        """The last time at which the series can be nonzero (inf for Constant, Linear, -useLast)."""
        if self.kind != "Path" or self.use_last:
            return np.inf
        return float(self.times[-1]) if self.times is not None else self.start + self.dt * (self.values.size - 1)


@dataclass
class Pattern:
    """A load pattern: ``Plain`` (nodal loads times a series) or ``UniformExcitation``.

    Attributes
    ----------
    kind : str
    series : int, the tag of its time series
    factor : float, ``-fact``
    direction : int, the ground motion's DOF (1: x, 2: y) of a UniformExcitation
    loads : list of (node, (3,) values) of a Plain pattern
    element_loads : list of (element tag, Wy, Wx) of a Plain pattern's ``eleLoad -beamUniform``
    frozen : float or None, the factor held by ``loadConst`` (None: follows its series)
    """

    kind: str
    series: int
    factor: float = 1.0
    direction: int = 0
    loads: list = field(default_factory=list)
    frozen: float | None = None
    element_loads: list = field(default_factory=list)


def _floats(what, values):
    try:
        return np.array([float(v) for v in values])
    except (TypeError, ValueError):
        refuse(what, f"the values {values!r} are not numbers", "give the samples as numbers")


def _options(what, args, known):
    """``{flag: [values...]}`` of the ``-flag value ...`` arguments, each flag in ``known``."""
    out, flag = {}, None
    for a in args:
        if isinstance(a, str) and a.startswith("-") and not _is_number(a):
            if a not in known:
                refuse(f"{what} option {a!r}", "the option is not in the supported subset",
                       f"the options {', '.join(known)}")
            flag = a
            out[flag] = []
        elif flag is None:
            refuse(what, f"the argument {a!r} is not after an option", f"the options {', '.join(known)}")
        else:
            out[flag].append(a)
    return out


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def parse_series(kind, args) -> Series:
    """The series of ``timeSeries(kind, tag, *args)``.

    Parameters
    ----------
    kind : str, ``"Constant"``, ``"Linear"`` or ``"Path"``
    args : tuple, the arguments after the tag

    Returns
    -------
    Series

    Raises
    ------
    OpenSeesRefused
        For another kind, an unknown option or inconsistent values.
    """
    what = f"timeSeries({kind!r})"
    if kind in ("Constant", "Linear"):
        opts = _options(what, args, ("-factor",))
        return Series(kind, factor=float(opts.get("-factor", [1.0])[0]))
    if kind != "Path":
        refuse(what, "only the Constant, Linear and Path series are in this slice",
               "a Path series of the samples of the function (timeSeries('Path', tag, '-dt', dt, '-values', ...))")
    opts = _options(what, args, ("-dt", "-values", "-time", "-filePath", "-fileTime", "-factor", "-startTime",
                                 "-useLast", "-prependZero"))
    if "-filePath" in opts:
        opts["-values"] = list(np.loadtxt(opts["-filePath"][0]).ravel())
    if "-fileTime" in opts:
        opts["-time"] = list(np.loadtxt(opts["-fileTime"][0]).ravel())
    if "-values" not in opts or not opts["-values"]:
        refuse(what, "a Path needs its values", "give '-values', v1, v2, ... or '-filePath', file")
    values = _floats(what, opts["-values"])
    times = _floats(what, opts["-time"]) if "-time" in opts else None
    if "-prependZero" in opts:
        values = np.concatenate([[0.0], values])
        if times is not None:
            times = np.concatenate([[times[0]], times])
    series = Series("Path", factor=float(opts.get("-factor", [1.0])[0]), values=values, times=times,
                    start=float(opts.get("-startTime", [0.0])[0]), use_last="-useLast" in opts)
    if times is None:
        if "-dt" not in opts:
            refuse(what, "a Path needs '-dt' or '-time'", "give '-dt', dt or '-time', t1, t2, ...")
        series.dt = float(opts["-dt"][0])
        if not series.dt > 0:
            refuse(what, f"-dt {series.dt!r} is not positive", "a sample interval > 0")
    elif times.size != values.size or np.any(np.diff(times) < 0):
        refuse(what, "'-time' must give one nondecreasing time per value", "as many times as values, in order")
    return series


def parse_pattern(kind, args, series_tags) -> Pattern:
    """The pattern of ``pattern(kind, tag, *args)``.

    Parameters
    ----------
    kind : str, ``"Plain"`` or ``"UniformExcitation"``
    args : tuple, the arguments after the tag
    series_tags : the tags of the time series defined

    Returns
    -------
    Pattern

    Raises
    ------
    OpenSeesRefused
        For another kind, a ground displacement or velocity, a rotation, an undefined series.
    """
    what = f"pattern({kind!r})"
    if kind == "Plain":
        if not args:
            refuse(what, "a Plain pattern needs its time series", "pattern('Plain', tag, tsTag)")
        ts = int(args[0])
        opts = _options(what, args[1:], ("-fact", "-factor"))
        factor = float((opts.get("-fact") or opts.get("-factor") or [1.0])[0])
        pattern = Pattern("Plain", ts, factor)
    elif kind == "UniformExcitation":
        if not args:
            refuse(what, "a UniformExcitation needs its direction", "pattern('UniformExcitation', tag, dir, '-accel', ts)")
        direction = int(args[0])
        opts = _options(what, args[1:], ("-accel", "-fact", "-factor", "-disp", "-vel", "-vel0"))
        for flag in ("-disp", "-vel", "-vel0"):
            if flag in opts:
                refuse(f"{what} {flag}", "the ground motion enters as the inertial load -M r a_g(t) of the "
                       "relative displacements; a ground displacement or velocity record is not that load",
                       "'-accel', tsTag with the ground acceleration")
        if "-accel" not in opts:
            refuse(what, "the ground acceleration series is missing", "'-accel', tsTag")
        if direction not in (1, 2, 3):
            refuse(f"{what} direction {direction}", "a ground rotation is not a rigid ground translation",
                   "direction 1 (x), 2 (y) or, in 3-D, 3 (z)")
        factor = float((opts.get("-fact") or opts.get("-factor") or [1.0])[0])
        pattern = Pattern("UniformExcitation", int(opts["-accel"][0]), factor, direction)
    else:
        refuse(what, "only the Plain and UniformExcitation patterns are in this slice",
               "pattern('Plain', ...) of nodal loads or pattern('UniformExcitation', ...)")
    if pattern.series not in series_tags:
        refuse(what, f"time series {pattern.series} is not defined", "define the timeSeries first")
    return pattern
