"""Command line of the benchmark suite: ``python -m unilateral.bench --help``."""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from pathlib import Path

from ..io.atomic import to_jsonable, write_json_atomic
from .problems import PROBLEMS
from .suite import METHODS, Limits, ScalingConfig, machine_info, run_one, run_scaling, run_suite

#: Default results file: in ./bench-results of the current directory, never inside the package.
DEFAULT_OUT = Path("bench-results") / "benchmarks.json"


def parser() -> argparse.ArgumentParser:
    """The argument parser."""
    p = argparse.ArgumentParser(
        prog="python -m unilateral.bench",
        description="Benchmark the methods of unilateral.solve: time per step, peak memory and "
                    "error against a converged reference, each run in its own subprocess.")
    p.add_argument("--quick", action="store_true", help="few steps and a small scaling sweep")
    p.add_argument("--problems", nargs="+", default=list(PROBLEMS), metavar="P",
                   help=f"problems (default: {' '.join(PROBLEMS)}; also winkler<m>)")
    p.add_argument("--methods", nargs="+", default=list(METHODS), choices=list(METHODS), metavar="M",
                   help="methods (default: all: " + ", ".join(f"'{m}'" for m in METHODS) + ")")
    p.add_argument("--out", type=Path, default=DEFAULT_OUT, help=f"JSON results (default ./{DEFAULT_OUT}, in the current directory); "
                        "the scaling figure goes next to it")
    p.add_argument("--no-figure", action="store_true", help="skip the scaling runs and their figure")
    p.add_argument("--max-memory-gib", type=float, default=None,
                   help="skip runs estimated to need more memory (default 4)")
    p.add_argument("--max-minutes", type=float, default=None,
                   help="skip runs estimated to take longer (default 10, quick 2)")
    p.add_argument("--timeout", type=float, default=None,
                   help="seconds before a run is stopped (default 900, quick 120)")
    p.add_argument("--run-one", nargs=2, metavar=("PROBLEM", "METHOD"),
                   help="internal: run one problem with one method (or 'reference'), print a JSON line")
    p.add_argument("--steps", type=int, default=None, help="with --run-one: number of steps")
    p.add_argument("--output", type=Path, default=None, help="with --run-one: .npz of the key output")
    return p


def main(argv=None) -> int:
    """Run the suite (or one run with ``--run-one``); return the exit code."""
    cli = parser()
    args = cli.parse_args(argv)
    if args.run_one:
        record = run_one(*args.run_one, quick=args.quick, steps=args.steps, output=args.output)
        print(json.dumps(to_jsonable(record)), flush=True)
        return 0
    defaults = Limits.default(args.quick)
    limits = Limits(
        memory_gib=defaults.memory_gib if args.max_memory_gib is None else args.max_memory_gib,
        minutes=defaults.minutes if args.max_minutes is None else args.max_minutes,
        timeout=defaults.timeout if args.timeout is None else args.timeout)
    try:
        records = run_suite(args.problems, args.methods, quick=args.quick, limits=limits,
                            progress=_progress)
    except ValueError as exc:                       # an unknown problem name
        cli.error(str(exc))
    results = {"machine": machine_info(), "quick": args.quick, "limits": asdict(limits),
               "runs": records}
    if not args.no_figure:
        results["scaling"] = run_scaling(ScalingConfig.default(args.quick), limits=limits,
                                         progress=_progress)
    from .report import format_table, save_scaling_figure     # matplotlib: not in the runs' subprocesses

    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_json_atomic(args.out, results)
    print(format_table(records))
    print(f"\nresults: {args.out}")
    if not args.no_figure:
        paths = save_scaling_figure(results["scaling"], args.out.with_name("scaling"))
        print("scaling figure: " + ", ".join(map(str, paths)))
    every = records + results.get("scaling", [])
    return int(any(record["status"] == "failed" for record in every))


def _progress(record) -> None:
    time_s = record.get("total_s")
    done = f"{time_s:.3g} s" if record["status"] == "ok" else f"{record['status']}: {record.get('reason', '')}"
    print(f"  {record['problem']:<12} {record['method']:<10} N={record['N']:<7} {done}",
          file=sys.stderr, flush=True)


if __name__ == "__main__":
    sys.exit(main())
