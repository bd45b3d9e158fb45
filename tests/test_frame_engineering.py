"""Distributed loads and self-weight, modal damping, P-Delta and the overturning point, against
closed forms."""

import json

import numpy as np
import pytest

from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.structure import Frame2D

E, A, I = 200e6, 1e-2, 1e-4


def dense(a):
    return a.toarray() if hasattr(a, "toarray") else np.asarray(a)


def static(st, f):
    return np.linalg.solve(dense(st.to_model().K), f)


def simply_supported(n=4, L=6.0, rho=None):
    fr = Frame2D()
    for k in range(n + 1):
        fr.node(k, L * k / n, 0.0)
    fr.support(0)
    fr.support(n, ux=False, uy=True)
    for k in range(n):
        fr.beam(f"b{k}", k, k + 1, E, A, I, rho=rho)
    return fr


# ---------------------------------------------------------------------- distributed loads, self-weight
@pytest.mark.parametrize("n", [2, 4, 6])
def test_uniform_load_on_a_simply_supported_beam_gives_5qL4_over_384EI(n):
    L, q = 6.0, 10.0
    st = simply_supported(n, L).build()
    f = sum(st.distributed_load(f"b{k}", wy=-q) for k in range(n))
    u = static(st, f)
    assert u[st.dofs.index(n // 2, "uy")] == pytest.approx(-5 * q * L**4 / (384 * E * I), rel=1e-10)
    assert u[st.dofs.index(0, "rz")] == pytest.approx(-q * L**3 / (24 * E * I), rel=1e-10)


def test_inclined_cantilever_under_a_global_load_gives_the_closed_form_tip_deflection():
    L, q, angle = 5.0, 3.0, np.radians(30.0)
    c, s = np.cos(angle), np.sin(angle)
    n = 3
    fr = Frame2D()
    for k in range(n + 1):
        fr.node(k, c * L * k / n, s * L * k / n)
    fr.support(0, rz=True)
    for k in range(n):
        fr.beam(f"b{k}", k, k + 1, E, A, I)
    st = fr.build()
    wx, wy = 1.0 * q, -2.0 * q
    f = sum(st.distributed_load(f"b{k}", wx=wx, wy=wy) for k in range(n))
    u = static(st, f)
    wt, wa = -s * wx + c * wy, c * wx + s * wy             # across and along the beam
    tip = np.array([u[st.dofs.index(n, "ux")], u[st.dofs.index(n, "uy")]])
    across, along = -s * tip[0] + c * tip[1], c * tip[0] + s * tip[1]
    assert across == pytest.approx(wt * L**4 / (8 * E * I), rel=1e-10)
    assert along == pytest.approx(wa * L**2 / (2 * E * A), rel=1e-10)
    assert u[st.dofs.index(n, "rz")] == pytest.approx(wt * L**3 / (6 * E * I), rel=1e-10)


def test_beam_density_lumps_half_its_mass_at_each_end_and_gravity_gives_its_weight():
    L, rho, g = 6.0, 7.85, 9.81
    st = simply_supported(3, L, rho=rho).build()
    assert st.nodal_mass[:, 0].sum() == pytest.approx(rho * A * L)
    assert st.nodal_mass[0, 0] == pytest.approx(rho * A * L / 6)       # an end node: half an element
    assert st.nodal_mass[1, 0] == pytest.approx(rho * A * L / 3)
    assert np.all(st.nodal_mass[:, 2] == 0)
    free_uy = [k for k, (node, dof) in enumerate(st.dofs.free) if dof == "uy"]
    assert st.gravity(g)[free_uy].sum() == pytest.approx(-rho * A * L * g * 2 / 3)   # the two inner nodes


def test_distributed_load_refuses_an_unknown_beam():
    st = simply_supported(2).build()
    with pytest.raises(ValueError, match="no beam 'nope'"):
        st.distributed_load("nope", wy=-1.0)


def frame_document(n=4, L=6.0, **extra):
    doc = {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "nodes": [{"id": k, "x": L * k / n, "y": 0.0} for k in range(n + 1)],
        "supports": [{"node": 0}, {"node": n, "ux": False, "uy": True}],
        "elements": [{"type": "beam", "name": f"b{k}", "node_i": k, "node_j": k + 1, "E": E, "A": A, "I": I}
                     for k in range(n)],
        "analysis": {"dt": 1e-3, "t_end": 0.01},
    }
    doc.update(extra)
    return doc


def write_toml(tmp_path, doc):
    from tests.test_modelfile import toml_text
    path = tmp_path / "model.toml"
    path.write_text(toml_text(doc))
    return path


def test_model_file_distributed_load_and_density(tmp_path):
    n, L, q = 4, 6.0, 10.0
    doc = frame_document(n, L, loads={"distributed": [{"beam": f"b{k}", "wy": -q} for k in range(n)]})
    for e in doc["elements"]:
        e["rho"] = 2.5
    spec = load_model_file(write_toml(tmp_path, doc))
    u = np.linalg.solve(dense(spec.model.K), spec.load(0.0))
    assert u[spec.structure.dofs.index(n // 2, "uy")] == pytest.approx(-5 * q * L**4 / (384 * E * I), rel=1e-10)
    assert spec.structure.nodal_mass[:, 0].sum() == pytest.approx(2.5 * A * L)
    doc["loads"]["distributed"][0]["beam"] = "nope"
    with pytest.raises(ModelFileError, match="loads.distributed"):
        load_model_file(write_toml(tmp_path, doc))


# ---------------------------------------------------------------------- modal damping
def shear_frame(m1=2.0, m2=1.0, k1=3000.0, k2=2000.0):
    """A 2-DOF shear frame: two masses on horizontal springs (the storeys), rigidly braced vertically."""
    fr = Frame2D()
    fr.node(0, 0.0, 0.0)
    fr.node(1, 0.0, 3.0)
    fr.node(2, 0.0, 6.0)
    fr.support(0)
    fr.support(1, ux=False, uy=True)
    fr.support(2, ux=False, uy=True)
    fr.spring("s1", 0, k1, j=1, direction="ux")
    fr.spring("s2", 1, k2, j=2, direction="ux")
    fr.mass(1, m1)
    fr.mass(2, m2)
    return fr


def damping_ratios(M, C, K):
    """Ratios ``-Re(s)/|s|`` of the eigenvalues ``s`` of ``M x'' + C x' + K x = 0``, lowest |s| first."""
    n = K.shape[0]
    Minv = np.linalg.inv(M)
    S = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ C]])
    s = np.linalg.eigvals(S)
    s = s[s.imag > 0]
    s = s[np.argsort(np.abs(s))]
    return -s.real / np.abs(s), np.abs(s)


@pytest.mark.parametrize("zeta", [0.05, (0.02, 0.07)])
def test_modal_damping_gives_each_mode_of_a_shear_frame_its_ratio(zeta):
    fr = shear_frame()
    fr.modal_damping(zeta)
    st = fr.build()
    model = st.to_model()
    M, C, K = dense(model.M), dense(model.C), dense(model.K)
    ratios, omega = damping_ratios(M, C, K)
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    assert ratios == pytest.approx(np.broadcast_to(zeta, 2), rel=1e-9)
    assert omega == pytest.approx(np.sqrt(w2), rel=1e-9)          # |s| = the undamped frequency


def test_modal_damping_of_the_first_mode_only_and_with_massless_rotations():
    fr = shear_frame()
    fr.modal_damping(0.05, modes=1)
    model = fr.build().to_model()
    ratios, _ = damping_ratios(dense(model.M), dense(model.C), dense(model.K))
    assert ratios == pytest.approx([0.05, 0.0], abs=1e-12)
    # a cantilever of beams: the rotations have no mass and are condensed
    fr = Frame2D()
    for k in range(3):
        fr.node(k, 0.0, 3.0 * k)
    fr.support(0, rz=True)
    for k in range(2):
        fr.beam(f"c{k}", k, k + 1, E, A, I)
        fr.mass(k + 1, 1.0)
    fr.modal_damping(0.03)
    st = fr.build()
    model = st.to_model()
    K, M, C = dense(model.K), dense(model.M), dense(model.C)
    mass = np.flatnonzero(np.diag(M) > 0)
    zero = np.setdiff1d(np.arange(st.n), mass)
    assert np.all(C[zero] == 0) and np.all(C[:, zero] == 0)
    Kc = K[np.ix_(mass, mass)] - K[np.ix_(mass, zero)] @ np.linalg.solve(K[np.ix_(zero, zero)], K[np.ix_(zero, mass)])
    ratios, _ = damping_ratios(M[np.ix_(mass, mass)], C[np.ix_(mass, mass)], Kc)
    assert ratios == pytest.approx(0.03, rel=1e-9)


def test_modal_damping_in_a_model_file(tmp_path):
    doc = frame_document(4, 6.0, masses=[{"node": k, "m": 1.0} for k in (1, 2, 3)],
                         damping={"modal": {"zeta": 0.05}})
    spec = load_model_file(write_toml(tmp_path, doc))
    fr = simply_supported(4, 6.0)
    for k in (1, 2, 3):
        fr.mass(k, 1.0)
    fr.modal_damping(0.05)
    assert dense(spec.model.C) == pytest.approx(dense(fr.build().C), abs=1e-9)
    with pytest.raises(ValueError, match="one per mode"):
        Frame2D().modal_damping([0.1, 0.2], modes=3)


# ---------------------------------------------------------------------- P-Delta
def cantilever_column(n=4, H=4.0, mass=None):
    fr = Frame2D()
    for k in range(n + 1):
        fr.node(k, 0.0, H * k / n)
    fr.support(0, rz=True)
    for k in range(n):
        fr.beam(f"c{k}", k, k + 1, E, A, I)
    if mass is not None:
        fr.mass(n, mass)
    return fr


def test_buckling_load_of_a_cantilever_column_is_eulers():
    from scipy.linalg import eigh

    H, n = 4.0, 4
    st = cantilever_column(n, H).build()
    axial = st.static_axial_forces(st.nodal_load(n, uy=-1.0))        # a unit compression
    assert axial == pytest.approx({f"c{k}": -1.0 for k in range(n)})
    K, KG = dense(st.to_model().K), dense(st.geometric_stiffness(axial))
    lam = 1 / eigh(-KG, K, eigvals_only=True)[-1]                     # det(K + lam K_G(-1)) = 0
    euler = np.pi**2 * E * I / (4 * H**2)
    assert lam == pytest.approx(euler, rel=1e-4)                      # consistent K_G: O(h^4) error
    assert abs(lam / euler - 1) > 1e-8                                # (not the exact value)


def test_p_delta_amplifies_the_drift_of_a_cantilever_by_about_1_over_1_minus_P_over_Pcr():
    H, n, g, lateral = 4.0, 8, 9.81, 1.0
    euler = np.pi**2 * E * I / (4 * H**2)
    P = 0.3 * euler
    fr = cantilever_column(n, H, mass=P / g)
    linear = fr.build()
    fr.p_delta(g=g)
    pd = fr.build()
    assert pd.axial_forces["c0"] == pytest.approx(-P)
    f = linear.nodal_load(n, ux=lateral)
    drift0 = static(linear, f)[linear.dofs.index(n, "ux")]
    drift = static(pd, f)[pd.dofs.index(n, "ux")]
    assert drift0 == pytest.approx(lateral * H**3 / (3 * E * I), rel=1e-10)
    kL = np.sqrt(P / (E * I)) * H
    exact = lateral / (P / H) * (np.tan(kL) - kL) / kL                 # second-order beam-column theory
    assert drift == pytest.approx(exact, rel=1e-5)
    assert drift / drift0 == pytest.approx(1 / (1 - P / euler), rel=0.01)
    # build(p_delta=...) switches it; above the buckling load the model is refused
    assert fr.build(p_delta=False).geometric is None
    heavy = cantilever_column(n, H, mass=1.2 * euler / g)
    with pytest.raises(ValueError, match="buckling"):
        heavy.build(p_delta=True).to_model()


def test_p_delta_in_a_model_file(tmp_path):
    H, n = 4.0, 4
    euler = np.pi**2 * E * I / (4 * H**2)
    doc = {
        "units": {"length": "m", "force": "kN", "time": "s"},
        "nodes": [{"id": k, "x": 0.0, "y": H * k / n} for k in range(n + 1)],
        "supports": [{"node": 0, "ux": True, "uy": True, "rz": True}],
        "elements": [{"type": "beam", "name": f"c{k}", "node_i": k, "node_j": k + 1, "E": E, "A": A, "I": I}
                     for k in range(n)],
        "masses": [{"node": n, "m": 0.3 * euler / 10.0}],
        "loads": {"gravity": {"g": 10.0}},
        "analysis": {"dt": 1e-3, "t_end": 0.01, "p_delta": True},
    }
    spec = load_model_file(write_toml(tmp_path, doc))
    fr = cantilever_column(n, H, mass=0.3 * euler / 10.0)
    fr.p_delta(g=10.0)
    assert dense(spec.model.K) == pytest.approx(dense(fr.build().to_model().K))
    assert spec.structure.axial_forces["c0"] == pytest.approx(-0.3 * euler)
    del doc["loads"]
    with pytest.raises(ModelFileError, match="p_delta"):
        load_model_file(write_toml(tmp_path, doc))


# ---------------------------------------------------------------------- the overturning point
def portal(h=3.0, span=6.0, m=2.0):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, span, 0.0)
    fr.node(3, 0.0, h)
    fr.node(4, span, h)
    fr.node(5, span / 2, 1.5 * h)        # a higher, off-base node: not part of the base
    fr.support(1, rz=True)
    fr.support(2, rz=True)
    fr.beam("c1", 1, 3, E, A, I)
    fr.beam("c2", 2, 4, E, A, I)
    fr.beam("g", 3, 4, E, A, I)
    fr.beam("r1", 3, 5, E, A, I)
    fr.beam("r2", 5, 4, E, A, I)
    for node in (3, 4):
        fr.mass(node, m)
    return fr


def test_the_overturning_moment_is_about_the_centre_of_the_base_by_default():
    import unilateral as ul
    from unilateral.analysis.results import structure_results
    from unilateral.loads import LoadHistory
    from unilateral.structure.forces import base_point

    h, span, lateral, g = 3.0, 6.0, 5.0, 9.81
    st = portal(h, span).build()
    assert base_point(st) == (span / 2, 0.0)
    load = LoadHistory(st.gravity(g) + st.nodal_load(3, ux=lateral))
    sol = ul.solve(st.to_model(), load, dt=1e-3, t_end=5e-3, method="direct", initial="static")
    res = structure_results(st, st.to_model(), {"unilateral": sol}, rule="bdf2", load_samples=load.sample(sol.t))
    dims, per_case, attrs = res["variables"]["overturning_moment"]
    # static equilibrium about the centre: the symmetric weights give no moment, the lateral load H h
    assert per_case["unilateral"][0] == pytest.approx(lateral * h, rel=1e-9)
    assert attrs["overturning_point"] == [span / 2, 0.0]
    assert res["peaks"]["unilateral"]["overturning_point"] == [span / 2, 0.0]
    about_left = structure_results(st, st.to_model(), {"unilateral": sol}, rule="bdf2", point=(0.0, 0.0))
    moment = about_left["variables"]["overturning_moment"][1]["unilateral"][0]
    assert moment == pytest.approx(lateral * h + 2 * 2.0 * g * span / 2, rel=1e-9)   # the weight's lever arm


def test_base_point_of_soil_elements_and_the_model_file_key(tmp_path):
    from unilateral.structure.forces import base_point

    fr = Frame2D()
    fr.node("top", 1.0, 5.0)
    fr.node("l", -2.0, 0.0)
    fr.node("r", 6.0, 0.0)
    fr.node("deep", 10.0, -1.0)          # a node below the base that the ground does not act on
    fr.beam("b1", "l", "top", E, A, I)
    fr.beam("b2", "top", "r", E, A, I)
    fr.beam("b3", "r", "deep", E, A, I)
    fr.soil("sl", "l", 1e4)
    fr.soil("sr", "r", 1e4)
    fr.spring("hx", "l", 1e4, direction="ux")
    fr.spring("hy", "deep", 1e4, direction="ux")
    assert base_point(fr.build()) == (10.0, -1.0)     # "deep" is on a spring to the ground: the lowest level
    doc = frame_document(4, 6.0, output={"overturning_about": [1.0, 2.0]})
    spec = load_model_file(write_toml(tmp_path, doc))
    assert spec.document.output.overturning_about == [1.0, 2.0]


# ---------------------------------------------------------------------- linear members, large drifts
def _portal_peaks(lateral, hinge=False):
    import unilateral as ul
    from unilateral.analysis.results import structure_results
    from unilateral.loads import LoadHistory

    fr = portal()
    if hinge:
        fr.hinge("h1", "c1", "i", My=1e6)
    st = fr.build()
    load = LoadHistory(st.nodal_load(3, ux=lateral))
    sol = ul.solve(st.to_model(), load, dt=1e-3, t_end=3e-3, method="direct", initial="static")
    return structure_results(st, st.to_model(), {"unilateral": sol}, rule="bdf2",
                             units={"length": "m", "force": "kN", "time": "s"})["peaks"]["unilateral"]


def test_a_note_when_linear_members_drift_above_2_percent():
    from unilateral.analysis.outputs import _result_lines

    small, large = _portal_peaks(5.0), _portal_peaks(3000.0)
    assert "linear_members_note" not in small
    ratio = max(abs(d["value"]) for d in large["drift_ratio"].values())
    assert ratio > 0.02
    note = large["linear_members_note"]
    assert note.startswith("the members do not yield in this model: drifts above 2 %")
    lines = _result_lines({"unilateral": large}, {"length": "m", "force": "kN", "time": "s"})
    assert any(line.strip() == f"note: {note}" for line in lines)
    assert "linear_members_note" not in _portal_peaks(3000.0, hinge=True)     # a yield family: no note


def test_base_shear_per_frame_of_two_pounding_frames(tmp_path):
    """Two cantilevers that pound through a gap: each frame's base shear is its own support's
    reaction, and the two add up to the total base shear."""
    from unilateral.analysis.run import analyse, settings_of
    from unilateral.structure import Frame2D
    from unilateral.structure.forces import frames

    fr = Frame2D()
    for k, x in enumerate((0.0, 1.0)):
        fr.node(f"b{k}", x, 0.0)
        fr.node(f"t{k}", x, 3.0)
        fr.support(f"b{k}", ux=True, uy=True, rz=True)
        fr.beam(f"col{k}", f"b{k}", f"t{k}", E=3e7, A=0.1, I=1e-3 * (k + 1))
        fr.mass(f"t{k}", 5.0 * (k + 1))
    fr.gap("joint", "t0", "t1", k=1e5, gap=0.002)
    st = fr.build()
    assert [sorted(g) for g in frames(st)] == [["b0", "t0"], ["b1", "t1"]]
    x = st.influence("ux")
    load = lambda t: -st.M @ x * (8.0 * np.sin(12.0 * t))
    result = analyse(st.to_model(), load, settings_of({"dt": 2e-3, "t_end": 1.0, "method": "cq", "rule": "bdf2", "lcp": "bpp"}), tmp_path / "out",
                     structure=st, units={"length": "m", "force": "kN", "time": "s"}, figure=None, title="two",
                     meta={}, cases=("unilateral",), labels=None, formats=())
    import xarray as xr

    with xr.open_dataset(tmp_path / "out" / "results.nc") as ds:
        per_frame = ds["frame_base_shear"].sel(case="unilateral").values
        total = ds["base_shear"].sel(case="unilateral").values
        support = ds["support_reaction"].sel(case="unilateral")
        assert list(ds["frame"].values) == ["frame of node b0", "frame of node b1"]
        assert np.allclose(per_frame.sum(axis=1), total, rtol=0, atol=1e-9 * np.abs(total).max())
        assert np.allclose(per_frame[:, 0], support.sel(support="b0.ux").values, rtol=0, atol=1e-12 * np.abs(total).max())
    peaks = result["results"]["unilateral"]
    assert set(peaks["frames"]) == {"frame of node b0", "frame of node b1"}
    # each cantilever alone (the gap open): T = 2 pi sqrt(m L^3 / (3 E I))
    for k in (0, 1):
        expected = 2 * np.pi * np.sqrt(5.0 * (k + 1) * 3.0 ** 3 / (3 * 3e7 * 1e-3 * (k + 1)))
        assert peaks["frame_periods"][f"frame of node b{k}"][0] == pytest.approx(expected, rel=1e-9)
