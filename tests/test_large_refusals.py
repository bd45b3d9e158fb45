"""Two footings of 400 sliding patches each (3208 soil unknowns): refused by the memory estimate of
``unilateral.solve`` (276 GiB of CQ weights alone) before any weight is computed (counted, not timed)."""

from __future__ import annotations

import pytest

import unilateral as ul
from unilateral.structure import Frame2D
from unilateral.structure.examples import two_bay_on_footings


def test_two_footings_of_400_sliding_patches_are_refused_before_the_weights(monkeypatch):
    from unilateral.soil.foundation_model import SoilFlexibility

    foundation = Frame2D.foundation
    monkeypatch.setattr(Frame2D, "foundation", lambda self, *a, patches, **k: foundation(self, *a, patches=400, **k))
    structure, load, _ = two_bay_on_footings(mu=0.4)
    model = structure.to_model()
    assert model.m == 3208
    calls = []
    monkeypatch.setattr(SoilFlexibility, "cq_weights", lambda *a, **k: calls.append(1))
    with pytest.raises(MemoryError) as info:
        ul.solve(model, load, dt=0.005, t_end=6.0, method="cq")
    message = str(info.value)
    assert message.startswith("t_end/dt = 1200 steps with method='cq' would need about ")
    assert "cut the footings into fewer patches" in message and calls == []
