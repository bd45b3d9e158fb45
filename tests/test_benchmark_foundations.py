"""Smoke test of ``benchmarks/foundation_halfspace.py`` at a tiny size (no timing asserted).

The benchmark's runs build their models afresh and solve them as a user would; at 2 strips per
footing and 40 steps they check that every row (one tower, two footings on one half-space, two
footings that slide) still runs and reports what the table prints.
"""

import importlib.util
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "foundation_halfspace.py"


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("foundation_halfspace", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("run, unknowns", [("run_once", 2), ("run_two_footings", 4), ("run_sliding", 8)])
def test_every_row_of_the_benchmark_runs(bench, run, unknowns):
    r = getattr(bench, run)(2, 40)
    assert r["success"] and r["m"] == unknowns and r["N"] == 40
    assert r["wall_s"] > 0 and {"weights", "steps"} <= set(r["parts_s"])
    assert bench.row(r).split()[:2] == [str(unknowns), "40"]
