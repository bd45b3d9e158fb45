"""Per-footing results (``footing_*`` in results.nc, ``footings`` in summary.json): uplift, settlement,
rotation, slip, bearing pressure and contact length of each footing, checked against what defines them:
a rigid footing's rotation is its node's, the uplift is the largest patch opening, the soil carries the
weight in the static state, the peak pressure is at least the mean, the contact length is the patches
that push."""

import json

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.footing_results import ROUND_OFF
from unilateral.structure import Frame2D, Frame3D

CONES = {"model": "cones", "G": 2e4, "nu": 0.3, "rho": 2.0}
G = 9.81


def tower(*, mu=0.3, patches=4, amplitude=9.0):
    """A column with a top mass on a rigid footing that rocks and slides on cones, under a pulse."""
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, 6.0)
    fr.beam("col", "base", "top", E=3e7, A=0.5, I=0.05)
    fr.mass("top", 40.0, J=10.0)
    fr.foundation("F", "base", width=4.0, length=4.0, soil=CONES, patches=patches, horizontal="soil", mu=mu,
                  mass=20.0, J=30.0)
    st = fr.build()
    x, gravity = st.influence("ux"), -G * (st.M @ st.influence("uy"))

    def load(t):
        return gravity - st.M @ x * (amplitude * np.sin(2 * np.pi * t) * (t < 1.0))

    return st, load


@pytest.fixture(scope="module")
def rocking():
    st, load = tower()
    sol = ul.solve(st.to_model(), load, method="cq", dt=5e-3, t_end=2.0, rule="trapezoidal")
    assert sol.success, sol.message
    return st, sol, ul.results_dataset(sol, st, load=load)


def test_a_rigid_footing_rotates_settles_and_lifts_as_its_node_and_patches(rocking):
    st, sol, ds = rocking
    f = ds.sel(foundation="F")
    rz, uy = sol.u[:, st.dofs.index("base", "rz")], sol.u[:, st.dofs.index("base", "uy")]
    peak = np.abs(rz).max()
    assert np.abs(f["footing_rz"].values - rz).max() <= 1e-12 * peak
    assert np.abs(f["footing_uy"].values - uy).max() <= 1e-12 * np.abs(uy).max()
    m = st.foundation.m
    opening = sol.v[:, st.foundation.first:st.foundation.first + m]
    assert np.array_equal(f["footing_uplift"].values, opening.max(axis=1))
    assert f["footing_uplift"].max() > 1e-3, "the pulse must lift the footing for this test to mean something"


def test_the_soil_carries_the_weight_and_the_pressure_peaks_above_the_mean(rocking):
    st, sol, ds = rocking
    f = ds.sel(foundation="F")
    weight = G * (40.0 + 20.0)
    assert abs(float(f["footing_vertical_force"][0]) - weight) <= 1e-9 * weight
    area = 4.0 * 4.0
    mean = f["footing_vertical_force"].values / area
    assert np.all(f["footing_peak_pressure"].values >= mean * (1 - 1e-12))


def test_the_contact_length_counts_the_patches_that_push(rocking):
    st, sol, ds = rocking
    f = ds.sel(foundation="F")
    c = -sol.psi[:, st.foundation.first:st.foundation.first + st.foundation.m]
    pushing = (c > ROUND_OFF * np.abs(c).max()).sum(axis=1)
    assert np.array_equal(f["footing_contact_length"].values, pushing * 1.0)       # 4 patches of 1 m
    assert np.array_equal(f["footing_contact_ratio"].values, pushing / 4)
    assert f["footing_contact_ratio"].min() < 1.0 and f["footing_contact_ratio"][0] == 1.0
    lifted = f["footing_uplift"].values > 0
    assert np.all(f["footing_contact_ratio"].values[lifted] < 1.0)


def test_the_slip_is_the_patches_mean_and_the_peaks_are_the_histories(rocking):
    st, sol, ds = rocking
    f = ds.sel(foundation="F")
    slips = st.foundation.slips(sol)
    assert np.abs(f["footing_slip"].values - slips.mean(axis=1)).max() <= 1e-15 * max(1.0, np.abs(slips).max())
    assert abs(float(f["footing_slip"][-1])) > 1e-4, "the footing must slide for this test to mean something"


def test_a_flexible_footing_rotates_as_the_plane_fitted_to_its_nodes():
    fr = Frame2D()
    xs = [-2.0, -0.5, 1.0, 2.5]
    for k, x in enumerate(xs):
        fr.node(k, x, 0.0)
    fr.node("top", 0.0, 5.0)
    for k in range(len(xs) - 1):
        fr.beam(f"b{k}", k, k + 1, E=3e7, A=0.5, I=0.02)
    fr.beam("col", 1, "top", E=3e7, A=0.5, I=0.05)
    fr.mass("top", 30.0)
    for k in range(len(xs)):
        fr.mass(k, 2.0)
    fr.foundation("S", 1, nodes=list(range(len(xs))), length=2.0, soil=CONES)
    st = fr.build()
    x, gravity = st.influence("ux"), -G * (st.M @ st.influence("uy"))
    sol = ul.solve(st.to_model(), lambda t: gravity - st.M @ x * (6.0 * np.sin(2 * np.pi * t) * (t < 0.5)), method="cq", dt=5e-3, t_end=1.0)
    assert sol.success, sol.message
    ds = ul.results_dataset(sol, st)
    z = np.column_stack([sol.u[:, st.dofs.index(k, "uy")] for k in range(len(xs))])
    areas = st.foundation.patches.areas
    slope = np.array([np.polyfit(xs, row, 1, w=np.sqrt(areas))[0] for row in z])
    assert np.abs(ds["footing_rz"].sel(foundation="S").values - slope).max() <= 1e-9 * np.abs(slope).max()


def test_a_3d_footing_rotates_about_both_axes_as_its_node():
    fr = Frame3D()
    fr.node("base", 0.0, 0.0, 0.0)
    fr.node("top", 0.0, 0.0, 6.0)
    fr.beam("col", "base", "top", E=3e7, G=1.2e7, A=0.5, Iy=0.05, Iz=0.05, J=0.08)
    fr.mass("top", 40.0, Jz=10.0)
    fr.foundation("F", "base", width=4.0, length=3.0, soil=CONES, patches=(3, 2), mass=20.0, Jx=30.0, Jy=30.0,
                  Jz=30.0)
    st = fr.build()
    d = np.cos(0.5) * st.influence("ux") + np.sin(0.5) * st.influence("uy")
    gravity = st.gravity(G)
    sol = ul.solve(st.to_model(), lambda t: gravity - st.M @ d * (9.0 * np.sin(2 * np.pi * t) * (t < 1.0)),
                   method="cq", dt=5e-3, t_end=1.5)
    assert sol.success, sol.message
    f = ul.results_dataset(sol, st).sel(foundation="F")
    for dof in ("rx", "ry", "uz"):
        node = sol.u[:, st.dofs.index("base", dof)]
        assert np.abs(f[f"footing_{dof}"].values - node).max() <= 1e-12 * np.abs(node).max(), dof
    assert abs(float(f["footing_vertical_force"][0]) - G * 60.0) <= 1e-9 * G * 60.0
    assert f["footing_contact_area"][0] == 12.0 and f["footing_uplift"].max() > 0


MODEL = """
units = { length = "m", force = "kN", time = "s" }
nodes = [ { id = 1, x = 0.0, y = 0.0 }, { id = 2, x = 6.0, y = 0.0 }, { id = 11, x = 0.0, y = 3.0 },
          { id = 12, x = 6.0, y = 3.0 } ]
elements = [
  { type = "beam", name = "c1", node_i = 1, node_j = 11, E = 3e7, A = 0.2, I = 2e-3 },
  { type = "beam", name = "c2", node_i = 2, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 },
  { type = "beam", name = "b", node_i = 11, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 },
]
masses = [ { node = 11, m = 20.0 }, { node = 12, m = 20.0 } ]
[[foundations]]
name = "A"
node = 1
width = 2.0
length = 2.0
patches = 4
mass = 2.0
J = 0.5
soil = { model = "cones", G = 2e4, nu = 0.3, rho = 2.0 }
[[foundations]]
name = "B"
node = 2
width = 2.0
length = 2.0
patches = 4
mass = 2.0
J = 0.5
soil = { model = "cones", G = 2e4, nu = 0.3, rho = 2.0 }
[loads.gravity]
g = "standard"
[[loads.nodal]]
node = 11
ux = 150.0
[analysis]
dt = 5e-3
t_end = 0.5
method = "cq"
"""


def test_a_run_reports_each_footing_in_the_summary_and_the_terminal(tmp_path):
    import xarray as xr
    from click.testing import CliRunner
    from unilateral.cli import main

    path = tmp_path / "portal.toml"
    path.write_text(MODEL)
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["run", str(path), "--out", str(out), "--figures", "none"])
    assert done.exit_code == 0, done.output
    results = json.loads((out / "summary.json").read_text())["results"]
    with xr.open_dataset(out / "results.nc") as ds:
        for case, peaks in results.items():
            for name in ("A", "B"):
                for q, got in peaks["footings"][name].items():
                    y = ds[f"footing_{q}"].sel(case=case, foundation=name).values
                    assert got["max"] == pytest.approx(float(y.max()), abs=0.0), (case, name, q)
                    assert got["final"] == pytest.approx(float(y[-1]), abs=0.0), (case, name, q)
        assert ds["footing_peak_pressure"].attrs["units"] == "kN/m^2"
        assert ds["footing_rz"].attrs["units"] == "rad"
    assert "footing A:" in done.output and "footing B:" in done.output


def test_a_run_that_barely_moves_has_no_energy_balance_error_and_no_warning(tmp_path):
    """A static load held on the footings (the run stays at its static state): the energy changes are
    round-off of the stored energy (1e-15 kN m of work); the balance's relative error read 7-15 % and
    warned before its scale had a floor of 1e-8 of the stored energy."""
    from click.testing import CliRunner
    from unilateral.cli import main

    path = tmp_path / "portal.toml"
    path.write_text(MODEL)
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["run", str(path), "--out", str(out), "--figures", "none"])
    assert done.exit_code == 0, done.output
    results = json.loads((out / "summary.json").read_text())["results"]
    for case, peaks in results.items():
        assert abs(peaks["energy"]["input_work"]) < 1e-12, "the run must barely move for this test to mean something"
        assert peaks["energy"]["max_relative_error"] < 1e-5, case
    assert "energy balance is off" not in done.output
