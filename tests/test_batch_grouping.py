"""Analyses grouped into Dask tasks (batch.runner.group_analyses, run_analyses): every analysis in
exactly one group, in order, groups of about equal cost; the results of a group equal those of its
analyses run one by one, a failure is recorded for its own analysis only, and a study gives the
same table with and without grouping."""

from __future__ import annotations

import copy
import math
from types import SimpleNamespace

import numpy as np
import pytest

from test_batch import record_files, write_study
from unilateral.batch import load_study, run_study
from unilateral.batch import runner
from unilateral.batch.inputs import study_inputs
from unilateral.batch.runner import analysis_cost, group_analyses, run_analyses
from unilateral.batch.worker import run_analysis

#: Entries of a result that name the process or the clock, not the analysis.
CIRCUMSTANCES = ("solve_time", "solve_cpu_time", "quantities_time", "task_time", "pid", "host", "worker",
                 "run_id", "cache")


def fake(key, steps):
    return SimpleNamespace(key=key, payload={"settings": {"dt": 0.01, "t_end": 0.01 * steps}})


def test_groups_cover_every_analysis_once_in_order_with_about_equal_cost():
    rng = np.random.default_rng(3)
    analyses = [fake(f"a{i}", int(s)) for i, s in enumerate(rng.integers(50, 5000, size=97))]
    groups = group_analyses(analyses, workers=2)
    assert [a for g in groups for a in g] == analyses
    assert len(groups) == max(2 * runner.TASKS_PER_WORKER, math.ceil(97 / runner.MAX_ANALYSES_PER_TASK))
    assert all(len(g) <= runner.MAX_ANALYSES_PER_TASK for g in groups)
    costs = [sum(analysis_cost(a) for a in g) for g in groups]
    share, largest = sum(costs) / len(groups), max(analysis_cost(a) for a in analyses)
    assert max(costs) <= share + largest                # a group stops at the first analysis past its share
    assert analysis_cost(analyses[0]) == pytest.approx(analyses[0].payload["settings"]["t_end"] / 0.01)


def test_one_group_per_analysis_when_asked_or_when_there_are_few():
    analyses = [fake(f"a{i}", 100) for i in range(5)]
    assert group_analyses(analyses, workers=2) == [[a] for a in analyses]          # 5 < 2 x 4 groups
    many = [fake(f"a{i}", 100) for i in range(30)]
    assert group_analyses(many, workers=2, most=1) == [[a] for a in many]
    assert group_analyses([], workers=2) == []
    assert analysis_cost(SimpleNamespace(payload={"settings": {"dt": 0.0, "t_end": 1.0}})) == 1.0
    assert analysis_cost(SimpleNamespace(payload={"settings": {"dt": 0.01, "t_end": math.nan}})) == 1.0


@pytest.fixture(scope="module")
def small_study(tmp_path_factory):
    folder = tmp_path_factory.mktemp("grouping")
    records = record_files(2)
    files = ", ".join(f'"{r.as_posix()}"' for r in records)
    path = write_study(folder, f"""
title = "grouping"
[[models]]
file = "tower.toml"
[records]
files = [{files}]
direction = "ux"
[scaling]
values = [0.1, 0.2, 8.0]
[analysis]
method = "cq"
dt = 4e-3
t_end = 2.0
lcp = "pgs"
lcp_options = {{ max_iter = 1 }}
""")
    return folder, path


def essentials(result):
    return {k: v for k, v in result.items() if k not in CIRCUMSTANCES}


def test_a_group_gives_each_analysis_its_own_result_and_a_failure_stays_with_its_analysis(small_study):
    folder, path = small_study
    study = load_study(path)
    analyses = study.analyses
    inputs = study_inputs(analyses)
    args = [runner._inputs_of(a, inputs.variants, inputs.records) for a in analyses]
    payloads = [a.payload for a in analyses]
    broken = [copy.deepcopy(p) for p in payloads]       # each its own (analyses share a settings dict)
    broken[1]["settings"]["t_end"] = math.nan           # an error in the middle of the group
    grouped = run_analyses(broken, [s for s, _ in args], [r for _, r in args], "group")
    alone = [run_analysis(p, s, r, "alone") for p, (s, r) in zip(broken, args)]
    assert [r["key"] for r in grouped] == [a.key for a in analyses]
    assert [essentials(r) for r in grouped] == [essentials(r) for r in alone]     # bit for bit
    status = [r["status"] for r in grouped]
    assert status[1] == "error" and "no end time" in grouped[1]["message"]
    scales = [a.payload["scale"] for a in analyses]
    expected = ["error" if i == 1 else "failed" if s > 1 else "ok" for i, s in enumerate(scales)]
    assert status == expected


def test_a_timeout_ends_its_group_and_leaves_the_rest_to_be_submitted_again(monkeypatch):
    calls = []

    def fake_run(payload, source, record, run_id):
        calls.append(payload["key"])
        return {"key": payload["key"], "status": "timeout" if payload["key"] == "b" else "ok",
                **({"restart_worker": True} if payload["key"] == "b" else {})}
    monkeypatch.setattr(runner, "run_analysis", fake_run)
    out = run_analyses([{"key": k} for k in "abcd"], [None] * 4, [None] * 4)
    assert [r["key"] for r in out] == ["a", "b"] and calls == ["a", "b"]


@pytest.mark.slow
def test_a_study_on_dask_gives_the_same_table_with_and_without_grouping(small_study, monkeypatch):
    distributed = pytest.importorskip("distributed")
    folder, path = small_study
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                       silence_logs=40)
    try:
        monkeypatch.setattr(runner, "TASKS_PER_WORKER", 1)      # 6 analyses, 2 workers: 2 tasks of 3
        assert [len(g) for g in group_analyses(load_study(path).analyses, 2)] == [3, 3]
        grouped = run_study(path, folder / "grouped", scheduler=cluster.scheduler_address, progress=False,
                            figures=False)
        monkeypatch.setattr(runner, "MAX_ANALYSES_PER_TASK", 1)
        single = run_study(path, folder / "single", scheduler=cluster.scheduler_address, progress=False,
                           figures=False)
    finally:
        cluster.close()
    assert grouped.ran == single.ran == 6
    for name in ("status", "message", "uplift", "force"):
        np.testing.assert_array_equal(grouped.table[name].values, single.table[name].values)
    assert list(grouped.table["status"].values[grouped.table["intensity"].values == 8.0]) == ["failed", "failed"]
