"""unilateral.figures: figure structure, labels with units, atomic saving."""

import os

import matplotlib as mpl
import numpy as np
import pytest
from matplotlib.figure import Figure

import unilateral as ul
from unilateral.figures import plots

UNITS = {"length": "m", "force": "kN", "time": "s"}
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def fake_solution(m, N=200):
    """Constraint ``i`` lifts off by ``(i+1) mm`` in the first half-period, bears load in the second."""
    t = np.linspace(0.0, 1.0, N + 1)
    s = np.sin(2 * np.pi * t)[:, None]
    scale = np.arange(1, m + 1)
    return ul.Solution(t=t, v=1e-3 * scale * np.maximum(s, 0), psi=-100.0 * scale * np.maximum(-s, 0),
                       psiL=-100.0 * scale * s, constraint_names=[f"c{i}" for i in range(m)])


def labels(ax):
    return ax.get_xlabel() + " " + ax.get_ylabel()


def test_plot_displacement():
    t = np.linspace(0, 1, 101)
    curves = {"with uplift": (t, np.sin(t)), "without uplift": (t, np.cos(t))}
    fig = plots.plot_displacement(curves, ylabel="vertical displacement of node 3 [mm]",
                                  title="Fig. 2", static=-0.667, units=UNITS)
    assert isinstance(fig, Figure) and len(fig.axes) == 1
    ax = fig.axes[0]
    assert len(ax.lines) == 3                                   # two curves and the static line
    assert "[mm]" in ax.get_ylabel() and "[s]" in ax.get_xlabel() and ax.get_title() == "Fig. 2"
    assert [x.get_text() for x in ax.get_legend().get_texts()] == [*curves, "static value"]
    assert len(plots.plot_displacement(curves, ylabel="y [m]").axes[0].lines) == 2


def test_plot_constraints_one_panel_each():
    sol = fake_solution(3)
    fig = plots.plot_constraints(sol, units=UNITS)
    assert len(fig.axes) == 6                                   # v axes, then the psi twins
    for k, name in enumerate(sol.constraint_names):
        ax, twin = fig.axes[k], fig.axes[3 + k]
        assert ax.get_title(loc="left") == name
        assert np.array_equal(ax.lines[0].get_ydata(), sol.v[:, k])
        assert np.array_equal(twin.lines[0].get_ydata(), sol.psi[:, k]) and len(twin.lines) == 1
        assert "m]" in ax.get_ylabel() and "[kN]" in twin.get_ylabel()
        assert ax.get_ylim()[0] / ax.get_ylim()[1] == pytest.approx(twin.get_ylim()[0] / twin.get_ylim()[1])
    assert "[$10^{-3}$ m]" in fig.axes[0].get_ylabel()          # millimetre uplifts: power in the label
    assert "[s]" in fig.axes[2].get_xlabel()


def test_plot_constraints_shows_the_largest_uplifts():
    sol = fake_solution(9)
    sol.v[:, 0] *= 100.0                                        # c0 now lifts off the most
    fig = plots.plot_constraints(sol, units=UNITS)
    assert len(fig.axes) == 12
    shown = [ax.get_title(loc="left") for ax in fig.axes[:6]]
    assert shown == ["c0", "c4", "c5", "c6", "c7", "c8"]
    assert "6 of 9" in fig.get_suptitle()


def test_plot_force_deformation():
    sol = fake_solution(4)
    deformation = dict(zip(sol.constraint_names, sol.v.T))
    force = dict(zip(sol.constraint_names, sol.psi.T))
    fig = plots.plot_force_deformation(deformation, force, units=UNITS, title="contact laws")
    assert len(fig.axes) == 4 and fig.get_suptitle() == "contact laws"
    for ax, name in zip(fig.axes, sol.constraint_names):
        assert len(ax.lines) == 1 and ax.get_title(loc="left") == name
        assert "m]" in ax.get_xlabel() and "[kN]" in ax.get_ylabel()
    with pytest.raises(ValueError, match="same elements"):
        plots.plot_force_deformation(deformation, {"c0": force["c0"]})


def test_plotting_leaves_rcparams_alone():
    before = dict(mpl.rcParams)
    plots.plot_constraints(fake_solution(2), units=UNITS)
    assert dict(mpl.rcParams) == before


def test_save_figure(tmp_path):
    t = np.linspace(0, 1, 11)
    fig = plots.plot_displacement({"a": (t, t)}, ylabel="y [m]")
    paths = plots.save_figure(fig, tmp_path / "fig2.v1")
    assert [p.name for p in paths] == ["fig2.v1.png", "fig2.v1.pdf"]
    png, pdf = (p.read_bytes() for p in paths)
    assert png.startswith(PNG_SIGNATURE) and pdf.startswith(b"%PDF") and len(png) > 1000
    width, height = np.frombuffer(png[16:24], dtype=">u4")
    assert (width, height) == (round(6.3 * 150), round(3.0 * 150))


def test_save_figure_is_atomic(tmp_path, monkeypatch):
    t = np.linspace(0, 1, 11)
    fig = plots.plot_displacement({"a": (t, t)}, ylabel="y [m]")
    (good,) = plots.save_figure(fig, tmp_path / "fig", formats=("png",))
    old = good.read_bytes()

    def broken(path, **kw):
        with open(path, "wb") as f:
            f.write(PNG_SIGNATURE)
        raise OSError("out of space")

    monkeypatch.setattr(fig, "savefig", broken)
    with pytest.raises(OSError, match="out of space"):
        plots.save_figure(fig, tmp_path / "fig", formats=("png",))
    assert good.read_bytes() == old and os.listdir(tmp_path) == ["fig.png"]
