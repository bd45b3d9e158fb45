"""Studies on a Dask scheduler and two workers started by hand (``python -m dask scheduler`` and
``python -m dask worker`` as subprocesses) whose processes cannot read the study's folder: the
inputs go to them through Dask and their results come back, so the table equals that of a
LocalCluster; an interrupted run continues; each worker builds a model variant once."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np
import pytest

from test_batch import ROOT, record_files, write_study
from unilateral.batch import load_study, run_study

distributed = pytest.importorskip("distributed")

HANG_GUARD = 600.0
"""Seconds after which a wait gives up (a hang, not a slow machine: no verdict depends on time)."""
RUN_COLUMNS = ("solve_time", "task_time", "run_id")
"""Columns of the table that differ between two runs of the same analyses."""


class DenyFolder(distributed.WorkerPlugin):
    """In the worker process, opening, listing or stat-ing a path under ``folder`` raises
    ``PermissionError``, as for a folder of a file system the worker's machine does not mount."""

    def __init__(self, folder):
        self.folder = os.path.abspath(folder)

    def setup(self, worker):
        import builtins
        import io

        def inside(path) -> bool:
            if isinstance(path, int):
                return False
            path = os.path.abspath(os.fsdecode(path))
            return path == self.folder or path.startswith(self.folder + os.sep)

        def guarded(function):
            def call(path=".", *args, **kwargs):
                if inside(path):
                    raise PermissionError(13, "Permission denied (the study folder, hidden from the workers)",
                                          os.fsdecode(path))
                return function(path, *args, **kwargs)
            return call

        builtins.open = io.open = guarded(builtins.open)
        for name in ("open", "stat", "lstat", "scandir", "listdir"):
            setattr(os, name, guarded(getattr(os, name)))


def _wait_until(condition, what: str) -> None:
    """Poll ``condition()`` until true; fail naming ``what`` after ``HANG_GUARD`` seconds."""
    deadline = time.monotonic() + HANG_GUARD
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"waited {HANG_GUARD:g} s for {what}; it did not happen")
        time.sleep(0.1)


@pytest.fixture(scope="module")
def hand_started(tmp_path_factory):
    """``(address, logs)``: a scheduler and two single-threaded workers, each a process started by
    hand in a folder of its own (not the study's)."""
    base = tmp_path_factory.mktemp("cluster")
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    scheduler_file = base / "scheduler.json"
    processes = []

    def start(name, *arguments):
        folder = base / name
        folder.mkdir()
        log = open(base / f"{name}.log", "w")
        processes.append(subprocess.Popen([sys.executable, "-m", "dask", *arguments], cwd=folder, env=env,
                                          stdout=log, stderr=subprocess.STDOUT, start_new_session=True))
        log.close()

    start("scheduler", "scheduler", "--port", "0", "--no-dashboard", "--scheduler-file", str(scheduler_file))
    try:
        _wait_until(lambda: scheduler_file.exists() and scheduler_file.stat().st_size > 0, "the scheduler file")
        address = json.loads(scheduler_file.read_text())["address"]
        for k in range(2):
            start(f"worker{k}", "worker", address, "--nthreads", "1", "--no-dashboard", "--name", f"hand-{k}",
                  "--local-directory", str(base / f"worker{k}"))
        with distributed.Client(address, timeout=HANG_GUARD) as client:
            client.wait_for_workers(2, timeout=HANG_GUARD)
        yield address
    finally:
        for process in processes[::-1]:
            process.terminate()
        for process in processes[::-1]:
            try:
                process.wait(60)
            except subprocess.TimeoutExpired:
                process.kill()


def _study(folder):
    """A study of 8 analyses whose model and records are all inside ``folder``: the tower with two
    soil stiffnesses under two records at two scale factors (records read by the client only)."""
    (folder / "records").mkdir(parents=True)
    for record in record_files(2):
        shutil.copy(record, folder / "records" / record.name)
    return write_study(folder, """
[[models]]
file = "tower.toml"
[records]
folder = "records"
direction = "ux"
[scaling]
values = [0.5, 2.0]
[[parameters]]
key = "unilateral.soil3.k"
values = [150e3, 200e3]
[analysis]
method = "modal"
dt = 2e-3
t_end = 2.0
""")


def _same_tables(a, b) -> None:
    """Every column of two study tables equal to round-off, but those of the run itself (times, run
    id): the analyses run in other processes on the two clusters, and a clean-clone CI run under
    load once differed by one unit in the last place (5.7e-14 in a base shear of 375.5)."""
    assert sorted(a.data_vars) == sorted(b.data_vars)
    for name in a.data_vars:
        if name not in RUN_COLUMNS:
            values = a[name].values
            if np.issubdtype(values.dtype, np.floating):
                np.testing.assert_allclose(values, b[name].values, rtol=1e-12, atol=0, err_msg=name)
            else:
                np.testing.assert_array_equal(values, b[name].values, err_msg=name)


def test_hand_started_workers_without_the_study_folder_give_the_table_of_a_local_cluster(
        tmp_path, hand_started, monkeypatch):
    """Workers that cannot read the study's folder: an interrupted run, then the same run again,
    give every analysis exactly once and the table of a LocalCluster."""
    from unilateral.batch.progress import Progress

    folder = tmp_path / "study"
    path = _study(folder)
    addresses = _hide_from_workers(hand_started, folder, "tower.toml")

    update, seen = Progress.update, []

    def interrupt_after_two(self, result):                               # Ctrl-C after the 2nd result
        update(self, result)
        seen.append(result["key"])
        if len(seen) == 2:
            raise KeyboardInterrupt

    monkeypatch.setattr(Progress, "update", interrupt_after_two)
    out = tmp_path / "remote"
    with pytest.raises(KeyboardInterrupt) as interrupted:
        run_study(path, out, scheduler=hand_started, progress=False, figures=False)
    assert interrupted.value.result.counts["pending"] == 6
    first = {p.name: p.read_text() for p in (out / "results").glob("*.json")}
    assert sorted(first) == sorted(f"{key}.json" for key in seen)
    monkeypatch.setattr(Progress, "update", update)

    remote = run_study(path, out, scheduler=hand_started, progress=False, figures=False)
    assert (remote.ran, remote.skipped) == (6, 2)
    after = {p.name: p.read_text() for p in (out / "results").glob("*.json")}
    assert sorted(after) == sorted(f"{a.key}.json" for a in load_study(path).analyses)   # each once
    assert all(after[name] == text for name, text in first.items())     # the first run's results kept
    assert not list((out / "results").glob(".*tmp*"))
    results = [json.loads(text) for text in after.values()]
    assert {r["worker"] for r in results} <= addresses and os.getpid() not in {r["pid"] for r in results}
    assert sum(r["cache"]["model"] == "miss" for r in results) <= 2 * 2       # per worker, once per variant

    local = run_study(path, tmp_path / "local", workers=2, progress=False, figures=False)
    assert local.counts["ok"] == 8 == remote.counts["ok"]
    _same_tables(remote.table, local.table)


def test_a_matrix_level_model_and_its_files_reach_workers_that_cannot_read_them(tmp_path, hand_started):
    """The Matrix Market files a model refers to and the study's influence vector go to the workers
    with the model text: the table equals that of the same study run in this process."""
    folder = tmp_path / "matrix-study"
    path = _matrix_study(folder)
    _hide_from_workers(hand_started, folder, "M.mtx")
    remote = run_study(path, tmp_path / "remote", scheduler=hand_started, progress=False, figures=False)
    alone = run_study(path, tmp_path / "alone", synchronous=True, progress=False, figures=False)
    assert remote.counts["ok"] == 4 and (remote.table["uplift"].values > 0).any()
    _same_tables(remote.table, alone.table)


def _matrix_study(folder):
    """A study of a one-DOF matrix-level model (files ``M.mtx`` ... and ``r.mtx``, all inside
    ``folder``) on a tensionless support under two records at two scale factors."""
    import scipy.io

    folder.mkdir(parents=True)
    for name, value in {"M": 40.0, "K": 1e4, "F": 1e4, "H": 1e4, "C": 50.0, "r": 1.0}.items():
        scipy.io.mmwrite(folder / f"{name}.mtx", np.array([[value]]))
    (folder / "matrix.toml").write_text("""units = { length = "m", force = "kN", time = "s" }
[matrices]
M = "M.mtx"
K = "K.mtx"
F = "F.mtx"
H = "H.mtx"
C = "C.mtx"
[[loads.nodal]]
dof = 0
value = -400.0
time_function = { type = "constant" }
[analysis]
dt = 2e-3
t_end = 2.0
""")
    (folder / "records").mkdir()
    for record in record_files(2):
        shutil.copy(record, folder / "records" / record.name)
    path = folder / "study.toml"
    path.write_text("""[[models]]
file = "matrix.toml"
[records]
folder = "records"
influence = "r.mtx"
[scaling]
values = [1.0, 20.0]
[[quantities]]
name = "uplift"
type = "uplift"
[[quantities]]
name = "u"
type = "displacement"
dof = "u0"
""")
    return path


def _hide_from_workers(address: str, folder, probe: str) -> set:
    """Install :class:`DenyFolder` of ``folder`` on the workers of ``address`` and check that it
    works (reading ``folder/probe`` fails there); return the workers' addresses."""
    import cloudpickle

    with distributed.Client(address, timeout=HANG_GUARD) as client:
        cloudpickle.register_pickle_by_value(sys.modules[__name__])        # the plugin is defined here
        client.register_plugin(DenyFolder(folder), name=f"test-deny-{folder}")
        denied = client.run(_denied, folder / probe)
        addresses = set(client.scheduler_info()["workers"])
    assert list(denied.values()) == ["PermissionError", "PermissionError"]  # the folder is hidden indeed
    return addresses


def _denied(path) -> str:
    """The name of the error of reading ``path`` in this process ("" if it can be read)."""
    try:
        path.read_bytes()
    except OSError as exc:
        return type(exc).__name__
    return ""
