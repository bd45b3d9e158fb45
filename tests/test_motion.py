"""Pictures of the motion (unilateral.figures.motion): the shape drawn is the beam's elastic shape,
the instant is the peak drift, the marks are the constraints' states, the animation has its
frames, bad input is refused by name."""

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

from unilateral.cli import main
from unilateral.figures import FigureDataError
from unilateral.figures.motion import ACTIVE_TOLERANCE, Motion, _beam_line, animate, deformed_shape_figure

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


@pytest.fixture(scope="module")
def pounding(tmp_path_factory):
    out = tmp_path_factory.mktemp("pounding")
    result = CliRunner().invoke(main, ["run", str(EXAMPLES / "pounding.toml"), "--out", str(out), "--t-end", "1.5",
                                       "--figures", "none"])
    assert result.exit_code == 0, result.output
    with xr.open_dataset(out / "results.nc") as ds:
        return out, ds.load()


@pytest.mark.parametrize("angle", [0.0, 30.0, 90.0])
def test_a_beam_is_drawn_with_its_exact_elastic_shape_under_an_end_load(angle):
    """A cantilever under a tip load deflects as the cubic w(x) = P x^2 (3 L - x) / (6 EI): the cubic
    of its end displacements and rotations is that shape, in any orientation of the beam."""
    L, P, EI, scale = 3.0, 10.0, 2e3, 5.0
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    w_tip, rot_tip = P * L**3 / (3 * EI), P * L**2 / (2 * EI)
    a, b = np.array([1.0, 2.0]), np.array([1.0, 2.0]) + L * np.array([c, s])
    tip = np.array([-s * w_tip, c * w_tip, rot_tip])          # transverse deflection in global x, y
    line = _beam_line(a, b, np.zeros(3), tip, scale)
    x = np.linspace(0.0, L, line.shape[0])
    exact = a + np.outer(x, [c, s]) + scale * np.outer(P * x**2 * (3 * L - x) / (6 * EI), [-s, c])
    assert np.max(np.abs(line - exact)) <= 1e-12 * L


def test_the_default_instant_is_the_peak_drift_and_the_marks_are_the_constraints_states(pounding):
    _, ds = pounding
    motion = Motion.of(ds)
    k = motion.peak_instant()
    base = motion.xy[:, 1] == motion.xy[:, 1].min()
    relative = motion.d[:, :, 0] - motion.d[:, base, 0].mean(axis=1, keepdims=True)
    assert np.max(np.abs(relative[k])) == pytest.approx(np.max(np.abs(relative)), rel=1e-15)
    v = ds["v"].sel(case="unilateral").values
    open_gap = v > ACTIVE_TOLERANCE * np.abs(v).max()
    assert np.array_equal(motion.marks["open"], open_gap)       # the pounding model's constraints are gaps
    assert 0 < motion.marks["open"].sum() < motion.marks["open"].size     # the gap opens and closes
    scale = motion.scale([k])
    assert np.max(np.abs(motion.d[k, :, :2])) * scale == pytest.approx(0.1 * motion.size)
    fig = deformed_shape_figure(ds)
    title = fig.axes[0].get_title()
    assert "case unilateral" in title and f"t = {motion.t[k]:.3f} s" in title and f"x {scale:.3g}" in title


def test_the_animation_is_a_gif_with_its_frames_written_atomically(pounding, tmp_path):
    from PIL import Image

    _, ds = pounding
    path = animate(ds, tmp_path / "motion.gif", frames=5, fps=5)
    with Image.open(path) as gif:
        assert gif.format == "GIF" and gif.n_frames == 5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["motion.gif"]      # no temporary file left


@pytest.mark.parametrize("kwargs, match", [
    (dict(path="motion.mp4"), "written as a GIF"),
    (dict(frames=1), "frames must be an integer >= 2, got 1"),
    (dict(fps=0), "fps must be an integer >= 1, got 0"),
    (dict(case="other"), "case='other' is not in this results.nc; valid: unilateral"),
])
def test_bad_animation_requests_are_refused_by_name(pounding, tmp_path, kwargs, match):
    _, ds = pounding
    path = tmp_path / kwargs.pop("path", "motion.gif")
    with pytest.raises((ValueError, FigureDataError), match=match):
        animate(ds, path, **kwargs)
    with pytest.raises(ValueError, match=r"time = 99 s is not in the run: valid 0 <= time <= 1.5"):
        deformed_shape_figure(ds, time=99)


def test_a_results_file_without_a_2d_drawing_is_refused_with_the_reason(pounding):
    _, ds = pounding
    three_d = ds.copy()
    drawing = json.loads(ds.attrs["model_drawing"])
    drawing["coords"] = {k: [*xy, 0.0] for k, xy in drawing["coords"].items()}
    three_d.attrs["model_drawing"] = json.dumps(drawing)
    with pytest.raises(FigureDataError, match="drawn for 2-D frames"):
        Motion.of(three_d)
    with pytest.raises(FigureDataError, match="model drawing and node_displacement"):
        Motion.of(ds.drop_vars("node_displacement"))


def test_plot_animate_writes_the_shape_and_the_motion(pounding, tmp_path):
    out, _ = pounding
    result = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path), "--figures", "none",
                                       "--animate"])
    assert result.exit_code == 0, result.output
    assert {p.name for p in tmp_path.iterdir()} >= {"deformed_shape.png", "motion.gif"}
