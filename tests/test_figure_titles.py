"""A title or label of a model file that is not valid mathtext (``title = "$\\frac{$"``): the run
draws it as plain text and writes everything, where matplotlib raised after the run was solved."""

from __future__ import annotations

from pathlib import Path

import pytest
from click.testing import CliRunner

from unilateral.cli import main
from unilateral.figures.plots import plain_text

EXAMPLE = Path(__file__).parents[1] / "examples" / "liolios1990.toml"


@pytest.mark.parametrize("text, drawn", [
    (r"$\frac{$", r"\$\frac{\$"), ("$$", r"\$\$"),
    (r"mass $m_1$ and $\alpha$", r"mass $m_1$ and $\alpha$"),         # valid mathtext: kept
    ("cost 5$", "cost 5$"), ("plain", "plain"), (r"\$ and $x", r"\$ and $x"),
])
def test_plain_text_escapes_only_what_is_not_mathtext(text, drawn):
    assert plain_text(text) == drawn


def test_a_title_and_label_that_are_not_mathtext_are_drawn_as_plain_text(tmp_path):
    source = EXAMPLE.read_text()
    assert 'title = "Liolios (1990)' in source and 'label = "vertical displacement of node 3 (m)"' in source
    text = "\n".join('title = "$\\\\frac{$"' if line.startswith('title = "Liolios (1990)') else line
                     for line in source.splitlines())
    text = text.replace('label = "vertical displacement of node 3 (m)"', 'label = "$^^{$ of node 3"')
    path = tmp_path / "model.toml"
    path.write_text(text)
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["run", str(path), "--out", str(out), "--t-end", "0.2"])
    assert result.exit_code == 0, result.output
    drawn = {p.name for p in out.glob("*.png")}
    assert {"fig2.png", "model.png", "constraints.png"} <= drawn
    assert (out / "results.nc").exists() and (out / "summary.json").exists()
    again = CliRunner().invoke(main, ["plot", str(out / "results.nc"), "--out", str(tmp_path / "again")])
    assert again.exit_code == 0, again.output
