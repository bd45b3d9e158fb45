"""Response spectra of a run: the spectrum against closed forms, the batch's spectrum and the run's
own accelerations; spectra.csv, spectra.png, summary.json and results.nc; the [output] keys."""

import json
from types import SimpleNamespace

import numpy as np
import pytest
from click.testing import CliRunner

from unilateral.analysis.run import run_model_file
from unilateral.analysis.spectra import period_grid, pseudo_acceleration
from unilateral.cli import main
from unilateral.modelfile import ModelFileError, load_model_file

#: A portal frame on fixed supports (kN, m, s), shaken by the record of ``sine.txt``.
FRAME = """
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [ {{ id = 1, x = 0.0, y = 0.0 }}, {{ id = 2, x = 6.0, y = 0.0 }}, {{ id = 3, x = 0.0, y = 3.0 }},
          {{ id = 4, x = 6.0, y = 3.0 }}, {{ id = 5, x = 6.05, y = 3.0 }} ]
supports = [ {{ node = 1, rz = true }}, {{ node = 2, rz = true }}, {{ node = 5 }} ]
elements = [
  {{ type = "beam", name = "c1", node_i = 1, node_j = 3, E = 3e7, A = 0.16, I = 2e-3 }},
  {{ type = "beam", name = "c2", node_i = 2, node_j = 4, E = 3e7, A = 0.16, I = 2e-3 }},
  {{ type = "beam", name = "b", node_i = 3, node_j = 4, E = 3e7, A = 0.18, I = 5e-3 }},
]
unilateral = [ {{ type = "gap", name = "stop", node_i = 4, node_j = 5, k = 1e5, gap = 0.002 }} ]
masses = [ {{ node = 3, m = 20.0 }}, {{ node = 4, m = 20.0 }} ]

[damping]
rayleigh = {{ a0 = 1.0 }}

{loads}

[analysis]
dt = 2e-3
t_end = 1.0
method = "cq"
bilateral_reference = true

[output]
{output}
"""

GROUND_MOTION = """
[[loads.ground_motion]]
file = "sine.txt"
units = "g"
dt = 0.01
direction = "ux"
"""

PUSH = """
[[loads.nodal]]
node = 3
ux = 50.0
time_function = { type = "half_sine", duration = 0.1 }
"""


def write_frame(tmp_path, *, output='floor_spectra = [4, 1]\nspectra_periods = { min = 0.05, max = 2.0, count = 30 }',
                loads=GROUND_MOTION):
    """The frame model in ``tmp_path`` with its record; returns the model file's path."""
    t = np.arange(0.0, 1.0, 0.01)
    np.savetxt(tmp_path / "sine.txt", 0.2 * np.sin(2 * np.pi * 2.5 * t) * np.minimum(t / 0.3, 1.0))
    path = tmp_path / "frame.toml"
    path.write_text(FRAME.format(loads=loads, output=output))
    return path


# ---------------------------------------------------------------------- the spectrum itself
def test_the_spectrum_is_the_batch_spectrum_for_every_period_and_record():
    from unilateral.analysis.response_spectrum import response_spectrum

    rng = np.random.default_rng(3)
    records = rng.normal(size=(600, 2))
    periods = period_grid(0.03, 3.0, 12)
    Sa = pseudo_acceleration(records, 0.01, periods, 0.05)
    assert Sa.shape == (12, 2)
    for k in range(2):
        expected = response_spectrum(SimpleNamespace(acceleration=records[:, k], dt=0.01), periods, 0.05)
        np.testing.assert_allclose(Sa[:, k], expected, rtol=1e-12)


def test_an_undamped_oscillator_at_resonance_grows_as_the_closed_form():
    """u'' + w^2 u = -A sin(w t) from rest: u = -A/(2 w^2) (sin w t - w t cos w t)."""
    A, T, cycles = 1.5, 0.4, 6
    w = 2 * np.pi / T
    dt = T / 400
    t = np.arange(0.0, cycles * T + dt / 2, dt)
    Sa = pseudo_acceleration(A * np.sin(w * t), dt, [T], damping=0.0)[0]
    fine = np.linspace(0.0, t[-1], 200_001)
    exact = A / 2 * np.max(np.abs(np.sin(w * fine) - w * fine * np.cos(w * fine)))
    assert Sa == pytest.approx(exact, rel=1e-3)


def test_a_stiff_oscillator_gives_the_peak_ground_acceleration():
    dt = 0.002
    t = np.arange(0.0, 4.0, dt)
    a = np.sin(2 * np.pi * 1.3 * t) + 0.5 * np.sin(2 * np.pi * 3.1 * t + 0.4)
    Sa = pseudo_acceleration(a, dt, [0.004], damping=0.05)[0]
    assert Sa == pytest.approx(np.max(np.abs(a)), rel=5e-3)


@pytest.mark.parametrize("kwargs, message", [
    (dict(periods=[0.0]), "periods must be finite and > 0"),
    (dict(damping=1.0), "damping must be in [0, 1)"),
    (dict(dt=-1.0), "dt must be finite and > 0"),
])
def test_bad_arguments_name_themselves(kwargs, message):
    args = dict(acceleration=np.ones(5), dt=0.01, periods=[0.1], damping=0.05) | kwargs
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace(")", r"\)")):
        pseudo_acceleration(**args)


# ---------------------------------------------------------------------- the run's outputs
@pytest.fixture(scope="module")
def frame_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("spectra")
    out = folder / "out"
    result = run_model_file(write_frame(folder), out)
    return out, result


def _columns(path):
    header, *rows = path.read_text().splitlines()
    values = np.array([[float(x) for x in row.split(",")] for row in rows])
    return {name: values[:, k] for k, name in enumerate(header.split(","))}


def test_the_run_writes_the_spectra_with_their_units_and_lists_them(frame_run):
    out, result = frame_run
    columns = _columns(out / "spectra.csv")
    assert list(columns) == ["period [s]", "Sa:ground [m/s^2]", "Sa:unilateral:4 [m/s^2]", "Sa:unilateral:1 [m/s^2]",
                             "Sa:bilateral:4 [m/s^2]", "Sa:bilateral:1 [m/s^2]"]
    np.testing.assert_allclose(columns["period [s]"], period_grid(0.05, 2.0, 30))
    manifest = json.loads((out / "manifest.json").read_text())["files"]
    assert {"spectra.csv", "spectra.png", "model.png"} <= set(manifest)
    assert (out / "spectra.png").stat().st_size > 0
    assert any(path.endswith("spectra.png") for path in result["figures"])


def test_the_floor_spectrum_at_the_ground_is_the_input_spectrum(frame_run):
    out, _ = frame_run
    columns = _columns(out / "spectra.csv")
    for case in ("unilateral", "bilateral"):
        np.testing.assert_allclose(columns[f"Sa:{case}:1 [m/s^2]"], columns["Sa:ground [m/s^2]"], rtol=1e-12)
    assert not np.allclose(columns["Sa:unilateral:4 [m/s^2]"], columns["Sa:ground [m/s^2]"])


def test_the_spectra_are_those_of_the_accelerations_in_results_nc(frame_run):
    from unilateral.io.results import open_results

    out, _ = frame_run
    ds = open_results(out / "results.nc")
    periods = ds["period"].values
    dt = float(ds["time"].values[1] - ds["time"].values[0])
    ag = ds["ground_acceleration"].sel(case="unilateral").values[:, 0]
    np.testing.assert_allclose(ds["ground_spectrum"].values, pseudo_acceleration(ag, dt, periods), rtol=1e-10)
    absolute = ds["absolute_acceleration"].sel(case="bilateral", dof="4.ux").values
    np.testing.assert_allclose(ds["floor_spectrum"].sel(case="bilateral", floor="4").values,
                               pseudo_acceleration(absolute, dt, periods), rtol=1e-10)
    assert ds["ground_spectrum"].attrs["damping"] == 0.05 and ds["ground_spectrum"].attrs["direction"] == "ux"


def test_the_summary_gives_the_peak_sa_and_its_period(frame_run):
    out, _ = frame_run
    spectra = json.loads((out / "summary.json").read_text())["spectra"]
    columns = _columns(out / "spectra.csv")
    k = int(np.argmax(columns["Sa:ground [m/s^2]"]))
    assert spectra["damping"] == 0.05 and spectra["direction"] == "ux"
    assert spectra["ground"] == {"Sa": pytest.approx(columns["Sa:ground [m/s^2]"][k]),
                                 "period": pytest.approx(columns["period [s]"][k])}
    top = spectra["floors"]["unilateral"]["4"]
    assert top["Sa"] == pytest.approx(columns["Sa:unilateral:4 [m/s^2]"].max())


def test_without_a_ground_motion_there_are_no_spectra(tmp_path):
    out = tmp_path / "out"
    result = run_model_file(write_frame(tmp_path, loads=PUSH), out)
    assert not (out / "spectra.csv").exists() and not (out / "spectra.png").exists()
    assert "spectra" not in result and (out / "model.png").is_file()


def test_the_input_spectrum_alone_by_default(tmp_path):
    out = tmp_path / "out"
    result = run_model_file(write_frame(tmp_path, output=""), out)
    assert list(_columns(out / "spectra.csv")) == ["period [s]", "Sa:ground [m/s^2]"]
    assert len(_columns(out / "spectra.csv")["period [s]"]) == 100
    assert "floors" not in result["spectra"]


# ---------------------------------------------------------------------- the [output] keys
@pytest.mark.parametrize("output, message", [
    ("spectra_damping = 1.5", "output.spectra_damping = 1.5: must be < 1"),
    ("spectra_damping = -0.1", "output.spectra_damping = -0.1: must be >= 0"),
    ('floor_spectra = [4, ""]', 'output.floor_spectra[1] = "": expected an integer or a non-empty string'),
    ("spectra_periods = { min = 2.0, max = 1.0 }", "output.spectra_periods: min must be < max"),
    ("spectra_periods = { count = 1 }", "output.spectra_periods.count = 1: must be >= 2"),
    ("spectra_periods = { min = -1.0 }", "output.spectra_periods.min = -1.0: must be > 0"),
    ("spectra_periods = { mni = 0.1 }", 'output.spectra_periods.mni: unknown key (did you mean "min"?'),
    ("spectra_dampin = 0.02", 'output.spectra_dampin: unknown key (did you mean "spectra_damping"?'),
])
def test_bad_output_keys_name_the_key_and_value(tmp_path, output, message):
    with pytest.raises(ModelFileError) as info:
        load_model_file(write_frame(tmp_path, output=output))
    assert message in str(info.value)


@pytest.mark.parametrize("output, message", [
    ("floor_spectra = [4, 99]", "output.floor_spectra[1] = 99: no node 99 (nodes are 1..5)"),
    ("floor_spectra = [4, 4]", "output.floor_spectra[1] = 4: node given twice"),
    ("spectra_periods = { min = 5.0 }", "output.spectra_periods: min must be < max, got min=5 and max=4"),
])
def test_floor_nodes_and_periods_are_checked_before_solving(tmp_path, output, message):
    path = write_frame(tmp_path, output=output)
    with pytest.raises(ModelFileError) as info:
        run_model_file(path, tmp_path / "out")
    assert message in str(info.value)
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
    result = CliRunner().invoke(main, ["run", str(path), "--out", str(tmp_path / "cli")])
    assert result.exit_code == 1 and message in result.output
