"""One structure-results function for 2-D and 3-D frames (:func:`unilateral.analysis.results.structure_results`),
the dimension's names, components and units from its :class:`~unilateral.analysis.dimension.Dimension`.

Defining properties: every variable the steps write has the dims and attributes of its spec in the
dimension's registry; the end-force components are the dimension's; a tower in the x-z plane of a
3-D frame on a footing gives the 2-D tower's axial force, base shear (``base_Fx``) and vertical
force (``base_Fz``) to round-off (the runs agree to 1e-9, ``tests/test_pdelta_footings3d.py``)."""

import numpy as np
import pytest
from test_pdelta_footings3d import tower2d, tower3d

import unilateral as ul
from unilateral.analysis.dimension import THREE_D, TWO_D, Units, dimension_of
from unilateral.analysis.results import load_samples_of, structure_results
from unilateral.loads import LoadHistory, Rectangular

UNITS = {"length": "m", "force": "kN", "time": "s"}


@pytest.fixture(scope="module")
def results():
    out = {}
    for name, st in (("2-D", tower2d()), ("3-D", tower3d())):
        load = LoadHistory(st.gravity(10.0), [(60.0 * st.nodal_load("top", ux=1.0), Rectangular(1.0, t_end=0.2))])
        sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=0.3, method="cq", rule="trapezoidal")
        assert sol.success, sol.message
        out[name] = st, structure_results(st, st.to_model(), {"u": sol}, rule="trapezoidal", units=UNITS,
                                          load_samples=load_samples_of(load, sol.t, 2e-3))
    return out


def test_the_dimension_of_a_structure(results):
    assert dimension_of(results["2-D"][0]) is TWO_D and dimension_of(results["3-D"][0]) is THREE_D
    assert results["2-D"][1]["coords"]["end_component"] == list(TWO_D.end_components)
    assert results["3-D"][1]["coords"]["end_component"] == list(THREE_D.end_components)
    assert set(results["2-D"][1]["attrs"]) == {"overturning_point"}
    assert set(results["3-D"][1]["attrs"]) == {"base_point"}


@pytest.mark.parametrize("name", ["2-D", "3-D"])
def test_every_variable_of_the_registry_has_its_spec(results, name):
    st, res = results[name]
    dim = dimension_of(st)
    written = [key for key in res["variables"] if key in dim.specs]
    assert len(written) >= 5                    # end forces, reactions, base forces at least
    for key in written:
        dims, _, attrs = res["variables"][key]
        spec = dim.spec(key)
        assert dims == spec.dims
        if key != "overturning_moment":         # its long name names the point
            assert (attrs["long_name"], attrs.get("units", "")) == spec.attributes(Units.of(UNITS))


def test_a_plane_tower_in_3d_has_the_2d_forces(results):
    (_, two), (_, three) = results["2-D"], results["3-D"]
    v2, v3 = two["variables"], three["variables"]
    scale = np.abs(v2["axial_force"][1]["u"]).max()
    assert np.abs(v3["axial_force"][1]["u"] - v2["axial_force"][1]["u"]).max() <= 1e-8 * scale
    for d2, d3 in (("base_shear", "base_Fx"), ("base_vertical", "base_Fz")):
        scale = np.abs(v2[d2][1]["u"]).max()
        assert scale > 0
        assert np.abs(v3[d3][1]["u"] - v2[d2][1]["u"]).max() <= 1e-8 * scale
    assert v2["axial_force"][2] == v3["axial_force"][2]          # the shared spec: the same attributes
