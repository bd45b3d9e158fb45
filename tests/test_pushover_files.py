"""Pushover from a model file: ``[analysis] type = "pushover"`` with ``[pushover]``, ``unilateral run``'s
outputs (pushover.csv, events.csv, summary.json, the capacity curve) and the errors of bad input."""

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from pushover_frames import independent_events

from unilateral.analysis import run_model_file
from unilateral.modelfile import ModelFileError, load_model_file

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "pushover_portal.toml"
COLLAPSE = 2 * (100.0 + 80.0) / 3.0


def _variant(tmp_path, old, new, name="model.toml"):
    text = EXAMPLE.read_text()
    assert old in text, old
    path = tmp_path / name
    path.write_text(text.replace(old, new))
    return path


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_the_example_file_through_the_command_line(tmp_path):
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "unilateral", "run", str(EXAMPLE), "--out", str(out)],
                          capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src"), "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "target reached" in proc.stdout and "peak base shear 120 kN" in proc.stdout
    rows = _rows(out / "pushover.csv")
    lam = np.array([float(r["load_factor"]) for r in rows])
    assert lam[-1] == pytest.approx(COLLAPSE, rel=1e-9)
    expected = independent_events()                     # gravity adds nothing to these moments
    events = _rows(out / "events.csv")
    assert [e["constraint"].split(".")[0] for e in events] == [name for name, _, _ in expected]
    for event, (_, P, d) in zip(events, expected):
        assert float(event["load_factor"]) == pytest.approx(P, rel=1e-9)
        assert float(event["2.ux"]) == pytest.approx(d, rel=1e-9)
        assert float(event["base_shear"]) == pytest.approx(P, rel=1e-9)
    drift = np.array([float(r["roof_drift"]) for r in rows])
    assert drift[-1] == pytest.approx(0.1 / 3.0, rel=1e-12)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["analysis"] == "pushover" and summary["success"] and summary["stats"]["events"] == 4
    assert summary["peak_base_shear"] == pytest.approx(COLLAPSE, rel=1e-9)
    assert (out / "capacity_curve.png").stat().st_size > 10_000


def test_cycles_and_string_p_delta_from_a_file(tmp_path):
    path = _variant(tmp_path, "target = 0.1 ", 'cycles = [0.05, -0.05]\np_delta = "string"\n')
    result = run_model_file(path, tmp_path / "out", figures=())
    assert result["success_all"] and result["stats"]["events"] == 12        # 4 yield, 4 unload, 4 yield
    rows = _rows(tmp_path / "out" / "pushover.csv")
    d = np.array([float(r["2.ux"]) for r in rows])
    assert d[-1] == pytest.approx(-0.05, rel=1e-12) and d.max() == pytest.approx(0.05, rel=1e-12)
    lam = np.array([float(r["load_factor"]) for r in rows])
    # lambda = -120 - W d / h on the reversed mechanism (W/h against the mean drift of nodes 2 and 3; the
    # beam's shortening makes d of node 2 differ from it by 2e-5: tests/test_pushover_cyclic.py)
    assert lam[-1] == pytest.approx(-COLLAPSE + 2 * 98.1 * 0.05 / 3.0, rel=1e-4)
    assert not list((tmp_path / "out").glob("*.png"))


def test_a_target_beyond_the_mechanism_under_load_control_ends_the_path(tmp_path):
    path = _variant(tmp_path, "target = 0.1 ", 'target = 500.0\ncontrol = "load"\n')
    result = run_model_file(path, tmp_path / "out", figures=())
    assert not result["success_all"] and not result["success"]
    assert result["message"].startswith("mechanism at load factor 120")
    assert "STOPPED" in result["report"] and result["end"]["load_factor"] == pytest.approx(COLLAPSE, rel=1e-9)
    proc = subprocess.run([sys.executable, "-m", "unilateral", "run", str(path), "--out", str(tmp_path / "o2"),
                           "--figures", "none"], capture_output=True, text=True, timeout=300,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert proc.returncode == 1 and "mechanism at load factor 120" in proc.stdout


@pytest.mark.parametrize("old, new, words", [
    ("node = 2\ndof", "node = 7\ndof", ["pushover.node = 7: no such node", "1, 2, 3, 4"]),
    ("pattern = [{ node = 2, ux = 1.0 }]", "pattern = [{ node = 9, ux = 1.0 }]", ["pushover.pattern[0].node = 9"]),
    ("pattern = [{ node = 2, ux = 1.0 }]", 'pattern = "parabolic"', ["pushover.pattern", "parabolic"]),
    ("target = 0.1 ", "target = 0.1\ncycles = [0.1, -0.1]\n", ["pushover", "not both"]),
    ("target = 0.1 ", "\n", ["pushover", "neither"]),
    ('type = "pushover"', 'type = "transient"', ["analysis", "dt and t_end"]),
    ('type = "pushover"', 'type = "static"', ["analysis.type", "transient, pushover"]),
    ('type = "pushover"', 'type = "transient"\ndt = 0.01\nt_end = 1.0', ["[pushover] table needs", "type"]),
    ("dof = \"ux\"", "dof = \"uz\"", ["pushover.dof", "uz", "ux, uy, rz"]),
    ("pattern = [{ node = 2, ux = 1.0 }]", "pattern = [{ node = 2, uz = 1.0 }]",
     ["pushover.pattern[0].uz = 1.0", "ux, uy, rz only"]),
    ("target = 0.1 ", 'target = 0.1\np_delta = "string"\ngravity = false\n', ["pushover.p_delta", "gravity"]),
])
def test_bad_pushover_tables_name_the_key(tmp_path, old, new, words):
    path = _variant(tmp_path, old, new)
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_type_pushover_without_its_table(tmp_path):
    path = tmp_path / "model.toml"
    path.write_text(EXAMPLE.read_text().split("\n[pushover]")[0])
    with pytest.raises(ModelFileError, match=r"pushover: missing section \(declare e.g. \[pushover\] pattern"):
        load_model_file(path)


@pytest.mark.parametrize("old, new, words", [
    ("node = 2\ndof", "node = 1\ndof", ["pushover: node=1", "cannot move"]),
    ("target = 0.1 ", "target = -0.1 ", ["pushover: target=-0.1", "wrong sign"]),
    ("target = 0.1 ", "cycles = [0.1, 0.1]", ["pushover: target[1]=0.1", "repeats"]),
])
def test_what_the_pushover_refuses_is_reported_under_its_key(tmp_path, old, new, words):
    path = _variant(tmp_path, old, new)
    with pytest.raises(ModelFileError) as info:
        run_model_file(path, tmp_path / "out", figures=())
    for word in words:
        assert word in str(info.value), (word, str(info.value))
    assert not (tmp_path / "out").exists()


def test_transient_options_are_refused_for_a_pushover(tmp_path):
    with pytest.raises(ValueError, match="--dt.*not for a pushover"):
        run_model_file(EXAMPLE, tmp_path / "out", figures=(), dt=0.01)
    with pytest.raises(ValueError, match="--bilateral: not for a pushover"):
        run_model_file(EXAMPLE, tmp_path / "out", figures=(), bilateral=True)


def test_a_frame_on_footings_that_lift_and_slide(tmp_path):
    """examples/yielding_frame.toml (beam hinges, column-base springs, footings on tensionless soil
    with Coulomb friction) pushed by its first mode: hinges yield, an edge lifts off, edges slip, and
    the path is in equilibrium with the constraint laws at every point."""
    text = (ROOT / "examples" / "yielding_frame.toml").read_text()
    head, _, rest = text.partition("[[loads.ground_motion]]")
    frame = head + "[analysis]\ntype = \"pushover\"\n\n[pushover]\npattern = \"mode\"\nnode = 31\ntarget = 0.3\n"
    path = tmp_path / "frame.toml"
    path.write_text(frame)
    result = run_model_file(path, tmp_path / "out", figures=("png",))
    assert result["success"], result["message"]
    kinds = {e["kind"] for e in result["events"]}
    assert kinds >= {"yield", "slip", "uplift", "unload"}
    assert result["stats"]["max_residual"] < 1e-10 and result["stats"]["max_lcp_error"] < 1e-10
    assert (tmp_path / "out" / "capacity_curve.png").stat().st_size > 10_000
    with_record = tmp_path / "with_record.toml"
    with_record.write_text(text.replace('file = "records/', f'file = "{ROOT}/examples/records/').split("[analysis]")[0]
                           + "[analysis]\ntype = \"pushover\"\n\n[pushover]\npattern = \"mode\"\nnode = 31\n"
                           "target = 0.05\n")
    result = run_model_file(with_record, tmp_path / "out2", figures=())
    assert result["not_applied"] == ["loads.ground_motion[0]"] and "not applied: loads.ground_motion[0]" in \
        result["report"]


PORTAL_3D = """
units = { length = "m", force = "kN", time = "s", mass = "t" }
frame = { dimensions = 3 }
nodes = [{ id = 1, x = 0.0, y = 0.0, z = 0.0 }, { id = 2, x = 0.0, y = 0.0, z = 3.0 },
         { id = 3, x = 4.0, y = 0.0, z = 3.0 }, { id = 4, x = 4.0, y = 0.0, z = 0.0 }]
supports = [{ node = 1, rx = true, ry = true, rz = true }, { node = 4, rx = true, ry = true, rz = true }]
elements = [
    { type = "beam", name = "c1", node_i = 1, node_j = 2, E = 30e6, A = 0.09, Iy = 6.75e-4, Iz = 6.75e-4, G = 12.5e6, J = 1.35e-3 },
    { type = "beam", name = "c2", node_i = 4, node_j = 3, E = 30e6, A = 0.09, Iy = 6.75e-4, Iz = 6.75e-4, G = 12.5e6, J = 1.35e-3 },
    { type = "beam", name = "g", node_i = 2, node_j = 3, E = 30e6, A = 0.09, Iy = 1.35e-3, Iz = 1.35e-3, G = 12.5e6, J = 2.7e-3 },
]
unilateral = [
    { type = "hinge", name = "hb1", beam = "c1", end = "i", My = 100.0, Mz = 100.0, shape = "box" },
    { type = "hinge", name = "hb2", beam = "c2", end = "i", My = 100.0, Mz = 100.0, shape = "box" },
    { type = "hinge", name = "hg1", beam = "g", end = "i", My = 80.0, Mz = 80.0, shape = "box" },
    { type = "hinge", name = "hg2", beam = "g", end = "j", My = 80.0, Mz = 80.0, shape = "box" },
]
masses = [{ node = 2, m = 10.0 }, { node = 3, m = 10.0 }]
loads.gravity = { g = 9.81, direction = [0.0, 0.0, -1.0] }
analysis = { type = "pushover" }
pushover = { pattern = [{ node = 2, ux = 1.0 }], node = 2, dof = "ux", target = 0.1 }
"""


def test_a_3d_frame_from_a_file(tmp_path):
    path = tmp_path / "portal3d.toml"
    path.write_text(PORTAL_3D)
    result = run_model_file(path, tmp_path / "out", figures=())
    assert result["success"], result["message"]
    assert result["end"]["load_factor"] == pytest.approx(COLLAPSE, rel=1e-9)
    assert [e["load_factor"] for e in result["events"]] == pytest.approx([P for _, P, _ in independent_events()],
                                                                          rel=1e-9)
    rows = _rows(tmp_path / "out" / "pushover.csv")
    assert float(rows[-1]["roof_drift"]) == pytest.approx(0.1 / 3.0, rel=1e-9)     # the height along z
    # controlled by node 2's uz (its column stretches as the frame sways): a target below its gravity value
    # is of the wrong sign
    path.write_text(PORTAL_3D.replace('dof = "ux", target = 0.1', 'dof = "uz", target = -0.01'))
    with pytest.raises(ModelFileError, match=r"pushover: target=-0.01 is of the wrong sign.*2\.uz"):
        run_model_file(path, tmp_path / "out2", figures=())
