"""Frame2D/Frame3D.equal_dof (OpenSees' equalDOF between free DOFs) and [[equal_dofs]]: the tied
model equals the untied one with the tie eliminated by hand, ``K = R^T K0 R``, ``M = R^T M0 R``
(``u0 = R u``), the slave's DOFs read the master's, and bad input names the call."""

import numpy as np
import pytest
import scipy.sparse as sp

from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.opensees.toml_writer import dumps
from unilateral.structure import Frame2D, Frame3D


def dense(a):
    return a.toarray() if sp.issparse(a) else np.asarray(a)


def hinged_portal(tie=True):
    """A portal whose beam ends (nodes 5, 6) sit on the column tops (2, 3) with a rotational spring:
    tied by equal_dof on ux, uy, or (tie=False) left untied."""
    fr = Frame2D()
    for node, x, y in ((1, 0, 0), (2, 0, 3), (3, 5, 3), (4, 5, 0), (5, 0, 3), (6, 5, 3)):
        fr.node(node, x, y)
    fr.support(1, rz=True)
    fr.support(4, rz=True)
    fr.beam("c1", 1, 2, 3e7, 0.1, 1e-3)
    fr.beam("c2", 4, 3, 3e7, 0.1, 1e-3)
    fr.beam("b", 5, 6, 3e7, 0.08, 8e-4)
    fr.spring("h5", 2, 4e4, j=5, direction="rz")
    fr.spring("h6", 3, 4e4, j=6, direction="rz")
    for node, m in ((2, 10.0), (3, 10.0), (5, 2.0), (6, 2.0)):
        fr.mass(node, m)
    if tie:
        fr.equal_dof(2, 5, "ux", "uy")
        fr.equal_dof(3, 6, "ux", "uy")
    return fr


def by_hand(untied, tied, ties):
    """``R`` (n0, n) with ``u0 = R u``: each untied DOF the same-named tied DOF, a slave's the master's."""
    at = {name: k for k, name in enumerate(tied.dofs.names)}
    R = np.zeros((untied.n, tied.n))
    for k, name in enumerate(untied.dofs.names):
        node, dof = name.split(".")
        R[k, at[f"{ties.get((int(node), dof), node)}.{dof}"]] = 1.0
    return R


def test_frame2d_equal_dof_is_the_tie_eliminated_by_hand():
    tied, untied = hinged_portal().build(), hinged_portal(tie=False).build()
    assert untied.n - tied.n == 4 and not {"5.ux", "5.uy", "6.ux", "6.uy"} & set(tied.dofs.names)
    R = by_hand(untied, tied, {(5, "ux"): 2, (5, "uy"): 2, (6, "ux"): 3, (6, "uy"): 3})
    m, m0 = tied.to_model(), untied.to_model()
    K, K0 = dense(m.K), dense(m0.K)
    np.testing.assert_allclose(K, R.T @ K0 @ R, rtol=0, atol=1e-13 * abs(K0).max())
    np.testing.assert_allclose(dense(m.M), R.T @ dense(m0.M) @ R, rtol=0, atol=1e-14)
    assert np.trace(dense(m.M)) == pytest.approx(2 * (2 * 10.0 + 2 * 2.0))     # the slaves' masses kept
    f = tied.nodal_load(2, ux=1.0) + tied.nodal_load(6, rz=0.5)               # a load on a slave's own DOF
    np.testing.assert_array_equal(tied.nodal_load(5, ux=1.0, uy=2.0), tied.nodal_load(2, ux=1.0, uy=2.0))
    u = np.linalg.solve(K, f)
    nodal = tied.dofs.nodal(u)
    at = {node: p for p, node in enumerate(tied.dofs.nodes)}
    for slave, master in ((5, 2), (6, 3)):
        np.testing.assert_array_equal(nodal[at[slave], :2], nodal[at[master], :2])
        assert nodal[at[slave], 2] != nodal[at[master], 2]                     # rz its own: the spring
    assert np.allclose(R.T @ (K0 @ (R @ u)), f, rtol=0, atol=1e-12 * abs(f).max())   # equilibrium


@pytest.mark.parametrize("pinned_master", [False, True])
def test_rz_tie_equals_a_rigid_rotational_connection(pinned_master):
    """equal_dof on every DOF of coincident nodes is a rigid link: the same K and M (also when only
    the slave's rotation is used: the master's rz then becomes a DOF)."""
    def portal(how):
        fr = hinged_portal(tie=False)
        if pinned_master:                               # node 7: bars only, no rotation of its own
            fr.node(7, 2.5, 3.0)
            fr.bar("t1", 2, 7, 2e8, 1e-3)
            fr.bar("t2", 7, 3, 2e8, 1e-3)
            fr.node(8, 2.5, 3.0)
            fr.beam("s", 8, 4, 3e7, 0.01, 1e-5)
        for master, slave in ((2, 5), (3, 6)) + (((7, 8),) if pinned_master else ()):
            fr.equal_dof(master, slave, "ux", "uy", "rz") if how == "tie" else fr.rigid_link(master, slave)
        return fr.build().to_model()
    a, b = portal("tie"), portal("link")
    assert ("7.rz" in a.dof_names) is pinned_master
    assert a.dof_names == b.dof_names
    np.testing.assert_allclose(dense(a.K), dense(b.K), rtol=0, atol=1e-13 * abs(dense(b.K)).max())
    np.testing.assert_array_equal(dense(a.M), dense(b.M))


def frame3d(tie=True):
    fr = Frame3D()
    for node, xyz in ((1, (0, 0, 0)), (2, (0, 0, 3)), (3, (4, 0, 3)), (4, (4, 0, 0)), (5, (4, 0, 3))):
        fr.node(node, *xyz)
    fr.support(1, rx=True, ry=True, rz=True)
    fr.support(4, rx=True, ry=True, rz=True)
    props = dict(E=3e7, G=1.2e7, A=0.1, Iy=1e-3, Iz=2e-3, J=5e-4)
    fr.beam("c1", 1, 2, **props)
    fr.beam("b", 2, 3, **props)
    fr.beam("c2", 4, 5, **props)
    fr.spring("h", 3, 1e4, j=5, direction="ry")
    fr.mass(2, 10.0)
    fr.mass(3, 10.0)
    fr.mass(5, 3.0, Jx=0.5)
    if tie:
        fr.equal_dof(3, 5, "ux", "uy", "uz", "rx", "rz")
    return fr


def test_frame3d_equal_dof_is_the_tie_eliminated_by_hand():
    tied, untied = frame3d().build(), frame3d(tie=False).build()
    ties = {(5, dof): 3 for dof in ("ux", "uy", "uz", "rx", "rz")}
    assert untied.n - tied.n == 5 and "5.ry" in tied.dofs.names
    R = by_hand(untied, tied, ties)
    m, m0 = tied.to_model(), untied.to_model()
    np.testing.assert_allclose(dense(m.K), R.T @ dense(m0.K) @ R, rtol=0, atol=1e-13 * abs(dense(m0.K)).max())
    np.testing.assert_allclose(dense(m.M), R.T @ dense(m0.M) @ R, rtol=0, atol=1e-14)
    u = np.random.default_rng(1).standard_normal(tied.n)
    nodal = tied.dofs.nodal(u)
    np.testing.assert_array_equal(nodal[4, [0, 1, 2, 3, 5]], nodal[2, [0, 1, 2, 3, 5]])
    with pytest.raises(ValueError, match=r"5\.ux is not a free DOF: it is tied to the ux of node 3"):
        tied.dofs.index(5, "ux")


def test_a_cycle_through_a_diaphragm_is_refused():
    fr = frame3d(tie=False)
    fr.rigid_diaphragm(3, [5])
    fr.equal_dof(5, 2, "ux")
    fr.equal_dof(2, 3, "ux")
    with pytest.raises(ValueError, match="cycle"):
        fr.build()


def _portal():
    fr = Frame2D()
    for node, x, y in ((1, 0, 0), (2, 0, 3), (3, 5, 3), (4, 5, 0), (5, 0, 3)):
        fr.node(node, x, y)
    fr.support(1)
    fr.support(4)
    return fr


BAD = {
    "unknown node": (lambda fr: fr.equal_dof(2, 9, "ux"), r"equal_dof\(2, 9, 'ux'\): slave=9 is not defined"),
    "3-D dof": (lambda fr: fr.equal_dof(2, 5, "uz"), r"dofs\[0\]='uz' is not a DOF of a 2-D frame; use 'ux', 'uy', 'rz'"),
    "no dof": (lambda fr: fr.equal_dof(2, 5), r"equal_dof\(2, 5\): no DOF given"),
    "twice in a call": (lambda fr: fr.equal_dof(2, 5, "ux", "ux"), "'ux' is given twice"),
    "same node": (lambda fr: fr.equal_dof(2, 2, "ux"), "master and slave are the same node 2"),
    "supported slave": (lambda fr: fr.equal_dof(2, 1, "ux"), "ux of slave node 1 is supported"),
    "supported master": (lambda fr: fr.equal_dof(1, 2, "uy"), "uy of master node 1 is supported; a tie to a supported"),
    "support after": (lambda fr: (fr.equal_dof(2, 5, "ux"), fr.support(5)), "support at node 5: ux of node 5 are tied"),
    "support of a master after": (lambda fr: (fr.equal_dof(2, 5, "ux"), fr.support(2)), "ux of node 2 are masters"),
    "rigid link slave": (lambda fr: (fr.rigid_link(2, 5), fr.equal_dof(3, 5, "uy")),
                         r"equal_dof\(3, 5, 'uy'\): uy of node 5 already follows node 2"),
    "link after": (lambda fr: (fr.equal_dof(3, 5, "uy"), fr.rigid_link(2, 5)),
                   r"rigid_link\(2, 5\): uy of node 5 are tied by equal_dof to node 3"),
    "tied twice": (lambda fr: (fr.equal_dof(2, 5, "ux"), fr.equal_dof(3, 5, "ux")),
                   r"equal_dof\(3, 5, 'ux'\): ux of node 5 is already tied to node 2"),
    "loop": (lambda fr: (fr.equal_dof(2, 5, "ux"), fr.equal_dof(3, 2, "ux"), fr.equal_dof(5, 3, "ux")),
             r"equal_dof\(5, 3, 'ux'\): the tie would close a loop of ties of ux through node 3"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_equal_dof(case):
    call, message = BAD[case]
    with pytest.raises(ValueError, match=message):
        call(_portal())


def document(**extra):
    """A model file of :func:`hinged_portal` (tied by ``[[equal_dofs]]``)."""
    nodes = ((1, 0, 0), (2, 0, 3), (3, 5, 3), (4, 5, 0), (5, 0, 3), (6, 5, 3))
    return {"units": {"length": "m", "force": "kN", "time": "s"},
            "nodes": [{"id": n, "x": float(x), "y": float(y)} for n, x, y in nodes],
            "supports": [{"node": 1, "rz": True}, {"node": 4, "rz": True}],
            "equal_dofs": [{"master": 2, "slave": 5, "dofs": ["ux", "uy"]},
                           {"master": 3, "slave": 6, "dofs": ["ux", "uy"]}],
            "elements": [{"type": "beam", "name": "c1", "node_i": 1, "node_j": 2, "E": 3e7, "A": 0.1, "I": 1e-3},
                         {"type": "beam", "name": "c2", "node_i": 4, "node_j": 3, "E": 3e7, "A": 0.1, "I": 1e-3},
                         {"type": "beam", "name": "b", "node_i": 5, "node_j": 6, "E": 3e7, "A": 0.08, "I": 8e-4},
                         {"type": "spring", "name": "h5", "node_i": 2, "node_j": 5, "k": 4e4, "direction": "rz"},
                         {"type": "spring", "name": "h6", "node_i": 3, "node_j": 6, "k": 4e4, "direction": "rz"}],
            "masses": [{"node": n, "m": m} for n, m in ((2, 10.0), (3, 10.0), (5, 2.0), (6, 2.0))],
            "analysis": {"dt": 1e-3, "t_end": 0.01}} | extra


def test_model_file_equal_dofs_builds_the_frame(tmp_path):
    path = tmp_path / "model.toml"
    path.write_text(dumps(document()))
    spec = load_model_file(path)
    ref = hinged_portal().build().to_model()
    assert spec.model.dof_names == ref.dof_names
    np.testing.assert_array_equal(dense(spec.model.K), dense(ref.K))
    np.testing.assert_array_equal(dense(spec.model.M), dense(ref.M))


@pytest.mark.parametrize("change, message", [
    ({"master": 9}, "equal_dofs[0].master"),
    ({"dofs": ["uz"]}, "equal_dofs[0].dofs"),
    ({"dofs": []}, "equal_dofs[0].dofs"),
    ({"slave": 2}, "master and slave are the same node 2"),
    ({"slave": 1}, "equal_dofs[0]: equal_dof(2, 1, 'ux', 'uy'): ux of slave node 1 is supported"),
    ({"dofs": ["ux", "ux"]}, "'ux' is given twice"),
])
def test_model_file_equal_dofs_errors(tmp_path, change, message):
    doc = document()
    doc["equal_dofs"][0] |= change
    path = tmp_path / "model.toml"
    path.write_text(dumps(doc))
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    assert message in str(info.value), str(info.value)


def test_model_file_3d_equal_dofs(tmp_path):
    fr = frame3d()
    ref = fr.build().to_model()
    nodes = ((1, (0, 0, 0)), (2, (0, 0, 3)), (3, (4, 0, 3)), (4, (4, 0, 0)), (5, (4, 0, 3)))
    props = {"E": 3e7, "G": 1.2e7, "A": 0.1, "Iy": 1e-3, "Iz": 2e-3, "J": 5e-4}
    doc = {"units": {"length": "m", "force": "kN", "time": "s"}, "frame": {"dimensions": 3},
           "nodes": [{"id": n, "x": float(x), "y": float(y), "z": float(z)} for n, (x, y, z) in nodes],
           "supports": [{"node": n, "rx": True, "ry": True, "rz": True} for n in (1, 4)],
           "equal_dofs": [{"master": 3, "slave": 5, "dofs": ["ux", "uy", "uz", "rx", "rz"]}],
           "elements": [{"type": "beam", "name": name, "node_i": i, "node_j": j, **props}
                        for name, i, j in (("c1", 1, 2), ("b", 2, 3), ("c2", 4, 5))]
           + [{"type": "spring", "name": "h", "node_i": 3, "node_j": 5, "k": 1e4, "direction": "ry"}],
           "masses": [{"node": 2, "m": 10.0}, {"node": 3, "m": 10.0}, {"node": 5, "m": 3.0, "Jx": 0.5}],
           "analysis": {"dt": 1e-3, "t_end": 0.01}}
    path = tmp_path / "model.toml"
    path.write_text(dumps(doc))
    spec = load_model_file(path)
    assert spec.model.dof_names == ref.dof_names
    np.testing.assert_array_equal(dense(spec.model.K), dense(ref.K))
    np.testing.assert_array_equal(dense(spec.model.M), dense(ref.M))
