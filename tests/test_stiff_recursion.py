"""Models whose conditioned (stiff-separated) model would be conditioned again: no RecursionError.

The paper's example with a soft soil spring, or with a yield link or slider of ``k = 1e-308``,
made ``initial.static_state`` and ``StiffCoordinates.of`` call each other without end.
"""

from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.methods.stiff import StiffCoordinates, _clip_round_off
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
