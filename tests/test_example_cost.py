"""The built-in examples with many runs say what they will cost and refuse, before anything is
solved, what would take more than an hour (``example halfspace --dt 1e-6``: 5.7e7 steps, which ran
for minutes without a word); counted by the solves started, never timed."""

from __future__ import annotations


import pytest

import importlib
from unilateral.analysis.example_cost import MAX_EXAMPLE_SECONDS, check_example_cost, example_seconds
from unilateral.analysis.run import run_example


@pytest.mark.parametrize("name", ["halfspace", "footings"])
def test_an_example_of_a_tiny_time_step_is_refused_before_any_solve(tmp_path, monkeypatch, name):
    solves = []
    monkeypatch.setattr(importlib.import_module("unilateral.solve"), "solve", lambda *a, **k: solves.append(1))
    with pytest.raises(ValueError) as info:
        run_example(name, tmp_path / "out", figures=(), dt=1e-6)
    message = str(info.value)
    assert message.startswith(f"--dt 1e-06: the {name} example would take about ")
    assert "more than the 1 h allowed for an example; give --dt " in message
    assert solves == [] and not (tmp_path / "out").exists()
    fits = float(message.split("give --dt ")[1].split(" ")[0])          # the time step it suggests fits
    steps = {"halfspace": [round(1.5 / fits), round(8.0 / fits)] * 6, "footings": [round(6.0 / fits)] * 4}[name]
    assert example_seconds(name, steps) <= MAX_EXAMPLE_SECONDS


def test_the_default_examples_are_within_the_limit_and_a_long_end_time_is_named():
    assert check_example_cost("halfspace", [750, 4000] * 6, None, None) < MAX_EXAMPLE_SECONDS
    assert check_example_cost("footings", [1200] * 4, None, None) < MAX_EXAMPLE_SECONDS
    with pytest.raises(ValueError, match=r"^--t-end 60000: the footings example would take about .* give --t-end "):
        check_example_cost("footings", [12_000_000] * 4, None, 60000.0)
