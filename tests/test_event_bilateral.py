"""``method="event"`` with the bilateral case (``bilateral=True``, a model file's default
``bilateral_reference = true``): the bilateral case has no contact change to follow and is solved
by ``method="direct"``; the unilateral case stays the event march's."""

from __future__ import annotations

import numpy as np
from click.testing import CliRunner
from conftest import GRAVITY, MASS, rocking_model

import unilateral as ul
from unilateral.cli import main
from unilateral.loads import LoadHistory, Rectangular

EX, EY = np.eye(5)[0], np.eye(5)[1]
ROOT = __import__("pathlib").Path(__file__).parents[1]


def _pulses():
    return LoadHistory(-MASS * GRAVITY * EY, [(300.0 * EX, Rectangular(1.0, t_end=0.1))])


def test_the_bilateral_case_of_the_event_method_is_the_direct_methods():
    model = rocking_model(kelvin=False)
    kw = dict(dt=2e-3, t_end=0.5, bilateral=True, rule="trapezoidal")
    event = ul.solve(model, _pulses(), method="event", **kw)
    direct = ul.solve(model, _pulses(), method="direct", **kw)
    assert event.success, event.message
    assert event.stats["bilateral_method"] == "direct"
    assert "solved by method='direct'" in event.stats["method_note"]
    np.testing.assert_array_equal(event.u, direct.u)
    np.testing.assert_array_equal(event.psi, direct.psi)
    assert np.abs(event.v).max() <= 1e-12                       # held: nothing opens
    assert (event.psi > 0).any()                                # and the supports pull
    unilateral = ul.solve(model, _pulses(), method="event", dt=2e-3, t_end=0.5)
    assert unilateral.stats["contact_changes"] > 0 and "bilateral_method" not in unilateral.stats


def test_run_with_method_event_solves_both_cases_of_a_model_file(tmp_path):
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["run", str(ROOT / "examples" / "liolios1990.toml"), "--method", "event",
                                       "--t-end", "0.5", "--out", str(out)])
    assert result.exit_code == 0, result.output
    import json

    summary = json.loads((out / "summary.json").read_text())
    assert summary["method"] == "event" and "contact changes (exact" in summary["message"]
    assert set(summary["results"]) == {"unilateral", "bilateral"}
