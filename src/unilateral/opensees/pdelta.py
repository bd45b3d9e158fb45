"""``geomTransf('PDelta', tag)`` (2-D and 3-D): the string (leaning-column) stiffness of each such element.

OpenSees's ``PDeltaCrdTransf2d`` adds to the linear transformation the end forces ``N (v_i - v_j) / L``
and ``-N (v_i - v_j) / L`` across the chord, ``v = -s u_x + c u_y`` the transverse displacements
and ``N = EA/L (u_j - u_i) . (c, s)`` the element's axial force (tension positive), and the
tangent ``N/L [[1, -1], [-1, 1]]`` on ``(v_i, v_j)``: the string P-Delta, without the cubic terms
of the consistent geometric stiffness (``6/5 N/L``, ``N L/10``). ``PDeltaCrdTransf3d`` adds the same
``N/L`` on both local transverse displacements: ``N/L [[P, -P], [-P, P]]`` on the translations at
``i`` and ``j``, ``P = I - e e^T`` across the chord ``e`` (in 2-D ``t t^T``). Here ``K`` becomes
``K + K_G(N)``, linear in ``u`` for given ``N``:

* a ``Static`` step iterates ``u -> N(u) -> K + K_G(N) -> u`` to the fixed point, the equilibrium
  OpenSees's Newton iterations converge to (the same equations, to round-off);
* a ``Transient`` analysis keeps the axial forces of the last static state (the gravity's): a
  constant geometric stiffness, while OpenSees updates ``N`` with the response (a lateral motion
  changes the columns' axial forces by overturning), so the two differ by that change
  (measured: a portal with its columns at 0.3 of the sway buckling load after gravity, then a
  ground motion, its columns' ``N`` swinging by 21 % in OpenSees: the roof drift 1.4e-4 of its
  peak apart, ``tests/test_opensees_geometry.py``);
* Rayleigh ``betaK`` and ``betaKcomm`` act on the tangent with ``K_G`` (OpenSees's current and
  committed tangents), ``betaKinit`` on the elastic stiffness;
* only elements of a ``PDelta`` transformation get it (``Linear`` and ``PDelta`` mix).

A model with a geometric stiffness is solved without the stiff-coordinate split of penalty-stiff
elements (that split rebuilds ``K`` from the natural form, which has no ``K_G``).
"""

from __future__ import annotations

import copy

import numpy as np
import scipy.sparse as sp

from ..model import check_definite
from .refusals import refuse

__all__ = ["pdelta_table", "axial_forces", "element_geometric", "with_axial", "STATIC_TOL", "MAX_ITER"]

#: The relative change of the axial forces at which the static fixed point is reached.
STATIC_TOL = 1e-13
#: The iterations of a static step at most.
MAX_ITER = 200


def pdelta_table(domain, row) -> dict:
    """``{tag: (rows (2 ndm,), w (2 ndm,), L, EA / L, beta)}`` of the beams of a ``PDelta`` transformation.

    Parameters
    ----------
    domain : Domain (2-D or 3-D)
    row : dict node tag -> its first nodal row

    Returns
    -------
    dict
        ``rows`` the nodal rows of the translations (``ndm`` of them) at ``i`` then ``j``; ``w`` the
        chord direction ``e`` on them (``(u_j - u_i) . e = w . U[rows]``, ``w = (-e, e)``); ``beta``
        the Rayleigh factor of the current and committed tangent, ``betaK + betaKcomm``, which include
        the string stiffness (``betaKinit`` multiplies the initial one, without it), or 0 for an
        element outside the ``rayleigh`` call.
    """
    from .elements import BeamColumn
    from .elements3d import BeamColumn3D

    factors, _, damped = domain.damping or ((0.0, 0.0, 0.0, 0.0), (), ())
    table = {}
    for tag, e in domain.elements.items():
        if not isinstance(e, (BeamColumn, BeamColumn3D)) or domain.transforms[e.transf][0] != "PDelta":
            continue
        d = np.subtract(domain.nodes[e.j], domain.nodes[e.i]).astype(float)
        L = float(np.linalg.norm(d))
        ndm = d.size
        rows = np.concatenate([row[e.i] + np.arange(ndm), row[e.j] + np.arange(ndm)])
        beta = factors[1] + factors[3] if tag in damped else 0.0
        table[tag] = (rows, np.concatenate([-d / L, d / L]), L, e.E * e.A / L, beta)
    return table


def axial_forces(table, U) -> dict:
    """The axial forces ``{tag: N}`` (tension positive) of the nodal displacements ``U``."""
    return {tag: float(k * (w @ U[rows])) for tag, (rows, w, _, k, _) in table.items()}


def _string(w, L, N) -> np.ndarray:
    """The string stiffness (2 ndm, 2 ndm) ``N/L [[P, -P], [-P, P]]`` on the translations at ``i``,
    ``j``, ``P = I - e e^T`` the projection across the chord ``e`` (2-D: ``t t^T``, ``t = (-s, c)``)."""
    ndm = w.size // 2
    e = w[ndm:]
    P = np.eye(ndm) - np.outer(e, e)
    return (N / L) * np.block([[P, -P], [-P, P]])


def element_geometric(table, tag, N) -> np.ndarray:
    """The string stiffness (2 ndf, 2 ndf) of element ``tag`` on its end DOFs (2-D: ``(ux, uy, rz)``
    at ``i``, ``j``; 3-D: the six DOFs of each end), zero on the rotations."""
    _, w, L, *_ = table[tag]
    ndm = w.size // 2
    ndf = 3 if ndm == 2 else 6
    at = np.concatenate([np.arange(ndm), ndf + np.arange(ndm)])
    k = np.zeros((2 * ndf, 2 * ndf))
    k[np.ix_(at, at)] = _string(w, L, N)
    return k


def _assembled(table, N, size, damping=False) -> sp.csr_matrix:
    """``K_G`` (size, size) on the nodal rows, or with ``damping`` its Rayleigh part ``beta K_G``."""
    rows, cols, vals = [], [], []
    for tag, (r, w, L, _, beta) in table.items():
        k = _string(w, L, (beta if damping else 1.0) * N.get(tag, 0.0))
        rows.append(np.repeat(r, r.size))
        cols.append(np.tile(r, r.size))
        vals.append(k.ravel())
    if not rows:
        return sp.csr_matrix((size, size))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size))


def with_axial(built, N):
    """Set the model of ``built`` to its linear model plus the string stiffness of the forces ``N``
    (in ``K``, and in the Rayleigh damping ``betaK + betaKcomm`` of the tangent).

    Parameters
    ----------
    built : Built, with ``pdelta`` (its table) and ``linear`` (the model without ``K_G``)
    N : dict tag -> axial force (missing elements: 0)

    Raises
    ------
    OpenSeesRefused
        If ``K + K_G`` is not positive definite (the axial forces reach a buckling load).
    """
    base = built.linear
    N = {tag: float(N.get(tag, 0.0)) for tag in built.pdelta}
    KG = built.P.T @ _assembled(built.pdelta, N, built.P.shape[0]) @ built.P
    model = copy.copy(base)
    model.__dict__.pop("_setup_cache", None)
    model.K = (base.K + KG).tocsr() if sp.issparse(base.K) else np.asarray(base.K + KG)
    model.natural = None
    CG = built.P.T @ _assembled(built.pdelta, N, built.P.shape[0], damping=True) @ built.P
    if CG.nnz:
        C = CG if base.C is None else base.C + CG
        model.C = sp.csr_matrix(C) if sp.issparse(base.K) else np.asarray(C.todense() if sp.issparse(C) else C)
    try:
        check_definite("K", model.K, strict=True)
    except ValueError as exc:
        refuse("geomTransf('PDelta')", f"K + K_G of the axial forces is not positive definite: they reach a "
               f"buckling load of the structure ({exc})", "smaller axial loads")
    built.model, built.axial = model, N
