"""A 3-D frame on compression-only supports against OpenSees: the same model, rule and dt give the
same roof-corner displacements.

The 2-storey, 2 x 1 bay asymmetric frame of ``benchmarks/opensees_frame3d.py`` (elastic beam-columns
with ``Iy != Iz`` and the same ``vecxz`` in both codes, unequal columns, an eccentric floor mass,
each column base on a tensionless vertical spring) under gravity and two horizontal ground
accelerations: OpenSees (``-ndm 3 -ndf 6``, ``elasticBeamColumn`` + ``geomTransf Linear``,
``zeroLength`` ``ENT`` springs, Newmark average acceleration, Newton) and ``method="direct"`` with
the trapezoidal rule. OpenSees comes with the ``test`` extra (``openseespy``) and runs in a
subprocess with its library path.
"""

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import opensees_frame3d as bench  # noqa: E402

pytestmark = pytest.mark.skipif(bench.opensees_environment() is None,
                                reason="openseespy is not installed (pip install '.[test]')")


def both(spec, dt, t_end):
    gms = bench.records(spec, dt, t_end)
    samples = [bench.record_samples(gm, dt, t_end) for gm in gms]
    ours, _, sol = bench.run_unilateral(spec, gms, dt, t_end)
    theirs, _, failed, opened = bench.opensees_in_subprocess(spec, samples, dt, t_end)
    assert failed == 0
    return ours, theirs, sol, opened


def test_roof_corner_equals_opensees_with_uplift():
    spec = bench.FRAMES[0]
    ours, theirs, sol, opened = both(spec, 0.005, 2.0)                 # 400 steps
    assert sol.stats["n"] == 78 and sol.stats["m"] == 6
    uplift = bench.open_steps(sol)
    assert uplift > 20 and sol.stats["contact_changes"] > 10          # springs lift off and land again
    assert uplift == opened                                           # the same steps open in OpenSees
    for dof in bench.COMPARED:
        peak = np.abs(theirs[dof]).max()
        assert peak > 0
        assert np.abs(ours[dof] - theirs[dof]).max() <= 1e-8 * peak  # measured ~2e-13


def test_rigid_footings_and_diaphragms_equal_opensees():
    """Rigid links (footings on four corner springs) and rigid diaphragms: a short run of the example
    building, one storey lower."""
    spec = dataclasses.replace(bench.FRAMES[1], storeys=2)
    ours, theirs, sol, opened = both(spec, 0.005, 0.75)
    assert bench.open_steps(sol) > 0
    for dof in bench.COMPARED:
        assert np.abs(ours[dof] - theirs[dof]).max() <= 1e-8 * np.abs(theirs[dof]).max()


def test_benchmark_smoke(tmp_path):
    """``benchmarks/opensees_frame3d.py --quick`` prints its table and writes its JSON (no timing asserted)."""
    import json
    import os
    import subprocess

    out = tmp_path / "frame3d.json"
    script = Path(__file__).resolve().parents[1] / "benchmarks" / "opensees_frame3d.py"
    proc = subprocess.run([sys.executable, str(script), "--quick", "--repeat", "1", "--out", str(out)],
                          capture_output=True, text=True, timeout=600, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "us/step" in proc.stdout and "OpenSees s" in proc.stdout and "load average" in proc.stdout
    data = json.loads(out.read_text())
    assert len(data["load_average"]) == 3
    rows = data["rows"]
    assert [(r["frame"], r["n"], r["m"]) for r in rows] == [("2-storey", 78, 6), ("building", 179, 42)]
    for r in rows:
        assert r["uplift_steps"] > 0 and r["opensees_failed_step"] == 0
        assert r["uplift_steps"] == r["opensees_uplift_steps"]
        assert r["max_difference_over_peak"] < 1e-8
