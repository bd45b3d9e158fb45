"""Wall time of the command line: ``--help``, ``example liolios1990``, ``run examples/pounding.toml``,
and ``run`` of the 9-storey frame with 58 hinges (``benchmarks/frame9.py``, 108 DOFs; 3000 steps of
5 ms, and 15000 of 1 ms), with the megabytes written and the share of the wall time spent solving
(the ``time_total`` of the cases in ``results.nc`` over the wall time).

Each command runs in a fresh process, ``--repeat`` times (default 3) after one warm-up run (numba's
disk cache filled); the table shows the best and the median, and the targets. The two analyses
also run with ``--figures none``: the difference is the time of the figures. Outputs go to a
temporary directory; the table is also written as JSON (``--out``, default in that directory).

    python benchmarks/cli_timing.py [--repeat 3] [--out timing.json] [--only example]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COMMANDS = {
    "--help": ["--help"],
    "example liolios1990": ["example", "liolios1990"],
    "example liolios1990 --figures none": ["example", "liolios1990", "--figures", "none"],
    "run examples/pounding.toml": ["run", str(ROOT / "examples" / "pounding.toml")],
    "run examples/pounding.toml --figures none": ["run", str(ROOT / "examples" / "pounding.toml"),
                                                  "--figures", "none"],
}
FRAME9 = {"run frame9 dt=5ms --figures none": (0.005, ["--figures", "none"]),
          "run frame9 dt=5ms": (0.005, []),
          "run frame9 dt=1ms --figures none": (0.001, ["--figures", "none"])}
TARGETS = {"example liolios1990": 1.0, "run examples/pounding.toml": 4.0, "run frame9 dt=5ms --figures none": 1.0,
           "run frame9 dt=5ms": 2.0, "run frame9 dt=1ms --figures none": 2.5}


def commands(work: Path) -> dict:
    """Every command of the table: :data:`COMMANDS` and the 9-storey frame's, its files written into ``work``."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from frame9 import write

    out = dict(COMMANDS)
    for label, (dt, extra) in FRAME9.items():
        path = write(work / f"frame9_{int(round(dt * 1e3))}ms", dt=dt)
        out[label] = ["run", str(path), *extra]
    return out


def written(folder: Path) -> tuple[float, float]:
    """``(MB, solve_s)``: the size of the files in ``folder`` and the solving time of its cases."""
    import h5py

    size = sum(p.stat().st_size for p in folder.iterdir() if p.is_file()) / 1e6
    with h5py.File(folder / "results.nc") as f:
        solve = float(sum(f["time_total"][()].ravel())) if "time_total" in f else float("nan")
    return size, solve


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--out", type=Path, default=None, help="JSON results (default: in a temporary directory)")
    p.add_argument("--only", default=None, help="Time only the commands whose label contains this text.")
    args = p.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="unilateral-cli-timing-"))
    rows = {}
    for k, (label, command) in enumerate(commands(work).items()):
        if args.only is not None and args.only not in label:
            continue
        extra = [] if command == ["--help"] else ["--out", str(work / f"out{k}")]
        argv_ = [sys.executable, "-m", "unilateral", *command, *extra]
        subprocess.run(argv_, check=True, capture_output=True)          # warm-up
        times = []
        for _ in range(args.repeat):
            start = time.perf_counter()
            subprocess.run(argv_, check=True, capture_output=True)
            times.append(time.perf_counter() - start)
        rows[label] = {"best_s": min(times), "median_s": statistics.median(times), "runs": times,
                       "target_s": TARGETS.get(label)}
        if command != ["--help"]:
            mb, solve = written(work / f"out{k}")
            rows[label] |= {"written_MB": mb, "solve_s": solve, "solve_share": solve / statistics.median(times)}
    print(f"{'command':<42} {'best [s]':>9} {'median [s]':>11} {'target [s]':>11} {'MB':>7} {'solving':>8}")
    for label, row in rows.items():
        target = "" if row["target_s"] is None else f"{row['target_s']:.1f}"
        extra = f" {row['written_MB']:>7.1f} {100 * row['solve_share']:>7.0f}%" if "written_MB" in row else ""
        print(f"{label:<42} {row['best_s']:>9.2f} {row['median_s']:>11.2f} {target:>11}{extra}")
    out = args.out or work / "cli_timing.json"
    out.write_text(json.dumps({"python": sys.version, "repeat": args.repeat, "rows": rows}, indent=2))
    print(f"\nresults: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
