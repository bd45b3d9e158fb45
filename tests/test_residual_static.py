"""The static residual (plastic deformations frozen, excitation removed), the roof drift ratio and
``[analysis] t_end = "record"`` with ``t_after`` (issue 31, item 5)."""

import numpy as np
import pytest

import unilateral
from unilateral.analysis.residual import ResidualUnavailable, roof_drift, static_residual
from unilateral.modelfile import ModelFileError, load_model_file

from hinge_frame import hinge_frame_toml


def _spec(tmp_path, text, name="frame.toml"):
    path = tmp_path / name
    path.write_text(text)
    return load_model_file(path)


def _record_text(t_after=10.0):
    return hinge_frame_toml().replace("t_end = 8.0", f't_end = "record"\nt_after = {t_after}')


def test_t_end_record_is_the_record_plus_t_after(tmp_path):
    spec = _spec(tmp_path, _record_text(2.5))
    assert spec.analysis["t_end"] == pytest.approx(5.0 + 2.5, abs=1e-12)      # 501 samples of 0.01 s
    assert spec.analysis["t_after"] == 2.5


def test_t_after_with_a_number_t_end_and_record_without_motion_are_refused(tmp_path):
    with pytest.raises(ModelFileError, match=r'analysis.t_after = 1.0: applies with t_end = "record" only'):
        _spec(tmp_path, hinge_frame_toml().replace("t_end = 8.0", "t_end = 8.0\nt_after = 1.0"))
    text = hinge_frame_toml()
    text = text[:text.index("[[loads.ground_motion]]")] + '[analysis]\ndt = 5e-3\nt_end = "record"\n'
    with pytest.raises(ModelFileError, match=r'analysis.t_end = "record": the model has no \[\[loads.ground_motion'):
        _spec(tmp_path, text, "nomotion.toml")


@pytest.fixture(scope="module")
def free_vibration(tmp_path_factory):
    """The undamped yielding hinge frame under its record and 10 s of free vibration after it."""
    spec = _spec(tmp_path_factory.mktemp("residual"), _record_text(10.0))
    return spec, unilateral.run(spec, figures=())


def test_static_residual_is_an_equilibrium_at_rest(free_vibration):
    """Started at rest in the static residual state (u_s, the last step's plastic rotations), under the
    gravity alone, the frame does not move and no hinge flows: an independent check of
    K u_s = q_s + F v (the dynamics of the library, not the static solve)."""
    spec, a = free_vibration
    sol = a.solutions["unilateral"]
    model = spec.structure.to_model()
    u_s = static_residual(model, spec.load.constant, sol.v[-1])
    assert np.abs(sol.v[-1]).max() > 1e-3                                   # the frame yielded
    rest = unilateral.solve(model, lambda t: spec.load.constant, dt=5e-3, t_end=1.0,
                            initial={"u0": u_s, "v0": sol.v[-1]})
    assert rest.success, rest.message
    scale = np.abs(sol.u).max()
    assert np.abs(rest.u - u_s).max() <= 1e-9 * scale
    assert np.abs(rest.v - sol.v[-1]).max() <= 1e-9 * np.abs(sol.v[-1]).max()


def test_free_vibration_oscillates_about_the_static_residual(free_vibration):
    """After the record the undamped frame vibrates about the static residual: the mean roof drift over
    the 10 s of free vibration is the static one to a fraction of the vibration's amplitude (the mean of
    a few modes' cosines over about 14 first periods), while the last step's drift is not."""
    spec, a = free_vibration
    sol = a.solutions["unilateral"]
    after = sol.t > 5.0 + 1e-9
    assert np.abs(sol.v[after] - sol.v[-1]).max() <= 1e-12 * np.abs(sol.v[-1]).max()   # no yield after it
    drift, height = roof_drift(spec.structure, sol.u)
    peak = a["results"]["unilateral"]["roof_drift_ratio"]
    static = peak["residual_static"]
    amplitude = 0.5 * np.ptp(drift[after] / height)
    assert abs(np.mean(drift[after] / height) - static) <= 0.05 * amplitude
    assert peak["residual"] == pytest.approx(drift[-1] / height, rel=1e-12)
    assert peak["value"] == pytest.approx(drift[np.argmax(np.abs(drift))] / height, rel=1e-12)
    storeys = a["results"]["unilateral"]["residual_drift_static"]["storeys"]
    u_s = static_residual(spec.structure.to_model(), spec.load.constant, sol.v[-1])
    roof, _ = roof_drift(spec.structure, u_s)
    assert sum(s["drift"] for s in storeys.values()) == pytest.approx(float(roof[0]), rel=1e-9)


def test_an_elastic_case_returns_to_the_gravity_state(free_vibration):
    """The bilateral case (no yielding) comes back to the static state under gravity: zero sway."""
    _, a = free_vibration
    assert abs(a["results"]["bilateral"]["roof_drift_ratio"]["residual_static"]) < 1e-12


def test_a_model_without_matrices_is_refused():
    with pytest.raises(ResidualUnavailable, match="not a matrix model"):
        static_residual(object(), np.zeros(1), np.zeros(0))


@pytest.mark.parametrize("name", ["liolios1990.toml", "pounding.toml"])
def test_with_contacts_and_nothing_frozen_it_is_the_initial_static_state(name):
    """A model of contacts alone (nothing yields or slips): the static residual is the static state under
    the gravity the run started from (:func:`unilateral.initial.static_state`, another code path), to
    1e-9 of the peak displacement; the contacts are solved again, not frozen."""
    from pathlib import Path

    spec = load_model_file(Path(__file__).resolve().parent.parent / "examples" / name)
    model = spec.model
    assert not np.asarray(model.law.rate).any() and model.m > 0
    sol = unilateral.solve(model, spec.load, dt=spec.analysis["dt"], t_end=min(spec.analysis["t_end"], 0.3))
    k = int(np.argmax(np.abs(sol.v - sol.v[0]).sum(axis=1)))                 # a step with a contact open
    assert sol.success and np.abs(sol.v[k] - sol.v[0]).max() > 0
    np.testing.assert_array_equal(spec.load(0.0), spec.load.constant)
    u_s = static_residual(model, spec.load.constant, sol.v[k])
    assert np.abs(u_s - sol.u[0]).max() <= 1e-9 * np.abs(sol.u).max()
