"""Smoke tests of the benchmark scripts that have no test of their own: each runs at a tiny size,
prints its table and writes its JSON. No time is asserted (the machines are shared); what is
checked is that the script runs, and the figures it computes that are not times (the histories'
agreement, the analyses' statuses)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(script, *args, timeout=600):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, str(ROOT / "benchmarks" / script), *map(str, args)], capture_output=True,
                          text=True, env=env, timeout=timeout, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def test_history_scaling_quick(tmp_path):
    out = tmp_path / "history.json"
    text = run("history_scaling.py", "--quick", "--out", out)
    assert "naive s" in text and f"wrote {out}" in text
    rows = json.loads(out.read_text())["rows"]
    assert [r["N"] for r in rows] == [256, 512]
    for r in rows:                                  # the FFT history gives the naive sums
        assert r["max_rel_diff"] < 1e-10 and r["fft_s"] > 0 and r["naive_s"] > 0


def test_cli_timing_of_the_help(tmp_path):
    out = tmp_path / "cli.json"
    text = run("cli_timing.py", "--repeat", "1", "--only", "help", "--out", out)
    assert "--help" in text
    rows = json.loads(out.read_text())["rows"]
    assert list(rows) == ["--help"] and len(rows["--help"]["runs"]) == 1


@pytest.mark.slow
def test_foundation_weights_quick(tmp_path):
    out = tmp_path / "weights.json"
    text = run("foundation_weights.py", "--quick", "--old-columns", "1", "--out", out, timeout=1200)
    assert "py/new" in text
    report = json.loads(out.read_text())
    assert report["rows"] and all(r["max_rel_diff"] < 1e-8 for r in report["rows"])


def test_batch_throughput_of_two_analyses(tmp_path):
    out = tmp_path / "batch.json"
    text = run("batch_throughput.py", "--analyses", "2", "--workers", "1", "--ceiling-rounds", "1", "--out", out)
    assert f"written: {out}" in text
    report = json.loads(out.read_text())
    assert report["analyses"] == 2
    for case in report["cases"]:
        assert case["analyses"] == 2 and case["statuses"] == ["ok"], case
    assert report["run_study"]["analyses"] == 2


@pytest.mark.slow
def test_cold_start_quick(tmp_path):
    """The tower of 400 steps in fresh processes, numba's cache empty and then filled (it compiles)."""
    out = tmp_path / "cold.json"
    text = run("cold_start.py", "--quick", "--out", out, timeout=1800)
    assert "cold auto chose" in text
    rows = json.loads(out.read_text())["models"][0]["rows"]
    assert set(rows) == {"cold auto", "cold compiled", "cached compiled", "cached auto"}
    assert rows["cold compiled"]["stats"]["engine"] == rows["cached compiled"]["stats"]["engine"] == "compiled"
    assert rows["cold auto"]["stats"]["engine"] == "python"      # 400 steps: less than loading compiled code
