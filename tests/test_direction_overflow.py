"""Direction vectors with huge components (> 1.3e154) are normalised without overflow.

Each case builds the same structure with a unit direction and with the direction scaled by
``1e200`` and checks the same answer; a zero or non-finite direction is refused by name.
"""

import numpy as np
import pytest

from unilateral.structure import Frame2D, Frame3D
from unilateral.structure.elements import length, unit

BIG = 1e200


def column3d(*, vecxz=None, soil=None, spring=None):
    """A 3-D cantilever column 1 -> 2 with a lumped mass at its top, optionally a soil or spring."""
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, 3.0)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("c", 1, 2, E=3e7, A=0.09, Iy=6.75e-4, Iz=1.2e-3, G=1.25e7, J=1.1e-3, vecxz=vecxz)
    fr.mass(2, 5.0)
    if soil is not None:
        fr.soil("s", 2, 1e4, direction=soil)
    if spring is not None:
        fr.spring("k", 2, 1e4, direction=spring)
    return fr.build()


def test_length_and_unit_do_not_overflow():
    assert length([BIG, BIG, 0.0]) == pytest.approx(np.sqrt(2.0) * BIG, rel=1e-15)
    assert length([1e-200, 0.0]) == 1e-200
    np.testing.assert_allclose(unit([BIG, BIG, 0.0]), [2 ** -0.5, 2 ** -0.5, 0.0], rtol=1e-15)
    np.testing.assert_allclose(unit([0.0, 0.0, -1e-300]), [0.0, 0.0, -1.0])


@pytest.mark.parametrize("bad", [(0.0, 0.0, 0.0), (np.inf, 0.0, 0.0), (np.nan, 1.0, 0.0)])
def test_unit_refuses_zero_or_non_finite(bad):
    with pytest.raises(ValueError, match="finite nonzero"):
        unit(bad)


def test_ground_motion_direction():
    s = column3d()
    np.testing.assert_allclose(s.influence((BIG, BIG, 0.0)), s.influence((1.0, 1.0, 0.0)), rtol=1e-15)
    assert np.abs(s.influence((BIG, BIG, 0.0))).max() > 0.5


def test_gravity_direction():
    s = column3d()
    np.testing.assert_allclose(s.gravity(9.81, (0.0, 0.0, -BIG)), s.gravity(9.81, (0.0, 0.0, -1.0)), rtol=1e-15)
    assert s.gravity(9.81, (0.0, 0.0, -BIG)).sum() == pytest.approx(-5.0 * 9.81)


def test_gravity_direction_2d():
    fr = Frame2D()
    fr.nodes([1, 2], [0.0, 0.0], [0.0, 3.0])
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("c", 1, 2, 3e7, 0.09, 6.75e-4)
    fr.mass(2, 5.0)
    s = fr.build()
    np.testing.assert_allclose(s.gravity(9.81, (0.0, -BIG)), s.gravity(9.81, (0.0, -1.0)), rtol=1e-15)


def test_beam_vecxz():
    unit_k = column3d(vecxz=(1.0, 1.0, 0.0)).to_model().K
    big_k = column3d(vecxz=(BIG, BIG, 0.0)).to_model().K
    np.testing.assert_allclose(np.asarray(big_k.todense() if hasattr(big_k, "todense") else big_k),
                               np.asarray(unit_k.todense() if hasattr(unit_k, "todense") else unit_k), rtol=1e-12)


@pytest.mark.parametrize("kind", ["soil", "spring"])
def test_soil_and_spring_direction(kind):
    unit_m = column3d(**{kind: (1.0, 0.0, 1.0)}).to_model()
    big_m = column3d(**{kind: (BIG, 0.0, BIG)}).to_model()
    dense = lambda A: np.asarray(A.todense() if hasattr(A, "todense") else A)
    np.testing.assert_allclose(dense(big_m.K), dense(unit_m.K), rtol=1e-12)
    if kind == "soil":
        np.testing.assert_allclose(dense(big_m.F), dense(unit_m.F), rtol=1e-12)


@pytest.mark.parametrize("bad", [(0.0, 0.0, 0.0), (np.inf, 0.0, 1.0), (np.nan, 0.0, 1.0)])
def test_zero_or_non_finite_direction_refused_by_name(bad):
    with pytest.raises(ValueError, match="direction"):
        column3d(soil=bad)
    with pytest.raises(ValueError, match="vecxz"):
        column3d(vecxz=bad)


def test_model_file_directions(tmp_path):
    """building3d.toml with its gravity, ground motion and vecxz scaled by 1e200: the same model and load."""
    from pathlib import Path

    from unilateral.modelfile import load_model_file

    root = Path(__file__).resolve().parents[1] / "examples"
    base = root.joinpath("building3d.toml").read_text().replace(
        "[loads.gravity]\ng = 9.81", "[loads.gravity]\ng = 9.81\ndirection = [0.0, 0.0, -1.0]").replace(
        'direction = "ux"\n', "direction = [1.0, 1.0, 0.0]\n")
    big = base.replace("direction = [0.0, 0.0, -1.0]", "direction = [0.0, 0.0, -1e200]").replace(
        "direction = [1.0, 1.0, 0.0]", "direction = [1e200, 1e200, 0.0]").replace(
        "vecxz = [0.0, 0.0, 1.0]", "vecxz = [0.0, 0.0, 1e200]")
    (tmp_path / "records").symlink_to(root / "records")
    specs = []
    for name, text in (("unit.toml", base), ("big.toml", big)):
        (tmp_path / name).write_text(text)
        specs.append(load_model_file(tmp_path / name))
    (unit_spec, big_spec) = specs
    dense = lambda A: np.asarray(A.todense() if hasattr(A, "todense") else A)
    np.testing.assert_allclose(dense(big_spec.model.K), dense(unit_spec.model.K), rtol=1e-12, atol=1e-6)
    t = np.array([0.0, 1.0, 2.0])
    for when in t:
        np.testing.assert_allclose(big_spec.load(when), unit_spec.load(when), rtol=1e-12, atol=1e-9)
    assert np.abs(big_spec.load(0.0)).max() > 0 and np.abs(big_spec.load(2.0) - big_spec.load(0.0)).max() > 0
