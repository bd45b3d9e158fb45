"""examples/pushover_portal.py runs as users run it and prints the exact capacity curve of the portal."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "pushover_portal.py"
NUMBER = r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"


def test_pushover_portal_example(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLE)], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    plateau, mechanism = map(float, re.search(rf"plateau {NUMBER} kN, sway mechanism .* = {NUMBER} kN", out).groups())
    assert plateau == pytest.approx(120.0, rel=1e-9) and mechanism == 120.0
    events = re.findall(rf"event: yield (\w+)\.plastic[+-] at load factor {NUMBER}", out)
    assert [name for name, _ in events] == ["hg1", "hg2", "hb1", "hb2"]
    assert float(events[0][1]) == pytest.approx(118.343618697, rel=1e-9)
    residual, lcp = map(float, re.search(rf"max equilibrium error {NUMBER}, max LCP error {NUMBER}", out).groups())
    assert residual < 1e-10 and lcp < 1e-10
    peak, last = map(float, re.search(rf"with P-Delta: peak base shear {NUMBER} kN, at 0.1 m {NUMBER} kN", out).groups())
    assert last < peak < 120.0
    assert "capacity curve" in out and (tmp_path / "pushover_portal.png").stat().st_size > 10_000
