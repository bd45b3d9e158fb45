"""The step time of the compiled direct march against the Python loop on the paper's example.

The paper's example (n = 5, m = 3; ``unilateral.bench.problems.build("paper")``) stepped by
``method="direct"`` with the compiled engine and with the Python one: the time of the steps
(``stats["time"]["steps"]``) per step, the median of ``--repeats`` runs in one process after a
warm-up run (compilation, caches), and the largest difference of the two engines' ``u`` and ``v``.
This was a test's assertion (under 20 us per step) until the machines it ran on were shared: a time
is a benchmark row, not a verdict (``tests/test_direct_compiled.py`` checks which march ran).
On a quiet 2-core machine the compiled march takes about 1 us per step, the Python loop 100+ us.

    python benchmarks/compiled_march.py [--repeats 3] [--steps 20000] [--out compiled_march.json]
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
from pathlib import Path


def measure(engine: str, steps: int, repeats: int) -> tuple[dict, object]:
    import unilateral as ul
    from unilateral.bench.problems import build
    from unilateral.methods import Direct

    p = build("paper", steps=steps)
    kw = dict(dt=p.dt, t_end=p.N * p.dt, method=Direct(engine=engine))
    ul.solve(p.model, p.load, **{**kw, "t_end": 20 * p.dt})          # warm-up: compilation, caches
    runs = [ul.solve(p.model, p.load, **kw) for _ in range(repeats)]
    times = [sol.stats["time"]["steps"] for sol in runs]
    sol = runs[-1]
    return {"engine": engine, "march": sol.stats["march"], "steps": p.N, "steps_s": statistics.median(times),
            "per_step_us": 1e6 * statistics.median(times) / p.N, "runs_s": times}, sol


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps", type=int, default=20_000)
    ap.add_argument("--out", type=Path, default=Path(__file__).parent / "results" / "compiled_march.json")
    args = ap.parse_args(argv)
    load = os.getloadavg()
    (compiled, a), (python, b) = (measure(engine, args.steps, args.repeats) for engine in ("compiled", "python"))
    difference = float(max(abs(a.u - b.u).max(), abs(a.v - b.v).max()))
    print(f"paper's example, {args.steps} steps, medians of {args.repeats}; "
          f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print(f"{'engine':<9} {'march':<20} {'steps [s]':>10} {'us/step':>9}")
    for r in (compiled, python):
        print(f"{r['engine']:<9} {r['march']:<20} {r['steps_s']:>10.4f} {r['per_step_us']:>9.2f}")
    print(f"python / compiled: {python['steps_s'] / compiled['steps_s']:.1f}; largest difference of u, v: "
          f"{difference:.1e}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({"python": sys.version, "load_average": list(load), "repeats": args.repeats,
                                    "max_difference": difference, "rows": [compiled, python]}, indent=2))
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
