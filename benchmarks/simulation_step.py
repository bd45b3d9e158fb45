"""The cost of stepping an analysis from Python: ``Simulation.step()`` against one ``solve`` call.

The five-storey rocking tower of the benchmark suite (17 DOFs, 3 contacts, 10^4 steps), compiled
direct stepping: ``solve`` marches every step in one call; the simulation is stepped one
``sim.step()`` at a time (the compiled march computes ahead in chunks). The overhead per step is
``(stepped - solve) / N``, the medians of ``--repeats`` runs in one process (after a warm-up run
that compiles); the target is 5 us per step. Also for the Python engine (one step per call, no
chunks). The table is printed and written as JSON (``--out``).

    python benchmarks/simulation_step.py [--repeats 5] [--steps 10000] [--out simulation_step.json]
"""

from __future__ import annotations

import os

if __name__ == "__main__":                  # before numpy is imported: BLAS in one thread
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

TARGET_US = 5.0


def measure(engine: str, steps: int, repeats: int) -> dict:
    import unilateral as ul
    from unilateral.bench.problems import build
    from unilateral.methods import Direct

    p = build("tower", steps=steps)
    kw = dict(dt=p.dt, t_end=p.N * p.dt, method=Direct(engine=engine))
    whole_s, stepped_s = [], []
    for i in range(repeats + 1):            # the first run warms up (compilation, caches)
        start = time.perf_counter()
        ref = ul.solve(p.model, p.load, **kw)
        whole = time.perf_counter() - start
        start = time.perf_counter()
        sim = ul.Simulation(p.model, p.load, **kw)
        while sim.status == "running":
            sim.step()
        sol = sim.solution()
        stepped = time.perf_counter() - start
        if i:
            whole_s.append(whole)
            stepped_s.append(stepped)
    same = float(max(abs(sol.u - ref.u).max(), abs(sol.v - ref.v).max()))
    whole, stepped = statistics.median(whole_s), statistics.median(stepped_s)
    return {"engine": engine, "steps": p.N, "solve_s": whole, "stepped_s": stepped,
            "per_step_solve_us": 1e6 * whole / p.N, "overhead_per_step_us": 1e6 * (stepped - whole) / p.N,
            "max_difference": same, "stepping": sim.stats["stepping"]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--steps", type=int, default=10_000)
    ap.add_argument("--out", type=Path, default=Path(__file__).parent / "results" / "simulation_step.json")
    args = ap.parse_args(argv)
    load = os.getloadavg()
    rows = [measure(engine, args.steps, args.repeats) for engine in ("compiled", "python")]
    print(f"tower, {args.steps} steps, medians of {args.repeats}; load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print(f"{'engine':<9} {'stepping':<8} {'solve [s]':>10} {'stepped [s]':>12} {'solve us/step':>14} "
          f"{'overhead us/step':>17} {'target':>7} {'max diff':>9}")
    for r in rows:
        target = f"{TARGET_US:g}" if r["engine"] == "compiled" else ""
        print(f"{r['engine']:<9} {r['stepping']:<8} {r['solve_s']:>10.4f} {r['stepped_s']:>12.4f} "
              f"{r['per_step_solve_us']:>14.2f} {r['overhead_per_step_us']:>17.2f} {target:>7} "
              f"{r['max_difference']:>9.1e}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"python": sys.version, "load_average": list(load), "repeats": args.repeats,
                                    "target_overhead_us": TARGET_US, "rows": rows}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
