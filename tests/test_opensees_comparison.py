"""A yielding moment frame against OpenSees: the same model, rule and dt give the same roof drift.

The 3-storey, 2-bay frame of ``benchmarks/opensees_frames.py`` (elastic beam-columns, elastic-
perfectly plastic rotational springs at every beam end and column base) under a synthetic record:
OpenSees (``elasticBeamColumn`` + ``zeroLength`` ``ElasticPP`` springs, Newmark average
acceleration, Newton) and ``method="direct"`` with the trapezoidal rule (the same Newmark rule, the
plastic rotations as rate-type constraints of one LCP per step). OpenSees comes with the ``test``
extra (``openseespy``) and runs in a subprocess with its library path.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import opensees_frames as bench  # noqa: E402

pytestmark = pytest.mark.skipif(bench.opensees_environment() is None,
                                reason="openseespy is not installed (pip install '.[test]')")


def both(spec, dt, t_end, gm):
    samples = bench.record_samples(gm, dt, t_end)
    ours, _, sol = bench.run_unilateral(spec, gm, dt, t_end)
    theirs, _, failed = bench.opensees_in_subprocess(spec, samples, dt, t_end)
    assert failed == 0
    return ours, theirs, sol


def test_roof_drift_equals_opensees_with_yielding_hinges():
    spec = bench.FrameSpec()
    gm = bench.record(duration=5.0, dt=0.005)
    ours, theirs, sol = both(spec, 0.005, 5.0, gm)
    assert sol.stats["contact_changes"] > 20                        # hinges yield and unload
    assert np.max(np.abs(np.diff(sol.v, axis=0))) > 0
    peak = np.abs(theirs).max()
    assert np.abs(ours - theirs).max() <= 1e-8 * peak               # measured 2.5e-13


def test_both_codes_converge_to_the_same_reference():
    spec = bench.FrameSpec()
    gm = bench.record(duration=3.0, dt=0.005)
    reference, _, _ = bench.run_unilateral(spec, gm, 0.000625, 3.0)
    errors = []
    for dt in (0.005, 0.0025, 0.00125):
        ours, theirs, _ = both(spec, dt, 3.0, gm)
        stride = int(round(dt / 0.000625))
        assert np.abs(ours - theirs).max() <= 1e-8 * np.abs(theirs).max()
        errors.append(np.abs(theirs - reference[::stride]).max() / np.abs(reference).max())
    assert errors[0] > errors[1] > errors[2]
    assert errors[-1] < 0.05


def test_benchmark_smoke(tmp_path):
    """``benchmarks/opensees_frames.py --quick`` prints its table and writes its JSON (no timing asserted)."""
    import json
    import os
    import subprocess

    out = tmp_path / "frames.json"
    script = Path(__file__).resolve().parents[1] / "benchmarks" / "opensees_frames.py"
    proc = subprocess.run([sys.executable, str(script), "--quick", "--repeat", "1", "--out", str(out)],
                          capture_output=True, text=True, timeout=900, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    assert "us/step" in proc.stdout and "OpenSees s" in proc.stdout
    rows = json.loads(out.read_text())["rows"]
    assert [r["storeys"] for r in rows] == [3, 6, 9, 12]
    for r in rows:
        assert r["yield_events"] > 0 and r["opensees_failed_step"] == 0
        assert r["drift_difference_over_peak"] < 1e-8
