"""Run a study on Dask: every analysis a task, results written one by one, resumable.

:func:`run_study` reads the study (or takes a :class:`~unilateral.batch.study.Study`), skips the
analyses whose result is already in ``<out>/results/`` (a JSON file named by the hash of
everything the result depends on), runs the others as Dask tasks — on a
:class:`~distributed.LocalCluster` with one single-threaded worker process per core, on an
existing cluster (``scheduler``), or in this process one after the other (``synchronous``) —
and writes the study table and its figures. Interrupting it (Ctrl-C) cancels the tasks, closes
the cluster and keeps every result already written; running it again continues.
"""

from __future__ import annotations

import logging
import math
import os
import signal
import threading
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path

from ..io.atomic import write_json_atomic
from .progress import FAILED, Progress
from .study import Study, load_study, package_version
from .table import read_result, write_table
from .worker import result_path, run_analysis, write_result

ALLOWED_FAILURES = 3
"""Times a task may be on a worker that dies before it is given up (``KilledWorker``)."""
WORKERS_PER_CORE = 4
"""Most worker processes of a local cluster per core of the machine."""
CONNECT_TIMEOUT = "10s"
"""How long to try to reach a scheduler given by its address."""


class ClusterError(ValueError):
    """A scheduler that cannot be reached, or a number of workers that cannot be started."""


def check_workers(workers) -> None:
    """Refuse more local workers than ``WORKERS_PER_CORE`` times the machine's cores.

    Raises
    ------
    ClusterError
        Naming the value and the limit.
    """
    cores = os.cpu_count() or 1
    if workers is not None and workers > WORKERS_PER_CORE * cores:
        raise ClusterError(f"workers={workers}: more than {WORKERS_PER_CORE} per core of this machine "
                           f"({cores} cores: at most {WORKERS_PER_CORE * cores}); a worker runs one analysis "
                           "at a time, so more workers than cores do not run faster")


class StudyInterrupted(KeyboardInterrupt):
    """A study stopped by Ctrl-C; ``result`` holds what was done (a later run continues)."""

    def __init__(self, result):
        super().__init__("study interrupted")
        self.result = result


@dataclass
class StudyResult:
    """What :func:`run_study` did."""

    study: Study
    out: Path
    table: object                     # xarray.Dataset
    counts: dict                      # status -> analyses
    ran: int                          # analyses run now
    skipped: int                      # done by an earlier run
    wall_time: float
    interrupted: bool = False
    figures: list = field(default_factory=list)
    fragility: list = field(default_factory=list)

    def summary(self) -> str:
        counts = ", ".join(f"{n} {s}" for s, n in self.counts.items() if n)
        state = "interrupted" if self.interrupted else "done"
        return (f"{self.study.title or self.study.source.name}: {len(self.study.analyses)} analyses ({counts}); "
                f"{self.ran} run now, {self.skipped} from an earlier run; {state} in {self.wall_time:.1f} s; "
                f"table {self.out / 'study.nc'}")


def run_study(study, out, *, scheduler=None, workers=None, synchronous=False, progress=True,
              retry_failed=False, figures=True, fsync=False) -> StudyResult:
    """Run every analysis of a study that is not done yet; write the table and the figures.

    Parameters
    ----------
    study : path, or Study
        The study file (TOML, see ``docs/study-file.md``) or a study read by
        :func:`~unilateral.batch.load_study`.
    out : path
        Output folder: ``results/<key>.json`` (one per analysis), ``study.json`` (the list of
        analyses), ``study.nc`` and ``study.csv`` (the table), ``ida.png``, ``fragility.png``,
        ``fragility.json``.
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``); its workers must see the
        files (model files, records and ``out``) at the same paths.
    workers : int, optional
        Worker processes of the local cluster (default: one per core).
    synchronous : bool
        Run the analyses one after the other in this process, without Dask (for debugging).
    progress : bool
        Draw a progress bar on stderr.
    retry_failed : bool
        Run again the analyses whose result is a failure (by default a failure is a result).
    figures : bool
        Draw the figures.
    fsync : bool
        Flush every result to disk (survives a crash of the machine; about 8 ms per analysis).
        Without it a result is still written atomically, and one that a crash of the machine left
        truncated is run again by the next run.

    Returns
    -------
    StudyResult

    Raises
    ------
    StudyInterrupted
        On Ctrl-C, after the tasks are cancelled, the cluster closed and the table written.
    ClusterError
        Too many ``workers``, or a ``scheduler`` that cannot be reached.
    """
    start = time.perf_counter()
    check_workers(workers)
    if not isinstance(study, Study):
        study = load_study(study)
    out = Path(out)
    # a scheduler given by its address is reached first: one that cannot be leaves no folder behind
    client = connect(scheduler) if scheduler and not synchronous else None
    results = out / "results"
    results.mkdir(parents=True, exist_ok=True)
    _remove_stale_temporaries(results)
    run_id = uuid.uuid4().hex[:12]
    _write_manifest(study, out)

    todo, seen, earlier, earlier_failed = [], set(), 0, 0
    for analysis in study.analyses:
        if analysis.key in seen:
            continue
        seen.add(analysis.key)
        result = read_result(results, analysis.key)
        if result is not None and not (retry_failed and result["status"] in FAILED):
            earlier += 1
            earlier_failed += result["status"] in FAILED
            continue
        if result is not None:
            result_path(results, analysis.key).unlink(missing_ok=True)
        todo.append(analysis)
    bar = Progress(len(seen), earlier, earlier_failed, enabled=progress)
    ran = 0
    interrupted = False
    try:
        pending = []
        for analysis in todo:
            if analysis.error is not None:             # e.g. an unreadable record: fails without running
                result = _failure(analysis, "error", analysis.error, run_id)
                write_result(result_path(results, analysis.key), result, fsync=fsync)
                bar.update(result)
                ran += 1
            else:
                pending.append(analysis)
        if synchronous or not pending:
            for analysis in pending:
                bar.update(run_analysis(dict(analysis.payload, fsync=fsync), str(results), run_id))
                ran += 1
        else:
            ran += _run_dask(pending, results, run_id, (client, workers), bar, fsync)
            client = None                               # closed by _run_dask
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()
        if client is not None:
            _close(client, None)
    table = write_table(study, results, out)
    counts = {s: int((table["status"].values == s).sum()) for s in ("ok", "failed", "error", "timeout", "pending")}
    outcome = StudyResult(study=study, out=out, table=table, counts=counts, ran=ran, skipped=earlier,
                          wall_time=time.perf_counter() - start, interrupted=interrupted)
    if interrupted:
        raise StudyInterrupted(outcome)
    if figures:
        outcome.figures, outcome.fragility = _figures(study, table, out)
    return outcome


def _failure(analysis, status: str, message: str, run_id: str) -> dict:
    return {"key": analysis.key, "status": status, "message": message, "values": {}, "notes": [], "stats": {},
            "solve_time": math.nan, "task_time": math.nan, "run_id": run_id, "pid": os.getpid(), "worker": ""}


def _remove_stale_temporaries(results: Path) -> None:
    """Temporary files of writes that were killed half-way (an atomic write leaves nothing else)."""
    for path in results.glob(".*.tmp*"):
        path.unlink(missing_ok=True)


def _write_manifest(study: Study, out: Path) -> None:
    write_json_atomic(out / "study.json", {
        "title": study.title, "study_file": str(study.source), "unilateral_version": package_version(),
        "intensity": study.intensity_label, "quantities": study.quantity_columns,
        "analyses": [a.inputs() for a in study.analyses],
    })


# ---------------------------------------------------------------------- Dask
def start_cluster(workers=None, scheduler=None):
    """``(client, cluster)``: a client of ``scheduler``, or of a new LocalCluster (cluster None otherwise)."""
    import dask
    from distributed import Client, LocalCluster

    if scheduler:
        return connect(scheduler), None
    check_workers(workers)
    n = int(workers or os.cpu_count() or 1)
    # Ctrl-C on a terminal reaches the whole process group: the workers leave it to this process
    # (which cancels the tasks and closes them) instead of dying with a traceback each. They are
    # spawned with SIGINT ignored (inherited), and workers started later (restarts) by the plugin.
    previous = _ignore_interrupts()
    try:
        # Dask sets MALLOC_TRIM_THRESHOLD_ in its workers, which also switches off glibc's dynamic
        # mmap threshold: every array over 128 KiB is then mapped and unmapped anew, and a worker
        # spent half its CPU time in page faults (1.2 million per 50 analyses of the IDA example,
        # against 557 in process). The analyses allocate and free many such arrays: leave malloc alone.
        with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES,
                              "distributed.admin.tick.limit": "10s",
                              "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                   silence_logs=logging.ERROR)
            client = Client(cluster)
    finally:
        if previous is not None:
            signal.signal(signal.SIGINT, previous)
    from .plugins import IgnoreInterrupts

    register = getattr(client, "register_plugin", None) or client.register_worker_plugin
    register(IgnoreInterrupts(), name=IgnoreInterrupts.name)
    return client, cluster


def connect(scheduler: str):
    """A client of the running scheduler at the address ``scheduler``.

    Raises
    ------
    ClusterError
        An address that is not valid, or a scheduler not reached within ``CONNECT_TIMEOUT``.
    """
    from distributed import Client
    from distributed.comm import registry

    scheme = scheduler.split("://", 1)[0] if "://" in scheduler else "tcp"
    if scheme not in registry.backends:
        raise ClusterError(f"scheduler={scheduler!r}: unknown address scheme {scheme!r} (valid: "
                           f"{', '.join(sorted(registry.backends))}, e.g. tcp://host:8786)")
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT)
    except (OSError, ValueError, TimeoutError) as exc:
        raise ClusterError(f"scheduler={scheduler!r}: cannot connect to a Dask scheduler there ({exc}); "
                           "start one (dask scheduler) or leave the scheduler out for a local cluster") from None


def _ignore_interrupts():
    """Ignore SIGINT in this process (main thread only); return the previous handler, or None."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGINT, signal.SIG_IGN)


def _run_dask(todo, results: Path, run_id: str, cluster_spec, bar: Progress, fsync=False) -> int:
    """Run ``todo`` on Dask: ``cluster_spec = (client, workers)``, a client of a scheduler already
    reached, or None and the workers of a new LocalCluster."""
    from distributed import as_completed

    client, workers = cluster_spec
    cluster = None
    if client is None:
        client, cluster = start_cluster(workers)
    futures = {}
    ran = 0
    try:
        submitted = client.map(run_analysis, [dict(a.payload, fsync=fsync) for a in todo],
                               [str(results)] * len(todo), [run_id] * len(todo),
                               key=[f"unilateral-analysis-{a.key}" for a in todo], pure=False, retries=0)
        futures = dict(zip(submitted, todo))
        for future in as_completed(list(futures)):
            analysis = futures.pop(future)
            if future.status == "finished":
                # The task wrote its result: read it here rather than fetch it from the worker (a
                # round trip per analysis, and CPU that the workers share on one machine). Fetched
                # only if this process cannot read it, or for a timeout (whether to restart the worker).
                result = read_result(results, analysis.key)
                if result is None or result["status"] == "timeout":
                    result = future.result()
            else:
                try:
                    exc = future.exception()
                    message = f"{type(exc).__name__}: {exc}"
                except BaseException as err:           # noqa: BLE001 - e.g. CancelledError
                    message = f"{type(err).__name__}: {err}"
                if "KilledWorker" in message:
                    message = (f"the workers running it died {ALLOWED_FAILURES} times ({message}); "
                               "too much memory, or a crash of compiled code?")
                result = _failure(analysis, "error", message, run_id)
                write_result(result_path(results, analysis.key), result, fsync=fsync)
            if result.pop("restart_worker", False) and result.get("worker"):
                try:                                    # stop the computation left running
                    client.restart_workers([result["worker"]], timeout=60)
                except Exception:                       # noqa: BLE001 - best effort
                    pass
            future.release()
            bar.update(result)
            ran += 1
    except KeyboardInterrupt:
        try:
            client.cancel(list(futures), force=True)
        except Exception:                               # noqa: BLE001 - the cluster is closed next anyway
            pass
        raise
    finally:
        _close(client, cluster)
    return ran


def _close(client, cluster) -> None:
    try:
        client.close(timeout=10)
    except Exception:                                   # noqa: BLE001
        pass
    if cluster is not None:
        try:
            cluster.close(timeout=20)
        except Exception:                               # noqa: BLE001
            pass


# ---------------------------------------------------------------------- figures
def _figures(study: Study, table, out: Path):
    from .figures import fragility_figure, ida_figure

    doc = study.document
    written, fits = [], []
    formats, dpi = doc.figures.formats, doc.figures.dpi
    ok = table["status"].values == "ok"
    if not ok.any():
        return written, fits
    if doc.records is not None and doc.scaling is not None:
        quantity = doc.figures.ida or study.quantity_columns[0]
        written += ida_figure(table, quantity, out / "ida.png", formats=formats, dpi=dpi, title=doc.title)
    if doc.limit_states and doc.scaling is not None:
        files, fits = fragility_figure(table, doc.limit_states, out / "fragility.png", formats=formats, dpi=dpi)
        written += files
        write_json_atomic(out / "fragility.json", [{k: v for k, v in f.items() if k != "fit"} for f in fits])
    return written, fits
