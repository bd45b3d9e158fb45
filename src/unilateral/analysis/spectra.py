"""Response spectra of a run: the input ground motion's and the floor spectra of chosen nodes.

The pseudo-acceleration spectrum ``Sa(T, zeta) = (2 pi / T)^2 max |u|`` is the peak response of a
linear oscillator ``u'' + 2 zeta w u' + w^2 u = -a(t)`` at rest at the first sample, ``w = 2 pi / T``.
The acceleration ``a`` is taken as piecewise linear between its samples and the oscillator is
stepped by the exact recurrence of :func:`unilateral.analysis.response_spectrum.oscillator_recurrence` (the
one the batch's :func:`~unilateral.analysis.response_spectrum.response_spectrum` steps), here for all periods
and all histories at once.

A run with a ground motion gets (:func:`run_spectra`):

* the *input spectrum* of the ground acceleration ``a_g`` along the ground motion's direction
  (the sum of the records along it), as sampled at the time steps of the analysis;
* a *floor spectrum* per chosen node and case: of the node's absolute acceleration along that
  direction, ``u''`` relative to the ground (of the time rule) plus ``a_g``. A node on the ground
  (supported along that direction) moves with it: its floor spectrum is the input spectrum.

The peaks are taken over the analysis, ``0 <= t <= t_end``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

DEFAULT_DAMPING = 0.05
#: Periods of the spectra by default: shortest and longest [s] and their number (log-spaced).
DEFAULT_PERIODS = (0.02, 4.0, 100)


@dataclass(frozen=True)
class SpectraSettings:
    """What spectra a run computes.

    Attributes
    ----------
    periods : (p,) ndarray
        Periods ``T > 0`` [model time unit], increasing.
    damping : float
        Damping ratio ``zeta``, ``0 <= zeta < 1``.
    nodes : tuple
        The node ids of the floor spectra (none: the input spectrum only).
    """

    periods: np.ndarray
    damping: float = DEFAULT_DAMPING
    nodes: tuple = ()


def period_grid(shortest: float, longest: float, count: int) -> np.ndarray:
    """``count`` periods from ``shortest`` to ``longest``, evenly spaced on a logarithmic scale.

    Parameters
    ----------
    shortest, longest : float
        ``0 < shortest < longest`` [time].
    count : int
        ``>= 2``.

    Returns
    -------
    (count,) ndarray
    """
    if not (np.isfinite(shortest) and np.isfinite(longest) and 0 < shortest < longest):
        raise ValueError(f"periods: need 0 < shortest < longest, got shortest={shortest!r}, longest={longest!r}")
    if isinstance(count, bool) or not isinstance(count, int | np.integer) or count < 2:
        raise ValueError(f"periods: count must be an integer >= 2, got {count!r}")
    return np.geomspace(shortest, longest, int(count))


def pseudo_acceleration(acceleration, dt: float, periods, damping: float = DEFAULT_DAMPING) -> np.ndarray:
    """Pseudo-spectral accelerations ``Sa(T) = (2 pi / T)^2 max |u|`` of acceleration histories.

    Parameters
    ----------
    acceleration : (N,) or (N, r) array_like
        ``r`` histories sampled at the step ``dt`` [length/time^2], piecewise linear in between.
    dt : float
        Time step > 0 [time].
    periods : (p,) array_like
        Periods ``T > 0`` [time].
    damping : float
        Damping ratio ``zeta``, ``0 <= zeta < 1``.

    Returns
    -------
    (p,) or (p, r) ndarray
        ``Sa`` [length/time^2]; the peak is taken over the samples of each history.
    """
    from .response_spectrum import oscillator_recurrence

    a = np.asarray(acceleration, dtype=float)
    T = np.asarray(periods, dtype=float).ravel()
    if a.ndim not in (1, 2) or a.shape[0] < 1 or not np.all(np.isfinite(a)):
        raise ValueError(f"acceleration must be (N,) or (N, r) finite samples, got shape {a.shape}")
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be finite and > 0, got {dt!r}")
    if T.size == 0 or not np.all(np.isfinite(T) & (T > 0)):
        raise ValueError(f"periods must be finite and > 0, got {periods!r}")
    if not 0 <= damping < 1:
        raise ValueError(f"damping must be in [0, 1), got {damping!r}")
    histories = a.reshape(a.shape[0], -1)
    steps = np.stack([oscillator_recurrence(period, damping, dt) for period in T])     # (p, 2, 4)
    peak = _peak_displacements(steps, histories, dt)
    Sa = (2 * np.pi / T)[:, None] ** 2 * peak
    return Sa[:, 0] if a.ndim == 1 else Sa


def _peak_displacements(steps: np.ndarray, histories: np.ndarray, dt: float) -> np.ndarray:
    """``max |u|`` (p, r) of the oscillators of ``steps`` (p, 2, 4) under ``histories`` (N, r)."""
    (a11, a12, b1, c1), (a21, a22, b2, c2) = np.moveaxis(steps[..., None], 0, 2)     # each (p, 1)
    slopes = np.diff(histories, axis=0) / dt
    u = np.zeros((steps.shape[0], histories.shape[1]))
    v = np.zeros_like(u)
    peak = np.zeros_like(u)
    for ak, sk in zip(histories[:-1], slopes):
        u, v = a11 * u + a12 * v + b1 * ak + c1 * sk, a21 * u + a22 * v + b2 * ak + c2 * sk
        np.maximum(peak, np.abs(u), out=peak)
    return peak


def spectrum_peak(periods, Sa) -> dict:
    """``{"Sa": peak, "period": T}``: the largest ``Sa`` (p,) and its period."""
    k = int(np.argmax(Sa))
    return {"Sa": float(Sa[k]), "period": float(np.asarray(periods)[k])}


def absolute_accelerations(structure, relative, ground, nodes, direction: str) -> np.ndarray:
    """Absolute accelerations of ``nodes`` along ``direction``: ``u''`` of the node plus ``a_g``.

    Parameters
    ----------
    structure : unilateral.structure.Structure
    relative : (N, n) ndarray
        ``u''`` of the free DOFs relative to the ground [length/time^2].
    ground : (N,) ndarray
        The ground acceleration along ``direction`` [length/time^2].
    nodes : sequence of node ids
    direction : ``"ux"`` or ``"uy"``

    Returns
    -------
    (N, len(nodes)) ndarray
        A supported node moves with the ground; a slave node follows its master rigidly.
    """
    rows = [structure.dofs.full_index(node, direction) for node in nodes]
    nodal = np.asarray(structure.dofs.T[rows] @ np.asarray(relative, dtype=float).T).T
    return nodal + np.asarray(ground, dtype=float)[:, None]


def run_spectra(structure, results: dict, settings: SpectraSettings, dt: float, direction=None) -> dict | None:
    """The input and floor spectra of a frame's results, or None without a ground motion.

    Parameters
    ----------
    structure : unilateral.structure.Structure
    results : dict
        :func:`unilateral.analysis.results.structure_results` of the cases: its ``variables``
        ``acceleration`` (N, n) and ``ground_acceleration`` (N, e) per case and the coordinate
        ``excitation`` (``"<k>:<direction>"`` per ground motion).
    settings : SpectraSettings
    dt : float
        Time step of the analysis [time].
    direction : ``"ux"``, ``"uy"`` or ``"uz"``, optional
        The direction of the spectra (a 3-D frame: each horizontal direction, :func:`directions`);
        default: ``"ux"`` if a ground motion acts along it, else ``"uy"``. None is returned if no
        ground motion acts along ``direction``.

    Returns
    -------
    dict or None
        ``direction`` (``"ux"``, or ``"uy"`` for a vertical ground motion only), ``periods`` (p,),
        ``damping``, ``ground`` (p,) the input spectrum, ``floors`` case -> (p, len(nodes)) and
        ``nodes``. A case that stopped early gives its spectra up to its last step.
    """
    variables = results["variables"]
    if "ground_acceleration" not in variables or "acceleration" not in variables:
        return None
    directions = [str(label).rpartition(":")[2] for label in results["coords"]["excitation"]]
    if direction is None:
        direction = "ux" if "ux" in directions else "uy"
    elif direction not in directions:
        return None
    along = np.array([d == direction for d in directions])
    ground_by_case = {case: a[:, along].sum(axis=1) for case, a in variables["ground_acceleration"][1].items()}
    longest = max(ground_by_case, key=lambda case: _finite_rows(ground_by_case[case]))
    ground = ground_by_case[longest][:_finite_rows(ground_by_case[longest])]
    out = {"direction": direction, "periods": settings.periods, "damping": settings.damping,
           "ground": pseudo_acceleration(ground, dt, settings.periods, settings.damping),
           "nodes": tuple(settings.nodes), "floors": {}}
    if not settings.nodes:
        return out
    for case, relative in variables["acceleration"][1].items():
        n = min(_finite_rows(relative), len(ground_by_case[case]))
        if n < 1:
            continue
        absolute = absolute_accelerations(structure, relative[:n], ground_by_case[case][:n], settings.nodes, direction)
        out["floors"][case] = pseudo_acceleration(absolute, dt, settings.periods, settings.damping)
    return out


def directions(results: dict) -> list[str]:
    """The directions of the spectra of a 3-D frame's results: those of its horizontal ground motions
    (``ux``, ``uy``), else ``uz`` for a vertical one alone; empty without a ground motion."""
    if "excitation" not in results.get("coords", {}):
        return []
    given = {str(label).rpartition(":")[2] for label in results["coords"]["excitation"]}
    return [d for d in ("ux", "uy") if d in given] or [d for d in ("uz",) if d in given]


def _finite_rows(values: np.ndarray) -> int:
    """The number of leading rows of ``values`` that are finite everywhere."""
    finite = np.isfinite(np.asarray(values).reshape(len(values), -1)).all(axis=1)
    return len(finite) if finite.all() else int(np.argmin(finite))


def spectra_summary(spectra: dict) -> dict:
    """The ``spectra`` entry of ``summary.json``: damping, direction and the peaks.

    Returns
    -------
    dict
        ``damping``, ``direction``, ``ground`` ``{"Sa", "period"}`` and, with floor spectra,
        ``floors`` case (``unilateral``, ``bilateral``) -> node -> ``{"Sa", "period"}``.
    """
    periods = spectra["periods"]
    out = {"damping": spectra["damping"], "direction": spectra["direction"],
           "ground": spectrum_peak(periods, spectra["ground"])}
    if spectra["floors"]:
        out["floors"] = {case: {str(node): spectrum_peak(periods, Sa[:, k])
                                                          for k, node in enumerate(spectra["nodes"])}
                         for case, Sa in spectra["floors"].items()}
    return out


def spectra_columns(spectra: dict, units: dict) -> dict:
    """The columns of ``spectra.csv``: ``period [s]``, ``Sa:ground [m/s^2]``, ``Sa:<case>:<node> [m/s^2]``."""
    time, length = (units or {}).get("time", ""), (units or {}).get("length", "")
    unit = f" [{length}/{time}^2]" if length and time else ""
    columns = {f"period [{time}]" if time else "period": spectra["periods"], f"Sa:ground{unit}": spectra["ground"]}
    for case, Sa in spectra["floors"].items():
        for k, node in enumerate(spectra["nodes"]):
            columns[f"Sa:{case}:{node}{unit}"] = Sa[:, k]
    return columns
