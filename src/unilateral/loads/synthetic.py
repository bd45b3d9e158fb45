"""Synthetic earthquake accelerograms: Kanai-Tajimi filtered white noise under an envelope.

No real earthquake record can be shipped with the package or downloaded where it runs, so
benchmarks and examples use a *synthetic* record instead. It is not a recorded ground motion:
any PEER NGA ``.AT2`` file read by :func:`~unilateral.loads.read_at2` (optionally scaled with
:meth:`~unilateral.loads.GroundMotion.scaled`) can be used in its place.

The record is built in four steps:

1. white noise from a seeded :class:`numpy.random.Generator` (deterministic for a seed);
2. the Kanai-Tajimi filter of a soil layer with frequency ``f_g`` and damping ``zeta_g``,

       H(s) = (2 zeta_g w_g s + w_g^2) / (s^2 + 2 zeta_g w_g s + w_g^2),   w_g = 2 pi f_g,

   applied exactly in the frequency domain (zero-padded FFT, so nothing wraps around);
3. an amplitude envelope that starts and ends small;
4. a baseline correction that makes the final ground velocity zero, and scaling to the
   requested peak ground acceleration.
"""

from __future__ import annotations

import math

import numpy as np

from unilateral._validate import choice, positive_float
from unilateral.loads.records import GroundMotion

ENVELOPES = ("saragoni-hart", "amin-ang")
"""Names of the amplitude envelopes of :func:`synthetic_accelerogram`."""

PEAK_FRACTION = 0.2
"""Saragoni-Hart envelope: time of its peak as a fraction of the duration (Boore 2003)."""

END_VALUE = 0.05
"""Value of either envelope at the end of the record (its peak is 1)."""


#: Most samples of a synthetic record (about 1.3 GiB of work arrays at :data:`BYTES_PER_SAMPLE`).
MAX_SAMPLES = 10_000_000
#: Memory of the generation per sample: the noise, time, envelope and record (8 bytes each) and the
#: filter's zero-padded FFT (two complex spectra and the transfer function of 2 n points).
BYTES_PER_SAMPLE = 4 * 8 + 3 * 2 * 16 + 2 * 8


def synthetic_accelerogram(duration: float = 20.0, dt: float = 0.01, pga: float = 3.0, *,
                           seed: int = 0, f_g: float = 2.5, zeta_g: float = 0.6,
                           envelope: str = "saragoni-hart") -> GroundMotion:
    """A synthetic ground acceleration record (Kanai-Tajimi filtered white noise).

    Parameters
    ----------
    duration : float
        Length of the record, s (the last sample is at ``duration``, rounded to ``dt``).
    dt : float
        Time step, s.
    pga : float
        Peak ground acceleration ``max |a|``, m/s^2.
    seed : int
        Seed of the white noise: the same seed gives the same record.
    f_g : float
        Predominant frequency of the soil filter, Hz.
    zeta_g : float
        Damping ratio of the soil filter.
    envelope : {"saragoni-hart", "amin-ang"}
        ``"saragoni-hart"``: ``(t/t_p)^b exp(b (1 - t/t_p))`` with its peak at
        ``t_p = 0.2 duration`` and 5 % left at the end (Boore 2003). ``"amin-ang"``: a quadratic
        rise over the first 10 %, a plateau up to 40 %, then an exponential decay to 5 %.

    Returns
    -------
    GroundMotion
        Accelerations in m/s^2, named ``"synthetic (Kanai-Tajimi, seed N)"``; zero at ``t = 0``
        and with zero final velocity (trapezoidal integration).

    Notes
    -----
    The record is synthetic: no real record can be shipped or downloaded here. Any PEER
    ``.AT2`` record (:func:`~unilateral.loads.read_at2`) can be used instead.
    """
    duration = positive_float("duration", duration)
    dt = positive_float("dt", dt)
    pga = positive_float("pga", pga)
    f_g = positive_float("f_g", f_g)
    zeta_g = positive_float("zeta_g", zeta_g)
    envelope = choice("envelope", envelope, ENVELOPES)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise TypeError(f"seed must be an integer, got {seed!r}")
    steps = duration / dt
    if not steps <= MAX_SAMPLES:
        memory = BYTES_PER_SAMPLE * min(steps, 1e300) / 2**30
        raise ValueError(f"duration={duration!r} with dt={dt!r} is {steps:.3g} samples: the record and its "
                         f"filtering would need about {memory:.3g} GiB; give at most {MAX_SAMPLES:.0e} samples "
                         "(a shorter duration or a larger dt)")
    npts = math.floor(steps + 1e-9) + 1
    if npts < 3:
        raise ValueError(f"duration={duration!r} must span at least 2 steps of dt={dt!r}")
    noise = np.random.default_rng(int(seed)).standard_normal(npts)
    t = np.arange(npts) * dt
    shape = _envelope(envelope, t / t[-1])
    a = shape * _kanai_tajimi(noise, dt, 2 * np.pi * f_g, zeta_g)
    a -= shape * (_integral(a) / _integral(shape))          # zero final velocity
    a *= pga / np.max(np.abs(a))
    return GroundMotion(dt, a, name=f"synthetic (Kanai-Tajimi, seed {int(seed)})",
                        source=f"unilateral.loads.synthetic: f_g={f_g:g} Hz, zeta_g={zeta_g:g}, "
                               f"envelope {envelope}")


def _kanai_tajimi(noise: np.ndarray, dt: float, w_g: float, zeta_g: float) -> np.ndarray:
    """``noise`` filtered by the Kanai-Tajimi transfer function, in the frequency domain."""
    size = 2 * noise.size
    s = 2j * np.pi * np.fft.rfftfreq(size, dt)
    H = (2 * zeta_g * w_g * s + w_g**2) / (s**2 + 2 * zeta_g * w_g * s + w_g**2)
    return np.fft.irfft(H * np.fft.rfft(noise, size), size)[: noise.size]


def _envelope(name: str, x: np.ndarray) -> np.ndarray:
    """Envelope (peak 1) at the normalised times ``x = t / duration`` in [0, 1]."""
    if name == "saragoni-hart":
        b = -PEAK_FRACTION * math.log(END_VALUE) / (1 + PEAK_FRACTION * (math.log(PEAK_FRACTION) - 1))
        y = x / PEAK_FRACTION
        return y**b * np.exp(b * (1 - y))
    rise, plateau = 0.1, 0.4                                   # "amin-ang"
    decay = -math.log(END_VALUE) / (1 - plateau)
    return np.where(x < rise, (x / rise) ** 2,
                    np.where(x <= plateau, 1.0, np.exp(-decay * (x - plateau))))


def _integral(y: np.ndarray) -> float:
    """Trapezoidal sum of ``y`` over its samples (the unit step cancels in the ratios)."""
    return float(y.sum() - 0.5 * (y[0] + y[-1]))
