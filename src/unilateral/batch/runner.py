"""Run a study on Dask: the analyses grouped into tasks, results written one by one, resumable.

:func:`run_study` reads the study (or takes a :class:`~unilateral.batch.study.Study`), skips the
analyses whose result is already in ``<out>/results/`` (a JSON file named by the hash of
everything the result depends on), reads the model files and records of the others once
(:mod:`unilateral.batch.inputs`), runs them as Dask tasks — on a
:class:`~distributed.LocalCluster` with one single-threaded worker process per core, on an
existing cluster (``scheduler``), or in this process one after the other (``synchronous``) —
and writes the study table and its figures. On Dask the analyses are grouped into a few tasks per
worker of about equal cost (:func:`group_analyses`: a task's round trip costs more than a short
analysis); a failure in a group is the result of its own analysis. The workers read and write no file: the inputs are
scattered to them, each task returns its result, and this process writes it, atomically, as it
comes back (so it is the only writer of ``<out>``). Interrupting it (Ctrl-C) cancels the tasks,
closes the cluster and keeps every result already written; running it again continues.
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
from .inputs import StudyInputs, study_inputs
from .table import read_result, result_path, write_result, write_table
from .worker import run_analysis

ALLOWED_FAILURES = 3
"""Times a task may be on a worker that dies before it is given up (``KilledWorker``)."""
WORKERS_PER_CORE = 4
"""Most worker processes of a local cluster per core of the machine."""
CONNECT_TIMEOUT = "10s"
"""How long to try to reach a scheduler given by its address."""
LOST_WORKER_TIMEOUT = "365 days"
"""While a study runs, how long a Dask cluster object of this process (a LocalCluster) waits for a
worker that left to come back before it closes the worker's nanny (Dask's default, 15 s, closed the
nanny of a worker restarted after a timeout whenever the restart outlasted it, on a loaded machine:
the cluster was left with no worker and the study waited for one forever). A restarted worker
always comes back: its nanny starts it again."""
TASKS_PER_WORKER = 4
"""Tasks per worker that the analyses are grouped into (:func:`group_analyses`): a task's round
trip costs 20-30 ms on Dask against 5-9 ms per analysis in one process, so analyses of 40 ms run
one per task made 2 workers slower than one process; a few tasks per worker still balance them."""
MAX_ANALYSES_PER_TASK = 25
"""Most analyses in one task: a task's results come back (and are written) when it ends."""
WORKER_WAIT = 600.0
"""Seconds the inputs wait for a worker to scatter them to (after a restart) before the study
stops with a :class:`ClusterError`: a hang guard, far beyond any restart."""


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
        Address of a running Dask scheduler (``tcp://host:8786``). Its workers need the package,
        not the study's files: the model files and records are sent to them through Dask, and
        the results come back to this process.
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

    todo, total, earlier, earlier_failed = _analyses_to_run(study, results, retry_failed)
    bar = Progress(total, earlier, earlier_failed, enabled=progress)
    done = _Recorder(results, bar, fsync)
    interrupted = _run_analyses(todo, run_id, done, synchronous=synchronous, cluster=(client, workers), bar=bar)
    table = write_table(study, results, out)
    counts = {s: int((table["status"].values == s).sum()) for s in ("ok", "failed", "error", "timeout", "pending")}
    outcome = StudyResult(study=study, out=out, table=table, counts=counts, ran=done.count, skipped=earlier,
                          wall_time=time.perf_counter() - start, interrupted=interrupted)
    if interrupted:
        raise StudyInterrupted(outcome)
    if figures:
        outcome.figures, outcome.fragility = _figures(study, table, out)
    return outcome


def _analyses_to_run(study, results: Path, retry_failed: bool) -> tuple[list, int, int, int]:
    """``(todo, total, earlier, earlier_failed)``: the analyses of ``study`` to run (each key once),
    the number of distinct analyses, and of those with a result in ``results`` from an earlier run,
    of which failed. With ``retry_failed`` a failed result is not kept: its file is removed and the
    analysis is run again."""
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
    return todo, len(seen), earlier, earlier_failed


def _run_analyses(todo, run_id, done, *, synchronous, cluster, bar) -> bool:
    """Run the analyses ``todo``, each result to ``done`` (a :class:`_Recorder`): in this process
    (``synchronous``, or nothing to send) or on Dask, ``cluster = (client, workers)`` (a connected
    client or None, and the local cluster's worker processes). The progress ``bar`` and the client
    are closed whatever happens; returns True if Ctrl-C interrupted the run."""
    client, workers = cluster
    interrupted = False
    try:
        pending, inputs = _runnable(todo, run_id, done)
        if synchronous or not pending:
            for analysis in pending:
                done(run_analysis(analysis.payload, *_inputs_of(analysis, inputs.variants, inputs.records), run_id))
        else:
            _run_dask(pending, inputs, run_id, (client, workers), done)
            client = None                               # closed by _run_dask
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()
        if client is not None:
            _close(client, None)
    return interrupted


def _failure(analysis, status: str, message: str, run_id: str) -> dict:
    return {"key": analysis.key, "status": status, "message": message, "values": {}, "notes": [], "stats": {},
            "solve_time": math.nan, "task_time": math.nan, "run_id": run_id, "pid": os.getpid(), "worker": ""}


class _Recorder:
    """Writes the results of a run (this process is their only writer) and counts them.

    Calling it with a result writes ``<results>/<key>.json`` atomically and updates the progress
    bar; it returns whether the result asks for its worker to be restarted (a timeout).
    """

    def __init__(self, results: Path, bar: Progress, fsync: bool):
        self.results, self.bar, self.fsync = results, bar, fsync
        self.count = 0

    def __call__(self, result: dict) -> bool:
        restart = bool(result.pop("restart_worker", False))
        write_result(result_path(self.results, result["key"]), result, fsync=self.fsync)
        self.bar.update(result)
        self.count += 1
        return restart


def _runnable(todo, run_id: str, done: _Recorder) -> tuple[list, StudyInputs]:
    """Read the inputs of ``todo`` (:func:`~unilateral.batch.inputs.study_inputs`) and record as
    errors the analyses that cannot run: ``Analysis.error`` (e.g. a record unreadable when the
    study was read), or an input that cannot be read now (e.g. a model file changed since).

    Returns
    -------
    (list of Analysis, StudyInputs)
        The analyses to run and their inputs.
    """
    for analysis in todo:
        if analysis.error is not None:
            done(_failure(analysis, "error", analysis.error, run_id))
    inputs = study_inputs([a for a in todo if a.error is None])
    pending = []
    for analysis in todo:
        if analysis.error is None and analysis.key in inputs.errors:
            done(_failure(analysis, "error", inputs.errors[analysis.key], run_id))
        elif analysis.error is None:
            pending.append(analysis)
    return pending, inputs


def _inputs_of(analysis, variants: dict, records: dict) -> tuple:
    """``(variant source, record)`` of ``analysis`` from the tables ``variants`` and ``records``
    (values or their Dask futures); the record is None for a study without records."""
    record = analysis.payload["record"]
    return variants[analysis.payload["variant"]], None if record is None else records[record]


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


def _run_dask(todo, inputs: StudyInputs, run_id: str, cluster_spec, done: _Recorder) -> None:
    """Run ``todo`` on Dask and record their results as they come back.

    ``cluster_spec = (client, workers)``: a client of a scheduler already reached, or None and the
    workers of a new LocalCluster. Each task returns its result to this process, which writes it.
    A worker restarted after a timeout gets the inputs again; a task cancelled because the inputs
    it needed were lost meanwhile (the restarted worker held their only copy) is submitted again,
    once per restart and up to ``ALLOWED_FAILURES`` times more (a cancellation by someone else).
    A worker that left is waited for (:data:`LOST_WORKER_TIMEOUT`, :data:`WORKER_WAIT`).
    """
    import dask

    with dask.config.set({"distributed.deploy.lost-worker-timeout": LOST_WORKER_TIMEOUT}):
        _run_on(todo, inputs, run_id, cluster_spec, done)


def _run_on(todo, inputs: StudyInputs, run_id: str, cluster_spec, done: _Recorder) -> None:
    """:func:`_run_dask` once the cluster's settings are set: the analyses grouped into tasks
    (:func:`group_analyses`), each task a list of analyses run by :func:`run_analyses`."""
    client, workers = cluster_spec
    cluster = None
    if client is None:
        client, cluster = start_cluster(workers)
    queue = None
    try:
        tasks = _Tasks(client, inputs, run_id)
        queue = _Queue(tasks, group_analyses(todo, _worker_count(client, workers)))
        for future, result in queue.results():
            group = queue.pop(future)
            if queue.cancelled(group, result):
                continue
            if not isinstance(result, list):           # the task raised: e.g. its workers died
                if len(group) > 1:                      # each alone, so that it is recorded for its own
                    queue.add(*([a] for a in group))
                    continue
                result = [_failure(group[0], "error", _task_error(result), run_id)]
            restart = [done(r) and r.get("worker") for r in result]
            if any(restart):
                _restart(client, result[-1]["worker"])
                tasks.ensure()                          # the worker may have held the only copies
                queue.restarts += 1
            if len(result) < len(group):                # the task stopped at a timeout: the rest again
                queue.add(group[len(result):])
    except KeyboardInterrupt:
        try:
            client.cancel(queue.pending() if queue is not None else [], force=True)
        except Exception:                               # noqa: BLE001 - the cluster is closed next anyway
            pass
        raise
    finally:
        _close(client, cluster)


class _Queue:
    """The tasks of a study in flight: each future's group of analyses, resubmissions after a
    cancellation (inputs lost with a restarted worker: once per restart, and up to
    ``ALLOWED_FAILURES`` times more)."""

    def __init__(self, tasks, groups):
        from distributed import as_completed

        self.tasks, self.futures, self.restarts, self.resubmitted = tasks, {}, 0, {}
        self.completed = as_completed([], with_results=True, raise_errors=False)
        self.add(*groups)

    def add(self, *groups) -> None:
        for group, future in zip(groups, self.tasks.submit(groups)):
            self.futures[future] = group
            self.completed.add(future)

    def results(self):
        return self.completed

    def pop(self, future) -> list:
        group = self.futures.pop(future)
        future.release()
        return group

    def pending(self) -> list:
        return list(self.futures)

    def cancelled(self, group, result) -> bool:
        """Submit ``group`` again if ``result`` is a cancellation it may be retried for; whether so."""
        from concurrent.futures import CancelledError

        key = group[0].key
        if not isinstance(result, CancelledError) or self.resubmitted.get(key, 0) >= ALLOWED_FAILURES + self.restarts:
            return False
        self.resubmitted[key] = self.resubmitted.get(key, 0) + 1
        self.tasks.ensure()
        self.add(group)
        return True


def _worker_count(client, workers) -> int:
    """Workers of the cluster (those of ``workers`` for a local one), at least 1."""
    if workers:
        return int(workers)
    try:
        return max(1, len(client.scheduler_info().get("workers", {})))
    except Exception:                                   # noqa: BLE001 - a guess is enough to group
        return max(1, os.cpu_count() or 1)


def analysis_cost(analysis) -> float:
    """The relative cost of an analysis: its steps (``t_end / dt``), 1 if they are unknown."""
    settings = analysis.payload.get("settings", {})
    try:
        steps = float(settings["t_end"]) / float(settings["dt"])
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return 1.0
    return steps if math.isfinite(steps) and steps > 0 else 1.0


def group_analyses(analyses, workers: int, *, per_worker: int | None = None, most: int | None = None) -> list:
    """The analyses in consecutive groups of about equal cost (:func:`analysis_cost`), one task each.

    ``per_worker * workers`` groups (:data:`TASKS_PER_WORKER`), more if a group would hold more than
    ``most`` analyses (:data:`MAX_ANALYSES_PER_TASK`), never more groups than analyses; each group
    takes the analyses in order (those of a model variant and record stay together: the worker's
    cached model serves them) until its share of the total cost is reached. ``most=1``: a task
    per analysis.
    """
    per_worker = TASKS_PER_WORKER if per_worker is None else per_worker
    most = MAX_ANALYSES_PER_TASK if most is None else most
    analyses = list(analyses)
    if not analyses:
        return []
    count = min(len(analyses), max(per_worker * max(1, workers), math.ceil(len(analyses) / max(1, most))))
    costs = [analysis_cost(a) for a in analyses]
    share, groups, current, filled = sum(costs) / count, [], [], 0.0
    for i, (analysis, cost) in enumerate(zip(analyses, costs)):
        current.append(analysis)
        filled += cost
        left = len(analyses) - i - 1
        groups_left = count - len(groups) - 1
        if groups_left and (filled >= share * (len(groups) + 1) or len(current) >= most or left == groups_left):
            groups.append(current)
            current = []
    if current:
        groups.append(current)
    return groups


def run_analyses(payloads, sources, records, run_id: str = "") -> list:
    """Run a group of analyses one after the other (:func:`~unilateral.batch.worker.run_analysis`
    each: a failure is the result of its own analysis, the others run); the results in order. A
    result that asks for its worker to be restarted (a timeout) ends the group there: the analyses
    after it are submitted again, to a worker without the stopped solve."""
    out = []
    for payload, source, record in zip(payloads, sources, records):
        out.append(run_analysis(payload, source, record, run_id))
        if out[-1].get("restart_worker"):
            break
    return out


class _Tasks:
    """Submits analyses as Dask tasks, their inputs scattered once to every worker.

    The model sources and the records are scattered with ``broadcast``: each worker runs analyses
    of any variant and record, and a copy survives the death of a worker. Their Dask keys name
    the run, the content and the time they were scattered (``unilateral-variant-<digest>-<run>-<n>``),
    so that inputs scattered again are never taken for lost ones, nor for another study's.

    Parameters
    ----------
    client : distributed.Client;  inputs : StudyInputs;  run_id : str
    """

    def __init__(self, client, inputs: StudyInputs, run_id: str):
        self.client, self.inputs, self.run_id = client, inputs, run_id
        self.variants, self.records, self.generation, self.submitted = {}, {}, 0, 0
        self.ensure()

    def scatter(self) -> None:
        """Send the inputs to every worker, as new keys."""
        tag = f"{self.run_id}-{self.generation}"
        variants = {index: f"unilateral-variant-{source['digest'][:24]}-{tag}"
                    for index, source in self.inputs.variants.items()}
        records = {digest: f"unilateral-record-{digest[:24]}-{tag}" for digest in self.inputs.records}
        data = {key: self.inputs.variants[index] for index, key in variants.items()}
        data.update({key: self.inputs.records[digest] for digest, key in records.items()})
        try:
            self.client.wait_for_workers(1, timeout=WORKER_WAIT)
        except TimeoutError:
            raise ClusterError(f"no worker joined the cluster within {WORKER_WAIT:g} s (after a restart, or at the "
                               "start): the study stops; run the same command again to continue") from None
        scattered = self.client.scatter(data, broadcast=True, hash=False)
        old = [*self.variants.values(), *self.records.values()]
        self.variants = {index: scattered[key] for index, key in variants.items()}
        self.records = {digest: scattered[key] for digest, key in records.items()}
        self.generation += 1
        for future in old:
            future.release()

    def ensure(self) -> None:
        """Scatter the inputs (again) until the scheduler knows a copy of each: the first time,
        and after a worker that held the only copy of one of them is gone."""
        while not self._held():
            self.scatter()

    def _held(self) -> bool:
        """Whether the inputs are scattered and the scheduler knows a copy of every one."""
        from concurrent.futures import CancelledError

        futures = [*self.variants.values(), *self.records.values()]
        if not futures or any(f.status != "finished" for f in futures):
            return False
        try:
            return all(self.client.who_has(futures).values())
        except CancelledError:                          # lost since the statuses were read
            return False

    def submit(self, groups) -> list:
        """The futures of ``groups`` (lists of analyses), a task of :func:`run_analyses` each, named
        by the first analysis, the group's size and a submission count (a cancelled task's key stays
        cancelled until the scheduler has forgotten it)."""
        futures = []
        for group in groups:
            sources, motions = zip(*(_inputs_of(a, self.variants, self.records) for a in group))
            self.submitted += 1
            futures.append(self.client.submit(
                run_analyses, [a.payload for a in group], list(sources), list(motions), self.run_id,
                key=f"unilateral-analyses-{group[0].key}-{len(group)}-{self.submitted}", pure=False, retries=0))
        return futures


def _task_error(exc) -> str:
    """The message of a task that raised ``exc`` instead of returning a result."""
    message = f"{type(exc).__name__}: {exc}"
    if "KilledWorker" in message:
        message = (f"the workers running it died {ALLOWED_FAILURES} times ({message}); "
                   "too much memory, or a crash of compiled code?")
    return message


def _restart(client, worker: str) -> None:
    """Restart ``worker`` to stop the computation a timed-out analysis left running (best effort)."""
    try:
        client.restart_workers([worker], timeout=60)
    except Exception:                                   # noqa: BLE001 - best effort
        pass


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
    from .collapse import collapse_limit_states
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
    limits = list(doc.limit_states) + collapse_limit_states(doc)       # with [collapse]: its fragility too
    if limits and doc.scaling is not None:
        files, fits = fragility_figure(table, limits, out / "fragility.png", formats=formats, dpi=dpi)
        written += files
        write_json_atomic(out / "fragility.json", [{k: v for k, v in f.items() if k != "fit"} for f in fits])
    return written, fits
