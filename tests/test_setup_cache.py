"""Set-up kept on a model between solves (``unilateral.model.remembered``): a batch's analyses of one model
variant solve its static state and find its poles once, with results equal to a fresh model's."""

import numpy as np

import unilateral as ul
from unilateral import initial
from unilateral.kernels import PoleResidueKernel
from unilateral.structure.examples import liolios1990


def test_the_static_state_and_the_poles_are_found_once_per_model(monkeypatch):
    calls = {"static": 0, "poles": 0}
    lcp, poles = initial.static_lcp, PoleResidueKernel.from_model.__func__

    def counted_lcp(*args, **kwargs):
        calls["static"] += 1
        return lcp(*args, **kwargs)

    def counted_poles(cls, *args, **kwargs):
        calls["poles"] += 1
        return poles(cls, *args, **kwargs)

    monkeypatch.setattr(initial, "static_lcp", counted_lcp)
    monkeypatch.setattr(PoleResidueKernel, "from_model", classmethod(counted_poles))
    structure, load, _ = liolios1990()
    model = structure.to_model()
    runs = [ul.solve(model, load, method="modal", dt=1e-3, t_end=0.2) for _ in range(3)]
    assert calls == {"static": 1, "poles": 1}
    fresh = ul.solve(structure.to_model(), load, method="modal", dt=1e-3, t_end=0.2)
    assert calls == {"static": 2, "poles": 2}
    for sol in runs:
        assert np.array_equal(sol.u, fresh.u) and np.array_equal(sol.psi, fresh.psi)
    scaled = ul.solve(model, lambda t: 2.0 * np.asarray(load(t)), method="modal", dt=1e-3, t_end=0.2)
    assert calls["static"] == 3 and not np.allclose(scaled.u[0], fresh.u[0])     # another q(0): solved again


def test_each_solve_gets_its_own_copy_of_the_static_state():
    structure, load, _ = liolios1990()
    model = structure.to_model()
    q0 = np.asarray(load(0.0), dtype=float)
    solver = ul.lcp.get_lcp_solver("bpp")
    first = initial.static_state(model, q0, solver)
    first.u[:] = 1e9
    first.v[:] = -1.0
    second = initial.static_state(model, q0, solver)
    assert np.all(np.abs(second.u) < 1.0) and np.all(second.v >= 0)
