"""Layer properties that overflowed the layered soil's and the site column's computations
(``thickness = 1e-308`` or ``1e308``, ``Vs = 1e308``, ``G = 1e308``): refused when the soil is
built, naming the value and the valid range, where an OverflowError came from deep inside."""

from __future__ import annotations

import numpy as np
import pytest

from unilateral.loads.site_response import free_field
from unilateral.soil.layered import Layered


def _layer(**kw):
    return {"thickness": 3.0, "Vs": 120.0, "nu": 0.35, "rho": 1.8} | kw


@pytest.mark.parametrize("layer, message", [
    (_layer(thickness=1e-308), r"layers\[0\]\['thickness'\] = 1e-308 is out of range: valid 1e-06 <= thickness <= 1e\+07"),
    (_layer(thickness=1e308), r"layers\[0\]\['thickness'\] = 1e\+308 is out of range"),
    (_layer(Vs=1e308), r"layers\[0\]\['Vs'\] = 1e\+308 is out of range: valid shear-wave speeds are at most 1e\+07"),
    ({"thickness": 3.0, "G": 1e308, "nu": 0.35, "rho": 1.8}, r"layers\[0\]\['G'\] = 1e\+308 with rho = 1.8"),
    (_layer(Vs=1e-308), r"the shear modulus rho Vs\^2 = 0.0"),
])
def test_a_layer_out_of_range_is_refused_naming_the_value_and_the_range(layer, message):
    with pytest.raises(ValueError, match=message):
        Layered([layer])


def test_layers_within_the_range_build():
    soil = Layered([_layer(thickness=1e7), _layer(Vs=1e7)])
    assert soil.thickness.tolist() == [1e7, 3.0]


def test_a_site_layer_too_thick_is_refused():
    acc = np.sin(np.linspace(0.0, 10.0, 200))
    with pytest.raises(ValueError, match=r"layers\[0\]: thickness = 1e\+308 must be > 0 and <= 1e\+07"):
        free_field(acc, 0.01, [{"thickness": 1e308, "Vs": 200.0, "rho": 1.9}], {"Vs": 1000.0, "rho": 2.2})
    out = free_field(acc, 0.01, [{"thickness": 20.0, "Vs": 200.0, "rho": 1.9}], {"Vs": 1000.0, "rho": 2.2})
    assert out.shape == acc.shape and np.isfinite(out).all()
