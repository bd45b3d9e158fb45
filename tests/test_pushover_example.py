"""examples/pushover_portal.py runs as users run it and prints the exact capacity curve of the portal."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "pushover_portal.py"
#: The examples run with this checkout's package (not an installed one).
ENV = {**os.environ, "MPLBACKEND": "Agg",
       "PYTHONPATH": os.pathsep.join(p for p in (str(EXAMPLE.parents[1] / "src"), os.environ.get("PYTHONPATH")) if p)}
NUMBER = r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"


def test_pushover_portal_example(tmp_path):
    proc = subprocess.run([sys.executable, str(EXAMPLE)], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                          env=ENV)
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


CYCLIC = EXAMPLE.parent / "pushover_cyclic.py"


def test_pushover_cyclic_example(tmp_path):
    proc = subprocess.run([sys.executable, str(CYCLIC)], cwd=tmp_path, capture_output=True, text=True, timeout=300,
                          env=ENV)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "history of 5 targets followed" in out
    high, low = map(float, re.search(rf"plateaus {NUMBER} kN and {NUMBER} kN", out).groups())
    assert high == pytest.approx(120.0, rel=1e-9) and low == pytest.approx(-120.0, rel=1e-9)
    assert len(re.findall(r"event: unload", out)) == 16                # 4 hinges at each of 4 reversals
    slope, closed = map(float, re.search(rf"slope {NUMBER} kN/m against the mean drift, -W/h = {NUMBER}", out).groups())
    assert slope == pytest.approx(closed, rel=1e-8)
    residual, lcp = map(float, re.search(rf"max equilibrium error {NUMBER}, max LCP error {NUMBER}", out).groups())
    assert residual < 1e-10 and lcp < 1e-10
    assert (tmp_path / "pushover_cyclic.png").stat().st_size > 10_000
