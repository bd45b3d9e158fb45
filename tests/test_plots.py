"""unilateral.figures.plots: the house style without side effects, atomic saving."""

import os

import matplotlib as mpl
import numpy as np
import pytest

from unilateral.figures import plots

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def simple_figure():
    fig, ax = plots._figure((plots.PAGE_WIDTH, 3.0))
    t = np.linspace(0, 1, 11)
    ax.plot(t, t)
    return fig


def test_plotting_leaves_rcparams_alone():
    before = dict(mpl.rcParams)
    styled = plots._styled(lambda: dict(mpl.rcParams))()
    assert styled["pdf.fonttype"] == 42 and dict(mpl.rcParams) == before


def test_save_figure(tmp_path):
    fig = simple_figure()
    paths = plots.save_figure(fig, tmp_path / "fig2.v1")
    assert [p.name for p in paths] == ["fig2.v1.png", "fig2.v1.pdf"]
    png, pdf = (p.read_bytes() for p in paths)
    assert png.startswith(PNG_SIGNATURE) and pdf.startswith(b"%PDF") and len(png) > 1000
    width, height = np.frombuffer(png[16:24], dtype=">u4")
    assert (width, height) == (round(6.3 * 150), round(3.0 * 150))


def test_save_figure_is_atomic(tmp_path, monkeypatch):
    fig = simple_figure()
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


def test_units_are_drawn_with_superscripts_and_ground_motions_are_named():
    from unilateral.figures.results import _excitation_label, pretty_unit

    assert pretty_unit("m/s^2") == "m/s\u00b2" and pretty_unit("s^-1") == "s\u207b\u00b9" and pretty_unit("kN m") == "kN m"
    assert _excitation_label("0:ux") == "horizontal ground acceleration"
    assert _excitation_label("1:uy") == "vertical ground acceleration"
