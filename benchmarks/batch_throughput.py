"""Throughput of studies: analyses per second of the IDA example, in process vs on Dask workers.

    python benchmarks/batch_throughput.py [--workers 2] [--out results.json] [--study examples/ida.toml]
                                          [--analyses K] [--ceiling-rounds 3]

Measures, for the 100 analyses of ``examples/ida.toml`` (the rocking tower under 10 records at
10 levels of Sa(T1)):

* ``plain loop``: every analysis in this process, one after the other, each building its model
  variant anew (what a loop over the analyses without the batch runner does);
* ``serial``: the same loop with the model variants cached per process (``run_analysis``, as
  ``--synchronous`` does: the second analysis of a variant skips the build);
* ``dask``: the same analyses as tasks on a LocalCluster of ``--workers`` single-threaded worker
  processes, once one analysis per task and once grouped as ``run_study`` groups them
  (:func:`unilateral.batch.runner.group_analyses`: a few tasks per worker of about equal cost; the
  target is 2 workers 1.8 times as fast as one process, on a quiet machine),
  their inputs (model text, record samples) scattered once and their results returned
  to this process, as ``run_study`` does; and the whole ``run_study`` (inputs read and scattered,
  results written, the table; not the figures, a cost per study) on the same cluster.

Every case comes after a warm-up (the first solve in a process loads the compiled numba code from
its disk cache, about 1 s, reported on its own; the cluster's start is reported on its own too).
The table gives the analyses per second and their ratio to the plain loop, and the model builds.
The overhead per analysis is the wall time per analysis (times the workers) less the time spent
in ``unilateral.solve``, relative to the latter; it covers the task round trip, building the load,
collecting the peaks (``peaks ms``, shown apart: the last column is the overhead besides it) and,
for the plain loop, the build. The parallel efficiency is ``throughput(dask) / (workers *
throughput(serial))``; the machine's own ceiling is measured too: ``--workers`` CPU-bound Python
processes started together against one alone (virtual CPUs that share a core give less than one
each). The CPU time of this process during the tasks (scheduler and client, per analysis) is
reported: on a machine with as many cores as workers it is taken from them.

BLAS runs single-threaded in this process (``OPENBLAS_NUM_THREADS=1`` and the like, unless set), as
Dask's nanny sets it in the workers: every case does the same work. All the numbers depend on the
load of the machine (``/proc/loadavg``, reported before and after): compare the ratios. Results go
to a JSON file (``--out``; default: a temporary folder, never the repository).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):       # before numpy is imported
    os.environ.setdefault(_name, "1")

ROOT = Path(__file__).resolve().parents[1]
#: A CPU-bound loop of pure Python for the machine's ceiling (about a second).
LOOP = "s = 0\nfor i in range(12_000_000):\n    s += i"


def in_process(study, inputs, *, cached: bool) -> dict:
    """The analyses one after the other in this process, the model variants cached or built anew."""
    from unilateral.batch.runner import _inputs_of
    from unilateral.batch.worker import cache_stats, clear_caches, run_analysis, warm_up

    t0 = time.perf_counter()
    warm = warm_up()
    first = study.analyses[0]
    run_analysis(first.payload, *_inputs_of(first, inputs.variants, inputs.records))
    warm_total = time.perf_counter() - t0
    builds = cache_stats()["model_builds"]
    out = []
    start = time.perf_counter()
    for analysis in study.analyses:
        if not cached:
            clear_caches()
        out.append(run_analysis(analysis.payload, *_inputs_of(analysis, inputs.variants, inputs.records), "serial"))
    wall = time.perf_counter() - start
    case = "serial (in process, cached)" if cached else "plain loop (in process)"
    return _summary(case, out, wall, 1, {"warm_up_s": warm_total, "numba_load_s": warm,
                                         "model_builds": cache_stats()["model_builds"] - builds})


def dask(study, inputs, folder: Path, workers: int) -> tuple[dict, dict]:
    """The analyses as tasks on a new LocalCluster, then the whole ``run_study`` on it."""
    from distributed import wait

    from unilateral.batch import run_study
    from unilateral.batch.runner import _close, _inputs_of, _Tasks, group_analyses, start_cluster
    from unilateral.batch.worker import cache_stats, run_analysis, warm_up

    t0 = time.perf_counter()
    client, cluster = start_cluster(workers)
    started = time.perf_counter() - t0
    t0 = time.perf_counter()
    client.run(warm_up)
    first = study.analyses[0]
    for address in client.scheduler_info()["workers"]:                  # each worker builds the variant
        client.submit(run_analysis, first.payload, *_inputs_of(first, inputs.variants, inputs.records),
                      workers=[address], pure=False).result()
    warm_total = time.perf_counter() - t0
    builds = sum(s["model_builds"] for s in client.run(cache_stats).values())
    submitter = _Tasks(client, inputs, "dask")                            # inputs scattered once
    cases = []
    for name, groups in ((f"dask ({workers} workers, 1 per task)", [[a] for a in study.analyses]),
                         (f"dask ({workers} workers, grouped)", group_analyses(study.analyses, workers))):
        cpu = _cpu_time()
        start = time.perf_counter()
        futures = submitter.submit(groups)
        wait(futures)
        out = [r for group in client.gather(futures) for r in group]     # the results come back here
        wall = time.perf_counter() - start
        here = (_cpu_time() - cpu) / len(out)
        done = sum(s["model_builds"] for s in client.run(cache_stats).values())
        cases.append(_summary(name, out, wall, workers,
                              {"cluster_start_s": started, "warm_up_s": warm_total, "client_scheduler_cpu_s": here,
                               "model_builds": done - builds, "tasks": len(groups)}))
        builds = done
        del futures
    start = time.perf_counter()
    result = run_study(study, folder / "study", scheduler=cluster.scheduler_address, progress=False, figures=False)
    whole = time.perf_counter() - start
    _close(client, cluster)
    solve = [r["solve_time"] for r in json_results(folder / "study" / "results")]
    end_to_end = {"case": f"run_study on the cluster ({workers} workers)", "analyses": len(solve),
                  "wall_s": whole, "per_second": len(solve) / whole, "counts": result.counts,
                  "mean_solve_s": statistics.fmean(solve)}
    return cases, end_to_end


def ceiling(workers: int, rounds: int = 3) -> dict:
    """The machine's ceiling: ``workers`` times the seconds of :data:`LOOP` in one process alone over
    those of the slowest of ``workers`` processes started together (``workers`` on idle cores),
    the median of ``rounds`` pairs run one after the other (a virtual machine's speed drifts)."""
    def run(n):
        procs = [subprocess.Popen([sys.executable, "-c", f"import time\nt = time.perf_counter()\n{LOOP}\n"
                                   "print(time.perf_counter() - t)"], stdout=subprocess.PIPE, text=True)
                 for _ in range(n)]
        return [float(p.communicate()[0]) for p in procs]

    pairs = [(run(1)[0], run(workers)) for _ in range(rounds)]
    speedups = [workers * alone / max(together) for alone, together in pairs]
    return {"pairs_s": pairs, "speedups": speedups, "speedup": statistics.median(speedups)}


def _cpu_time() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def json_results(folder: Path):
    return [json.loads(p.read_text()) for p in folder.glob("*.json")]


def _summary(case, out, wall, workers, extra) -> dict:
    solve = [r["solve_time"] for r in out]
    task = [r["task_time"] for r in out]
    n = len(out)
    mean_solve = statistics.fmean(solve)
    quantities = statistics.fmean(r.get("quantities_time", 0.0) for r in out)
    per_analysis = wall * workers / n
    return {"case": case, "analyses": n, "workers": workers, "wall_s": wall, "per_second": n / wall,
            "mean_solve_s": mean_solve, "mean_task_s": statistics.fmean(task),
            "mean_solve_cpu_s": statistics.fmean(r["solve_cpu_time"] for r in out),
            "wall_per_analysis_x_workers_s": per_analysis,
            "overhead_in_task": (statistics.fmean(task) - mean_solve) / mean_solve,
            "overhead_end_to_end": (per_analysis - mean_solve) / mean_solve,
            "mean_quantities_s": quantities,
            "overhead_end_to_end_besides_quantities": (per_analysis - mean_solve - quantities) / mean_solve,
            "statuses": sorted({r["status"] for r in out}), **extra}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--study", type=Path, default=ROOT / "examples" / "ida.toml")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out", type=Path, default=None, help="JSON file (default: in a temporary folder)")
    parser.add_argument("--analyses", type=int, default=None,
                        help="only the first K analyses of the study (a smoke test: 2); default all")
    parser.add_argument("--ceiling-rounds", type=int, default=3, help="pairs of runs of the machine's ceiling")
    args = parser.parse_args(argv)
    if args.analyses is not None and args.analyses < 1:
        parser.error(f"--analyses {args.analyses}: give at least 1")

    from dataclasses import replace

    from unilateral.batch import load_study
    from unilateral.batch.inputs import study_inputs

    study = load_study(args.study)
    if args.analyses is not None:
        study = replace(study, analyses=study.analyses[:args.analyses])
    inputs = study_inputs(study.analyses)
    folder = Path(tempfile.mkdtemp(prefix="unilateral-batch-bench-"))
    load_before = _loadavg()
    rows = [in_process(study, inputs, cached=False), in_process(study, inputs, cached=True)]
    tasks, whole = dask(study, inputs, folder, args.workers)
    rows += tasks
    load_after = _loadavg()
    machine = ceiling(args.workers, max(1, args.ceiling_rounds))
    plain = rows[0]["per_second"]
    efficiency = rows[3]["per_second"] / (args.workers * rows[1]["per_second"])
    report = {"study": str(args.study), "analyses": len(study.analyses), "cpu_count": os.cpu_count(),
              "machine": platform.platform(), "python": platform.python_version(),
              "loadavg_before": load_before, "loadavg_after": load_after,
              "cases": [dict(r, ratio_to_plain_loop=r["per_second"] / plain) for r in rows],
              "run_study": dict(whole, ratio_to_plain_loop=whole["per_second"] / plain),
              "parallel_efficiency": efficiency, "ceiling": machine,
              "grouped_over_serial": rows[3]["per_second"] / rows[1]["per_second"],
              "one_per_task_over_serial": rows[2]["per_second"] / rows[1]["per_second"]}
    _print(report, args.workers)
    out = args.out or folder / "batch_throughput.json"
    out.write_text(json.dumps(report, indent=2) + "\n")
    print(f"written: {out}")


def _loadavg() -> str:
    """``/proc/loadavg`` (the 1, 5 and 15 minute load averages, ...), or ``os.getloadavg()``."""
    try:
        return Path("/proc/loadavg").read_text().strip()
    except OSError:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())


def _print(report: dict, workers: int) -> None:
    """The table of the cases, the end-to-end run and the machine's ceiling."""
    rows, whole, machine = report["cases"], report["run_study"], report["ceiling"]
    print(f"{'case':30s} {'an/s':>7s} {'x plain':>8s} {'wall s':>7s} {'builds':>7s} {'solve ms':>9s} "
          f"{'peaks ms':>9s} {'task ms':>8s} {'overhead/solve (task)':>22s} {'(end to end)':>13s} "
          f"{'(besides peaks)':>16s}")
    for r in rows:
        print(f"{r['case']:30s} {r['per_second']:7.2f} {r['ratio_to_plain_loop']:8.2f} {r['wall_s']:7.2f} "
              f"{r['model_builds']:7d} {1e3 * r['mean_solve_s']:9.1f} {1e3 * r['mean_quantities_s']:9.2f} "
              f"{1e3 * r['mean_task_s']:8.1f} {100 * r['overhead_in_task']:21.1f}% "
              f"{100 * r['overhead_end_to_end']:12.1f}% {100 * r['overhead_end_to_end_besides_quantities']:15.1f}%")
    print(f"{whole['case']:30s} {whole['per_second']:7.2f} {whole['ratio_to_plain_loop']:8.2f} "
          f"{whole['wall_s']:7.2f}         {1e3 * whole['mean_solve_s']:9.1f}   (inputs read and scattered, results written, table)")
    print(f"{workers} workers over one process (serial): grouped {report['grouped_over_serial']:.2f}x, one analysis per "
          f"task {report['one_per_task_over_serial']:.2f}x (target 1.8x on a quiet machine)")
    print(f"parallel efficiency on {workers} workers (dask grouped over {workers} x serial): "
          f"{100 * report['parallel_efficiency']:.0f}%   (warm-up: serial {rows[1]['warm_up_s']:.1f} s, cluster start "
          f"{rows[3]['cluster_start_s']:.1f} s + warm-up {rows[3]['warm_up_s']:.1f} s)")
    print(f"load average (/proc/loadavg) before: {report['loadavg_before']}; after: {report['loadavg_after']}")
    print(f"this process (scheduler, client) during the tasks: {1e3 * rows[3]['client_scheduler_cpu_s']:.1f} ms CPU "
          f"per analysis; machine ceiling: {workers} CPU-bound processes together run "
          f"{machine['speedup']:.2f}x one alone (median of {', '.join(f'{x:.2f}' for x in machine['speedups'])})")


if __name__ == "__main__":
    main()
