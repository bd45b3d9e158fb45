"""Cost of ``method="event"``: set-up, per event, per output step (smooth stretch), total.

The exact event-driven march (:mod:`unilateral.march.event`) integrates each configuration with
matrix exponentials and brackets the events on a sub-grid that resolves the fastest oscillation of
the configuration (half a radian of it). On the benchmark tower (:func:`unilateral.bench.problems.tower`:
five storeys, axially rigid columns, 17 DOFs, 3 tensionless Kelvin soil elements, a 10 s
piecewise-linear accelerogram) that is 1.7e5 rad/s, 3.5 million sub-intervals whatever the output
step: a fixed cost of seconds. The sub-grid is now evaluated only where a modal bound of the event
functions cannot rule out a crossing (``_March._plan``); this script states what is left.

Models: the tower at two output steps (``dt`` = 0.01 and 0.001 s), the paper's example
(:func:`unilateral.bench.problems.paper`, 0.5 s, 2000 steps) and an elastic-perfectly-plastic SDOF
under a half-sine pulse (yield and unloading events of rate unknowns, 2 s, 2000 steps). Columns:

``setup s``
    Everything but the march through the output grid: the checks, the load generator, the static
    initial state, the matrices, the first configuration (its modal split included).
``per event ms``
    The time spent locating the events (Brent's method on the exact solution) and deciding the new
    contact set at them, per contact change.
``per step us``, ``per stretch us``
    The rest of the march (advancing between output times, the sparse sampling, the outputs, the
    load breakpoints' re-initialisations), per output step and per smooth stretch (the march
    between two consecutive stops, output times and load breakpoints: ``stretches``).
``total s``
    The call to ``unilateral.solve``.
``first call s``
    The same, the first time in the process (the warm-up run: lazy imports, first configurations).

Medians of ``--repeat`` runs (3) after a warm-up run; BLAS in one thread; ``os.getloadavg()`` is
printed and stored. Timings on a machine that runs other work are several times worse: quote the
load average with them.

``python benchmarks/event_speed.py [--quick] [--repeat 3] [--out FILE]`` prints the table and writes
``benchmarks/results/event_speed.json`` (``--quick``: the smallest sizes, one run, a smoke test).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path

if __name__ == "__main__":                  # before numpy is imported: BLAS in one thread
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"


def cases(quick: bool):
    """``(name, model, load, dt, N, initial)`` of the table."""
    import unilateral as ul
    from unilateral.bench.problems import build
    from unilateral.constraints import Yield
    from unilateral.loads import HalfSine, LoadHistory

    out = []
    for steps in ((100,) if quick else (1000, 10_000)):
        p = build("tower", steps=steps)
        out.append((f"tower dt={p.dt:g}", p.model, p.load, p.dt, p.N, "static"))
    p = build("paper", steps=200 if quick else 2000)
    out.append((f"paper dt={p.dt:g}", p.model, p.load, p.dt, p.N, "static"))
    epp = ul.Model.from_natural(G=[[1.0]], E=[[100.0]], B=[[1.0, -1.0]], M=[[1.0]], C=[[1.0]],
                                r=[5.0, 5.0], families=[Yield([0, 1])])
    pulse = LoadHistory([0.0], [([1.0], HalfSine(12.0, duration=0.4))])
    N = 200 if quick else 2000
    out.append((f"epp sdof dt={2.0 / N:g}", epp, pulse, 2.0 / N, N, "rest"))
    return out


class Clock:
    """Wall time spent in the event march's phases, by wrapping its methods (``perf_counter``)."""

    def __init__(self):
        from unilateral.march import event

        self.march, self.puller = event._March, event.EventMarch
        names = ("_locate", "decide", "advance", "_glide")
        self.saved = {name: getattr(self.march, name) for name in names if hasattr(self.march, name)}
        self.saved["extend"] = self.puller.extend           # the march is followed as it is pulled
        self.reset()

    def reset(self):
        self.follow = self.events = 0.0
        self.stretches = 0

    def __enter__(self):
        clock, saved = self, self.saved

        def follow(self, *args):
            start = time.perf_counter()
            try:
                return saved["extend"](self, *args)
            finally:
                clock.follow += time.perf_counter() - start

        def locate(self, *args):
            start = time.perf_counter()
            try:
                return saved["_locate"](self, *args)
            finally:
                clock.events += time.perf_counter() - start

        def decide(self, cfg, Y, t, forced):
            start = time.perf_counter()
            new, Yn = saved["decide"](self, cfg, Y, t, forced)
            if forced or new is not cfg:                          # a decision at an event
                clock.events += time.perf_counter() - start
            return new, Yn

        def advance(self, *args, **kwargs):
            clock.stretches += 1
            return saved["advance"](self, *args, **kwargs)

        def glide(self, *args):
            count, Y = saved["_glide"](self, *args)
            clock.stretches += count
            return count, Y

        self.puller.extend, self.march._locate, self.march.decide = follow, locate, decide
        self.march.advance = advance
        if "_glide" in saved:
            self.march._glide = glide
        return self

    def __exit__(self, *exc):
        for name, method in self.saved.items():
            setattr(self.puller if name == "extend" else self.march, name, method)


def measure(name, model, load, dt, N, initial, repeat):
    import unilateral as ul

    runs = []
    with Clock() as clock:
        for i in range(repeat + 1):                 # the first run warms up (imports, caches)
            clock.reset()
            start = time.perf_counter()
            sol = ul.solve(model, load, dt=dt, t_end=N * dt, method="event", initial=initial)
            total = time.perf_counter() - start
            if not sol.success:
                raise RuntimeError(f"{name}: {sol.message}")
            if i == 0:
                first = total
            else:
                runs.append((total, clock.follow, clock.events))
                stretches = clock.stretches
    total, follow, events = (statistics.median(x) for x in zip(*runs))
    n_events = int(sol.stats["events"])
    return {
        "model": name, "n": int(model.n), "m": int(model.m), "dt": dt, "steps": N,
        "events": n_events, "decisions": int(sol.stats["decisions"]),
        "substeps": int(sol.stats["substeps"]), "configurations": int(sol.stats["configurations"]),
        "setup_s": total - follow,
        "per_event_ms": 1e3 * events / n_events if n_events else None,
        "stretches": stretches,
        "per_step_us": 1e6 * (follow - events) / N,
        "per_stretch_us": 1e6 * (follow - events) / stretches,
        "total_s": total,
        "first_call_s": first,
        "runs": repeat,
    }


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="the smallest sizes, one run (a smoke test)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", type=Path, default=RESULTS / "event_speed.json")
    args = parser.parse_args(argv)
    repeat = 1 if args.quick else args.repeat
    load_before = os.getloadavg()
    rows = [measure(*case, repeat) for case in cases(args.quick)]
    load = os.getloadavg()
    print(f"method='event', medians of {repeat}; load average {load_before[0]:.2f} -> "
          f"{load[0]:.2f} {load[1]:.2f} {load[2]:.2f} (1, 5, 15 min)")
    print(f"{'model':>20} {'n':>3} {'m':>3} {'steps':>6} {'events':>6} {'substeps':>9} {'setup s':>8} "
          f"{'per event ms':>12} {'per step us':>11} {'stretches':>9} {'per stretch us':>14} {'total s':>8} "
          f"{'first call s':>12}")
    for r in rows:
        per_event = "-" if r["per_event_ms"] is None else f"{r['per_event_ms']:.2f}"
        print(f"{r['model']:>20} {r['n']:>3} {r['m']:>3} {r['steps']:>6} {r['events']:>6} {r['substeps']:>9} "
              f"{r['setup_s']:8.3f} {per_event:>12} {r['per_step_us']:11.1f} {r['stretches']:>9} "
              f"{r['per_stretch_us']:14.1f} {r['total_s']:8.3f} {r['first_call_s']:12.3f}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"load_average_before": load_before, "load_average": load,
                               "numpy": np.__version__, "rows": rows}, indent=1) + "\n")
    tmp.replace(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
