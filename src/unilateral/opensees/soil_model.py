"""The models of the extensions that are not the frame's natural form alone: footings on a soil medium
(``ops.footing``: the script's model on its reduced DOFs resting on the soil, a
:class:`~unilateral.soil.FoundationModel`, :func:`on_soil`) and rigid contacts (``ops.rigidContact``:
their columns ``N`` with ``H = 0`` appended, as ``Frame2D``'s rigid contacts, :func:`rigid_model`);
see :mod:`.soil_analysis` for their analysis."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..soil.foundation_model import FoundationModel
from .refusals import OpenSeesRefused, refuse

__all__ = ["on_soil", "rigid_model"]


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


def rigid_model(st, T, M, C, names):
    """The model of the frame ``st`` with rigid contacts on the reduced DOFs ``u_structure = T u``:
    its elements' natural form with the columns ``T^T N`` of the contacts' normals appended, ``H = 0``,
    ``g = -gap`` and the family :class:`~unilateral.constraints.RigidContact`, as
    :mod:`unilateral.structure.rigid` makes it (``K`` may be singular: a body resting on the contacts).

    Parameters
    ----------
    st : the built frame with ``rigid``;  T : (n_structure, n) csr, the ties
    M, C : (n, n) the script's mass and damping (C None: none);  names : the n DOF names
    """
    from ..structure.rigid import contact_model

    if st.foundation is not None:
        refuse("rigidContact with a footing on a soil medium", "the rigid contacts are mapped on the frame's own "
               "model only", "rigidContact on a frame without ops.footing")
    return contact_model(st, st.rigid, M=M, C=C, dof_names=names, T=T)
