"""Time NaiveHistory against FFTBlockedHistory over a full value/push sweep.

m = 3, N = 2^10 .. 2^16 (naive only up to 2^14), median of 3 runs. Prints a table and writes
``benchmarks/results/history_scaling.json``. Run: ``python benchmarks/history_scaling.py``
(``--quick``: N = 2^8 and 2^9, one run, a smoke test; ``--out`` another JSON file).
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

from unilateral.history import NaiveHistory
from unilateral.history.fft_blocked import DEFAULT_BASE_BLOCK, FFTBlockedHistory

M = 3
EXPONENTS = range(10, 17)
NAIVE_MAX = 2**14
RUNS = 3
OUT = Path(__file__).parent / "results" / "history_scaling.json"


def problem(N, m, rng):
    """Damped oscillatory weights (N+1, m, m) and random increments (N+1, m), ``dv_0 = 0``."""
    t = np.arange(N + 1)[:, None] / 1000.0
    omega = np.array([7.0, 19.0, 43.0])[:m]
    g = 1e-3 * np.exp(-0.02 * omega * t) * np.sin(omega * t)
    modes = np.linalg.qr(rng.standard_normal((m, m)))[0]
    W = np.einsum("ak,jk,bk->jab", modes, g, modes)
    W[0] = np.eye(m)
    dv = rng.standard_normal((N + 1, m))
    dv[0] = 0.0
    return W, dv


def sweep(history_class, W, dv, runs=RUNS):
    """Median wall time of ``runs`` full sweeps (construction included) and the values (N, m)."""
    N = W.shape[0] - 1
    times = []
    for _ in range(runs):
        h = np.empty((N, dv.shape[1]))
        start = time.perf_counter()
        history = history_class(W)
        for n in range(1, N + 1):
            h[n - 1] = history.value(n)
            history.push(n, dv[n])
        times.append(time.perf_counter() - start)
    return statistics.median(times), h


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="N = 2^8 and 2^9, one run (a smoke test)")
    parser.add_argument("--out", type=Path, default=OUT, help="JSON file (default: %(default)s)")
    args = parser.parse_args(argv)
    runs, exponents = (1, range(8, 10)) if args.quick else (RUNS, EXPONENTS)
    rng = np.random.default_rng(0)
    rows = []
    print(f"{'N':>7} {'naive s':>9} {'fft s':>8} {'ratio':>7} {'max rel diff':>13}")
    for e in exponents:
        N = 2**e
        W, dv = problem(N, M, rng)
        t_fft, h_fft = sweep(FFTBlockedHistory, W, dv, runs)
        row = {"N": N, "m": M, "naive_s": None, "fft_s": t_fft, "ratio": None, "max_rel_diff": None}
        if N <= NAIVE_MAX:
            t_naive, h_naive = sweep(NaiveHistory, W, dv, runs)
            row.update(naive_s=t_naive, ratio=t_naive / t_fft,
                       max_rel_diff=float(np.abs(h_fft - h_naive).max() / np.abs(h_naive).max()))
        rows.append(row)
        naive = "-" if row["naive_s"] is None else f"{row['naive_s']:.3f}"
        ratio = "-" if row["ratio"] is None else f"{row['ratio']:.1f}"
        diff = "-" if row["max_rel_diff"] is None else f"{row['max_rel_diff']:.1e}"
        print(f"{N:>7} {naive:>9} {t_fft:>8.3f} {ratio:>7} {diff:>13}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"runs": runs, "base_block": DEFAULT_BASE_BLOCK, "quick": args.quick,
                                    "rows": rows}, indent=2))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
