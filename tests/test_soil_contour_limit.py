"""A layered soil whose top layer is far thinner than the footing: the wavenumber contour grows as
1 / thickness (12 / h_1 in panels set by the footprint), and one that would exceed
``MAX_CONTOUR_NODES`` nodes is refused before the contour is allocated, naming the layer, the
value, the count and a thickness that fits (counted by the calls of the integration, never timed)."""

from __future__ import annotations

import numpy as np
import pytest

from unilateral.soil import HalfSpace
from unilateral.soil.layer_ranges import MAX_CONTOUR_NODES
from unilateral.soil.layered import Layered
from unilateral.soil.patches import RectangularPatches

PATCHES = RectangularPatches([[x, 0.0] for x in np.linspace(-1.5, 1.5, 6)], [[0.5, 2.0]] * 6)
S = 1j * np.linspace(0.0, 200.0, 8) + 5.0


def soil(h1):
    return Layered([dict(thickness=h1, G=2e7, nu=0.3, rho=1800.0), dict(thickness=5.0, G=4e7, nu=0.3, rho=1900.0)],
                   HalfSpace(G=8e7, nu=0.3, rho=2000.0))


def test_the_nodes_grow_as_one_over_the_top_layer(monkeypatch):
    nodes = {h: soil(h).contour(S, 3.5)[0].size for h in (1.0, 0.1, 0.01)}
    assert nodes[0.01] < MAX_CONTOUR_NODES
    assert 7.5 < nodes[0.1] / nodes[1.0] < 10.0 and 9.5 < nodes[0.01] / nodes[0.1] < 10.0


@pytest.mark.parametrize("h1", [1e-3, 1e-6])
def test_a_millimetre_top_layer_is_refused_before_the_integration(monkeypatch, h1):
    calls = {"contours": 0, "kernels": 0}
    layered, real = soil(h1), Layered.contour

    def counted(*args, **kwargs):           # a contour allocated and returned
        out = real(*args, **kwargs)
        calls["contours"] += 1
        return out

    def kernels(*args, **kwargs):
        calls["kernels"] += 1
        raise AssertionError("the integration ran")

    monkeypatch.setattr(Layered, "contour", counted)
    monkeypatch.setattr(Layered, "kernels", kernels)
    with pytest.raises(ValueError) as info:
        layered.surface_flexibility(PATCHES, S)
    assert calls == {"contours": 0, "kernels": 0}                                # nothing allocated, nothing run
    message = str(info.value)
    assert message.startswith(f"layers[0]['thickness'] = {h1!r}: a top layer this thin needs")
    assert f"more than the {MAX_CONTOUR_NODES:,} nodes allowed" in message and "make the top layer at least" in message
    fits = float(message.split("at least ")[1].split(" ")[0])
    assert soil(fits * 1.01).contour(S, 3.5)[0].size <= MAX_CONTOUR_NODES     # the thickness it names fits
