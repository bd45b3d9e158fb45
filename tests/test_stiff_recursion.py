"""Models whose conditioned (stiff-separated) model would be conditioned again: no RecursionError.

The paper's example with a soft soil spring, or with a yield link or slider of ``k = 1e-308``,
made ``initial.static_state`` and ``StiffCoordinates.of`` call each other without end.
"""

from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.model.stiff import StiffCoordinates, _clip_round_off
from unilateral.modelfile import ModelFileError, load_model_file

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "liolios1990.toml"
SOIL3 = 'name = "soil3", node = 3, k = 200e3, c = 10e3 }'


def spec_of(tmp_path, text):
    path = tmp_path / "model.toml"
    path.write_text(text)
    return load_model_file(path)


def solve(spec, t_end=0.02):
    return ul.solve(spec.model, spec.load, dt=1e-3, t_end=t_end)


def test_conditioning_is_idempotent(tmp_path):
    text = EXAMPLE.read_text().replace(SOIL3, 'name = "soil3", node = 3, k = 1e-6, c = 10e3 }')
    stiff = StiffCoordinates.of(spec_of(tmp_path, text).model)
    assert stiff is not None
    assert StiffCoordinates.of(stiff.conditioned) is None


def test_soft_soil_spring_solves_like_a_soft_one(tmp_path):
    text = EXAMPLE.read_text()
    soft = solve(spec_of(tmp_path, text.replace(SOIL3, 'name = "soil3", node = 3, k = 1e-6, c = 10e3 }')))
    softer = solve(spec_of(tmp_path, text.replace(SOIL3, 'name = "soil3", node = 3, k = 1e-3, c = 10e3 }')))
    assert np.all(np.isfinite(soft.u))
    np.testing.assert_allclose(soft.u, softer.u, rtol=1e-6, atol=1e-12)


@pytest.mark.parametrize("entry", [
    '{ type = "yield", name = "y", node = 1, k = K, Fy = 10.0 }',
    '{ type = "slider", name = "sl", node = 1, mu = 0.3, N = 100.0, k = K }',
])
def test_tiny_yield_link_or_slider_stiffness_is_a_link_that_carries_nothing(tmp_path, entry):
    text = EXAMPLE.read_text()
    anchor = '    { type = "soil", name = "soil4"'
    run = lambda k: solve(spec_of(tmp_path, text.replace(anchor, "    " + entry.replace("K", k) + ",\n" + anchor)))
    tiny, small = run("1e-308"), run("1e-6")
    np.testing.assert_allclose(tiny.u, small.u, rtol=1e-6, atol=1e-12)


def test_tiny_stick_stiffness_refused_by_name(tmp_path):
    text = EXAMPLE.read_text().replace(SOIL3, 'name = "soil3", node = 3, k = 200e3, c = 10e3, mu = 0.5, kt = 1e-308 }')
    with pytest.raises(ModelFileError, match=r"soil3.*kt = 1e-308.*k = 200000"):
        spec_of(tmp_path, text)


def test_tiny_hinge_stiffness_is_refused_not_recursion(tmp_path):
    text = EXAMPLE.read_text().replace(
        '    { type = "soil", name = "soil4"',
        '    { type = "hinge", name = "h", beam = "column", end = "i", My = 1e3, k = 1e-308 },\n'
        '    { type = "soil", name = "soil4"')
    with pytest.raises(ValueError, match="positive definite|mechanism"):
        solve(spec_of(tmp_path, text))


def test_round_off_of_the_congruence_is_clipped():
    M = np.diag([40.0, 40.0, -9.7e-17, 0.0])
    M[0, 2] = M[2, 0] = 1e-13
    clipped = _clip_round_off(M)
    assert clipped[2, 2] == 0.0 and clipped[0, 2] == 0.0 and clipped[2, 0] == 0.0
    assert np.all(np.diag(clipped) >= 0.0)
    kept = _clip_round_off(np.array([[40.0, 1.0], [1.0, 1e-3]]))
    assert kept[1, 1] == 1e-3 and kept[0, 1] == 1.0


def frame3d(base_springs, link_k):
    """Four columns under a rigid floor diaphragm (plan 2.24 x 3.11 m, height 2.69 m), rigid-plastic
    3-D hinges at their feet and a yield link on the floor; fixed bases or vertical base springs."""
    from unilateral.structure import Frame3D

    fr = Frame3D()
    X, Y, H = 2.24, 3.11, 2.69
    for i, (x, y) in {1: (0, 0), 2: (X, 0), 3: (X, Y), 4: (0, Y)}.items():
        fr.node(i, x, y, 0.0)
        fr.node(10 + i, x, y, H)
        fr.support(i, ux=True, uy=True, uz=not base_springs, rx=True, ry=True, rz=True)
        if base_springs:
            fr.spring(f"k{i}", i, 1e6, direction="uz")
        fr.beam(f"c{i}", i, 10 + i, E=3e7, A=0.09, Iy=6.75e-4, Iz=6.75e-4, G=1.25e7, J=1.1e-3)
        fr.hinge(f"h{i}", f"c{i}", "i", My=50.0, Mz=50.0)
        fr.mass(10 + i, 5.0)
    fr.node(20, X / 2, Y / 2, H)
    fr.rigid_diaphragm(20, [11, 12, 13, 14])
    fr.support(20, ux=False, uy=False, uz=True, rx=True, ry=True, rz=False)
    fr.yield_link("y", 20, k=link_k, Fy=20.0, direction="ux")
    return fr.build()


@pytest.mark.parametrize("base_springs", [False, True])
def test_frame3d_with_a_negligible_yield_link_solves(base_springs):
    runs = {}
    for k in (1e-4, 1e-308):
        s = frame3d(base_springs, k)
        q = s.gravity()
        push = s.nodal_load(20, ux=10.0)
        runs[k] = ul.solve(s.to_model(), lambda t: q + push, dt=1e-3, t_end=0.02).u
    assert np.all(np.isfinite(runs[1e-308]))
    np.testing.assert_allclose(runs[1e-308], runs[1e-4], rtol=1e-6, atol=1e-12)
