"""Fast figures: lines decimated to min/max envelopes that keep every peak, fixed margins that clip
no text."""

import numpy as np
import pytest
import xarray as xr

import unilateral
from unilateral.figures import results as R
from unilateral.figures.plots import MAX_POINTS, envelope

EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples"


def test_envelope_keeps_short_curves_as_they_are():
    t = np.linspace(0.0, 1.0, MAX_POINTS)
    y = np.sin(40 * t)
    x2, y2 = envelope(t, y)
    np.testing.assert_array_equal(x2, t)
    np.testing.assert_array_equal(y2, y)


def test_envelope_keeps_the_extremes_of_every_bucket():
    rng = np.random.default_rng(3)
    n = 100_003
    t = np.arange(n) * 1e-4
    y = np.cumsum(rng.standard_normal(n))
    y[77_777] = 1e3                                              # one sharp spike
    x2, y2 = envelope(t, y)
    assert len(x2) <= MAX_POINTS + 2 and np.all(np.diff(x2) > 0)
    assert x2[0] == t[0] and x2[-1] == t[-1]
    assert y2.max() == 1e3 and x2[y2.argmax()] == t[77_777]
    assert y2.min() == y.min() and x2[y2.argmin()] == t[y.argmin()]
    # in any stretch of the time axis longer than a bucket the drawn band equals the true one
    size = -(-n // (MAX_POINTS // 2))
    for start in range(0, n - 3 * size, 7919):
        stop = start + 3 * size
        kept = (x2 >= t[start]) & (x2 <= t[stop - 1])
        inner = slice(start + size, stop - size)
        assert y2[kept].max() >= y[inner].max() and y2[kept].min() <= y[inner].min()
    # every kept sample is a true sample
    index = np.searchsorted(t, x2)
    np.testing.assert_array_equal(y[index], y2)


def test_envelope_of_a_parametric_curve_keeps_both_coordinates_extremes():
    s = np.linspace(0.0, 50.0, 40_001)
    x, y = np.cos(s) * (1 + s), np.sin(3 * s)
    _, x2, y2 = envelope(s, x, y)
    assert len(x2) <= MAX_POINTS + 2
    assert (x2.max(), x2.min(), y2.max(), y2.min()) == (x.max(), x.min(), y.max(), y.min())


@pytest.fixture(scope="module")
def datasets(tmp_path_factory):
    """results.nc of a long rocking run (5000 steps) and of the pounding frames (a gap, a record)."""
    out = tmp_path_factory.mktemp("figures")
    unilateral.run(EXAMPLES / "liolios1990.toml", out / "rocking", figures=(), t_end=0.5, dt=1e-4,
                   method="modal")
    unilateral.run(EXAMPLES / "pounding.toml", out / "pounding", figures=(), t_end=1.6)
    return {name: xr.load_dataset(out / name / "results.nc") for name in ("rocking", "pounding")}


DRAWINGS = (R.history_figure, R.constraints_figure, R.force_deformation_figure, R.gaps_figure,
            R.ground_motion_figure, R.base_forces_figure, R.energy_figure)


@pytest.mark.parametrize("name", ["rocking", "pounding"])
def test_figures_draw_no_more_points_than_needed_and_keep_the_peaks(datasets, name):
    ds = datasets[name]
    steps = ds.sizes["time"]
    drawn = 0
    for draw in DRAWINGS:
        fig = draw(ds)
        if fig is None:
            continue
        drawn += 1
        for ax in fig.axes:
            for line in ax.get_lines():
                x = np.asarray(line.get_xdata())
                assert len(x) <= max(MAX_POINTS + 2, 2) or len(x) < steps, (draw.__name__, len(x))
    assert drawn >= (5 if name == "rocking" else 4)
    if name == "rocking":
        assert steps == 5001
        fig = R.history_figure(ds)
        y = ds["node_displacement"].sel(case="unilateral", node="3", component="uy").values
        line = fig.axes[0].get_lines()[0]
        factor = np.max(line.get_ydata()) / y.max()               # the figure's length unit (mm)
        assert len(line.get_xdata()) <= MAX_POINTS + 2
        factor = min((1.0, 1e3), key=lambda f: abs(f - factor))
        assert np.max(line.get_ydata()) == pytest.approx(factor * y.max(), rel=1e-15)
        assert np.min(line.get_ydata()) == pytest.approx(factor * y.min(), rel=1e-15)


@pytest.mark.parametrize("name", ["rocking", "pounding"])
def test_fixed_margins_clip_no_text(datasets, name):
    ds = datasets[name]
    for draw in DRAWINGS:
        fig = draw(ds)
        if fig is None:
            continue
        fig.canvas.draw()
        renderer = fig.canvas.get_renderer()
        box = fig.get_tightbbox(renderer)                         # inches: everything drawn, text included
        width, height = fig.get_size_inches()
        tol = 1.0 / fig.dpi
        assert box.x0 >= -tol and box.y0 >= -tol and box.x1 <= width + tol and box.y1 <= height + tol, (
            draw.__name__, box.bounds, (width, height))
        for ax in fig.axes:                                       # a y label no longer than its axes
            label = ax.yaxis.label.get_window_extent(renderer)
            slack = 0.15 * fig.dpi
            assert label.y0 >= ax.bbox.y0 - slack and label.y1 <= ax.bbox.y1 + slack, (
                draw.__name__, ax.yaxis.label.get_text())


def test_axes_state_their_units(datasets):
    ds = datasets["rocking"]
    assert R.history_figure(ds).axes[0].get_xlabel() == "time t [s]"
    assert R.history_figure(ds).axes[0].get_ylabel().endswith("[mm]")           # 0.003 m drawn in mm
    top, low = R.base_forces_figure(ds).axes
    assert top.get_ylabel() == "base shear [kN]" and low.get_ylabel().endswith("[kN m]")
    panel = R.constraints_figure(ds).axes[0]
    assert panel.get_ylabel() == "opening v [mm]"
