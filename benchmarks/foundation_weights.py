"""Time the structure's CQ weights: the per-contact sweeps of ``FoundationModel.weights`` against
:func:`unilateral.soil.structure_weights.structure_weights` (all impulses in one compiled loop).

The structure: a chain of ``n`` masses (1-3 t) and springs (1-2 MN/m) without a spring to the
ground (``K`` singular: it rests only on the soil), Rayleigh damping ``C = 0.2 M + 1e-3 K``, and
``m`` contacts on its first ``min(n, 20)`` DOFs; dense matrices for ``n = 20``, CSR above (as a
finite-element model would give them). BDF2, ``dt = 1e-3`` s, weights ``W_0 .. W_N``.

Columns of the table (seconds, median of ``--repeat`` runs, default 3):

* ``old py``: the loop of ``FoundationModel.weights`` as the command line runs it below 10^4
  steps and for every model above 400 DOFs: one Python :func:`~unilateral.march.direct.sweep_direct`
  (``compiled=False``) per impulse;
* ``old jit``: the same loop with the per-impulse compiled sweep, the library's default up to 400
  DOFs (not applicable above);
* ``new``: :func:`structure_weights` (``engine="auto"``: the path it chose is shown);
* ``py/new``, ``jit/new``: the ratios; ``rel diff``: the largest difference of the weights,
  relative to the largest weight, new against old py; ``jit-py``: the same between the two old
  loops (the round-off floor of the reference itself).

The old loops sweep each impulse independently, so their time is exactly linear in the number of
impulses ``r``: they are timed on at most ``--old-columns`` impulses (default 4) and scaled by
``r / columns`` (marked ``*``). BLAS runs single-threaded (``OPENBLAS_NUM_THREADS=1``, set before
numpy is imported). The machine is shared: the load average (``os.getloadavg()``) is printed before
and after and stored. The fitted exponents of the new time, ``t ~ r^a`` and ``t ~ N^b``, are printed
per ``n``. Writes ``benchmarks/results/foundation_weights.json``.

Run: ``python benchmarks/foundation_weights.py [--repeat 3] [--quick] [--out FILE]``.
"""

from __future__ import annotations

import os

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):       # before numpy is imported
    os.environ.setdefault(_name, "1")

import argparse                     # noqa: E402
import json                         # noqa: E402
import platform                     # noqa: E402
import statistics                   # noqa: E402
import subprocess                   # noqa: E402
import tempfile                     # noqa: E402
import sys                          # noqa: E402
import time                         # noqa: E402
from pathlib import Path            # noqa: E402

import numpy as np                  # noqa: E402
import scipy.sparse as sp           # noqa: E402

OUT = Path(__file__).parent / "results" / "foundation_weights.json"
DT = 1e-3
RULE = "bdf2"
N_DOFS = (20, 200, 2000)
M_CONTACTS = (4, 40)
N_STEPS = (1_000, 10_000)
#: The old (per-impulse) compiled sweep applies up to this many DOFs (stepper.COMPILED_MAX_N).
OLD_JIT_MAX_N = 400


def chain_model(n: int, m: int, seed: int = 0):
    """The benchmark's FoundationModel (see the module's docstring)."""
    from unilateral.soil.flexibility import SoilFlexibility
    from unilateral.soil.foundation_model import FoundationModel

    rng = np.random.default_rng(seed)
    k = rng.uniform(1e6, 2e6, n)
    main = k + np.r_[k[1:], 0.0]
    main[0] -= k[0]                                          # no spring to the ground
    K = sp.diags([main, -k[1:], -k[1:]], [0, 1, -1], format="csr")
    M = sp.diags(rng.uniform(1.0, 3.0, n), format="csr")
    C = (0.2 * M + 1e-3 * K).tocsr()
    nf, j = min(n, 20), np.arange(m)
    T = sp.csr_matrix((np.r_[np.ones(m), 0.5 * np.ones(m)], (np.r_[j % nf, (j + 1) % nf], np.r_[j, j])),
                      shape=(n, m))
    if n <= 64:
        M, K, C, T = (A.toarray() for A in (M, K, C, T))
    return FoundationModel(M, K, T, SoilFlexibility.kelvin(np.full(m, 1e6)), C=C)


def old_loop(model, N: int, basis, compiled: bool):
    """The loop of ``FoundationModel.weights`` (structure part) over the columns of ``basis``."""
    from unilateral.march.direct import sweep_direct
    from unilateral.march.stepper import StructureStepper
    from unilateral.rules import get_rule

    rule = get_rule(RULE, cq=True)
    n, m = model.n, model.m
    free = model.stepping_model()
    zeros_n, zeros_m = np.zeros((N + 2, n)), np.zeros((N + 2, m))
    W = np.empty((N + 1, m, basis.shape[1]))
    for j in range(basis.shape[1]):
        stepper = StructureStepper(free, rule, DT, zeros_n, zeros_m, None, condensed=False)
        impulse = np.zeros((N + 2, m))
        impulse[1] = basis[:, j]
        _, _, _, opening, _ = sweep_direct(stepper, N + 1, np.zeros(m), np.zeros(m), impulse, compiled=compiled)
        W[:, :, j] = opening[1:]
    return W


def timed(func, repeat: int):
    """Median wall time (s) of ``repeat`` calls, all times, and the last result."""
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = func()
        times.append(time.perf_counter() - start)
    return statistics.median(times), times, out


def chosen_path(model, N: int) -> str:
    """The loop ``engine="auto"`` takes (:func:`structure_weights`' own choice)."""
    from unilateral.rules import get_rule
    from unilateral.soil.structure_weights import _choose_engine

    return _choose_engine("auto", (model.M, model.K, model.C, model.T), get_rule(RULE).coefficients(DT), N)[0]


def fresh_process_first_call(cache_dir=None) -> float:
    """Wall time of a first call (n = 5, N = 100) in a new process: numba import and the cached
    machine code, or (``cache_dir``: an empty numba cache) the compilation of the loops."""
    env = dict(os.environ)
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    code = ("import time; t = time.perf_counter(); import numpy as np; "
            "from unilateral.soil.structure_weights import structure_weights; "
            "structure_weights(np.eye(5), np.eye(5), None, np.eye(5)[:, :2], 'bdf2', 1e-3, 100); "
            "print(time.perf_counter() - t)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    return float(out.stdout.strip().splitlines()[-1])


def exponent(xs, ys) -> float:
    """Slope of log(ys) against log(xs)."""
    return float(np.polyfit(np.log(xs), np.log(ys), 1)[0])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per configuration (median reported)")
    parser.add_argument("--old-columns", type=int, default=4, help="impulses the old loops are timed on")
    parser.add_argument("--quick", action="store_true", help="N = 1000 only, one run")
    parser.add_argument("--out", type=Path, default=OUT, help=f"JSON file (default {OUT})")
    args = parser.parse_args(argv)
    repeat = 1 if args.quick else max(1, args.repeat)
    steps = N_STEPS[:1] if args.quick else N_STEPS

    import numba

    from unilateral.soil.structure_weights import structure_weights

    load_before = os.getloadavg()
    first_call = fresh_process_first_call()
    with tempfile.TemporaryDirectory() as empty:
        cold_call = fresh_process_first_call(empty)
    for engine in ("small", "dense", "sparse"):                 # compile (or load) every loop once
        warm = chain_model(70, 2)
        structure_weights(warm.M, warm.K, warm.C, warm.T, RULE, DT, 10, engine=engine)
    old_loop(chain_model(20, 2), 10, np.eye(2), True)           # the old compiled sweep too

    rows = []
    header = (f"{'n':>5} {'m':>3} {'r':>3} {'N':>6} {'old py s':>10} {'old jit s':>10} {'new s':>8} "
              f"{'path':>6} {'py/new':>7} {'jit/new':>8} {'rel diff':>9} {'jit-py':>8}")
    print(header)
    print("-" * len(header))
    for n in N_DOFS:
        for m in M_CONTACTS:
            model = chain_model(n, m)
            basis = model.impulse_basis()
            r = basis.shape[1]
            cols = min(r, args.old_columns)
            scale = r / cols
            for N in steps:
                t_new, runs_new, W = timed(lambda: structure_weights(model.M, model.K, model.C, model.T,
                                                                     RULE, DT, N, basis=basis), repeat)
                t_py, runs_py, W_old = timed(lambda: old_loop(model, N, basis[:, :cols], False), repeat)
                t_py *= scale
                t_jit = runs_jit = floor = None
                if n <= OLD_JIT_MAX_N:
                    t_jit, runs_jit, W_jit = timed(lambda: old_loop(model, N, basis[:, :cols], True), repeat)
                    t_jit *= scale
                    floor = float(np.abs(W_jit - W_old).max() / np.abs(W_old).max())
                diff = float(np.abs(W[:, :, :cols] - W_old).max() / np.abs(W_old).max())
                row = {"n": n, "m": m, "r": r, "N": N, "path": chosen_path(model, N), "old_columns": cols,
                       "old_python_s": t_py, "old_python_runs_s": runs_py, "old_compiled_s": t_jit,
                       "old_compiled_runs_s": runs_jit, "new_s": t_new, "new_runs_s": runs_new,
                       "ratio_python": t_py / t_new, "ratio_compiled": None if t_jit is None else t_jit / t_new,
                       "max_rel_diff": diff, "old_compiled_vs_python_rel_diff": floor,
                       "loadavg": os.getloadavg()}
                rows.append(row)
                mark = "*" if cols < r else " "
                jit = "-" if t_jit is None else f"{t_jit:.3f}{mark}"
                jit_ratio = "-" if t_jit is None else f"{t_jit / t_new:.1f}"
                print(f"{n:>5} {m:>3} {r:>3} {N:>6} {t_py:>9.3f}{mark} {jit:>10} {t_new:>8.3f} {row['path']:>6} "
                      f"{t_py / t_new:>7.1f} {jit_ratio:>8} {diff:>9.1e} "
                      f"{'-' if floor is None else format(floor, '.1e'):>8}", flush=True)

    scaling = {}
    for n in N_DOFS:
        mine = [r for r in rows if r["n"] == n]
        top = max(steps)
        in_r = [r for r in mine if r["N"] == top]
        out = {"exponent_r": exponent([r["r"] for r in in_r], [r["new_s"] for r in in_r])}
        if len(steps) > 1:
            in_N = [r for r in mine if r["m"] == max(M_CONTACTS)]
            out["exponent_N"] = exponent([r["N"] for r in in_N], [r["new_s"] for r in in_N])
        scaling[n] = out
    load_after = os.getloadavg()
    print("* old loops timed on the first few impulses and scaled by r / columns (one independent sweep each)")
    print("new time ~ r^a N^b:  " + ";  ".join(
        f"n = {n}: a = {s['exponent_r']:.2f}" + (f", b = {s['exponent_N']:.2f}" if "exponent_N" in s else "")
        for n, s in scaling.items()))
    print(f"first call in a fresh process (n = 5, N = 100): {first_call:.2f} s with numba's cache, "
          f"{cold_call:.2f} s compiling (empty cache)")
    print(f"load average (1, 5, 15 min): before {', '.join(f'{x:.2f}' for x in load_before)}; "
          f"after {', '.join(f'{x:.2f}' for x in load_after)}  (2 shared cores)")
    report = {"rule": RULE, "dt": DT, "repeat": repeat, "old_columns": args.old_columns,
              "machine": platform.platform(), "cpu_count": os.cpu_count(), "python": platform.python_version(),
              "numpy": np.__version__, "numba": numba.__version__,
              "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
              "loadavg_before": load_before, "loadavg_after": load_after,
              "fresh_process_first_call_s": first_call, "fresh_process_first_call_cold_cache_s": cold_call,
              "scaling": {str(k): v for k, v in scaling.items()},
              "rows": rows}
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=2) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
