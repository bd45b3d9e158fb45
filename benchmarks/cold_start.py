"""The first run after a fresh install, and the first run of a new process, against OpenSees.

Each cell runs the model of ``opensees_winkler.py`` (the Winkler beam of 998 DOFs on 10 springs,
500 steps, and the 17-DOF tower, 10^4 steps) in a new Python process, end to end (the model built
and solved by ``method="auto"``, the import of the package counted separately), with an empty numba
cache of its own (``NUMBA_CACHE_DIR`` a fresh folder: as after a fresh install) and then again with
the cache the first run filled (a new process of an installed package). Rows:

* ``cold auto``: the default policy on an empty cache (its ``stats["engine_reason"]`` is printed:
  the engine it chose and why);
* ``cold compiled``: engine ``"compiled"`` pinned on an empty cache: the cost of compiling;
* ``cached auto`` and ``cached compiled``: the same in a new process with the cache filled;
* OpenSees: the same model end to end (built, gravity step, transient), in a new process.

``ratio`` is the run over OpenSees's (target: at most 3 after a fresh install); ``load s`` the
cached compiled run minus the same run in a process that had compiled it (target: at most 0.2 s).
BLAS threads as the environment leaves them (as a user runs it). ``python benchmarks/cold_start.py``
prints the table with the load average and writes ``benchmarks/results/cold_start.json``;
``--quick``: the tower of 1 s (400 steps) only, no OpenSees.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"
RESULTS = HERE / "results"

#: The code a cell runs in its new process: ``(import s, first solve s, second solve s, stats)``.
CELL = r"""
import json, sys, time
start = time.perf_counter()
sys.path.insert(0, sys.argv[1])
import numpy as np
import opensees_winkler as b
import unilateral as ul
from unilateral.methods import Direct
imported = time.perf_counter() - start
a = json.loads(sys.argv[2])
method = "auto" if a["engine"] == "auto" else Direct(engine=a["engine"])
def run():
    if a["model"] == "beam":
        return b.run_unilateral(b.BeamSpec(nodes=a["nodes"], springs=a["springs"]), a["steps"], b.DT, method=method)
    spec = b.TowerSpec(duration=a["duration"])
    return b.run_tower_unilateral(spec, a["steps"], b.tower_samples(spec, a["steps"]), method=method)
first = run()
second = run()
keys = ("method", "march", "engine", "engine_reason", "numba_cache", "n", "m")
print(json.dumps({"import_s": imported, "first_s": first[1], "second_s": second[1],
                  "stats": {k: first[3].stats.get(k) for k in keys}}))
"""

MODELS = {
    "beam": {"model": "beam", "nodes": 333, "springs": 10, "steps": 500},
    "tower": {"model": "tower", "duration": 10.0, "steps": 10_000},
}
QUICK = {"tower": {"model": "tower", "duration": 1.0, "steps": 400}}


def cell(spec, engine, cache_dir):
    """One new process: the model of ``spec`` solved twice with ``engine``, numba's cache in
    ``cache_dir``; its JSON output."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache_dir), "PYTHONPATH": str(SRC)}
    env.pop("UNILATERAL_ENGINE_CHOICE", None)           # the default policy, as a user runs it
    proc = subprocess.run([sys.executable, "-c", CELL, str(HERE), json.dumps({**spec, "engine": engine})],
                          capture_output=True, text=True, env=env, timeout=3600)
    if proc.returncode:
        raise RuntimeError(f"cell {spec} {engine} failed:\n{proc.stderr[-3000:]}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def opensees_time(spec):
    """OpenSees's end-to-end seconds for the model of ``spec`` (a new process), or None."""
    import opensees_winkler as b

    if spec["model"] == "beam":
        out = b.opensees_in_subprocess(b.BeamSpec(nodes=spec["nodes"], springs=spec["springs"]), spec["steps"], b.DT)
    else:
        tower = b.TowerSpec(duration=spec["duration"])
        out = b.tower_opensees_in_subprocess(tower, spec["steps"], b.tower_samples(tower, spec["steps"]))
    return None if out is None else out[1]


def rows_of(name, spec, opensees=True):
    """The rows of one model: cold and cached, auto and compiled, and OpenSees."""
    out = {"model": name, "spec": spec, "rows": {}}
    with tempfile.TemporaryDirectory() as auto_dir, tempfile.TemporaryDirectory() as compiled_dir:
        out["rows"]["cold auto"] = cell(spec, "auto", Path(auto_dir) / "numba")
        out["rows"]["cold compiled"] = cell(spec, "compiled", Path(compiled_dir) / "numba")
        out["rows"]["cached compiled"] = cell(spec, "compiled", Path(compiled_dir) / "numba")
        out["rows"]["cached auto"] = cell(spec, "auto", Path(compiled_dir) / "numba")
    cached = out["rows"]["cached compiled"]
    out["load_s"] = cached["first_s"] - cached["second_s"]
    out["opensees_s"] = opensees_time(spec) if opensees else None
    return out


def print_table(models, load, file=None):
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}", file=file)
    print(f"{'model':>6} {'run':>16} {'import s':>8} {'first s':>8} {'second s':>8} {'engine':>9} {'cache':>7} "
          f"{'OpenSees s':>10} {'ratio':>6}", file=file)
    for m in models:
        os_s = m["opensees_s"]
        for name, r in m["rows"].items():
            ratio = f"{r['first_s'] / os_s:6.2f}" if os_s else f"{'':>6}"
            print(f"{m['model']:>6} {name:>16} {r['import_s']:8.3f} {r['first_s']:8.3f} {r['second_s']:8.3f} "
                  f"{r['stats']['engine']:>9} {str(r['stats'].get('numba_cache')):>7} "
                  f"{os_s if os_s else float('nan'):10.3f} {ratio}", file=file)
        print(f"{m['model']:>6} load of the cached compiled loops in a new process: {m['load_s']:.3f} s; "
              f"cold auto chose: {m['rows']['cold auto']['stats']['engine_reason']}", file=file)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="the tower of 400 steps, no OpenSees")
    parser.add_argument("--out", type=Path, default=RESULTS / "cold_start.json")
    args = parser.parse_args(argv)
    sys.path.insert(0, str(HERE))
    start = time.perf_counter()
    models = [rows_of(name, spec, opensees=not args.quick) for name, spec in (QUICK if args.quick else MODELS).items()]
    load = os.getloadavg()
    print_table(models, load)
    wall = time.perf_counter() - start
    print(f"the table took {wall:.0f} s")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "load_average": load,
                               "cpus": os.cpu_count(), "quick": args.quick, "wall_s": wall, "models": models},
                              indent=1))
    tmp.replace(args.out)
    return models


if __name__ == "__main__":
    main()
