"""Rational (pole-residue) fits of tabulated impedances/flexibilities by AAA.

The AAA algorithm (Nakatsukasa, Sete & Trefethen 2018, SIAM J. Sci. Comput. 40, A1494;
``scipy.interpolate.AAA``) gives poles; the model is then made usable as a Laplace-domain kernel:

1. data are mirrored (``H(conj s) = conj H(s)``) so AAA sees a conjugate-symmetric problem;
2. poles are cleaned: spurious/far poles (``|p| > pole_limit * max|s|``) are removed, unstable ones
   (``Re p >= 0``) are reflected to ``-conj p`` (or just left of the axis), and pairs are symmetrised;
3. with the poles fixed, real parameters are refitted by weighted linear least squares:
   ``H(s) = d + e s + sum_k r_k/(s - p_k) + sum_pairs [c/(s - p) + conj(c)/(s - conj p)]``,
   so the kernel is exactly real (conjugate symmetric) and stable;
4. optional passivity (``Re H(i omega) >= 0``, for a single-DOF impedance or flexibility) is checked on a
   dense grid and enforced by raising ``d`` (a reported, crude correction).

Range of validity: single scalar functions sampled on (or near) the imaginary axis; matrices are
fitted entry by entry (no common-pole guarantee of matrix passivity).
"""

from __future__ import annotations

import csv

import numpy as np
from scipy.interpolate import AAA

from .. import _validate as V

__all__ = ["RationalFit", "fit_rational", "read_table"]


class RationalFit:
    """Pole-residue model ``H(s) = d + e s + sum_k residues_k / (s - poles_k)``.

    Attributes
    ----------
    poles, residues : (r,) complex
        Conjugate-closed, ``Re poles < 0``.
    constant, linear : float
        ``d`` and ``e``.
    fit_error : float
        Max relative error on the data, ``max |H(s_i) - y_i| / |y_i|``.
    report : dict
        Corrections made: ``removed`` (far/spurious poles dropped), ``flipped`` (unstable poles
        reflected), ``passivity_shift`` (amount added to ``d``), ``passivity_violation`` (min Re H found
        before the shift), ``aaa_terms``.
    """

    def __init__(self, poles, residues, constant, linear, fit_error, report):
        self.poles, self.residues = poles, residues
        self.constant, self.linear = float(constant), float(linear)
        self.fit_error, self.report = float(fit_error), report

    def __call__(self, s) -> np.ndarray:
        """Evaluate ``H(s)``; ``s`` scalar or (n,), returns (n,) complex."""
        s = np.atleast_1d(np.asarray(s, dtype=complex))
        out = self.constant + self.linear * s
        if self.poles.size:
            out = out + np.sum(self.residues[None, :] / (s[:, None] - self.poles[None, :]), axis=1)
        return out

    def __repr__(self):
        return f"RationalFit(order={self.poles.size}, fit_error={self.fit_error:.2e})"


def _design(s, real_poles, pair_poles, linear):
    cols = [np.ones_like(s)]
    if linear:
        cols.append(s)
    for p in real_poles:
        cols.append(1.0 / (s - p))
    for p in pair_poles:
        a, b = 1.0 / (s - p), 1.0 / (s - np.conj(p))
        cols.append(a + b)            # real part of residue
        cols.append(1j * (a - b))     # imaginary part of residue
    return np.column_stack(cols)


def _stable_conjugate_poles(poles, smax, pole_limit, report) -> tuple[np.ndarray, np.ndarray]:
    """The poles of an AAA fit made fit for a real, stable rational function: those beyond
    ``pole_limit * smax`` dropped, unstable ones reflected into ``Re p < 0``, and the rest split into
    distinct real poles and upper-half-plane poles of conjugate pairs (a lower one without its
    partner becomes an upper one). Counts ``removed`` and ``flipped`` in ``report``.
    Returns ``(real_poles, pair)``."""
    far = np.abs(poles) > pole_limit * smax
    report["removed"] = int(far.sum())
    poles = poles[~far]
    unstable = poles.real >= 0
    report["flipped"] = int(unstable.sum())
    poles = np.where(unstable, -np.abs(poles.real) - 1e-6 * smax + 1j * poles.imag, poles)
    tol = 1e-8 * smax
    real_poles = np.unique(np.round(poles[np.abs(poles.imag) <= tol].real, 12))
    upper = poles[poles.imag > tol]
    lower = poles[poles.imag < -tol]
    # pair every lower pole with an upper one (symmetrise); unmatched lower poles become upper ones
    pair = list(upper)
    for p in lower:
        if not pair or np.min(np.abs(np.array(pair) - np.conj(p))) > 1e-6 * max(abs(p), smax):
            pair.append(np.conj(p))
    pair = np.array(pair, dtype=complex)
    if pair.size:
        keep = np.ones(pair.size, bool)
        for i in range(pair.size):
            for j in range(i):
                if keep[j] and abs(pair[i] - pair[j]) < 1e-6 * max(abs(pair[i]), smax):
                    keep[i] = False
        pair = pair[keep]
    return real_poles, pair


def fit_rational(samples, values, *, frequency=True, linear=True, passive=False, rtol=1e-9,
                 max_terms=40, pole_limit=10.0) -> RationalFit:
    """Stable, real, optionally passive rational fit of sampled data.

    Parameters
    ----------
    samples : (n,) array_like
        Frequencies in Hz (``frequency=True``; then ``s = 2 pi i f``) or complex ``s`` values with
        ``Re s >= 0`` (``frequency=False``).
    values : (n,) complex array_like
        ``H`` at the samples (e.g. an impedance in N/m, or a flexibility in m/N).
    linear : bool
        Allow the term ``e s`` (impedances with radiation dashpots grow like ``s``; set False for a
        flexibility).
    passive : bool
        Enforce ``Re H(i omega) >= 0`` for all ``omega`` (checked on a dense grid up to 10x the data range).
    rtol, max_terms : passed to ``scipy.interpolate.AAA``.
    pole_limit : float
        Poles with ``|p| > pole_limit * max|s|`` are dropped (their effect is absorbed by ``d``, ``e``).

    Returns
    -------
    RationalFit
    """
    x = np.asarray(samples)
    y = np.asarray(values, dtype=complex)
    if x.ndim != 1 or y.shape != x.shape:
        raise ValueError(f"samples and values must be 1-D of equal length, got {x.shape} and {y.shape}")
    V.check_finite("values", y.view(float))
    s = 2j * np.pi * x.astype(float) if frequency else x.astype(complex)
    if np.any(s.real < 0):
        raise ValueError("samples must have Re s >= 0")
    mirror = np.abs(s.imag) > 0
    z = np.concatenate([s, np.conj(s[mirror])])
    yz = np.concatenate([y, np.conj(y[mirror])])
    aaa = AAA(z, yz, rtol=rtol, max_terms=max_terms)
    poles = np.asarray(aaa.poles())
    smax = np.max(np.abs(s))
    report = {"aaa_terms": int(len(aaa.support_points)), "removed": 0, "flipped": 0,
              "passivity_shift": 0.0, "passivity_violation": 0.0}
    real_poles, pair = _stable_conjugate_poles(poles, smax, pole_limit, report)
    A = _design(s, real_poles, pair, linear)
    w = 1.0 / np.maximum(np.abs(y), 1e-300)
    Aw = A * w[:, None]
    rhs = y * w
    coef, *_ = np.linalg.lstsq(np.vstack([Aw.real, Aw.imag]), np.concatenate([rhs.real, rhs.imag]),
                               rcond=None)
    d = coef[0]
    e = coef[1] if linear else 0.0
    off = 2 if linear else 1
    nr = real_poles.size
    res_real = coef[off:off + nr].astype(complex)
    cpair = coef[off + nr::2] + 1j * coef[off + nr + 1::2]
    poles_all = np.concatenate([real_poles.astype(complex), pair, np.conj(pair)])
    res_all = np.concatenate([res_real, cpair, np.conj(cpair)])
    fit = RationalFit(poles_all, res_all, d, e, 0.0, report)
    if passive:
        wmax = 10.0 * smax
        grid = 1j * np.concatenate([[0.0], np.geomspace(1e-4 * wmax, wmax, 4000)])
        worst = float(np.min(fit(grid).real))
        if worst < 0:
            report["passivity_violation"] = worst
            report["passivity_shift"] = -worst
            fit.constant += -worst
    fit.fit_error = float(np.max(np.abs(fit(s) - y) / np.maximum(np.abs(y), 1e-300)))
    return fit


def read_table(path):
    """Read tabulated frequency-domain data from a CSV file.

    Format: a header row; the first column is the frequency in Hz (any name); every other quantity
    ``<name>`` occupies two columns named ``<name>_re`` and ``<name>_im`` (real and imaginary parts, in
    the user's units, e.g. N/m for impedances or m/N for flexibilities). Use one name per DOF
    (``Kv``, ``Kh``, ``Kr``) or per matrix entry (``F_0_1``). Lines starting with ``#`` are ignored.

    Returns
    -------
    freq : (n,) float, Hz
    data : dict name -> (n,) complex
    """
    with open(path, newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    header = [h.strip() for h in rows[0]]
    body = np.array([[float(v) for v in r] for r in rows[1:]])
    if body.ndim != 2 or body.shape[1] != len(header):
        raise ValueError(f"{path}: every row must have {len(header)} numbers")
    freq = body[:, 0]
    data = {}
    for j, name in enumerate(header[1:], start=1):
        if name.endswith("_re"):
            base = name[:-3]
            if base + "_im" not in header:
                raise ValueError(f"{path}: column {name!r} has no matching {base + '_im'!r}")
            data[base] = body[:, j] + 1j * body[:, header.index(base + "_im")]
        elif not name.endswith("_im"):
            raise ValueError(f"{path}: column {name!r} must end in '_re' or '_im'")
    return freq, data
