"""The pushover against OpenSees's DisplacementControl on the same portal frame (zeroLength ElasticPP
hinges, tests/pushover_opensees_portal.py): the capacity curve at OpenSees's 200 steps to 1e-6.

OpenSees's steps straddle the hinge formations; its Newton iterations (NormDispIncr 1e-12) find the
state of every ElasticPP spring at each step, which on this monotonic path is the exact
piecewise-linear curve, so the two agree to the solvers' round-off."""

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from pushover_frames import E, H, I_COL, portal

from unilateral.pushover import pushover

SCRIPT = Path(__file__).resolve().parent / "pushover_opensees_portal.py"
K_HINGE = 20 * 6 * E * I_COL / H


def opensees_environment():
    """The environment in which openseespy imports (its wheel's ``lib`` on LD_LIBRARY_PATH), or None."""
    spec = importlib.util.find_spec("openseespylinux")
    if spec is None or not spec.submodule_search_locations:
        return None
    lib = Path(list(spec.submodule_search_locations)[0]) / "lib"
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (str(lib), env.get("LD_LIBRARY_PATH")) if p)
    return env


ENV = opensees_environment()


@pytest.mark.skipif(ENV is None, reason="openseespy is not installed (pip install '.[test]')")
def test_capacity_curve_equals_opensees_displacement_control():
    proc = subprocess.run([sys.executable, str(SCRIPT), repr(K_HINGE)], capture_output=True, text=True, env=ENV,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    ref = {key: np.asarray(value) for key, value in json.loads(proc.stdout.strip().splitlines()[-1]).items()}
    st = portal(k_hinge=K_HINGE)
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81)
    assert r.success and [e.kind for e in r.events] == ["yield"] * 4
    here = r.at(ref["ux2"] - r.displacement[0])         # the path parameter: node 2's ux from its gravity value
    assert here["displacement"] == pytest.approx(ref["ux2"], rel=1e-12, abs=1e-15)
    peak = np.max(np.abs(ref["base_shear"]))
    assert np.max(np.abs(here["base_shear"] - ref["base_shear"])) <= 1e-6 * peak
    assert np.max(np.abs(here["load_factor"] - ref["load_factor"])) <= 1e-6 * peak
    assert np.max(np.abs(ref["base_shear"] - ref["load_factor"])) <= 1e-9 * peak   # OpenSees's own balance
