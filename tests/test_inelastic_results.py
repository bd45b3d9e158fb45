"""Results of yielding and friction elements: results.nc, CSV, summary.json, the terminal summary,
the hysteresis figure and the case labels (unilateral.analysis.inelastic, unilateral.analysis.outputs).

The frame of tests/test_yield_elements.py (hinges rigid-plastic and elastic-plastic, a soil contact
with friction, a slider, a yielding brace) runs from a model file through ``unilateral.run``; every
reported figure is checked against the solution it comes from.
"""

import json

import numpy as np
import pytest
from click.testing import CliRunner

import unilateral
import unilateral as ul
from unilateral.analysis.run import case_labels
from unilateral.cli import main
from unilateral.constraints import Yield
from unilateral.io import load_netcdf
from yield_portal import PORTAL_TOML

MODEL = PORTAL_TOML + """
[loads.gravity]
g = 10.0
[[loads.nodal]]
node = 2
ux = 160.0
time_function = { type = "half_sine", duration = 0.5 }
[[loads.nodal]]
node = 3
ux = -120.0
time_function = { type = "half_sine", t_start = 0.6, duration = 0.4 }
[analysis]
dt = 1e-3
t_end = 1.5
method = "direct"
rule = "trapezoidal"
[output]
figure = { node = 3, dof = "ux" }
"""
YIELDS = ("h1", "h3", "h2", "br")          # in the order of v: c1 (h1), c2 (h3), g (h2), s1, b4, br
FRICTIONS = ("s1", "b4")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The frame run by the command line: its folder, the terminal output and results.nc."""
    folder = tmp_path_factory.mktemp("yielding")
    model = folder / "frame.toml"
    model.write_text(MODEL)
    result = CliRunner().invoke(main, ["run", str(model), "--out", str(folder / "out")])
    assert result.exit_code == 0, result.output
    return folder / "out", result.output, load_netcdf(folder / "out" / "results.nc")


def column(ds, name):
    return list(ds["constraint"].values).index(name)


def test_results_nc_holds_plastic_deformations_and_slips_with_their_forces(run):
    _, _, ds = run
    d = ds.sel(case="unilateral")
    assert list(d["yield_element"].values) == list(YIELDS)
    assert list(d["friction_element"].values) == list(FRICTIONS)
    assert list(d["yield_element_kind"].values) == ["hinge", "hinge", "hinge", "yield link"]
    assert list(d["yield_deformation_unit"].values) == ["rad", "rad", "rad", "m"]
    assert list(d["friction_element_kind"].values) == ["soil", "slider"]
    for name in ("plastic_deformation", "yield_force", "yield_element_deformation", "slip", "friction_force",
                 "normal_force", "tangential_deformation"):
        assert ds[name].dims[0] == "case" and ds[name].attrs["long_name"] and ds[name].attrs["units"], name
    v, psi = d["v"].values, d["psi"].values
    for k, name in enumerate(YIELDS):
        np.testing.assert_array_equal(d["plastic_deformation"].values[:, k],
                                      v[:, column(d, f"{name}.plastic+")] - v[:, column(d, f"{name}.plastic-")])
    for k, name in enumerate(FRICTIONS):
        np.testing.assert_array_equal(d["slip"].values[:, k],
                                      v[:, column(d, f"{name}.slip+")] - v[:, column(d, f"{name}.slip-")])
    # the soil's N is its compression -psi; the slider's is its constant N
    np.testing.assert_allclose(d["normal_force"].values[:, 0], -psi[:, column(d, "s1")], atol=1e-9)
    np.testing.assert_allclose(d["normal_force"].values[:, 1], 150.0)
    # force and deformation: a hinge's moment stays within My, the brace's force within (-Fy_c, Fy_t) shifted
    # by its hardening, and |T| <= mu N to round-off
    assert np.abs(d["yield_force"].values[:, 0]).max() == pytest.approx(40.0, rel=1e-9)
    T, N = d["friction_force"].values, d["normal_force"].values
    assert np.all(np.abs(T) <= np.array([0.4, 0.3]) * N + 1e-9)
    brace = d["constraint_deformation"].values[:, column(d, "br.plastic+")]
    np.testing.assert_array_equal(d["yield_element_deformation"].values[:, 3], brace)
    np.testing.assert_allclose(d["yield_force"].values[:, 3], 2e4 * (brace - d["plastic_deformation"].values[:, 3]),
                               atol=1e-9)
    # the case held linear keeps every multiplier at its initial (static) value
    b = ds.sel(case="bilateral")
    assert np.ptp(b["plastic_deformation"].values, axis=0).max() == 0.0 and np.ptp(b["slip"].values, axis=0).max() == 0


def test_energy_terms_by_family_and_per_element_work(run):
    out, _, ds = run
    d = ds.sel(case="unilateral")
    for key in ("plastic_work", "friction_work", "contact_dissipated"):
        assert d[f"energy_{key}"].attrs["units"] == "kN m"
    assert d["energy_relative_error"].values.max() < 1e-4      # the load's hat averages against its samples
    summary = json.loads((out / "summary.json").read_text())
    peaks = summary["results"]["unilateral"]
    energy = peaks["energy"]
    assert energy["plastic_work"] == pytest.approx(float(d["energy_plastic_work"][-1]))
    assert energy["plastic_work"] > 0.05 * energy["input_work"] and energy["friction_work"] > 0
    assert sum(e["plastic_work"] for e in peaks["yield_elements"].values()) == pytest.approx(energy["plastic_work"])
    friction = sum(e["friction_work"] for e in peaks["friction_elements"].values())
    assert friction == pytest.approx(energy["friction_work"])
    base = (out / "base.csv").read_text().splitlines()[0].split(",")
    assert "energy_plastic_work [kN m]" in base and "energy_friction_work [kN m]" in base


def test_summary_reports_ductility_excursions_residuals_and_slip(run):
    out, _, ds = run
    d = ds.sel(case="unilateral")
    peaks = json.loads((out / "summary.json").read_text())["results"]["unilateral"]
    yields, frictions = peaks["yield_elements"], peaks["friction_elements"]
    assert list(yields) == list(YIELDS) and list(frictions) == list(FRICTIONS)
    plastic = d["plastic_deformation"].values
    for k, name in enumerate(YIELDS):
        e = yields[name]
        assert e["residual_plastic_deformation"] == plastic[-1, k]
        assert abs(e["peak_plastic_deformation"]["value"]) == pytest.approx(np.abs(plastic[:, k]).max())
        assert e["yielded"] == (e["yield_excursions"] > 0)
    assert yields["h1"]["yielded"] and "ductility" not in yields["h1"]          # rigid-plastic: no yield rotation
    assert yields["h1"]["unit"] == "rad" and yields["br"]["unit"] == "m"
    # an elastic-plastic hinge: the spring's rotation M/k + plastic over My/k
    h2 = yields["h2"]
    moment = d["yield_force"].values[:, 2]
    assert h2["yield_deformation"] == [pytest.approx(40.0 / 2e4)] * 2
    assert h2["ductility"]["value"] == pytest.approx(np.abs(moment / 2e4 + plastic[:, 2]).max() / (40.0 / 2e4))
    assert h2["ductility"]["value"] > 1.0 and h2["peak_force_ratio"]["value"] >= 1.0
    slip = d["slip"].values
    for k, name in enumerate(FRICTIONS):
        e = frictions[name]
        assert e["total_slip"] >= abs(e["peak_slip"]["value"]) - 1e-15
        assert e["residual_slip"] == slip[-1, k]
    assert frictions["s1"]["slid"]
    drift = peaks["residual_drift"]
    assert drift["ratio"] == pytest.approx(float(d["drift_ratio"].values[-1, 0])) and drift["t"] == 1.5


def test_summary_and_contact_figures_leave_out_multipliers(run):
    from unilateral.figures.results import _constraint_data

    out, output, ds = run
    summary = json.loads((out / "summary.json").read_text())
    assert list(summary["constraints"]) == ["s1"]              # the only contact: no uplift of a hinge
    assert list(_constraint_data(ds)["constraint"].values) == ["s1"]
    assert "h1.plastic+" not in output


def test_terminal_lines_csv_and_labels(run):
    out, output, ds = run
    assert "yield: 4 of 4 yield elements yielded, peak ductility" in output
    assert "friction: " in output and "friction elements slid" in output
    assert "residual drift ratio" in output
    labels = json.loads(ds.attrs["case_labels"])
    assert labels == {"unilateral": "with yield, slip and uplift", "bilateral": "linear (constraints held)"}
    header = (out / "yield_and_slip.csv").read_text().splitlines()[0].split(",")
    assert header[0] == "time [s]" and "plastic_deformation:h1 [rad]" in header and "yield_force:br [kN]" in header
    assert "yield_force:h1 [kN m]" in header and "plastic_deformation:br [m]" in header
    assert "slip:s1 [m]" in header and "friction_force:b4 [kN]" in header and "normal_force:s1 [kN]" in header
    constraints = (out / "constraints.csv").read_text().splitlines()[0].split(",")
    assert "v:h1.plastic+ [rad]" in constraints and "psi:h1.plastic+ [kN m]" in constraints
    assert "v:s1 [m]" in constraints and "psi:s1 [kN]" in constraints
    assert (out / "bilateral_yield_and_slip.csv").exists() and (out / "bilateral_base.csv").exists()


def test_hysteresis_figure_is_drawn_by_run_and_plot_alike(run, tmp_path):
    out, _, _ = run
    assert (out / "hysteresis.png").exists()
    assert "hysteresis.png" in json.loads((out / "manifest.json").read_text())["files"]
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    for name in ("hysteresis.png", "energy.png", "constraints.png"):
        assert (tmp_path / name).read_bytes() == (out / name).read_bytes(), name


def test_hysteresis_panels_are_ordered_by_dissipated_energy(run):
    from unilateral.figures.results import MAX_HYSTERESIS, hysteresis_figure

    _, _, ds = run
    fig = hysteresis_figure(ds)
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert sorted(titles) == sorted(YIELDS + FRICTIONS) and len(titles) <= MAX_HYSTERESIS
    peaks = ds.sel(case="unilateral")
    work = {name: float(w) for name, w in zip(YIELDS, _work(peaks["yield_force"], peaks["plastic_deformation"]))}
    work |= {name: float(w) for name, w in zip(FRICTIONS, _work(peaks["friction_force"], peaks["slip"]))}
    assert titles[0] == max(work, key=work.get)
    for ax in fig.axes:
        assert "[" in ax.get_xlabel() and "[" in ax.get_ylabel()            # a unit on every axis


def _work(force, deformation):
    f, x = force.values, deformation.values
    return np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x, axis=0), axis=0)


@pytest.mark.parametrize("kinds, expected", [
    (["soil", "soil"], {"unilateral": "with uplift", "bilateral": "without uplift"}),
    ([], None),
    (["yield", "yield"], {"unilateral": "with yield", "bilateral": "elastic"}),
    (["friction", "friction"], {"unilateral": "with slip", "bilateral": "no slip"}),
    (["soil", "friction", "friction", "yield", "yield"],
     {"unilateral": "with yield, slip and uplift", "bilateral": "linear (constraints held)"}),
    (["gap", "yield"], {"unilateral": "with yield and pounding", "bilateral": "linear (constraints held)"}),
])
def test_case_labels_say_what_acts_and_what_is_held(kinds, expected):
    assert case_labels(kinds) == expected


def test_a_matrix_level_yield_model_reports_no_uplift(tmp_path):
    """Without a structure the families give the kinds: a plastic multiplier is no uplift."""
    from unilateral.analysis import write_outputs

    epp = ul.Model.from_natural(G=[[1.0]], E=[[100.0]], B=[[1.0, -1.0]], M=[[1.0]], r=[5.0, 5.0],
                                families=[Yield([0, 1])])
    pulse = ul.LoadHistory([0.0], [([1.0], ul.loads.Rectangular(12.0, t_end=0.3))])
    sol = ul.solve(epp, pulse, dt=1e-2, t_end=1.0, initial="rest")
    result = write_outputs(tmp_path / "out", {"unilateral": sol}, model=epp, formats=("png",))
    assert result["constraints"] == {}
    ds = load_netcdf(tmp_path / "out" / "results.nc")
    assert list(ds["constraint_kind"].values) == ["yield", "yield"]
    assert not (tmp_path / "out" / "constraints.png").exists()
    assert unilateral.analysis.report(result)                  # prints without a contact table
