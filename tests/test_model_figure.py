"""The model figure: every part named once, names apart, units in mathtext, a legend of the kinds,
the first modes; `unilateral plot --model` and `run` writing model.png and listing it."""

import itertools
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from unilateral.cli import main
from unilateral.figures.model import ModelDrawing, model_figure, model_file_drawing

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

#: A portal frame with a tension-only brace on two rigid footings (four patches each) on
#: Winkler-Kelvin soil, pushed at the top (kN, m, s).
FOOTINGS = """
units = { length = "m", force = "kN", time = "s" }
nodes = [ { id = 1, x = 0.0, y = 0.0 }, { id = 2, x = 6.0, y = 0.0 }, { id = 11, x = 0.0, y = 3.0 },
          { id = 12, x = 6.0, y = 3.0 } ]
elements = [
  { type = "beam", name = "c1", node_i = 1, node_j = 11, E = 3e7, A = 0.2, I = 2e-3 },
  { type = "beam", name = "c2", node_i = 2, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 },
  { type = "beam", name = "b", node_i = 11, node_j = 12, E = 3e7, A = 0.2, I = 2e-3 },
]
unilateral = [ { type = "cable", name = "brace", node_i = 1, node_j = 12, E = 2e8, A = 1e-4 } ]
masses = [ { node = 11, m = 20.0 }, { node = 12, m = 20.0 } ]

[[foundations]]
name = "A"
node = 1
width = 2.0
length = 2.0
patches = 4
mass = 2.0
J = 0.5
soil = { model = "winkler-kelvin", k = 4e4, c = 4e2 }

[[foundations]]
name = "B"
node = 2
width = 2.0
length = 2.0
patches = 4
mass = 2.0
J = 0.5
soil = { model = "winkler-kelvin", k = 4e4, c = 4e2 }

[loads.gravity]
g = "standard"

[[loads.nodal]]
node = 11
ux = 50.0
time_function = { type = "half_sine", duration = 0.1 }

[analysis]
dt = 5e-3
t_end = 0.3
method = "cq"
"""


@pytest.fixture(scope="module")
def footings_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("footings") / "footings.toml"
    path.write_text(FOOTINGS)
    return path


def _model_files(footings_file):
    return [EXAMPLES / f"{name}.toml" for name in ("liolios1990", "pounding", "winkler_beam", "yielding_frame")] + [
        footings_file]


def _names(ax, category):
    """The texts of the names of ``category`` drawn on ``ax`` (their ``gid`` is ``"<category>:<name>"``)."""
    return [t.get_text() for t in ax.texts if str(t.get_gid() or "").startswith(f"{category}:")]


@pytest.fixture(scope="module")
def figures(footings_file):
    """``{stem: (document, drawing, figure)}`` of every model file."""
    out = {}
    for path in _model_files(footings_file):
        drawing = model_file_drawing(path)
        out[path.stem] = (tomllib.loads(path.read_text()), drawing, model_figure(drawing))
    return out


def test_one_label_per_named_unilateral_element_and_element(figures):
    for stem, (document, drawing, fig) in figures.items():
        ax = fig.axes[0]
        unilateral = sorted(entry["name"] for entry in document.get("unilateral", ()))
        assert sorted(_names(ax, "unilateral")) == unilateral == sorted(drawing.unilateral_names), stem
        elements = sorted(entry["name"] for entry in document.get("elements", ()))
        assert sorted(_names(ax, "element")) == elements, stem
        nodes = sorted(str(node["id"]) for node in document["nodes"])
        assert sorted(_names(ax, "node")) == nodes, stem


def test_footings_and_their_patches_are_named(figures):
    _, drawing, fig = figures["footings"]
    ax = fig.axes[0]
    assert sorted(_names(ax, "footing")) == ["A", "B"]
    assert sorted(_names(ax, "patch")) == sorted(["1", "2", "3", "4"] * 2)
    assert [f.patch_names for f in drawing.footings] == [tuple(f"{n}.{k}" for k in range(1, 5)) for n in "AB"]
    assert drawing.footings[0].x0 == pytest.approx(-1.0) and drawing.footings[0].x1 == pytest.approx(1.0)


def test_names_do_not_overlap(figures):
    for stem, (_, _, fig) in figures.items():
        renderer = fig.canvas.get_renderer()
        boxes = [t.get_window_extent(renderer) for t in fig.axes[0].texts if t.get_gid()]
        overlapping = [(a, b) for a, b in itertools.combinations(boxes, 2)
                       if min(a.x1, b.x1) > max(a.x0, b.x0) and min(a.y1, b.y1) > max(a.y0, b.y0)]
        assert not overlapping, stem


def test_units_in_mathtext_and_a_legend_of_the_kinds(figures):
    expected = {"liolios1990": {"beam", "rigid link", "soil spring (compression only)", "support", "mass"},
                "pounding": {"beam", "gap (pounding link)", "support", "mass"},
                "winkler_beam": {"beam", "soil spring (compression only)"},
                "yielding_frame": {"beam", "rigid link", "soil spring (compression only)", "plastic hinge", "mass"},
                "footings": {"beam", "cable (tension only)", "footing (numbered contact patches)", "mass"}}
    for stem, (_, _, fig) in figures.items():
        ax = fig.axes[0]
        assert ax.get_xlabel() == r"$x$ [$\mathrm{m}$]" and ax.get_ylabel() == r"$y$ [$\mathrm{m}$]"
        legend = {t.get_text() for t in fig.legends[0].get_texts()}
        assert expected[stem] <= legend, (stem, legend)


def test_the_first_modes_are_drawn_with_their_periods(figures):
    from unilateral.structure.modes import modes
    from unilateral.modelfile import load_model_file

    _, drawing, fig = figures["pounding"]
    periods = modes(load_model_file(EXAMPLES / "pounding.toml").model, count=3)["period"]
    assert len(fig.axes) == 4
    assert [ax.get_title() for ax in fig.axes[1:]] == [f"mode {k + 1}: T = {T:.3g} s" for k, T in enumerate(periods)]
    shape = drawing.modes[0][1]
    assert max(np.max(np.abs(d)) for d in shape.values()) == pytest.approx(1.0)  # largest component 1
    assert shape["1"] == (0.0, 0.0)                                            # a support does not move


def test_supports_hinges_and_ground_elements(figures):
    _, pounding, _ = figures["pounding"]
    assert sorted(pounding.supports) == [(n, ("ux", "uy", "rz")) for n in ("1", "2", "5", "6")]
    _, frame, _ = figures["yielding_frame"]
    hinges = {name: (node, other) for name, node, other in frame.hinges}
    assert hinges["B1_1.i"] == ("11", "12") and hinges["B1_1.j"] == ("12", "11") and hinges["C1_1.base"] == ("1", "11")
    soil = {name: direction for kind, name, _, direction in frame.grounded if kind == "soil"}
    assert soil["F1.left"] == pytest.approx((0.0, -1.0))                      # the soil is below the node
    assert ("1", "101") in frame.links


def test_the_drawing_survives_json(figures):
    for stem, (_, drawing, _) in figures.items():
        again = ModelDrawing.from_json(drawing.to_json())
        assert json.loads(again.to_json()) == json.loads(drawing.to_json()), stem


def test_plot_model_writes_model_png_and_joins_a_run_manifest(footings_file, tmp_path):
    run_out = tmp_path / "run"
    result = CliRunner().invoke(main, ["run", str(footings_file), "--out", str(run_out)])
    assert result.exit_code == 0, result.output
    manifest = json.loads((run_out / "manifest.json").read_text())["files"]
    assert "model.png" in manifest and (run_out / "model.png").is_file()
    (run_out / "model.png").unlink()
    result = CliRunner().invoke(main, ["plot", "--model", str(footings_file), "--out", str(run_out)])
    assert result.exit_code == 0, result.output
    assert result.output.strip() == str(run_out / "model.png") and (run_out / "model.png").is_file()
    result = CliRunner().invoke(main, ["plot", "--model", str(EXAMPLES / "pounding.toml"), "--out",
                                       str(tmp_path / "new"), "--figures", "png,svg"])
    assert result.exit_code == 0, result.output
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == ["model.png", "model.svg"]


def test_plot_needs_results_or_a_model_and_names_a_bad_key(tmp_path):
    result = CliRunner().invoke(main, ["plot"])
    assert result.exit_code == 2 and "give either RESULTS" in result.output
    bad = tmp_path / "bad.toml"
    bad.write_text(FOOTINGS.replace("A = 0.2, I", "A = -0.2, I", 1))
    result = CliRunner().invoke(main, ["plot", "--model", str(bad), "--out", str(tmp_path / "out")])
    assert result.exit_code == 1 and "elements[0].A = -0.2: must be > 0" in result.output
    assert not (tmp_path / "out").exists()
