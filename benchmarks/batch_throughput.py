"""Throughput of studies: analyses per second of the IDA example, in process vs on Dask workers.

    python benchmarks/batch_throughput.py [--workers 2] [--out results.json] [--study examples/ida.toml]

Measures, for the 100 analyses of ``examples/ida.toml`` (the rocking tower under 10 records at
10 levels of Sa(T1)):

* ``serial``: every analysis in this process, one after the other (``run_analysis``, as
  ``--synchronous`` does), after one warm-up analysis (the first solve in a process loads the
  compiled numba code from its disk cache, about 1 s, which is reported on its own);
* ``dask``: the same analyses as tasks on a LocalCluster of ``--workers`` single-threaded worker
  processes, after a warm-up task on every worker (cluster start and warm-up reported on their
  own), their results read from their files as ``run_study`` does; and the whole ``run_study``
  (table and figures included) on the same cluster.

The overhead per analysis is the wall time per analysis (times the workers) less the time spent
in ``unilateral.solve``, relative to the latter; it covers the task round trip, building the load
(models and records are cached per worker), collecting the peaks and writing the result
atomically. Collecting the peak quantities (``peaks ms``: for the IDA example the base shear and
the energy balance over every step, which the study asks for) is part of it, and shown apart: the
last column is the overhead besides it. The parallel efficiency is ``throughput(dask) / (workers * throughput(serial))``; the
machine's own ceiling is measured too: ``--workers`` CPU-bound Python processes started together
against one alone (virtual CPUs that share a core give less than one each). The CPU time of this
process during the tasks (scheduler and client, per analysis) is reported: on a machine with as
many cores as workers it is taken from them.

BLAS runs single-threaded in this process (``OPENBLAS_NUM_THREADS=1`` and the like, unless set), as
Dask's nanny sets it in the workers: both cases do the same work, and a multi-threaded BLAS call
waiting for a busy core does not stall the serial case. All the numbers depend on the load of the
machine (``os.getloadavg()`` is reported). Results go to a JSON file (``--out``; default: a temporary
folder, never the repository).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import shutil
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


def serial(study, folder: Path) -> dict:
    from unilateral.batch.worker import run_analysis, warm_up

    results = folder / "serial"
    results.mkdir(parents=True)
    t0 = time.perf_counter()
    warm = warm_up()
    (results / "warm").mkdir()
    run_analysis(study.analyses[0].payload, str(results / "warm"), "")       # builds the model: cached
    warm_total = time.perf_counter() - t0
    start = time.perf_counter()
    out = [run_analysis(a.payload, str(results), "serial") for a in study.analyses]
    wall = time.perf_counter() - start
    return _summary("serial (in process)", out, wall, 1, {"warm_up_s": warm_total, "numba_load_s": warm})


def dask(study, folder: Path, workers: int) -> tuple[dict, dict]:
    from distributed import wait

    from unilateral.batch import run_study
    from unilateral.batch.runner import _close, start_cluster
    from unilateral.batch.worker import run_analysis, warm_up

    t0 = time.perf_counter()
    client, cluster = start_cluster(workers)
    started = time.perf_counter() - t0
    t0 = time.perf_counter()
    client.run(warm_up)
    for k, address in enumerate(client.scheduler_info()["workers"]):     # a folder each: none finds the
        warm = folder / "warm" / str(k)                                   # other's result and skips the build
        warm.mkdir(parents=True)
        client.submit(run_analysis, study.analyses[0].payload, str(warm), "", workers=[address], pure=False).result()
    warm_total = time.perf_counter() - t0
    results = folder / "dask"
    results.mkdir()
    cpu = _cpu_time()
    start = time.perf_counter()
    futures = client.map(run_analysis, [a.payload for a in study.analyses], [str(results)] * len(study.analyses),
                         ["dask"] * len(study.analyses), pure=False)
    wait(futures)
    wall = time.perf_counter() - start
    here = (_cpu_time() - cpu) / len(futures)
    out = json_results(results)                        # as run_study: read, not fetched from the workers
    tasks = _summary(f"dask ({workers} workers)", out, wall, workers,
                     {"cluster_start_s": started, "warm_up_s": warm_total, "client_scheduler_cpu_s": here})
    start = time.perf_counter()
    result = run_study(study, folder / "study", scheduler=cluster.scheduler_address, progress=False)
    whole = time.perf_counter() - start
    _close(client, cluster)
    solve = [r["solve_time"] for r in json_results(folder / "study" / "results")]
    end_to_end = {"case": f"run_study on the cluster ({workers} workers)", "analyses": len(solve),
                  "wall_s": whole, "per_second": len(solve) / whole, "counts": result.counts,
                  "mean_solve_s": statistics.fmean(solve)}
    return tasks, end_to_end


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
    args = parser.parse_args(argv)

    from unilateral.batch import load_study

    study = load_study(args.study)
    folder = Path(tempfile.mkdtemp(prefix="unilateral-batch-bench-"))
    load_before = os.getloadavg()
    try:
        rows = [serial(study, folder)]
        tasks, whole = dask(study, folder, args.workers)
        rows.append(tasks)
    finally:
        shutil.rmtree(folder / "serial", ignore_errors=True)
    machine = ceiling(args.workers)
    efficiency = rows[1]["per_second"] / (args.workers * rows[0]["per_second"])
    report = {"study": str(args.study), "analyses": len(study.analyses), "cpu_count": os.cpu_count(),
              "machine": platform.platform(), "python": platform.python_version(),
              "loadavg_before": load_before, "loadavg_after": os.getloadavg(),
              "cases": rows, "run_study": whole, "parallel_efficiency": efficiency, "ceiling": machine}
    print(f"{'case':32s} {'an/s':>7s} {'wall s':>7s} {'solve ms':>9s} {'(cpu ms)':>9s} {'peaks ms':>9s} "
          f"{'task ms':>8s} {'overhead/solve (task)':>22s} {'(end to end)':>13s} {'(besides peaks)':>16s}")
    for r in rows:
        print(f"{r['case']:32s} {r['per_second']:7.2f} {r['wall_s']:7.2f} {1e3 * r['mean_solve_s']:9.1f} "
              f"{1e3 * r['mean_solve_cpu_s']:9.1f} {1e3 * r['mean_quantities_s']:9.2f} {1e3 * r['mean_task_s']:8.1f} "
              f"{100 * r['overhead_in_task']:21.1f}% {100 * r['overhead_end_to_end']:12.1f}% "
              f"{100 * r['overhead_end_to_end_besides_quantities']:15.1f}%")
    print(f"{whole['case']:32s} {whole['per_second']:7.2f} {whole['wall_s']:7.2f} "
          f"{1e3 * whole['mean_solve_s']:9.1f}   (table, figures included)")
    print(f"parallel efficiency on {args.workers} workers: {100 * efficiency:.0f}%   "
          f"(warm-up: serial {rows[0]['warm_up_s']:.1f} s, cluster start {rows[1]['cluster_start_s']:.1f} s "
          f"+ warm-up {rows[1]['warm_up_s']:.1f} s; load average {load_before[0]:.2f} -> {os.getloadavg()[0]:.2f})")
    print(f"this process (scheduler, client) during the tasks: {1e3 * rows[1]['client_scheduler_cpu_s']:.1f} ms CPU "
          f"per analysis; machine ceiling: {args.workers} CPU-bound processes together run "
          f"{machine['speedup']:.2f}x one alone (median of {', '.join(f'{x:.2f}' for x in machine['speedups'])})")
    out = args.out or folder / "batch_throughput.json"
    out.write_text(json.dumps(report, indent=2) + "\n")
    print(f"written: {out}")


if __name__ == "__main__":
    main()
