"""The models of the extensions that are not the frame's natural form alone: footings on a soil medium
(``ops.footing``: the script's model on its reduced DOFs resting on the soil, a
:class:`~unilateral.soil.FoundationModel`, :func:`on_soil`) and rigid contacts (``ops.rigidContact``:
their columns ``N`` with ``H = 0`` appended, as ``Frame2D``'s rigid contacts, :func:`with_rigid`);
see :mod:`.soil_analysis` for their analysis."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..soil.foundation_model import FoundationModel
from .refusals import OpenSeesRefused, refuse

__all__ = ["on_soil", "with_rigid"]


def on_soil(built) -> None:
    """Make ``built.model`` the :class:`FoundationModel` of its footings on a soil medium (in place)."""
    st = built.structure
    fnd = st.foundation
    if built.pdelta:
        refuse("geomTransf('PDelta') with a footing on a soil medium", "the P-Delta axial forces on a soil "
               "medium are not mapped here", "geomTransf('Linear', tag), or Frame2D.p_delta in Python")
    frame = built.model
    T = built.ties.T @ fnd.T(st.dofs, st.coords)
    slide = dict(Tx=built.ties.T @ fnd.Tx(st.dofs), mu=fnd.mu) if fnd.sliding else {}
    try:
        model = _foundation_model(frame, T, fnd, slide)
    except ValueError as exc:
        raise OpenSeesRefused("analyze", f"the footings on the soil cannot be built: {exc}",
                              "a footing whose node moves vertically and rotates freely") from None
    built.frame_model, built.model, built.linear = frame, model, model
    rows, S_u, S_v, s0, ne = built.stress           # the stresses read v of the frame's constraints only
    S_v = sp.hstack([S_v, sp.csr_matrix((S_v.shape[0], model.m - frame.m))]).tocsr()
    built.stress = (rows, S_u, S_v, s0, ne)


def _foundation_model(frame, T, fnd, slide) -> FoundationModel:
    """The frame's model on the soil: :meth:`FoundationModel.on` with constraints of its own; without, the
    plain model of its ``M, K, C`` (dense up to 2000 DOFs), as ``Frame2D`` makes it."""
    names = list(fnd.contact_names)
    if frame.m or np.any(frame.q_imposed(0.0)):
        return FoundationModel.on(frame, T, fnd.soil, gap=fnd.gap, contact_names=names, **slide)
    small = frame.n <= 2000
    M, K, C = (None if X is None else (X.toarray() if small and sp.issparse(X) else X)
               for X in (frame.M, frame.K, frame.C))
    if small:
        T, slide = np.asarray(T.todense() if sp.issparse(T) else T), {
            key: (np.asarray(value.todense() if sp.issparse(value) else value) if key == "Tx" else value)
            for key, value in slide.items()}
    return FoundationModel(M, K, T, fnd.soil, C=C, gap=fnd.gap, dof_names=list(frame.dof_names),
                           contact_names=names, **slide)


def with_rigid(built) -> None:
    """Append the rigid contacts of ``built.structure`` to ``built.model`` (in place): the columns
    ``T^T N`` of their normals on the reduced DOFs, ``H = 0``, ``g = -gap`` and the family
    :class:`~unilateral.constraints.RigidContact` (as :func:`unilateral.structure.rigid` does)."""
    from ..constraints import RigidContact as RigidFamily
    from ..model import Model

    part, old = built.structure.rigid, built.model
    if built.structure.foundation is not None or built.pdelta:
        refuse("rigidContact with a footing on a soil medium or geomTransf('PDelta')", "the rigid contacts are "
               "mapped on the frame's own model only", "rigidContact on a frame without them")
    n, m, mr = old.n, old.m, len(part.contacts)
    N = sp.csr_matrix(built.ties.T @ part.N)
    F = np.hstack([np.asarray(old.F.todense() if sp.issparse(old.F) else old.F), N.toarray()])
    H = np.zeros((m + mr, m + mr))
    H[:m, :m] = old.H
    g = np.concatenate([np.asarray(old.g(0.0), dtype=float), -part.gap])
    F_v = H_v = None
    if old.F_v is not None:
        F_v = np.hstack([np.asarray(old.F_v.todense() if sp.issparse(old.F_v) else old.F_v), np.zeros((n, mr))])
        H_v = np.zeros((m + mr, m + mr))
        H_v[:m, :m] = old.H_v
    mu = [c.mu for c in part.contacts]
    tangent = (built.ties.T @ part.tangent).toarray() if any(mu) else None
    families = list(old.families) + [RigidFamily(np.arange(m, m + mr), name="rigid contact", mu=mu, tangent=tangent,
                                                 restitution=[c.restitution for c in part.contacts])]
    model = Model(M=old.M, K=sp.identity(n, format="csr"), F=F, H=H, C=old.C, g=g, F_v=F_v, H_v=H_v,
                  q_imposed=old.q_imposed(0.0), dof_names=list(old.dof_names),
                  constraint_names=list(old.constraint_names) + list(part.names), families=families)
    model.K = old.K                                # (singular for a free body: see unilateral.structure.rigid)
    built.model = built.linear = model
    rows, S_u, S_v, s0, ne = built.stress
    built.stress = (rows, S_u, sp.hstack([S_v, sp.csr_matrix((S_v.shape[0], mr))]).tocsr(), s0, ne)
