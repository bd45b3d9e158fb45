"""Inputs whose outputs cannot be represented in double precision are refused by name.

Each once ran with exit 0 and infinite or NaN outputs: a mass of 1e-300 (periods), My or Fy of
1e-308 (ductility and force ratio NaN), spectra_periods.min = 1e-308 (Sa NaN) and
overturning_about = [1e308, 1e308] (every overturning moment inf). E = 1.18e21 (a column far
stiffer than the soil) is solved: its periods come from the stiff-separated coordinates.
"""

from pathlib import Path

import numpy as np
import pytest

from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.structure import Frame2D, Frame3D
from unilateral.structure.modes import modes

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "liolios1990.toml"
SOIL4 = '    { type = "soil", name = "soil4"'


def variant(tmp_path, *pairs, source=EXAMPLE):
    text = source.read_text()
    for old, new in pairs:
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "model.toml"
    path.write_text(text)
    return path


def test_tiny_mass_refused_naming_the_dof_and_mass(tmp_path):
    with pytest.raises(ModelFileError, match=r"mass 1e-300 of DOF 1\.uy is too small.*>= 1e-189"):
        load_model_file(variant(tmp_path, ("m = 40.0", "m = 1e-300")))


def test_tiny_mass_refused_by_frame2d():
    fr = Frame2D()
    fr.nodes([1, 2], [0.0, 0.0], [0.0, 3.0])
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("c", 1, 2, 3e7, 0.09, 6.75e-4)
    fr.mass(2, 1e-300)
    with pytest.raises(ValueError, match=r"mass 1e-300 of DOF 2\.u[xy]"):
        fr.build()


def test_small_but_representable_mass_is_kept():
    fr = Frame2D()
    fr.nodes([1, 2], [0.0, 0.0], [0.0, 3.0])
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("c", 1, 2, 3e7, 0.09, 6.75e-4)
    fr.mass(2, 1e-20)
    assert np.all(np.isfinite(modes(fr.build().to_model())["period"]))


@pytest.mark.parametrize("entry, arg", [
    ('{ type = "hinge", name = "h", beam = "column", end = "j", My = 1e-308, k = 1e5 }', "My"),
    ('{ type = "yield", name = "y", node = 1, k = 1e5, Fy = 1e-308 }', "Fy"),
    ('{ type = "yield", name = "y", node = 1, k = 1e5, Fy_t = 1.0, Fy_c = 1e-308 }', "Fy_c"),
])
def test_tiny_strength_refused_by_name(tmp_path, entry, arg):
    path = variant(tmp_path, (SOIL4, f"    {entry},\n{SOIL4}"))
    with pytest.raises(ModelFileError, match=rf"{arg}=1e-308 is below 1e-150"):
        load_model_file(path)


def test_tiny_3d_hinge_strength_refused():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, 3.0)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("c", 1, 2, E=3e7, A=0.09, Iy=6.75e-4, Iz=6.75e-4, G=1.25e7, J=1.1e-3)
    with pytest.raises(ValueError, match=r"Mz=1e-308 is below"):
        fr.hinge("h", "c", "i", My=10.0, Mz=1e-308)


def test_tiny_spectrum_period_refused(tmp_path):
    source = ROOT / "examples" / "yielding_frame.toml"
    path = variant(tmp_path, ("[output]\n", "[output]\nspectra_periods = { min = 1e-308 }\n"), source=source)
    (tmp_path / "records").symlink_to(ROOT / "examples" / "records")
    from unilateral.analysis.run import spectra_settings

    with pytest.raises(ModelFileError, match=r"spectra_periods: min = 1e-308 is below 1e-06"):
        spectra_settings(load_model_file(path))


def test_far_overturning_point_refused(tmp_path):
    path = variant(tmp_path, ("overturning_about = [-5.0, 0.0]", "overturning_about = [1e308, 1e308]"))
    with pytest.raises(ModelFileError, match=r"overturning_about = \[1e\+308, 1e\+308\].*x in \[-1e\+07, 1e\+07\]"):
        load_model_file(path)


def test_near_overturning_point_kept(tmp_path):
    path = variant(tmp_path, ("overturning_about = [-5.0, 0.0]", "overturning_about = [-500.0, 0.0]"))
    assert load_model_file(path).model.n == 5


def test_very_stiff_column_has_finite_periods(tmp_path):
    stiff = load_model_file(variant(tmp_path, ("E = 1.0", "E = 1.18e21")))
    period = modes(stiff.model)["period"]
    assert np.all(np.isfinite(period)) and np.all(period > 0)
    rigid = load_model_file(variant(tmp_path, ("E = 1.0", "E = 1e3")))         # nearly rigid, not split
    np.testing.assert_allclose(period, modes(rigid.model)["period"], rtol=1e-3)
