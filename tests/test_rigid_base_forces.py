"""The ground's forces on rigid blocks and boxes in the results (``results.nc``, ``summary.json``), and
their accelerations.

The base forces of a rocking block or box came out 0 (no element carries its held base; the corner
contacts' forces were not counted), and the accelerations of the trapezoidal rule rang at +-1e5
after the first impact. Now: the vertical force of the ground minus the weight is the mass times
the centre's mean vertical acceleration of each step (Newton, to round-off: the contact forces
against the velocities), the horizontal one is the mass times the centre's absolute horizontal
acceleration, ``m a_g`` while nothing lifts (for ``moreau-jean`` the accelerations, the ground's
included, are the means of the steps), and a block that has come to rest has no acceleration."""

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import unilateral as ul
from unilateral.analysis.run import run_model_file
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, rigid

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
MASS, G = 2.0, 9.80665


def _results(example, tmp_path):
    run_model_file(EXAMPLES / f"{example}.toml", tmp_path / example, figures=(), t_end=1.5)
    return (xr.open_dataset(tmp_path / example / "results.nc").sel(case="unilateral"),
            json.loads((tmp_path / example / "summary.json").read_text())["results"]["unilateral"])


@pytest.mark.parametrize("example, vertical, horizontal", [("rocking_block", "base_vertical", "base_shear"),
                                                           ("rocking_box", "base_Fz", "base_Fx")])
def test_the_ground_forces_on_a_rocking_block_are_its_momentum_rate(example, vertical, horizontal, tmp_path):
    ds, summary = _results(example, tmp_path)
    if example == "rocking_block":              # the centre is above the base: its uy is the base's
        a_z = ds["acceleration"].sel(dof="cabinet.base.uy").values
    else:
        a_z = ds["node_absolute_acceleration"].sel(node="centre", component="uz").values
    fz, fx = ds[vertical].values, ds[horizontal].values
    a_g = ds["ground_acceleration"].values[:, 0]        # moreau-jean: the means of the steps, as the accelerations
    assert np.abs(fz[1:] - MASS * G - MASS * a_z[1:]).max() <= 1e-10 * np.abs(fz).max()
    assert fz.max() > MASS * G > fz.min() >= 0                                  # it rocks: impacts and lift-off
    lifted = 1 + np.flatnonzero(np.abs(a_z[1:]) > 1e-9)[0]
    before = slice(1, lifted - 1)                                               # at rest on its base
    assert np.abs(fx[before] - MASS * a_g[before]).max() <= 1e-10 * np.abs(MASS * a_g).max()
    if example == "rocking_box":                # and then the momentum rate of the centre
        a_x = ds["node_absolute_acceleration"].sel(node="centre", component="ux").values
        assert np.abs(fx - MASS * a_x).max() <= 1e-10 * np.abs(fx).max()
        assert np.abs(a_x[before] - a_g[before]).max() <= 1e-10 * np.abs(a_g).max()
    forces = summary["base_forces"]["Fx"] if example == "rocking_box" else summary["base_shear"]
    assert forces["max"] > MASS * np.abs(a_g).max()                            # impacts: impulsive forces


def test_a_block_at_rest_after_rocking_has_no_acceleration():
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    st = fr.build()
    model = st.to_model()
    u0 = np.array([block.b * 0.05, -0.05])                 # tilted on its right corner
    q = st.gravity(block.g)
    sol = ul.solve(model, LoadHistory(q), dt=1e-3, t_end=4.0, method="moreau-jean", rule="trapezoidal",
                   initial={"u0": u0, "v0": rigid.initial_forces(model, u0, q)})
    assert sol.success, sol.message
    ds = ul.results_dataset(sol, st, load=LoadHistory(q))
    a = ds["acceleration"].values.reshape(len(sol.t), -1)
    assert len(sol.stats["impacts"]) >= 3
    assert np.abs(sol.udot[-200:]).max() < 1e-9                             # at rest
    assert np.abs(a[-200:]).max() < 1e-6, np.abs(a[-200:]).max()            # the rule's recurrence rang at 1e5
    vertical = ds["base_vertical"].values.ravel()
    assert abs(vertical[-1] - block.W) <= 1e-9 * block.W
