"""Time a tower on a rigid footing on the elastic half-space (``Frame2D.foundation``), CQ march.

The structure is the paper's tower (mass 40 on a 10 m column; 5 DOFs: 1.ux, 1.uy, 1.rz, 2.uy,
2.rz) on a rigid 10 m x 10 m footing cut into ``m`` strips, on the half-space of
:func:`unilateral.structure.examples.halfspace_tower` (Vs = 97 m/s, nu = 1/3, rho = 2 t/m^3), under
gravity and a synthetic earthquake (PGA 5 m/s^2), with uplift. ``dt = 1e-3`` s, ``N`` steps
(``t_end = N dt``), BDF2, ``method="cq"``. Every run builds its model afresh: the wall time includes
the soil's kernel (``Phi(s)`` on the CQ circle), the structure's weights, the bilateral sweep, the
march and the recovery.

Reports the median over ``--repeat`` runs of

* the target: ``m = 20``, ``N = 10^4`` (aim: <= 60 s on the development machine);
* two such towers on footings of 20 strips each, 5 m apart on one half-space (40 coupled contacts),
  ``N = 10^4`` (aim: <= 60 s);
* two footings of 10 strips (``N = 1000``) and of 20 strips (``N = 10^4``, aim: <= 60 s) sliding
  on the soil (x and z forces, friction): 40 and 80 soil unknowns, as many slips;
* the scaling in ``m`` (5, 10, 20, 40 at ``N = 10^4``) and in ``N`` (2500, 5000, 10^4, 2 10^4 at
  ``m = 20``), with the fitted exponents of ``time ~ m^a`` and ``time ~ N^b``.

Prints a table and writes JSON to ``<temp dir>/unilateral-bench/foundation_halfspace.json`` (or
``--out``). Run: ``python benchmarks/foundation_halfspace.py [--quick] [--repeat 3] [--out FILE]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

DT = 1e-3
TARGET = (20, 10_000)
M_VALUES = (5, 10, 20, 40)
N_VALUES = (2_500, 5_000, 10_000, 20_000)
#: (strips per footing, N) of the sliding footings' rows. Their weights take (N+1) (8 m)^2 numbers
#: (2 GB at 20 strips and 10^4 steps; the history sums only the 4 m soil unknowns' quarter); the x-z
#: soil kernel is evaluated for about three travel times across the footings, its weights continued
#: by their algebraic tail (SoilFlexibility.cq_weights), so its cost hardly grows with N.
SLIDING = ((10, 1_000), (20, 10_000))


def run_once(m: int, N: int) -> dict:
    """One run from scratch: wall time (s), its parts and a few figures of the solution."""
    import unilateral as ul
    from unilateral.loads import synthetic_accelerogram
    from unilateral.structure.examples import halfspace_tower

    t_end = N * DT
    record = synthetic_accelerogram(max(t_end, 1.0), 0.01, 5.0, seed=1, f_g=4.0)
    start = time.perf_counter()
    structure, load, _ = halfspace_tower("halfspace", load="earthquake", patches=m, record=record)
    model = structure.to_model()
    sol = ul.solve(model, load, dt=DT, t_end=t_end, method="cq", rule="bdf2")
    wall = time.perf_counter() - start
    parts = {key: float(value) for key, value in sol.stats.get("time", {}).items()}
    return {"m": m, "N": N, "wall_s": wall, "parts_s": parts, "success": bool(sol.success),
            "max_uplift_m": float(sol.v.max()), "contact_changes": int(sol.stats.get("contact_changes", 0))}


def run_two_footings(m: int, N: int, sliding: bool = False) -> dict:
    """Two such towers, their 10 m footings 15 m apart (5 m of ground between them) on one
    half-space: ``2 m`` coupled contacts (structure-soil-structure interaction). ``sliding``: the
    footings rest on the soil horizontally too (x-z Green's tensor, ``mu = 0.5``): ``4 m`` soil
    unknowns (``c``, ``f``) and ``4 m`` slips."""
    import unilateral as ul
    from unilateral.loads import LoadHistory, synthetic_accelerogram
    from unilateral.structure import Frame2D
    from unilateral.structure.examples import EA_RIGID, EI, HEIGHT, MASS, SOIL_NU, SOIL_RHO, SOIL_VS

    t_end = N * DT
    record = synthetic_accelerogram(max(t_end, 1.0), 0.01, 5.0, seed=1, f_g=4.0)
    start = time.perf_counter()
    fr = Frame2D()
    for k, x in enumerate((0.0, 15.0)):
        fr.node(f"top{k}", x, HEIGHT)
        fr.node(f"base{k}", x, 0.0)
        fr.beam(f"column{k}", f"base{k}", f"top{k}", E=1.0, A=EA_RIGID, I=EI * (1 + k))
        fr.mass(f"top{k}", MASS)
        fr.foundation(f"F{k}", f"base{k}", width=10.0, length=10.0, patches=m,
                      soil={"model": "halfspace", "Vs": SOIL_VS, "nu": SOIL_NU, "rho": SOIL_RHO},
                      **(dict(horizontal="soil", mu=0.5, mass=MASS / 4, J=MASS) if sliding else {}))
    structure = fr.build()
    load = LoadHistory(structure.gravity(10.0), [structure.ground_motion(record, "ux")])
    sol = ul.solve(structure.to_model(), load, dt=DT, t_end=t_end, method="cq", rule="bdf2")
    wall = time.perf_counter() - start
    parts = {key: float(value) for key, value in sol.stats.get("time", {}).items()}
    return {"m": (4 if sliding else 2) * m, "N": N, "wall_s": wall, "parts_s": parts, "success": bool(sol.success),
            "max_uplift_m": float(sol.v[:, :2 * m].max()),
            "contact_changes": int(sol.stats.get("contact_changes", 0))}


def run_sliding(m: int, N: int) -> dict:
    """:func:`run_two_footings` with footings that slide."""
    return run_two_footings(m, N, sliding=True)


def median_run(m: int, N: int, repeat: int, once=run_once) -> dict:
    runs = [once(m, N) for _ in range(repeat)]
    best = sorted(runs, key=lambda r: r["wall_s"])[len(runs) // 2]
    return {**best, "wall_s": statistics.median(r["wall_s"] for r in runs),
            "runs_s": [r["wall_s"] for r in runs]}


def exponent(xs, ys) -> float:
    """Least-squares slope of log(ys) against log(xs)."""
    return float(np.polyfit(np.log(xs), np.log(ys), 1)[0])


def row(r: dict) -> str:
    p = r["parts_s"]
    return (f"{r['m']:>4} {r['N']:>7} {r['wall_s']:>9.2f} {p.get('weights', float('nan')):>9.2f} "
            f"{p.get('steps', float('nan')):>8.2f} {r['max_uplift_m']:>11.3e} {r['contact_changes']:>8}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per configuration (median reported)")
    parser.add_argument("--quick", action="store_true", help="the target only, one run")
    parser.add_argument("--out", type=Path, default=None, help="JSON file (default: in the temp folder)")
    args = parser.parse_args(argv)
    if args.repeat < 1:
        parser.error(f"--repeat {args.repeat}: give at least 1")
    out = args.out or Path(tempfile.gettempdir()) / "unilateral-bench" / "foundation_halfspace.json"
    repeat = 1 if args.quick else args.repeat
    header = f"{'m':>4} {'N':>7} {'wall s':>9} {'weights':>9} {'steps':>8} {'max uplift':>11} {'changes':>8}"
    print(f"tower on a rigid 10 m x 10 m footing on the half-space, dt = {DT:g} s, median of {repeat}")
    print(header)
    results = {"dt": DT, "repeat": repeat, "target": None, "m_scaling": [], "N_scaling": []}
    target = median_run(*TARGET, repeat)
    results["target"] = target
    print(row(target), " <- target (aim <= 60 s)")
    two = median_run(TARGET[0], TARGET[1], repeat, once=run_two_footings)
    results["two_footings"] = two
    print(row(two), " <- two footings of 20 strips on one half-space (aim <= 60 s)")
    results["sliding"] = []
    for m, N in SLIDING[:1] if args.quick else SLIDING:
        r = median_run(m, N, repeat, once=run_sliding)
        results["sliding"].append(r)
        aim = " (aim <= 60 s)" if N >= 10_000 else ""
        print(row(r), f" <- two footings of {m} strips sliding: {4 * m} soil unknowns (x, z), {4 * m} slips{aim}")
    if not args.quick:
        for m in M_VALUES:
            r = target if (m, TARGET[1]) == TARGET else median_run(m, TARGET[1], repeat)
            results["m_scaling"].append(r)
            print(row(r))
        for N in N_VALUES:
            r = target if (TARGET[0], N) == TARGET else median_run(TARGET[0], N, repeat)
            results["N_scaling"].append(r)
            print(row(r))
        a = exponent([r["m"] for r in results["m_scaling"]], [r["wall_s"] for r in results["m_scaling"]])
        b = exponent([r["N"] for r in results["N_scaling"]], [r["wall_s"] for r in results["N_scaling"]])
        results["exponent_m"], results["exponent_N"] = a, b
        print(f"fitted: wall time ~ m^{a:.2f} (N = {TARGET[1]}), ~ N^{b:.2f} (m = {TARGET[0]})")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(results, indent=2) + "\n", encoding="utf-8")
    print(f"written {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
