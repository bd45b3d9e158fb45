"""Throughput of studies: analyses per second of the IDA example, in process vs on Dask workers.

    python benchmarks/batch_throughput.py [--workers 2] [--out results.json] [--study examples/ida.toml]

Measures, for the 100 analyses of ``examples/ida.toml`` (the rocking tower under 10 records at
10 levels of Sa(T1)):

* ``serial``: every analysis in this process, one after the other (``run_analysis``, as
  ``--synchronous`` does), after one warm-up analysis (the first solve in a process loads the
  compiled numba code from its disk cache, about 1 s, which is reported on its own);
* ``dask``: the same analyses as tasks on a LocalCluster of ``--workers`` single-threaded worker
  processes, after a warm-up task on every worker (cluster start and warm-up reported on their
  own); and the whole ``run_study`` (table and figures included) on the same cluster.

The overhead per analysis is the wall time per analysis (times the workers) less the time spent
in ``unilateral.solve``, relative to the latter; it covers the task round trip, building the load
(models and records are cached per worker), collecting the peaks and writing the result
atomically (with fsync). The parallel efficiency is ``throughput(dask) / (workers * throughput(serial))``.
Both depend on the load of the machine (``os.getloadavg()`` is reported). Results go to a JSON file
(``--out``; default: a temporary folder, never the repository).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import statistics
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


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
    from distributed import as_completed

    from unilateral.batch import run_study
    from unilateral.batch.runner import _close, start_cluster
    from unilateral.batch.worker import run_analysis, warm_up

    t0 = time.perf_counter()
    client, cluster = start_cluster(workers)
    started = time.perf_counter() - t0
    t0 = time.perf_counter()
    client.run(warm_up)
    (folder / "warm").mkdir()
    for address in client.scheduler_info()["workers"]:
        client.submit(run_analysis, study.analyses[0].payload, str(folder / "warm"), "", workers=[address],
                      pure=False).result()
    warm_total = time.perf_counter() - t0
    results = folder / "dask"
    results.mkdir()
    start = time.perf_counter()
    futures = [client.submit(run_analysis, a.payload, str(results), "dask", pure=False) for a in study.analyses]
    out = [f.result() for f in as_completed(futures)]
    wall = time.perf_counter() - start
    tasks = _summary(f"dask ({workers} workers)", out, wall, workers,
                     {"cluster_start_s": started, "warm_up_s": warm_total})
    start = time.perf_counter()
    result = run_study(study, folder / "study", scheduler=cluster.scheduler_address, progress=False)
    whole = time.perf_counter() - start
    _close(client, cluster)
    solve = [r["solve_time"] for r in json_results(folder / "study" / "results")]
    end_to_end = {"case": f"run_study on the cluster ({workers} workers)", "analyses": len(solve),
                  "wall_s": whole, "per_second": len(solve) / whole, "counts": result.counts,
                  "mean_solve_s": statistics.fmean(solve)}
    return tasks, end_to_end


def json_results(folder: Path):
    return [json.loads(p.read_text()) for p in folder.glob("*.json")]


def _summary(case, out, wall, workers, extra) -> dict:
    solve = [r["solve_time"] for r in out]
    task = [r["task_time"] for r in out]
    n = len(out)
    mean_solve = statistics.fmean(solve)
    per_analysis = wall * workers / n
    return {"case": case, "analyses": n, "workers": workers, "wall_s": wall, "per_second": n / wall,
            "mean_solve_s": mean_solve, "mean_task_s": statistics.fmean(task),
            "mean_solve_cpu_s": statistics.fmean(r["solve_cpu_time"] for r in out),
            "wall_per_analysis_x_workers_s": per_analysis,
            "overhead_in_task": (statistics.fmean(task) - mean_solve) / mean_solve,
            "overhead_end_to_end": (per_analysis - mean_solve) / mean_solve,
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
    efficiency = rows[1]["per_second"] / (args.workers * rows[0]["per_second"])
    report = {"study": str(args.study), "analyses": len(study.analyses), "cpu_count": os.cpu_count(),
              "machine": platform.platform(), "python": platform.python_version(),
              "loadavg_before": load_before, "loadavg_after": os.getloadavg(),
              "cases": rows, "run_study": whole, "parallel_efficiency": efficiency}
    print(f"{'case':32s} {'an/s':>7s} {'wall s':>7s} {'solve ms':>9s} {'(cpu ms)':>9s} {'task ms':>8s} "
          f"{'overhead/solve (task)':>22s} {'(end to end)':>13s}")
    for r in rows:
        print(f"{r['case']:32s} {r['per_second']:7.2f} {r['wall_s']:7.2f} {1e3 * r['mean_solve_s']:9.1f} "
              f"{1e3 * r['mean_solve_cpu_s']:9.1f} {1e3 * r['mean_task_s']:8.1f} {100 * r['overhead_in_task']:21.1f}% "
              f"{100 * r['overhead_end_to_end']:12.1f}%")
    print(f"{whole['case']:32s} {whole['per_second']:7.2f} {whole['wall_s']:7.2f} "
          f"{1e3 * whole['mean_solve_s']:9.1f}   (table, figures included)")
    print(f"parallel efficiency on {args.workers} workers: {100 * efficiency:.0f}%   "
          f"(warm-up: serial {rows[0]['warm_up_s']:.1f} s, cluster start {rows[1]['cluster_start_s']:.1f} s "
          f"+ warm-up {rows[1]['warm_up_s']:.1f} s; load average {load_before[0]:.2f} -> {os.getloadavg()[0]:.2f})")
    out = args.out or folder / "batch_throughput.json"
    out.write_text(json.dumps(report, indent=2) + "\n")
    print(f"written: {out}")


if __name__ == "__main__":
    main()
