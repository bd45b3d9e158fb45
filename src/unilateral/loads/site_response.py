"""Free-field motion by linear 1D site response: a record moved to the ground surface.

The ground under a footing is idealised as horizontal layers over an elastic half-space (or a
rigid base), shaken by vertically incident plane waves: S waves for the horizontal motion, P
waves for the vertical motion. A record given at a rock outcrop or at depth (a borehole) is
turned into the motion of the ground surface (the *free field*) by the transfer functions of the
profile, in the frequency domain.

:func:`free_field`
    Surface acceleration (N,) from a record (N,).
:func:`transfer_function`
    The complex ratio surface motion / record motion at given frequencies.

Formulation
-----------
In layer ``j`` (thickness ``h_j``, density ``rho_j``, modulus ``G_j`` for S waves or the
constrained modulus ``M_j = 2 G_j (1 - nu_j) / (1 - 2 nu_j)`` for P waves, damping ratio ``xi_j``)
the displacement of frequency ``omega`` (time factor ``exp(i omega t)``) is

    u_j(z) = A_j exp(i k_j z) + B_j exp(-i k_j z),     0 <= z <= h_j from the layer's top,

``A_j`` the up-going and ``B_j`` the down-going wave, with the complex modulus ``G_j (1 + 2 i xi_j)``
(hysteretic, frequency-independent damping, as in SHAKE), the complex speed
``v*_j = v_j sqrt(1 + 2 i xi_j)`` and the wavenumber ``k_j = omega / v*_j``. The free surface
gives ``A_1 = B_1``; continuity of displacement and stress at the bottom of layer ``j`` gives
(Kramer 1996, ch. 7)

    A_{j+1} = (A_j (1 + a_j) exp(i k_j h_j) + B_j (1 - a_j) exp(-i k_j h_j)) / 2
    B_{j+1} = (A_j (1 - a_j) exp(i k_j h_j) + B_j (1 + a_j) exp(-i k_j h_j)) / 2

with the complex impedance ratio ``a_j = rho_j v*_j / (rho_{j+1} v*_{j+1})``. With ``A_1 = B_1 = 1``
the surface motion is 2 and the transfer function surface / record is

- ``at="outcrop"``: ``2 / (2 A_{N+1})`` -- the outcrop motion of the half-space is twice its
  incident (up-going) wave ``A_{N+1}``, referred to the top of the half-space;
- ``at="within"``: ``2 / (A_j exp(i k_j z) + B_j exp(-i k_j z))``, the total (up + down) motion at
  ``depth`` (layer ``j``, ``z`` below its top). It depends on the layers above ``depth`` only;
  a rigid base is the case ``depth`` = the profile's thickness.

The recursion carries ``A``, ``B`` normalised, with the growth ``exp(-Im(k_j) h_j)`` of damped
layers factored out as a logarithm, so that thick, damped profiles do not overflow at high
frequencies (their transfer function underflows to 0 instead).

Zero padding
------------
The padding of :func:`free_field` (its default ``pad``). A discrete Fourier transform makes the
record periodic: the surface response to the end of the record -- the column's free ringing,
trapped by the impedance contrasts and decaying only by damping and radiation into the half-space
-- would wrap around onto the record's start. The record is therefore padded with zeros long enough
for that ringing to decay to :data:`RINGING_TOLERANCE` of its amplitude: the fundamental mode of
the column above the record point (period about ``T1 = 4 t_s``, ``t_s = sum h_j / v_j`` the
vertical travel time) loses per round trip ``2 t_s`` the factor ``q = |r| exp(-pi xi_min)``, ``r``
the reflection coefficient at the base (``|r| = 1`` for a rigid base and for ``at="within"``) and
``xi_min`` the smallest layer damping; the padding is twice the time of ``ln(tol)/ln(q)`` round
trips (a margin for the quarter-wavelength estimate of ``T1``), plus ``t_s``. The padding also
leaves room for the small acausal precursor of frequency-independent (hysteretic) damping, which
wraps to the end of the padded window and is discarded. The FFT length is capped at
``max(16 N, MAX_FFT_LENGTH)``; an undamped column over a rigid base (or ``at="within"``) rings
forever: the cap is used with a ``RuntimeWarning``.

Deconvolution
-------------
``at="within"`` divides by the motion at depth, which nearly vanishes at the frequencies where
``depth`` is a node of a mode of the column above it: with little damping those frequencies are
amplified strongly (as in SHAKE; filter the record or give damping).

Units and conventions
---------------------
Any consistent set of units: thickness [L], G [F/L^2], rho [F T^2/L^4] (mass/L^3), Vs [L/T], dt [T]
(e.g. m, kN, s with rho in t/m^3). The acceleration comes out in the unit it goes in.

References
----------
Kramer, S. L. (1996). *Geotechnical Earthquake Engineering*, ch. 7 (ground response analysis),
Prentice Hall.
Schnabel, P. B., Lysmer, J., Seed, H. B. (1972). SHAKE: a computer program for earthquake response
analysis of horizontally layered sites. Report EERC 72-12, University of California, Berkeley.
Roesset, J. M. (1977). Soil amplification of earthquakes. In *Numerical Methods in Geotechnical
Engineering* (Desai, Christian, eds.), ch. 19, McGraw-Hill.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.fft

from unilateral._validate import as_vector, positive_float

LOCATIONS = ("surface", "outcrop", "within")
"""Where a record is given: the ground surface, a rock outcrop, or at depth inside the profile."""

WAVES = ("S", "P")
"""S waves (horizontal motion) or P waves (vertical motion), vertically incident."""

RINGING_TOLERANCE = 1e-6
"""Amplitude, relative to its start, down to which the column's free ringing is let decay in the
zero padding of :func:`free_field`."""

MAX_FFT_LENGTH = 2 ** 22
"""Largest FFT length :func:`free_field` pads to (beyond 16 times the record's length)."""

#: Thickest layer [L]: far beyond any site, and the FFT length of the column stays computable
#: (``1e308`` overflowed it).
MAX_THICKNESS = 1e7
_LAYER_KEYS = ("thickness", "G", "Vs", "nu", "rho", "damping")
_BASE_KEYS = ("G", "Vs", "nu", "rho", "damping")


@dataclass(frozen=True)
class _Profile:
    """The checked profile: per layer (N,) and the base (None: rigid), for one wave type."""

    thickness: np.ndarray       # (N,) [L]
    speed: np.ndarray           # (N,) Vs or Vp [L/T]
    rho: np.ndarray             # (N,)
    damping: np.ndarray         # (N,)
    base: tuple | None          # (speed, rho, damping) or None

    @property
    def depth(self) -> float:
        return float(self.thickness.sum())


def transfer_function(frequency, layers, base, *, at="outcrop", depth=None, wave="S") -> np.ndarray:
    """Surface motion over record motion of a layered profile, at the given frequencies.

    Parameters
    ----------
    frequency : (nf,) array_like
        Frequencies [1/T] >= 0 (cycles per time unit, not rad).
    layers, base, at, depth, wave
        As for :func:`free_field`.

    Returns
    -------
    (nf,) complex ndarray
        ``H(f)``, with the time factor ``exp(+i 2 pi f t)`` of :func:`numpy.fft.rfft`/``irfft``: a
        record ``cos(2 pi f t)`` gives the steady surface motion ``Re(H(f) exp(i 2 pi f t))``. The
        same ratio holds for displacement, velocity and acceleration. ``H(0) = 1``. An undamped
        column has poles (``inf``) where the record point is a node of a mode (e.g. a rigid base at
        ``f = (2n+1) Vs / (4 H)``).
    """
    f = as_vector("frequency", frequency, None)
    if np.any(f < 0):
        raise ValueError(f"frequency must be >= 0, got a minimum of {f.min()!r}")
    at, depth, wave = _check_location(at, depth, wave)
    profile = _profile(layers, base, wave)
    _check_depth(at, depth, profile)
    return _transfer(2.0 * np.pi * f, profile, at, depth)


def free_field(acc, dt, layers, base, *, at="outcrop", depth=None, wave="S", pad=None) -> np.ndarray:
    """Surface (free-field) acceleration of a layered profile shaken by a record.

    Linear 1D site response to vertically incident waves (SHAKE-type, without the strain
    iterations): the record's spectrum times :func:`transfer_function`, back to time.

    Parameters
    ----------
    acc : (N,) array_like
        The record, sampled at ``k dt``, k = 0..N-1, in any acceleration unit (the result is in the
        same unit). Zero before its start.
    dt : float
        Time step [T] > 0.
    layers : list of dict
        The layers from the surface down, each with ``thickness`` [L] > 0, ``G`` [F/L^2] or ``Vs``
        [L/T] (one of them, > 0), ``rho`` [F T^2/L^4] > 0, ``nu`` (Poisson's ratio, 0 <= nu < 0.5;
        required for P waves) and ``damping`` (hysteretic damping ratio, 0 <= xi < 1, default 0:
        the complex modulus ``G (1 + 2 i xi)``). May be empty (the record's own level).
    base : dict or None
        The elastic half-space under the layers (``G`` or ``Vs``, ``rho``, ``nu``, ``damping``, no
        ``thickness``), or None for a rigid base (total reflection: the column rings on only by its
        damping).
    at : {"outcrop", "surface", "within"}
        Where ``acc`` was recorded. ``"surface"``: at the ground surface, returned unchanged (a
        copy). ``"outcrop"``: at an outcrop of the half-space, that is twice the up-going wave
        incident from below (needs an elastic base). ``"within"``: the total motion at ``depth``
        inside the profile (a borehole record; with a rigid base, ``depth`` = the profile's
        thickness is the motion of the base).
    depth : float, optional
        Depth [L] of the record below the surface, for ``at="within"`` only: 0 <= depth <= the sum
        of the thicknesses (the top of the half-space).
    wave : {"S", "P"}
        ``"S"``: horizontal motion, shear waves of speed ``Vs = sqrt(G/rho)``. ``"P"``: vertical
        motion, compression waves with the constrained modulus ``M = 2 G (1 - nu)/(1 - 2 nu)`` and
        speed ``Vp = sqrt(M/rho)``, with the same damping ratio.
    pad : float, optional
        Length [T] of the zeros appended before the FFT; default: automatic (Notes).

    Returns
    -------
    (N,) ndarray
        The surface acceleration at the record's samples (the ringing after the record's end is
        cut off).

    Raises
    ------
    ValueError
        A layer or base property missing, given twice (``G`` and ``Vs``) or out of range, ``depth``
        outside the profile or without ``at="within"``, an unknown ``at`` or ``wave``, or
        ``at="outcrop"`` over a rigid base (a rigid base has no outcrop motion).

    Notes
    -----
    The record is padded with zeros against the wrap-around of the column's free ringing (the
    default ``pad``), and ``at="within"`` deconvolves: see the module's *Zero padding* and
    *Deconvolution*.

    Examples
    --------
    >>> layers = [{"thickness": 20.0, "Vs": 200.0, "rho": 1.9, "damping": 0.05}]
    >>> rock = {"Vs": 1000.0, "rho": 2.2, "damping": 0.01}
    >>> surface = free_field(acc, 0.01, layers, rock, at="outcrop")    # doctest: +SKIP
    """
    at, depth, wave = _check_location(at, depth, wave)
    acc = _record(acc)
    dt = positive_float("dt", dt)
    profile = _profile(layers, base, wave)
    _check_depth(at, depth, profile)
    if at == "surface":
        return acc.copy()
    return _surface_motion(acc, dt, profile, at, depth, _padding(pad))


def _record(acc) -> np.ndarray:
    """The record ``acc`` as a float vector (N,) of at least one sample (ValueError otherwise)."""
    acc = as_vector("acc", acc, None)
    if acc.size == 0:
        raise ValueError("acc must hold at least one sample, got an empty array")
    return acc


def _padding(pad) -> float | None:
    """The time [T] of zeros appended before the FFT as a float >= 0, or None (automatic)."""
    if pad is not None:
        pad = float(pad)
        if not 0.0 <= pad < math.inf:
            raise ValueError(f"pad must be a time >= 0 (the zeros appended before the FFT), got {pad!r}")
    return pad


def _surface_motion(acc, dt, profile: _Profile, at: str, depth, pad) -> np.ndarray:
    """The surface acceleration (N,) of the record ``acc`` (N,) at ``at`` (not ``"surface"``): its
    spectrum, zero padded (:func:`_fft_length`), times the transfer function of the profile, back
    to time and cut to the record's N samples. ValueError if the transfer function is infinite at
    a frequency of the FFT (an undamped resonance)."""
    n = acc.size
    n_fft = _fft_length(n, dt, profile, at, depth, pad)
    omega = 2.0 * np.pi * scipy.fft.rfftfreq(n_fft, dt)
    H = _transfer(omega, profile, at, depth)
    if not np.all(np.isfinite(H)):
        f = omega[~np.isfinite(H)][0] / (2.0 * np.pi)
        raise ValueError(f"the transfer function is infinite at f = {f:g} (an undamped resonance of the column "
                         "above the record point falls on a frequency of the FFT); give the layers damping > 0")
    return scipy.fft.irfft(H * scipy.fft.rfft(acc, n_fft), n_fft)[:n]


# ---------------------------------------------------------------------- checks
def _check_location(at, depth, wave):
    if not isinstance(at, str) or at not in LOCATIONS:
        raise ValueError(f"at must be one of {', '.join(map(repr, LOCATIONS))} (where the record was taken), "
                         f"got {at!r}")
    if not isinstance(wave, str) or wave not in WAVES:
        raise ValueError(f"wave must be 'S' (horizontal motion) or 'P' (vertical motion), got {wave!r}")
    if at == "within":
        if depth is None:
            raise ValueError("depth is required with at='within': the depth [L] of the record below the surface")
        if isinstance(depth, bool) or not isinstance(depth, int | float | np.floating | np.integer):
            raise TypeError(f"depth must be a number [L], got {depth!r}")
        depth = float(depth)
        if not 0.0 <= depth < math.inf:
            raise ValueError(f"depth must be a finite number >= 0 [L], got {depth!r}")
    elif depth is not None:
        raise ValueError(f"depth is only for at='within' (a record at depth), got depth={depth!r} with at={at!r}")
    return at, depth, wave


def _check_depth(at, depth, profile: _Profile) -> None:
    if at == "outcrop" and profile.base is None:
        raise ValueError("at='outcrop' needs an elastic half-space: a rigid base (base=None) has no outcrop "
                         "motion; give the motion of the rigid base with at='within', depth=<the profile's "
                         f"thickness, {profile.depth:g}>, or give base as a dict")
    if at == "within" and depth > profile.depth * (1.0 + 1e-12):
        raise ValueError(f"depth={depth!r} is below the profile: give 0 <= depth <= {profile.depth:g} (the sum of "
                         "the layer thicknesses, the top of the half-space)")


def _number(where: str, key: str, value, *, lower: float, upper: float = math.inf, closed: bool,
            upper_closed: bool = False, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise TypeError(f"{where}: {key} must be a number ({what}), got {value!r}")
    value = float(value)
    ok = (value >= lower if closed else value > lower) and (value <= upper if upper_closed else value < upper)
    if not ok:
        low = f"{'>=' if closed else '>'} {lower:g}"
        high = "" if upper == math.inf else f" and {'<=' if upper_closed else '<'} {upper:g}"
        raise ValueError(f"{where}: {key} = {value!r} must be {low}{high} ({what})")
    return value


def _material(where: str, spec, keys: tuple, wave: str) -> tuple[float, float, float, float | None]:
    """``(speed, rho, damping, thickness)`` of a layer or base dict (thickness None for the base)."""
    if not isinstance(spec, dict):
        raise TypeError(f"{where} must be a dict with the keys {', '.join(keys)}, got {spec!r}")
    unknown = [k for k in spec if k not in keys]
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r} (valid keys: {', '.join(keys)})")
    thickness = None
    if "thickness" in keys:
        if "thickness" not in spec:
            raise ValueError(f"{where}: missing 'thickness' (the layer's thickness [L] > 0)")
        thickness = _number(where, "thickness", spec["thickness"], lower=0.0, closed=False, what="the layer's "
                            "thickness [L]", upper=MAX_THICKNESS, upper_closed=True)
    if "rho" not in spec:
        raise ValueError(f"{where}: missing 'rho' (the mass density [F T^2/L^4] > 0)")
    rho = _number(where, "rho", spec["rho"], lower=0.0, closed=False, what="mass density [F T^2/L^4]")
    has_G, has_Vs = spec.get("G") is not None, spec.get("Vs") is not None
    if has_G == has_Vs:
        raise ValueError(f"{where}: give either G (shear modulus [F/L^2]) or Vs (shear-wave speed [L/T]), "
                         + ("not both" if has_G else "neither is given"))
    if has_G:
        G = _number(where, "G", spec["G"], lower=0.0, closed=False, what="shear modulus [F/L^2]")
        vs = math.sqrt(G / rho)
    else:
        vs = _number(where, "Vs", spec["Vs"], lower=0.0, closed=False, what="shear-wave speed [L/T]")
    nu = spec.get("nu")
    if nu is not None:
        nu = _number(where, "nu", nu, lower=0.0, upper=0.5, closed=True, what="Poisson's ratio, 0 <= nu < 0.5")
    damping = _number(where, "damping", spec.get("damping", 0.0), lower=0.0, upper=1.0, closed=True,
                      what="hysteretic damping ratio")
    speed = vs
    if wave == "P":
        if nu is None:
            raise ValueError(f"{where}: missing 'nu' (P waves need Poisson's ratio, 0 <= nu < 0.5, for the "
                             "constrained modulus M = 2 G (1 - nu)/(1 - 2 nu))")
        speed = vs * math.sqrt(2.0 * (1.0 - nu) / (1.0 - 2.0 * nu))
    if not 0.0 < speed < math.inf or not 0.0 < rho * speed < math.inf:
        raise ValueError(f"{where}: the wave speed {speed:g} or the impedance rho v = {rho * speed:g} is not a "
                         "finite number > 0; give values of a consistent unit set")
    return speed, rho, damping, thickness


def _profile(layers, base, wave) -> _Profile:
    if isinstance(layers, dict) or not isinstance(layers, list | tuple):
        raise TypeError(f"layers must be a list of dicts (one per layer, from the surface down), got {layers!r}")
    rows = [_material(f"layers[{j}]", layer, _LAYER_KEYS, wave) for j, layer in enumerate(layers)]
    base_row = None if base is None else _material("base", base, _BASE_KEYS, wave)[:3]
    columns = np.array([row[:4] for row in rows], dtype=float).reshape(-1, 4)
    return _Profile(thickness=columns[:, 3], speed=columns[:, 0], rho=columns[:, 1], damping=columns[:, 2],
                    base=base_row)


# ---------------------------------------------------------------------- transfer functions
def _transfer(omega: np.ndarray, profile: _Profile, at: str, depth) -> np.ndarray:
    """Surface / record at the circular frequencies ``omega`` (nf,), complex."""
    if at == "surface":
        return np.ones(omega.shape, dtype=complex)
    v = profile.speed * np.sqrt(1.0 + 2.0j * profile.damping)          # complex speeds (N,)
    Z = profile.rho * v                                                  # complex impedances (N,)
    A = np.ones(omega.shape, dtype=complex)
    B = np.ones(omega.shape, dtype=complex)
    log_scale = np.zeros(omega.shape)        # A, B are kept normalised; their true size is exp(log_scale) times

    def waves(k, z):
        """``A exp(ikz)``, ``B exp(-ikz)`` over ``exp(g)``, ``g = -Im(k) z >= 0`` the growth, and ``g``."""
        g = -k.imag * z
        return A * np.exp(1j * k.real * z), B * np.exp(-1j * k.real * z - 2.0 * g), g

    top = 0.0
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        for j, h in enumerate(profile.thickness):
            k = omega / v[j]
            if at == "within" and depth <= top + h:
                up, down, g = waves(k, max(depth - top, 0.0))
                return 2.0 * np.exp(-log_scale - g) / (up + down)
            up, down, g = waves(k, h)
            if j + 1 < profile.thickness.size:
                a = Z[j] / Z[j + 1]
            elif profile.base is not None:
                speed, rho, damping = profile.base
                a = Z[j] / (rho * speed * np.sqrt(1.0 + 2.0j * damping))
            else:                                   # the bottom of the last layer over a rigid base
                return 2.0 * np.exp(-log_scale - g) / (up + down)
            A, B = 0.5 * (up * (1.0 + a) + down * (1.0 - a)), 0.5 * (up * (1.0 - a) + down * (1.0 + a))
            scale = np.maximum(np.abs(A), np.abs(B))
            A, B, log_scale = A / scale, B / scale, log_scale + g + np.log(scale)
            top += h
        if at == "within":                          # depth at the top of the half-space, or no layers
            return 2.0 * np.exp(-log_scale) / (A + B)
        return np.exp(-log_scale) / A               # 2 / (2 A_{N+1})


def _fft_length(n: int, dt: float, profile: _Profile, at: str, depth, pad) -> int:
    """The padded FFT length for a record of ``n`` samples (see the module's *Zero padding*)."""
    cap = max(16 * n, MAX_FFT_LENGTH)
    if pad is not None:
        if n + math.ceil(pad / dt) > cap:
            raise ValueError(f"pad={pad!r} makes an FFT longer than {cap} samples (at most "
                             f"{(cap - n) * dt:g} time units of zeros for this record)")
        return scipy.fft.next_fast_len(n + math.ceil(pad / dt), real=True)
    pad = _ringing_time(profile, at, depth)
    wanted = n + (math.ceil(pad / dt) + 1 if pad < math.inf else cap)
    if wanted > cap:
        warnings.warn(f"the column's free ringing does not decay to {RINGING_TOLERANCE:g} within the largest FFT "
                      f"({cap} samples, {cap * dt:g} time units): the surface motion includes some wrap-around of "
                      "the ringing of the record's end onto its start; give the layers damping > 0",
                      RuntimeWarning, stacklevel=4)                 # the caller of free_field
        wanted = cap
    return scipy.fft.next_fast_len(wanted, real=True)


def _ringing_time(profile: _Profile, at: str, depth) -> float:
    """Time [T] for the free ringing of the column above the record point to decay (inf: never)."""
    bottom = profile.depth if at == "outcrop" else depth
    tops = np.concatenate([[0.0], np.cumsum(profile.thickness)[:-1]])
    above = np.clip(bottom - tops, 0.0, profile.thickness)          # the part of each layer above
    travel = float(np.sum(above / profile.speed))                   # vertical travel time t_s
    if travel == 0.0:
        return 0.0
    reflection = 1.0                                                # rigid base, or at="within"
    if at == "outcrop":
        speed, rho, _ = profile.base
        z_layer, z_base = profile.rho[-1] * profile.speed[-1], rho * speed
        reflection = abs(z_layer - z_base) / (z_layer + z_base)
    xi = float(np.min(profile.damping[above > 0]))
    decay = math.pi * xi - (math.log(reflection) if reflection > 0 else -math.inf)   # -ln q per round trip
    if decay == 0.0:
        return math.inf
    trips = max(-math.log(RINGING_TOLERANCE) / decay, 1.0)
    return 2.0 * trips * 2.0 * travel + travel
