"""The yield and slip histories of 3-D frames in a run's outputs (:mod:`unilateral.analysis.inelastic`,
:func:`unilateral.analysis.outputs._structure_results_3d`).

A yield or friction element is the polygon of its facets on its one or two strains: its plastic
deformation (slip) is the vector ``sum_k v_k n_k`` on its components (a 3-D hinge's ``roty``,
``rotz``; a friction cone's ``t1``, ``t2``), its force the element's stresses on them. Defining
properties, each on a run written as ``unilateral run`` writes it:

* a 3-D portal in its plane with 8-facet hinges writes the plastic rotations, moments, peaks and
  plastic work of the 2-D portal's run (the in-plane component), to round-off;
* a cantilever with an 8-facet hinge pushed obliquely there and back: the plastic work is the
  integral of ``M . d(theta_p)`` computed from the run's ``u``, ``v`` and the structure's matrices
  (``theta_p = G^T u - E^-1 sigma`` on the end rotations) and the energy balance's; the force
  never leaves the polygon (``yield_ratio <= 1``);
* a block sliding on a friction cone (4 and 8 facets) along a bent path: the total slip is the
  length of the path of ``s = t . u - T / kt`` (from the kinematics and the stresses), the
  friction work the energy balance's ``energy_friction_work``;
* one-strain elements of a 3-D file (a yield link, a slider) keep the 2-D variables.

The 2-D outputs are unchanged: ``tests/test_inelastic_results.py``, ``tests/test_example_outputs.py``.
"""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest
from test_modelfile3d import write

import unilateral as ul
from unilateral.analysis.outputs import report
from unilateral.io import load_netcdf
from unilateral.modelfile import load_model_file
from unilateral.structure import elements3d as el3

H, L = 3.0, 5.0
E, A, I, I_OUT, G, J = 3e7, 0.16, 2e-3, 1.5e-3, 1.2e7, 3e-3
MY, MASS = 60.0, 5.0
MEMBERS = {"c1": (1, 3), "c2": (2, 4), "g": (3, 4)}
HINGES = ("c1.i", "c2.i", "g.i", "g.j")
COORDS = {1: (0.0, 0.0), 2: (L, 0.0), 3: (0.0, H), 4: (L, H)}


def _csv(path) -> dict:
    header, *rows = path.read_text().splitlines()
    values = np.array([[float(x) for x in row.split(",")] for row in rows])
    return {name: values[:, k] for k, name in enumerate(header.split(","))}


def _run(folder, document, name):
    path = write(folder, document, f"{name}.toml")
    result = ul.run(path, folder / name, figures=())
    assert result["success_all"]
    out = folder / name
    return (load_model_file(path), load_netcdf(out / "results.nc"), json.loads((out / "summary.json").read_text()),
            out)


# ---------------------------------------------------------------------- a plane portal, 2-D and 3-D
def portal_2d() -> dict:
    """A fixed-base portal in x-y with hinges at the column bases (one with a spring and hardening)
    and at the girder's ends, pushed by a pulse beyond its collapse load and back."""
    hinges = [{"type": "hinge", "name": f"{beam}.{end}", "beam": beam, "end": end, "My": MY}
              for beam, end in (name.split(".") for name in HINGES)]
    hinges[1] |= {"k": 4e3, "hardening": 0.05}
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "nodes": [{"id": k, "x": x, "y": y} for k, (x, y) in COORDS.items()],
        "supports": [{"node": 1, "rz": True}, {"node": 2, "rz": True}],
        "elements": [{"type": "beam", "name": name, "node_i": i, "node_j": j, "E": E, "A": A, "I": I}
                     for name, (i, j) in MEMBERS.items()],
        "unilateral": hinges,
        "masses": [{"node": 3, "m": MASS}, {"node": 4, "m": MASS}],
        "damping": {"rayleigh": {"a0": 2.0}},
        "loads": {"nodal": [{"node": 3, "ux": 1.5 * 4 * MY / H,
                             "time_function": {"type": "half_sine", "duration": 0.5}}]},
        "analysis": {"dt": 2e-3, "t_end": 1.0, "method": "direct", "rule": "trapezoidal"},
    }


def portal_3d() -> dict:
    """:func:`portal_2d` in the x-z plane of a 3-D frame, its hinges ellipses of 8 facets (``Mz = 0.7 My``
    out of the plane)."""
    d = copy.deepcopy(portal_2d())
    d["frame"] = {"dimensions": 3}
    d["nodes"] = [{"id": n["id"], "x": n["x"], "y": 0.0, "z": n["y"]} for n in d["nodes"]]
    d["supports"] = [{"node": 1, "rx": True, "ry": True, "rz": True}, {"node": 2, "rx": True, "ry": True, "rz": True}]
    for e in d["elements"]:
        e |= {"Iy": e.pop("I"), "Iz": I_OUT, "G": G, "J": J}
    for h in d["unilateral"]:
        h |= {"Mz": 0.7 * MY, "shape": "ellipse", "facets": 8}
    return d


def in_plane_sign(beam) -> float:
    """The 2-D moment (counter-clockwise in x-y) of a beam of the x-z plane is ``sign * M_y'``: the 2-D
    rotation turns x towards z, about -Y, and ``y'`` of the beam is ``-Y`` (columns) or ``+Y`` (girder)."""
    i, j = MEMBERS[beam]
    _, R = el3.local_axes("", i, (COORDS[i][0], 0.0, COORDS[i][1]), j, (COORDS[j][0], 0.0, COORDS[j][1]))
    assert abs(abs(R[1, 1]) - 1.0) < 1e-12
    return -float(R[1, 1])


@pytest.fixture(scope="module")
def portals(tmp_path_factory):
    folder = tmp_path_factory.mktemp("portals")
    return _run(folder, portal_2d(), "portal_2d"), _run(folder, portal_3d(), "portal_3d")


def test_a_3d_portal_in_its_plane_writes_the_2d_portals_yield_histories(portals):
    (_, two, s2, out2), (spec3, three, s3, out3) = portals
    assert list(three["yield_element"].values) == list(two["yield_element"].values) == list(HINGES)
    assert three["plastic_deformation"].dims == ("case", "time", "yield_element", "yield_component")
    assert two["plastic_deformation"].dims == ("case", "time", "yield_element")
    assert [list(c) for c in three["yield_component_name"].values] == [["roty", "rotz"]] * 4
    assert list(three["yield_facets"].values) == [8] * 4
    np.testing.assert_allclose(three["yield_limit_positive"].values, [[MY, 0.7 * MY]] * 4, rtol=1e-13)
    np.testing.assert_allclose(three["yield_limit_negative"].values, [[MY, 0.7 * MY]] * 4, rtol=1e-13)
    assert np.abs(two["plastic_deformation"].sel(case="unilateral").values).max(axis=0).min() > 1e-3  # all yield
    sign = np.array([in_plane_sign(name.split(".")[0]) for name in HINGES])
    for name in ("plastic_deformation", "yield_force", "yield_element_deformation"):
        a, b = two[name].values, three[name].values
        assert three[name].attrs["units"] == two[name].attrs["units"]
        np.testing.assert_allclose(sign * b[..., 0], a, rtol=0, atol=1e-9 * np.abs(a).max(), err_msg=name)
        assert np.abs(b[..., 1]).max() <= 1e-9 * np.abs(a).max(), name          # nothing out of the plane
    # the force over the polygon: in the plane |M| / My, the 2-D ratio
    m2 = two["yield_force"].sel(case="unilateral").values
    np.testing.assert_allclose(three["yield_ratio"].sel(case="unilateral").values, np.abs(m2) / MY, rtol=0, atol=1e-9)
    # the summary: peaks (the 3-D ones magnitudes, with their vector), residuals, ductility, work
    for case in ("unilateral", "bilateral"):
        y2, y3 = s2["results"][case]["yield_elements"], s3["results"][case]["yield_elements"]
        for k, name in enumerate(HINGES):
            a, b = y2[name], y3[name]
            assert b["components"] == ["roty", "rotz"] and b["facets"] == 8 and b["kind"] == a["kind"] == "hinge"
            for key in ("yielded", "yield_excursions", "unit"):
                assert b[key] == a[key], (case, name, key)
            scale = max(abs(a["peak_plastic_deformation"]["value"]), 1e-12)
            assert b["peak_plastic_deformation"]["value"] == pytest.approx(abs(a["peak_plastic_deformation"]["value"]),
                                                                           rel=0, abs=1e-9 * scale)
            if scale > 1e-9:
                assert b["peak_plastic_deformation"]["t"] == a["peak_plastic_deformation"]["t"]
                assert b["peak_plastic_deformation"]["vector"][0] * sign[k] == pytest.approx(
                    a["peak_plastic_deformation"]["value"], rel=1e-9)
            assert sign[k] * b["residual_plastic_deformation"][0] == pytest.approx(
                a["residual_plastic_deformation"], rel=0, abs=1e-9 * scale)
            assert b["peak_force_ratio"]["value"] == pytest.approx(a["peak_force_ratio"]["value"], rel=1e-9)
            assert b["plastic_work"] == pytest.approx(a["plastic_work"], rel=1e-9, abs=1e-12)
            assert ("ductility" in b) == ("ductility" in a) == (name == "c2.i")
            if "ductility" in a:
                assert b["ductility"]["value"] == pytest.approx(a["ductility"]["value"], rel=1e-9)
        energy2, energy3 = s2["results"][case]["energy"], s3["results"][case]["energy"]
        assert energy3["plastic_work"] == pytest.approx(energy2["plastic_work"], rel=1e-9, abs=1e-12)
        assert sum(e["plastic_work"] for e in y3.values()) == pytest.approx(energy3["plastic_work"], rel=1e-12)
    assert s2["results"]["unilateral"]["energy"]["plastic_work"] > 1.0
    # yield_and_slip.csv: a column per component, the 2-D column along roty
    c2, c3 = _csv(out2 / "yield_and_slip.csv"), _csv(out3 / "yield_and_slip.csv")
    for k, name in enumerate(HINGES):
        for quantity, unit in (("plastic_deformation", "rad"), ("yield_force", "kN m")):
            a = c2[f"{quantity}:{name} [{unit}]"]
            np.testing.assert_allclose(sign[k] * c3[f"{quantity}:{name}:roty [{unit}]"], a, rtol=0,
                                       atol=1e-9 * max(np.abs(a).max(), 1e-12))
            assert f"{quantity}:{name}:rotz [{unit}]" in c3
        assert f"yield_ratio:{name} [1]" in c3 and f"yield_ratio:{name} [1]" not in c2
    assert "yield_and_slip" not in s3["notes"][0].partition("Not written")[2]


# ---------------------------------------------------------------------- a cantilever pushed obliquely
HC, PY, PZ, K_SPRING, K_TIP = 2.0, 100.0, 60.0, 800.0, 40.0
PHI = np.radians(30.0)


def cantilever() -> dict:
    """A column along z fixed at its base (node 1), with a base hinge (an ellipse of 8 facets with a
    spring, no hardening) and springs from its tip to the ground along x and y (the column is no
    mechanism once the hinge yields), pushed at its tip along 30 degrees in plan to 1.5 times the
    hinge's strength and back along the opposite direction; a yield link at the tip along z (it
    carries nothing: a one-strain element beside the polygon)."""
    push = 1.5 * PY / HC
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "frame": {"dimensions": 3},
        "nodes": [{"id": 1, "x": 0.0, "y": 0.0, "z": 0.0}, {"id": 2, "x": 0.0, "y": 0.0, "z": HC}],
        "supports": [{"node": 1, "rx": True, "ry": True, "rz": True}],
        "elements": [{"type": "beam", "name": "col", "node_i": 1, "node_j": 2, "E": 1e4, "A": 1.0, "Iy": 1.0,
                      "Iz": 0.8, "G": 4e3, "J": 1.0},
                     {"type": "spring", "name": "kx", "node_i": 2, "k": K_TIP, "direction": "ux"},
                     {"type": "spring", "name": "ky", "node_i": 2, "k": K_TIP, "direction": "uy"}],
        "unilateral": [{"type": "hinge", "name": "H", "beam": "col", "end": "i", "My": PY, "Mz": PZ, "facets": 8,
                        "k": K_SPRING},
                       {"type": "yield", "name": "y", "node": 2, "k": 1e3, "Fy": 50.0, "direction": "uz"}],
        "masses": [{"node": 2, "m": 1e-3, "Jx": 1e-4, "Jy": 1e-4, "Jz": 1e-4}],
        "damping": {"rayleigh": {"a0": 50.0}},
        "loads": {"nodal": [
            {"node": 2, "ux": float(push * np.cos(PHI)), "uy": float(push * np.sin(PHI)),
             "time_function": {"type": "triangular", "t_peak": 2.0, "t_end": 4.0}},
            {"node": 2, "ux": float(-push * np.cos(PHI)), "uy": float(-push * np.sin(PHI)),
             "time_function": {"type": "triangular", "t_start": 4.0, "t_peak": 6.0, "t_end": 8.0}}]},
        "analysis": {"dt": 0.01, "t_end": 8.0, "method": "direct", "rule": "trapezoidal"},
    }


def test_the_plastic_work_of_an_obliquely_pushed_hinge_is_the_integral_of_m_dtheta_p(tmp_path):
    spec, ds, summary, out = _run(tmp_path, cantilever(), "cantilever")
    st = spec.structure
    d = ds.sel(case="unilateral")
    assert list(d["yield_element"].values) == ["H", "y"]
    assert [list(c) for c in d["yield_component_name"].values] == [["roty", "rotz"], ["d", ""]]
    t, u, v = d["time"].values, d["u"].values, d["v"].values
    rows = [st.strain_names.index("col.roty_i"), st.strain_names.index("col.rotz_i")]
    sigma = st.natural.stresses(t, u, v)
    strains = np.asarray((st.natural.G.T @ u.T).T)
    E_inv = np.linalg.inv(st.natural.E.toarray() if hasattr(st.natural.E, "toarray") else st.natural.E)
    M = sigma[:, rows]
    theta_p = (strains - sigma @ E_inv.T)[:, rows]                 # total end rotations minus elastic
    assert np.abs(theta_p).max() > 1e-2                             # it yields, both ways
    work = float(np.sum(0.5 * (M[1:] + M[:-1]) * np.diff(theta_p, axis=0)))
    assert work > 1.0
    np.testing.assert_allclose(d["plastic_deformation"].values[:, 0], theta_p, rtol=0,
                               atol=1e-9 * np.abs(theta_p).max())
    np.testing.assert_allclose(d["yield_force"].values[:, 0], M, rtol=0, atol=1e-9 * PY)
    H = summary["results"]["unilateral"]["yield_elements"]["H"]
    assert H["plastic_work"] == pytest.approx(work, rel=1e-9)
    assert H["plastic_work"] == pytest.approx(float(d["energy_plastic_work"].values[-1]), rel=1e-9)
    assert summary["results"]["unilateral"]["energy"]["max_relative_error"] < 1e-9
    # the force over the polygon: the polygon's gauge of M, never above 1, 1 while it flows
    n, r = el3.hinge_polygon("ellipse", 8, PY, PZ)
    ratio = np.max(M @ n.T / r, axis=1)
    np.testing.assert_allclose(d["yield_ratio"].values[:, 0], ratio, rtol=0, atol=1e-12)
    assert ratio.max() <= 1.0 + 1e-9 and ratio.max() >= 1.0 - 1e-9
    flowing = np.linalg.norm(np.diff(theta_p, axis=0), axis=1) > 1e-9
    np.testing.assert_allclose(ratio[1:][flowing], 1.0, atol=1e-9)
    assert H["peak_force_ratio"]["value"] == pytest.approx(ratio.max(), abs=1e-12)
    # peaks: the largest |theta_p| and the last; ductility: the gauge of the spring's rotation M/k + theta_p
    magnitude = np.linalg.norm(theta_p, axis=1)
    assert H["peak_plastic_deformation"]["value"] == pytest.approx(magnitude.max(), rel=1e-9)
    np.testing.assert_allclose(H["residual_plastic_deformation"], theta_p[-1], rtol=1e-9)
    ductility = np.max((M / K_SPRING + theta_p) @ n.T / (r / K_SPRING), axis=1).max()
    assert H["ductility"]["value"] == pytest.approx(ductility, rel=1e-9) and H["ductility"]["value"] > 3.0
    assert H["yield_deformation"] == pytest.approx(list(r[[0, 4, 1, 5, 2, 6, 3, 7]] / K_SPRING))
    assert H["yielded"] and H["yield_excursions"] >= 2
    # the one-strain link keeps its 2-D figures; its second component is none
    y = summary["results"]["unilateral"]["yield_elements"]["y"]
    assert not y["yielded"] and isinstance(y["residual_plastic_deformation"], float) and "components" not in y
    assert np.isnan(d["plastic_deformation"].values[:, 1, 1]).all()
    columns = _csv(out / "yield_and_slip.csv")
    assert {"plastic_deformation:H:roty [rad]", "plastic_deformation:H:rotz [rad]", "yield_force:H:rotz [kN m]",
            "plastic_deformation:y [m]", "yield_force:y [kN]", "yield_ratio:H [1]"} <= set(columns)
    np.testing.assert_allclose(columns["yield_force:H:rotz [kN m]"], M[:, 1], rtol=1e-12, atol=1e-9)


def test_the_hysteresis_figure_of_a_3d_run_shows_each_hinge_along_its_larger_component(tmp_path):
    from unilateral.figures.results import _case, _yield_panels, main_case

    document = cantilever() | {"analysis": {"dt": 0.05, "t_end": 8.0, "method": "direct"}}
    result = ul.run(write(tmp_path, document, "drawn.toml"), tmp_path / "drawn", figures=("png",))
    assert result["success_all"]
    assert any(p.endswith("hysteresis.png") for p in result["figures"])
    ds = load_netcdf(tmp_path / "drawn" / "results.nc")
    panels = _yield_panels(_case(ds, main_case(ds)))
    # pushed along 30 degrees, M along (cos, sin) 30: the flow, normal to the polygon, is mostly about z'
    # (along (cos / My^2, sin / Mz^2))
    assert [p["name"] for p in panels] == ["H (rotz)", "y"]
    assert list(panels[0]["limits"]) == pytest.approx([PZ, -PZ])
    assert panels[0]["work"] == pytest.approx(result["results"]["unilateral"]["yield_elements"]["H"]["plastic_work"],
                                              rel=1e-9)


def test_every_hinge_shape_writes_its_end_rotations_plastic_rotations_and_work(tmp_path):
    """The portal of tests/test_hinge3d.py pushed out of its plane: hinges of 8 and 16 facets, a box
    and a diamond (whose facets all enter one end rotation as their primary strain), with springs
    and hardening. For each: the deformation is ``G^T u`` and the plastic rotation ``G^T u - E^-1
    sigma`` on its (roty, rotz) rows; the plastic works add up to the energy balance's."""
    from test_hinge3d import PORTAL_3D

    from unilateral.rules import EnergyPairing

    spec, ds, summary, out = _run(tmp_path, PORTAL_3D, "shapes")
    st = spec.structure
    d = ds.sel(case="unilateral")
    assert list(d["yield_facets"].values) == [8, 16, 4, 4]
    t, u, v = d["time"].values, d["u"].values, d["v"].values
    sigma = st.natural.stresses(t, u, v)
    strains = np.asarray((st.natural.G.T @ u.T).T)
    E_inv = np.linalg.inv(st.natural.E.toarray() if hasattr(st.natural.E, "toarray") else st.natural.E)
    plastic = strains - sigma @ E_inv.T
    yields = summary["results"]["unilateral"]["yield_elements"]
    pairing = EnergyPairing(summary["rule"])
    for k, name in enumerate(d["yield_element"].values):
        beam, end = str(name).split(".")
        rows = [st.strain_names.index(f"{beam}.roty_{end}"), st.strain_names.index(f"{beam}.rotz_{end}")]
        np.testing.assert_allclose(d["yield_element_deformation"].values[:, k], strains[:, rows], rtol=0, atol=1e-15)
        scale = np.abs(plastic[:, rows]).max()
        assert scale > 1e-4, name                                   # every hinge yields
        np.testing.assert_allclose(d["plastic_deformation"].values[:, k], plastic[:, rows], rtol=0,
                                   atol=1e-9 * scale)
        M = sigma[:, rows]               # the work paired as the run's rule, as the energy balance pairs it
        p = np.concatenate([plastic[:1, rows]] * pairing.lead + [plastic[:, rows]])
        work = float(np.sum(pairing.weights(M.T) * pairing.increments(p.T)))
        assert yields[str(name)]["plastic_work"] == pytest.approx(work, rel=1e-9), name
    assert sum(e["plastic_work"] for e in yields.values()) == pytest.approx(
        summary["results"]["unilateral"]["energy"]["plastic_work"], rel=1e-12)


# ---------------------------------------------------------------------- a block on a friction cone
MU, KT, GRAVITY = 0.5, 1e5, 10.0


def block(facets) -> dict:
    """A unit mass on a soil contact along z with a friction cone of ``facets`` facets, pushed in plan
    along 20 degrees and then along 110 degrees, each time to twice Coulomb's strength: it slides
    along a bent path (a drag, mass-proportional damping, keeps the sliding steady)."""
    push = 2.0 * MU * GRAVITY
    return {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "frame": {"dimensions": 3},
        "nodes": [{"id": 1, "x": 0.0, "y": 0.0, "z": 0.0}],
        "unilateral": [{"type": "soil", "name": "s", "node": 1, "k": 1e6, "mu": MU, "kt": KT, "facets": facets}],
        "masses": [{"node": 1, "m": 1.0}],
        "damping": {"rayleigh": {"a0": 20.0}},
        "loads": {"gravity": {"g": GRAVITY},
                  "nodal": [{"node": 1, "ux": float(push * np.cos(np.radians(a))),
                             "uy": float(push * np.sin(np.radians(a))),
                             "time_function": {"type": "triangular", "t_start": t0, "t_peak": t0 + 0.5,
                                               "t_end": t0 + 1.0}}
                            for a, t0 in ((20.0, 0.0), (110.0, 1.0))]},
        "analysis": {"dt": 0.002, "t_end": 2.5, "method": "direct", "rule": "trapezoidal"},
    }


@pytest.mark.parametrize("facets", [4, 8])
def test_the_slip_path_and_friction_work_of_a_block_on_a_friction_cone(tmp_path, facets):
    spec, ds, summary, out = _run(tmp_path, block(facets), f"block{facets}")
    st = spec.structure
    d = ds.sel(case="unilateral")
    assert list(d["friction_element"].values) == ["s"]
    assert d["slip"].dims == ("time", "friction_element", "friction_component")
    assert [list(c) for c in d["friction_component_name"].values] == [["t1", "t2"]]
    assert list(d["friction_facets"].values) == [facets]
    t, u, v = d["time"].values, d["u"].values, d["v"].values
    rows = [st.strain_names.index("s.tangential"), st.strain_names.index("s.tangential2")]
    sigma = st.natural.stresses(t, u, v)
    motion = np.asarray((st.natural.G.T @ u.T).T)[:, rows]          # t1 . u, t2 . u
    T = sigma[:, rows]
    slip = motion - T / KT                                          # the tangential motion less the elastic
    steps = np.linalg.norm(np.diff(slip, axis=0), axis=1)
    path = float(steps.sum())
    assert path > 0.05 and path > 1.2 * np.linalg.norm(slip[-1])    # a bent path, longer than its chord
    np.testing.assert_allclose(d["slip"].values[:, 0], slip, rtol=0, atol=1e-9 * path)
    np.testing.assert_allclose(d["friction_force"].values[:, 0], T, rtol=0, atol=1e-9)
    np.testing.assert_allclose(d["tangential_deformation"].values[:, 0], motion, rtol=0, atol=1e-12)
    np.testing.assert_allclose(d["normal_force"].values[:, 0], GRAVITY, rtol=1e-6)
    s = summary["results"]["unilateral"]["friction_elements"]["s"]
    assert s["slid"] and s["components"] == ["t1", "t2"] and s["facets"] == facets
    assert s["total_slip"] == pytest.approx(path, rel=1e-9)
    assert float(d["slip_path"].values[-1, 0]) == pytest.approx(path, rel=1e-9)
    # the integral of the tangential speed over the steps that slide: the same path, to the elastic part
    sliding = np.diff(v, axis=0).max(axis=1) > 1e-12
    speed = np.linalg.norm(np.diff(motion, axis=0), axis=1)
    assert float(speed[sliding].sum()) == pytest.approx(path, rel=1e-3)
    # the friction work: the integral of T . ds, the energy balance's friction work
    work = float(np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(slip, axis=0)))
    assert work > 0.2
    assert s["friction_work"] == pytest.approx(work, rel=1e-9)
    assert s["friction_work"] == pytest.approx(float(d["energy_friction_work"].values[-1]), rel=1e-9)
    assert summary["results"]["unilateral"]["energy"]["max_relative_error"] < 1e-9
    # peaks: the largest |s| and |T| with their vectors; |T| within the polygon around mu N
    peak = np.linalg.norm(slip, axis=1).max()
    assert s["peak_slip"]["value"] == pytest.approx(peak, rel=1e-9)
    np.testing.assert_allclose(s["residual_slip"], slip[-1], rtol=1e-9)
    force = np.linalg.norm(T, axis=1).max()
    assert s["peak_friction_force"]["value"] == pytest.approx(force, rel=1e-9)
    assert MU * GRAVITY * (1 - 1e-6) <= force <= MU * GRAVITY / np.cos(np.pi / facets) * (1 + 1e-6)
    columns = _csv(out / "yield_and_slip.csv")
    assert {"slip:s:t1 [m]", "slip:s:t2 [m]", "friction_force:s:t1 [kN]", "friction_force:s:t2 [kN]",
            "normal_force:s [kN]"} <= set(columns)
    np.testing.assert_allclose(columns["slip:s:t2 [m]"], slip[:, 1], rtol=0, atol=1e-9 * path)
    assert "friction: 1 of 1 friction elements slid" in report(summary)
    # the hysteresis panel: along the component of the larger peak slip; the work of both
    from unilateral.figures.results import _case, _friction_panels, main_case

    (panel,) = _friction_panels(_case(ds, main_case(ds)))
    assert panel["name"] == f"s ({['t1', 't2'][int(np.argmax(np.abs(slip).max(axis=0)))]})"
    assert panel["work"] == pytest.approx(work, rel=1e-9)


# ---------------------------------------------------------------------- one-strain elements in 3-D
def test_yield_links_and_sliders_of_a_3d_file_keep_the_2d_variables(tmp_path):
    """A 3-D file with a yield link and a slider alone: no component dimension, the 2-D figures."""
    document = {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "frame": {"dimensions": 3},
        "nodes": [{"id": 1, "x": 0.0, "y": 0.0, "z": 0.0}, {"id": 2, "x": 2.0, "y": 0.0, "z": 0.0}],
        "supports": [{"node": 1, "ux": False, "uy": False}, {"node": 2, "ux": False, "uy": False}],
        "masses": [{"node": 1, "m": 2.0}, {"node": 2, "m": 1.0}],
        "elements": [{"type": "spring", "name": "keep1", "node_i": 1, "k": 1e3, "direction": [1.0, -1.0, 0.0]},
                     {"type": "spring", "name": "keep2", "node_i": 2, "k": 1e3, "direction": "ux"}],
        "unilateral": [{"type": "yield", "name": "y", "node": 1, "k": 1e3, "Fy": 50.0, "hardening": 0.05,
                        "direction": [1.0, 1.0, 0.0]},
                       {"type": "slider", "name": "s", "node": 2, "mu": 0.3, "N": 100.0, "k": 2e3, "direction": "uy"}],
        "loads": {"nodal": [{"node": 1, "ux": 80.0, "uy": 80.0, "time_function": {"type": "ramp", "t_ramp": 1.0}},
                            {"node": 2, "uy": 60.0, "time_function": {"type": "ramp", "t_ramp": 1.0}}]},
        "analysis": {"t_end": 1.0, "dt": 0.005, "method": "direct", "rule": "trapezoidal"},
    }
    _, ds, summary, out = _run(tmp_path, document, "links")
    d = ds.sel(case="unilateral")
    assert d["plastic_deformation"].dims == ("time", "yield_element") and "yield_component" not in ds.dims
    assert d["slip"].dims == ("time", "friction_element") and "yield_ratio" not in ds
    v, names = d["v"].values, list(d["constraint"].values)
    np.testing.assert_array_equal(d["plastic_deformation"].values[:, 0],
                                  v[:, names.index("y.plastic+")] - v[:, names.index("y.plastic-")])
    np.testing.assert_array_equal(d["slip"].values[:, 0], v[:, names.index("s.slip+")] - v[:, names.index("s.slip-")])
    peaks = summary["results"]["unilateral"]
    y, s = peaks["yield_elements"]["y"], peaks["friction_elements"]["s"]
    assert y["yielded"] and y["kind"] == "yield link" and y["ductility"]["value"] > 1.0
    assert s["slid"] and s["kind"] == "slider" and s["total_slip"] > 1e-3
    assert y["plastic_work"] + s["friction_work"] == pytest.approx(
        peaks["energy"]["plastic_work"] + peaks["energy"]["friction_work"], rel=1e-9)
    header = (out / "yield_and_slip.csv").read_text().splitlines()[0]
    assert header == ("time [s],plastic_deformation:y [m],yield_force:y [kN],slip:s [m],friction_force:s [kN],"
                      "normal_force:s [kN]")
