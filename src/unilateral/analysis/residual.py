"""The static residual state of a run and the roof drift ratio, for ``summary.json``.

The *static residual* is the static equilibrium the structure comes to rest in once the
excitation is removed, with the plastic deformations and slips frozen at their values at the
last step (as OpenSees users compute it after a record: a static analysis, or free vibration
with damping until at rest, without further yielding). With the rate unknowns (yield,
friction) ``v_r`` held at the last step's values, the contacts ``v_c`` solve the static LCP

    K u = q_s + F_r v_r + F_c v_c,   psi_c = F_c^T u - H_cr v_r - H_cc v_c - g_c(0) <= 0,
    v_c >= 0,   psi_c^T v_c = 0,

(``q_s``: the time-independent part of the load, the gravity; ``Lambda = H_cc - F_c^T K^-1 F_c``).
On an undamped frame that does not yield again, the free vibration after the record oscillates
about this state; ``residual_drift`` (the drift at the last step) includes that vibration.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from ..initial import static_lcp
from ..lcp import get_lcp_solver
from ..linalg import Factorization, dense, transpose_times
from ..model import Model
from ..model.stiff import StiffCoordinates


class ResidualUnavailable(ValueError):
    """The static residual cannot be computed for this model (the message says why)."""


def static_residual(model, q_static, v_end, solver=None) -> np.ndarray:
    """The displacements ``u`` (n,) of the static residual state of a matrix model.

    Parameters
    ----------
    model : Model, the one the run solved (plain matrices; not a soil medium)
    q_static : (n,) the applied load with the excitation removed [force] (the load of the model's imposed
        strains, ``q_imposed(0)``: gaps, prestrains, is added)
    v_end : (m,) the unknowns at the last step; its rate (yield, friction) entries are frozen
    solver : LCP solver for the contacts (default ``"bpp"``, Lemke as fallback)

    Raises
    ------
    ResidualUnavailable
        For a model other than a plain :class:`~unilateral.model.Model`, one with free unknowns,
        or one whose static contact problem has no solution.
    """
    if not isinstance(model, Model):
        raise ResidualUnavailable(f"the model is a {type(model).__name__}, not a matrix model (a soil medium's "
                                  "static residual is not computed)")
    q_static = np.asarray(q_static, dtype=float).ravel()
    v_end = np.asarray(v_end, dtype=float).ravel()
    if q_static.shape != (model.n,) or v_end.shape != (model.m,):
        raise ResidualUnavailable(f"q_static has shape {q_static.shape} and v_end {v_end.shape}: expected "
                                  f"({model.n},) and ({model.m},)")
    if model.law.free.any():
        raise ResidualUnavailable("the model has unknowns of either sign (free rows): no static residual")
    return _residual(model, q_static + np.asarray(model.q_imposed(0.0), dtype=float), v_end, solver)


def _residual(model, q0, v_end, solver) -> np.ndarray:
    """:func:`static_residual` under the total load ``q0`` (imposed strains' load included), in the
    coordinates of the stiff split where the model has penalty-stiff elements (as :func:`unilateral.initial.static_state`)."""
    law = model.law
    stiff = StiffCoordinates.of(model)
    if stiff is not None:
        T = stiff.split.T
        return np.asarray(T @ _residual(stiff.conditioned, T.T @ q0, v_end, solver)).ravel()
    K = Factorization(model.K, what="K (the structure with every constraint held bilateral)")
    F, H = dense(model.F), dense(model.H)
    frozen = np.asarray(law.rate, dtype=bool)
    c = ~frozen
    uq = K.solve(q0 + F[:, frozen] @ v_end[frozen])
    if not c.any():
        return np.asarray(uq).ravel()
    Fc = F[:, c]
    KFc = K.solve(Fc)
    Lambda = H[np.ix_(c, c)] - transpose_times(Fc, KFc)
    Lambda = 0.5 * (Lambda + Lambda.T)
    psiL = transpose_times(Fc, uq) - H[np.ix_(c, frozen)] @ v_end[frozen] - np.asarray(model.g(0.0))[c]
    v_c, _, message = static_lcp(Lambda, psiL, solver or get_lcp_solver("bpp"))
    if message:
        raise ResidualUnavailable(message.replace("under the load at t = 0", "with the plastic deformations frozen"))
    return np.asarray(uq + KFc @ v_c).ravel()


def roof_drift(structure, u) -> tuple[np.ndarray, float] | None:
    """The roof drift ``ux(top) - ux(base)`` (N+1,) of displacements ``u`` (N+1, n) of a 2-D frame and
    the height ``y(top) - y(base)``: each level's ``ux`` the mean over its nodes; None for fewer than
    two levels."""
    from ..structure import forces as F

    levels = F.storeys(structure)
    if len(levels) < 2:
        return None
    nodal = structure.dofs.nodal(np.atleast_2d(u))
    position = {node: p for p, node in enumerate(structure.dofs.nodes)}
    mean = [nodal[:, [position[node] for node in nodes], 0].mean(axis=1) for _, nodes in (levels[0], levels[-1])]
    return mean[1] - mean[0], float(levels[-1][0] - levels[0][0])


def residual_peaks(structure, sol, t, static_load=None, load_samples=None, storey_pairs=None, model=None) -> dict:
    """The ``roof_drift_ratio`` (peak, last step, static residual) and ``residual_drift_static`` (the
    storeys' drifts in the static residual state: ``storey``, ``drift``, ``ratio``, ``storeys``) of one
    case of a 2-D frame, or ``residual_drift_static_note`` with the reason it was not computed.

    ``static_load`` (n,): the load with the excitation removed (default: ``load_samples[0]``, the load
    the run's static state was under)."""
    from ..structure import forces as F

    out: dict = {}
    q_static = static_load if static_load is not None else (None if load_samples is None else load_samples[0])
    roof = roof_drift(structure, sol.u)
    u_s, note = None, None
    if q_static is None:
        note = "no load given: no static residual"
    else:
        try:
            u_s = static_residual(model if model is not None else structure.to_model(), q_static, sol.v[-1])
        except (ResidualUnavailable, ValueError) as exc:
            note = str(exc)
    if roof is not None and roof[1] != 0:
        ratio = roof[0] / roof[1]
        k = int(np.argmax(np.abs(ratio)))
        out["roof_drift_ratio"] = {"value": float(ratio[k]), "t": float(t[k]), "residual": float(ratio[-1]),
                                   "height": roof[1]}
        if u_s is not None:
            out["roof_drift_ratio"]["residual_static"] = float(roof_drift(structure, u_s)[0][0] / roof[1])
    if u_s is not None:
        drifts = F.storey_drifts(structure, SimpleNamespace(u=u_s[None, :]), storey_pairs)
        if drifts:
            storeys = {label: {"drift": float(d[0]), "ratio": float(r[0])} for label, (d, r) in drifts.items()}
            label = max(storeys, key=lambda s: abs(storeys[s]["ratio"]))
            out["residual_drift_static"] = {"storey": label, **storeys[label], "storeys": storeys}
    elif note:
        out["residual_drift_static_note"] = note
    return out
