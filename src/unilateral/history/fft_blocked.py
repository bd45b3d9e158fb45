"""Fast online evaluation of the CLCP history ``h_n = sum_{j=1..n} W_j dv_{n-j}``.

The scheme of Hairer, Lubich & Schlichte (1985): the lower triangle of pairs ``(i, n)``,
``0 <= i < n <= N``, in which ``W_{n-i} dv_i`` contributes to ``h_n``, is tiled recursively.
A triangle of size ``2B`` starting at ``a`` (``a`` a multiple of ``2B``) is two triangles of size
``B`` plus the square ``i in [a, a+B), n in [a+B, a+2B)``; triangles of the base size ``b`` are
summed directly. The square only needs the lags ``1..2B-1`` -- the same for every square of a
level -- and is a Toeplitz block: one FFT convolution of length ``2B`` whose weight spectrum is
computed once. The square's sources ``dv_a .. dv_{a+B-1}`` are all known after ``push(a+B-1)`` and
its targets start at ``a+B``, so it is evaluated then and stored in an accumulator.

Per level, ``N / 2B`` squares of FFT length ``2B``: ``O(m N log N + m^2 N)`` work, so
``O(m N log^2 N + m^2 N log N)`` in all, plus ``O(m^2 N b)`` for the direct part.
"""

from __future__ import annotations

from collections import Counter

import numpy as np

DEFAULT_BASE_BLOCK = 64


class FFTBlockedHistory:
    """Blocked FFT evaluation of the history sum; same interface as :class:`NaiveHistory`.

    ``value(n)`` and ``push(n, dv_n)`` must be called for ``n = 1, 2, ...`` in order, ``value(n)``
    before ``push(n, ...)``; ``dv_0 = 0``. Stopping at any step is allowed.

    Parameters
    ----------
    W : (N+1, m, m) convolution weights (``W_0`` is never used)
    base_block : int, optional
        Size ``b >= 1`` of the triangles summed directly (default 64; values above ``N + 1``
        are reduced to ``N + 1``, i.e. direct summation throughout).

    Attributes
    ----------
    dv : (N+1, m) the increments pushed so far (zero beyond)
    stats : dict
        Work done so far: ``direct_terms`` (products ``W_j dv_i`` summed directly),
        ``fft_sizes`` (``{FFT length: number of square convolutions}``), ``skipped_blocks``
        (squares whose sources were all zero).

    Notes
    -----
    Memory: the weight spectra of all levels take about ``2 N m^2`` complex numbers.
    """

    name = "fft"

    def __init__(self, W: np.ndarray, *, base_block: int | None = None):
        W = np.asarray(W, dtype=float)
        if W.ndim != 3 or W.shape[0] < 1 or W.shape[1] != W.shape[2]:
            raise ValueError(f"W must have shape (N+1, m, m), got shape {W.shape}")
        if base_block is None:
            base_block = DEFAULT_BASE_BLOCK
        if isinstance(base_block, bool) or not isinstance(base_block, (int, np.integer)) or base_block < 1:
            raise ValueError(f"base_block must be a positive integer, got {base_block!r}")
        N, m = W.shape[0] - 1, W.shape[1]
        b = min(int(base_block), N + 1)
        self.W = W
        self.N, self.m, self.base_block = N, m, b
        self.dv = np.zeros((N + 1, m))
        self._dv_flat = self.dv.reshape(-1)
        self._acc = np.zeros((N + 1, m))         # contributions of the squares done so far
        # Direct part: columns (b-1-r)*m .. (b-1)*m of ``_near`` hold W_r .. W_1 side by side.
        self._near = np.ascontiguousarray(W[b - 1:0:-1].transpose(1, 0, 2).reshape(m, (b - 1) * m))
        # Levels B = b 2^l <= N: spectra of the lags 0..2B-1 (lag 0 zeroed, lags > N absent).
        self._spectra = {}
        B = b
        while B <= N:
            seg = np.zeros((2 * B, m, m))
            top = min(2 * B, N + 1)
            seg[1:top] = W[1:top]
            self._spectra[B] = np.fft.rfft(seg, axis=0)
            B *= 2
        self._direct_terms = 0
        self._fft_sizes = Counter()
        self._skipped = 0

    @property
    def stats(self) -> dict:
        """Work counters (see the class attributes), a fresh dict."""
        return {"direct_terms": self._direct_terms, "fft_sizes": dict(self._fft_sizes),
                "skipped_blocks": self._skipped}

    def value(self, n: int) -> np.ndarray:
        """``sum_{j=1..n} W_j dv_{n-j}``, shape (m,)."""
        r = n % self.base_block
        if r == 0:
            return self._acc[n].copy()
        self._direct_terms += r
        m, e = self.m, (self.base_block - 1) * self.m
        return self._acc[n] + self._near[:, e - r * m:] @ self._dv_flat[(n - r) * m:n * m]

    def push(self, n: int, dv_n: np.ndarray) -> None:
        """Record ``dv_n`` (m,) and add the square whose sources it completes, if any."""
        self.dv[n] = dv_n
        t = n + 1
        if t % self.base_block or t > self.N:
            return
        q = t // self.base_block
        B = self.base_block * (q & -q)               # t = a + B with a a multiple of 2B
        src = self.dv[t - B:t]
        if not src.any():
            self._skipped += 1
            return
        self._fft_sizes[2 * B] += 1
        X = np.fft.rfft(src, 2 * B, axis=0)
        y = np.fft.irfft(np.matmul(self._spectra[B], X[:, :, None])[:, :, 0], 2 * B, axis=0)
        T = min(B, self.N + 1 - t)
        self._acc[t:t + T] += y[B:B + T]
