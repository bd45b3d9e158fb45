"""Fast at the prompt: wall times of the command line as a new user meets it.

Times, each the median of ``--repeat`` (default 5) fresh processes after one warm-up run:

- ``import unilateral.cli`` (what every command pays first);
- ``unilateral run`` on a wrong model file, which must fail at once: a typo in a key (``kk = ...``),
  a TOML syntax error (a missing ``=``) and an element on a node that does not exist (a cross check);
- ``unilateral example liolios1990 --figures none`` and ``unilateral example liolios1990`` (its figures).

Each process's wall time is measured from outside (subprocess start to exit). BLAS runs
single-threaded (``OPENBLAS_NUM_THREADS=1`` and the like, unless set). Byte code is cached as on a
user's machine (in a folder of the run, ``PYTHONPYCACHEPREFIX``, even where
``PYTHONDONTWRITEBYTECODE`` is set), so the warm-up compiles and the timed runs do not. The times
depend on the machine's load: the table and the JSON give the load average (``os.getloadavg()``)
before and after; compare runs on a quiet machine. Prints a table and writes
``benchmarks/results/prompt.json`` (``--out`` to change).

    python benchmarks/prompt.py [--repeat 5] [--out benchmarks/results/prompt.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(__file__).parent / "results" / "prompt.json"
EXAMPLE = ROOT / "examples" / "liolios1990.toml"
#: Targets of the issue "Fast at the prompt" [s], on a quiet machine.
TARGETS = {"import unilateral.cli": 0.5, "run: a model file with a typo": 0.5,
           "run: a TOML syntax error": 0.5, "run: an element on a missing node": 0.5,
           "example liolios1990 --figures none": 1.0, "example liolios1990": 1.5}
#: The rows of a wrong model file: the command must fail.
FAILING = ("run: a model file with a typo", "run: a TOML syntax error", "run: an element on a missing node")


def _broken(work: Path, name: str, old: str, new: str) -> Path:
    """examples/liolios1990.toml with ``old`` replaced by ``new``, written to ``work/name``."""
    text = EXAMPLE.read_text()
    if old not in text:
        raise RuntimeError(f"{EXAMPLE} no longer holds {old!r}: update benchmarks/prompt.py")
    path = work / name
    path.write_text(text.replace(old, new, 1))
    return path


def commands(work: Path) -> dict[str, list[str]]:
    typo = _broken(work, "typo.toml", "node = 3, k = 200e3", "node = 3, kk = 200e3")
    syntax = _broken(work, "syntax.toml", 'title = "Liolios', 'title "Liolios')
    node = _broken(work, "node.toml", "node_j = 1\n", "node_j = 99\n")
    cli = [sys.executable, "-m", "unilateral"]
    return {
        "import unilateral.cli": [sys.executable, "-c", "import unilateral.cli"],
        "run: a model file with a typo": [*cli, "run", str(typo), "--out", str(work / "typo")],
        "run: a TOML syntax error": [*cli, "run", str(syntax), "--out", str(work / "syntax")],
        "run: an element on a missing node": [*cli, "run", str(node), "--out", str(work / "node")],
        "example liolios1990 --figures none": [*cli, "example", "liolios1990", "--figures", "none",
                                               "--out", str(work / "none")],
        "example liolios1990": [*cli, "example", "liolios1990", "--out", str(work / "figures")],
    }


def environment(work: Path) -> dict:
    env = dict(os.environ)
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(name, "1")
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env["PYTHONPYCACHEPREFIX"] = str(work / "pycache")
    return env


def wall_time(argv: list[str], env: dict, expect_failure: bool) -> float:
    start = time.perf_counter()
    done = subprocess.run(argv, env=env, capture_output=True, text=True, timeout=600)
    elapsed = time.perf_counter() - start
    if (done.returncode != 0) != expect_failure:
        raise RuntimeError(f"{' '.join(argv)} exited with {done.returncode}:\n{done.stdout}\n{done.stderr}")
    return elapsed


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=5)
    p.add_argument("--out", type=Path, default=OUT, help="JSON results (default: %(default)s)")
    args = p.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="unilateral-prompt-"))
    env = environment(work)
    load_before = os.getloadavg()
    rows = {}
    for label, command in commands(work).items():
        failing = label in FAILING
        wall_time(command, env, failing)                                # warm-up: byte code, numba's cache
        times = [wall_time(command, env, failing) for _ in range(args.repeat)]
        rows[label] = {"median_s": statistics.median(times), "best_s": min(times), "runs_s": times,
                       "target_s": TARGETS.get(label), "loadavg_after": os.getloadavg()}
    load_after = os.getloadavg()
    print(f"{'command':<38} {'median [s]':>10} {'best [s]':>9} {'target [s]':>10} {'load (1 min)':>13}")
    for label, row in rows.items():
        print(f"{label:<38} {row['median_s']:>10.2f} {row['best_s']:>9.2f} {row['target_s']:>10.1f} "
              f"{row['loadavg_after'][0]:>13.2f}")
    print(f"\nload average {load_before[0]:.2f} -> {load_after[0]:.2f} (1 min) on {os.cpu_count()} cores; "
          f"median of {args.repeat} runs each, after a warm-up run")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps({
        "python": sys.version, "platform": platform.platform(), "cpu_count": os.cpu_count(),
        "repeat": args.repeat, "loadavg_before": load_before, "loadavg_after": load_after,
        "env": {name: env.get(name) for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")},
        "rows": rows}, indent=2) + "\n")
    print(f"results: {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
