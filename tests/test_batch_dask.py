"""Studies on a real Dask LocalCluster (2 worker processes): results equal the analyses run one by
one bit for bit, failures are reported, a killed worker loses nothing, Ctrl-C and resume.

The tests wait for events (results written, workers back, processes gone), never for a time: a
wait gives up only after ``HANG_GUARD`` seconds, a hang on any machine, however loaded.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import unilateral as ul
from test_batch import ROOT, ground_motion, record_files, tower, write_study
from unilateral.batch import load_study, run_study
from unilateral.modelfile import load_model_file

distributed = pytest.importorskip("distributed")

HANG_GUARD = 600.0
"""Seconds after which a wait gives up (a hang, not a slow machine): a safety net, never a verdict."""


@pytest.fixture(scope="module")
def cluster():
    import dask

    from unilateral.batch.runner import LOST_WORKER_TIMEOUT

    # a worker restarted after a timeout is waited for, however long its restart takes on a loaded
    # machine (Dask's default closes its nanny 15 s after it left: the cluster then lost a worker)
    with dask.config.set({"distributed.scheduler.allowed-failures": 3,
                          "distributed.deploy.lost-worker-timeout": LOST_WORKER_TIMEOUT}):
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                           dashboard_address=None, silence_logs=40)
        yield cluster
        cluster.close()


def _one_by_one(tmp_path, row, records) -> dict:
    """The analysis of a table row run alone from a model file with its record and scale."""
    record = records[str(row["record"])]
    path = tmp_path / f"alone_{row['analysis']}.toml"
    path.write_text(tower(k3=row["param.unilateral.soil3.k"], ground=ground_motion(record, row["scale"]),
                          dt=2e-3, t_end=2.0))
    spec = load_model_file(path)
    a = spec.analysis
    sol = ul.solve(spec.model, spec.load, dt=a["dt"], t_end=a["t_end"], method=a["method"], rule=a["rule"],
                   lcp=a["lcp"], initial=a["initial"])
    st = spec.structure
    top = st.node_displacement(sol, 1, "ux")
    return {"uplift": sol.v.max(), "uplift_each.soil3": sol.v[:, 0].max(), "force": (-sol.psi).max(),
            "top": np.abs(top).max(), "drift": np.abs((top - st.node_displacement(sol, 2, "ux")) / 10.0).max(),
            "residual": abs(st.node_displacement(sol, 3, "uy")[-1] - st.node_displacement(sol, 3, "uy")[0])}


def test_a_study_equals_the_analyses_run_one_by_one_bit_for_bit(tmp_path, cluster):
    records = record_files(3)
    files = ", ".join(f'"{r.as_posix()}"' for r in records)
    path = write_study(tmp_path, f"""
title = "equality"
[[models]]
file = "tower.toml"
[records]
files = [{files}]
direction = "ux"
[scaling]
measure = "sa"
values = [0.5, 2.0]
[[parameters]]
key = "unilateral.soil3.k"
values = [150e3, 200e3]
[analysis]
method = "modal"
dt = 2e-3
t_end = 2.0
""")
    result = run_study(path, tmp_path / "out", scheduler=cluster.scheduler_address, progress=False)
    table = result.table
    assert result.counts["ok"] == 12 and result.ran == 12
    assert (table["uplift"].values > 0).any() and (table["uplift"].values == 0).any()   # some lift off
    frame = table.to_dataframe().reset_index()
    by_stem = {r.stem: r for r in records}
    for _, row in frame.iterrows():
        alone = _one_by_one(tmp_path, row, by_stem)
        for name, value in alone.items():
            assert row[name] == value, (name, row["record"], row["intensity"])       # bit for bit
    # a model variant is built once per worker, not once per task (the records come from this process)
    import json

    results = [json.loads(p.read_text()) for p in (tmp_path / "out" / "results").glob("*.json")]
    workers = {r["pid"] for r in results}
    assert len(workers) == 2
    assert sum(r["cache"]["model"] == "miss" for r in results) <= 2 * len(workers)
    assert all(0 < r["solve_time"] and 0 < r["quantities_time"] and
               r["solve_time"] + r["quantities_time"] <= r["task_time"] for r in results)     # the benchmark's split
    assert (tmp_path / "out" / "ida.png").stat().st_size > 0 and (tmp_path / "out" / "study.csv").exists()


def test_an_lcp_failure_is_reported_and_the_rest_finish(tmp_path, cluster):
    records = record_files(2)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{records[0].as_posix()}", "{records[1].as_posix()}"]
direction = "ux"
[scaling]
values = [0.1, 0.2, 8.0]
[analysis]
method = "cq"
dt = 4e-3
t_end = 4.0
lcp = "pgs"
lcp_options = {{ max_iter = 1 }}
""")
    result = run_study(path, tmp_path / "out", scheduler=cluster.scheduler_address, progress=False)
    status = result.table["status"].values
    scale = result.table["intensity"].values
    assert list(status[scale == 8.0]) == ["failed", "failed"] and (status[scale < 1] == "ok").all()
    assert all("PGS did not converge" in m for m in result.table["message"].values[scale == 8.0])
    assert len(list((tmp_path / "out" / "results").glob("*.json"))) == 6


def test_a_worker_killed_mid_task_loses_nothing(tmp_path, cluster):
    records = record_files(3)
    files = ", ".join(f'"{r.as_posix()}"' for r in records)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = [{files}]
direction = "ux"
[scaling]
values = [0.5, 1.0]
[analysis]
method = "cq"
dt = 1e-3
t_end = 20.0
""")                                                           # about 1-2 s per analysis: long enough to kill one
    client = distributed.Client(cluster)
    pids = client.run(os.getpid)                               # worker address -> pid
    box = {}
    thread = threading.Thread(target=lambda: box.setdefault("result", run_study(
        path, tmp_path / "out", scheduler=cluster.scheduler_address, progress=False, figures=False)))
    thread.start()
    killed = None
    deadline = time.monotonic() + HANG_GUARD
    while killed is None and time.monotonic() < deadline and thread.is_alive():
        busy = {w: tasks for w, tasks in client.processing().items() if tasks}
        done = list((tmp_path / "out" / "results").glob("*.json"))
        if done and busy:
            address = next(iter(busy))
            time.sleep(0.2)
            if client.processing().get(address):
                os.kill(pids[address], signal.SIGKILL)            # mid-task: nothing written for it
                killed = address
        time.sleep(0.05)
    thread.join(HANG_GUARD)
    client.close()
    assert not thread.is_alive(), f"the study did not end within {HANG_GUARD:g} s"
    assert killed is not None, "no worker was busy to kill"
    result = box["result"]
    assert result.counts == {"ok": 6, "failed": 0, "error": 0, "timeout": 0, "pending": 0}
    assert len(list((tmp_path / "out" / "results").glob("*.json"))) == 6


def test_timed_out_analyses_are_recorded_and_their_workers_restarted(tmp_path, cluster):
    """A timeout on the cluster: the result is read back from the task (the worker to restart)."""
    records = record_files(2)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{records[0].as_posix()}", "{records[1].as_posix()}"]
direction = "ux"
[analysis]
method = "direct"
dt = 1e-4
t_end = 6.0
timeout = 0.001
""")                                                           # 60 000 steps: seconds, far beyond the limit
    client = distributed.Client(cluster)
    before = set(client.run(os.getpid).values())
    result = run_study(path, tmp_path / "out", scheduler=cluster.scheduler_address, progress=False, figures=False)
    client.wait_for_workers(2, timeout=HANG_GUARD)             # the restarted worker is back
    after = set(client.run(os.getpid).values())
    client.close()
    assert list(result.table["status"].values) == ["timeout", "timeout"]
    assert all("stopped after 0.001 s" in m for m in result.table["message"].values)
    assert before - after                                      # a worker that ran one was restarted


def _wait_until(condition, what: str, detail=lambda: "") -> None:
    """Poll ``condition()`` until true; fail naming ``what`` after ``HANG_GUARD`` seconds."""
    deadline = time.monotonic() + HANG_GUARD
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"waited {HANG_GUARD:g} s for {what}; it did not happen. {detail()}")
        time.sleep(0.1)


def _group(pgid) -> list[str]:
    """Command lines of the live processes of process group ``pgid``."""
    out = subprocess.run(["ps", "-o", "pid=,pgid=,stat=,args=", "-A"], capture_output=True, text=True).stdout
    return [line for line in out.splitlines()
            if line.split()[1] == str(pgid) and not line.split()[2].startswith("Z")]


def _results(out) -> list:
    """The result files of a study's output folder: not the hidden temporary files of atomic writes
    (``.<name>.<random>.tmp.json``, which ``*.json`` matches too)."""
    return [p for p in (out / "results").glob("*.json") if not p.name.startswith(".")]


@pytest.mark.slow
def test_ctrl_c_stops_cleanly_and_a_second_run_continues(tmp_path):
    """Ctrl-C (SIGINT to the process group of `python -m unilateral.batch`) half-way; the same command
    again ends the study with every analysis exactly once."""
    records = record_files(3)
    files = ", ".join(f'"{r.as_posix()}"' for r in records)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = [{files}]
direction = "ux"
[scaling]
values = [0.5, 1.0, 1.5]
[analysis]
method = "direct"
dt = 2e-5
t_end = 5.0
""")                                                  # 250 000 steps, about 1 s each: long enough to be interrupted
    out = tmp_path / "out"
    command = [sys.executable, "-m", "unilateral.batch", str(path), "--out", str(out), "--workers", "2",
               "--no-figures"]
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    with open(tmp_path / "stderr.txt", "w") as err:            # a file: a full pipe would stall the study
        # SIGINT as a terminal's process has it: a test runner started in the background of a
        # non-interactive shell passes it on ignored, and the study could not be interrupted at all
        process = subprocess.Popen(command, env=env, start_new_session=True, stdout=subprocess.DEVNULL,
                                   stderr=err, text=True,
                                   preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        _wait_until(lambda: len(_results(out)) >= 2 or process.poll() is not None,
                    "the first run to write 2 results")
        assert process.poll() is None, "the study ended before it was interrupted"
        os.killpg(process.pid, signal.SIGINT)               # Ctrl-C on a terminal: the whole process group
        _wait_until(lambda: process.poll() is not None, "the interrupted run to exit")
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    stderr = (tmp_path / "stderr.txt").read_text()
    assert process.returncode == 130, stderr
    assert "interrupted" in stderr and "run the same command again" in stderr
    assert "Traceback" not in stderr                         # the workers leave Ctrl-C to the study
    _wait_until(lambda: not _group(process.pid), "the workers to exit with the cluster",
                lambda: f"processes left behind: {_group(process.pid)}")
    first = {p.name: p.read_text() for p in _results(out)}
    assert 2 <= len(first) < 9
    assert not list((out / "results").glob(".*tmp*"))
    second = subprocess.run(command, env=env, capture_output=True, text=True, timeout=HANG_GUARD)
    assert second.returncode == 0, second.stderr
    after = {p.name: p.read_text() for p in (out / "results").glob("*.json")}
    assert len(after) == 9                                    # every analysis exactly once
    assert all(after[name] == text for name, text in first.items())   # the first run's results kept
    study = load_study(path)
    assert sorted(after) == sorted(f"{a.key}.json" for a in study.analyses)
    import xarray as xr

    with xr.open_dataset(out / "study.nc", engine="h5netcdf") as table:
        assert (table["status"].values == "ok").all() and table.sizes["analysis"] == 9
        assert len(set(table["run_id"].values)) == 2


def test_timeouts_on_a_one_worker_cluster_restart_it_and_the_other_analyses_still_run(tmp_path):
    """The restarted worker held the only copy of the scattered inputs: they are sent again and the
    analyses cancelled meanwhile are submitted again, not recorded as errors."""
    records = record_files(5)                                  # the last one is cancelled by 4 restarts
    files = ", ".join(f'"{r.as_posix()}"' for r in records)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = [{files}]
direction = "ux"
[analysis]
method = "direct"
dt = 1e-4
t_end = 6.0
timeout = 0.001
""")                                                           # 60 000 steps: seconds, far beyond the limit
    result = run_study(path, tmp_path / "out", workers=1, progress=False, figures=False)
    assert list(result.table["status"].values) == ["timeout"] * 5, list(result.table["message"].values)


def test_a_restart_that_outlasts_dasks_lost_worker_timeout_keeps_the_worker(tmp_path):
    """A restart slower than Dask's ``lost-worker-timeout`` (what a loaded machine does to its 15 s
    default, here made 0.5 s where a restart takes seconds): the cluster closed the restarted
    worker's nanny, was left with no worker and the study waited for one forever. The study keeps
    its workers: every analysis is recorded, after a restart each."""
    import dask

    records = record_files(2)
    path = write_study(tmp_path, f"""
[[models]]
file = "tower.toml"
[records]
files = ["{records[0].as_posix()}", "{records[1].as_posix()}"]
direction = "ux"
[analysis]
method = "direct"
dt = 1e-4
t_end = 6.0
timeout = 0.001
""")
    box = {}

    def study():
        with dask.config.set({"distributed.deploy.lost-worker-timeout": "0.5s"}):
            box["result"] = run_study(path, tmp_path / "out", workers=1, progress=False, figures=False)

    thread = threading.Thread(target=study, daemon=True)
    thread.start()
    thread.join(HANG_GUARD)
    assert not thread.is_alive(), f"the study did not end within {HANG_GUARD:g} s: no worker left to run it"
    assert list(box["result"].table["status"].values) == ["timeout", "timeout"]
    assert len(_results(tmp_path / "out")) == 2
