"""Lateral load patterns of a pushover: a given load vector, ``"uniform"``, ``"triangular"``, ``"mode"``.

For a direction ``dof`` (``"ux"`` or ``"uy"``) with the influence vector ``r`` (n,) (1 on the free
translations along it, 0 elsewhere) and the mass matrix ``M``:

* ``"uniform"``: ``p = M r``, the masses times the direction;
* ``"triangular"``: ``p_k = (M r)_k h_k``, proportional to the height ``h`` of the DOF's node above the
  lowest node (along y in 2-D, z in 3-D) times its mass;
* ``"mode"``: ``p = r * (M phi_1)``, the first mode shape of the bilateral structure
  (``K phi = omega^2 M phi``, DOFs without mass condensed statically) times the masses, on the
  translations along the direction, signed so that its resultant is positive.

The named patterns are scaled so that their resultant ``r^T p`` is the total mass ``r^T M r``: the
load factor is then the base shear per unit mass (an acceleration; over ``g``, the base-shear
coefficient). A given vector (n,) is used as it is (force units).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

#: The named patterns.
PATTERNS = ("uniform", "triangular", "mode")


def direction_vector(structure, model, dof: str) -> np.ndarray:
    """The influence vector ``r`` (n,) of a rigid translation along ``dof`` (``"ux"``, ``"uy"``).

    Parameters
    ----------
    structure : Structure or None (then the DOFs named ``"node.dof"`` of ``model`` are used)
    model : Model
    dof : str
    """
    if structure is not None:
        return np.asarray(structure.influence(dof), dtype=float)
    return np.array([1.0 if str(name).endswith("." + dof) else 0.0 for name in model.dof_names])


def load_pattern(structure, model, pattern, dof: str) -> np.ndarray:
    """The lateral load vector ``p`` (n,) of ``pattern`` along ``dof``.

    Parameters
    ----------
    structure : Structure or None (a bare model: no ``"triangular"``, which needs the nodes' heights)
    model : Model
    pattern : (n,) array_like (force units) or one of :data:`PATTERNS`
    dof : str, the direction of a named pattern (``"ux"`` or ``"uy"``)

    Returns
    -------
    (n,) ndarray

    Raises
    ------
    ValueError
        An unknown name, a vector of the wrong shape, not finite or zero, or a named pattern
        without masses along the direction.
    """
    if isinstance(pattern, str):
        return _named(structure, model, pattern, dof)
    p = np.asarray(pattern, dtype=float)
    if p.shape != (model.n,):
        raise ValueError(f"pattern must be a load vector of shape ({model.n},) (one entry per DOF) or one of "
                         f"{', '.join(map(repr, PATTERNS))}; got an array of shape {p.shape}")
    if not np.all(np.isfinite(p)) or not np.any(p):
        raise ValueError("pattern must be a finite, nonzero load vector; got "
                         + ("a zero vector" if np.all(np.isfinite(p)) else "non-finite entries"))
    return p


def _named(structure, model, pattern: str, dof: str) -> np.ndarray:
    """``"uniform"``, ``"triangular"`` or ``"mode"`` (see the module), scaled to the total mass."""
    if pattern not in PATTERNS:
        raise ValueError(f"pattern={pattern!r} is not valid; use a load vector (n,) or one of "
                         f"{', '.join(map(repr, PATTERNS))}")
    translations = ("ux", "uy", "uz") if structure is not None and len(structure.dofs.dof_names) == 6 else ("ux", "uy")
    if dof not in translations:
        raise ValueError(f"pattern={pattern!r} acts along dof={dof!r}, which is not a translation; "
                         f"use dof={' or '.join(map(repr, translations))} (or give the pattern as a load vector)")
    if pattern == "triangular" and structure is None:
        raise ValueError("pattern='triangular' needs the heights of the nodes: give a structure "
                         "(Frame2D or Structure), not a bare Model, or give the pattern as a load vector")
    r = direction_vector(structure, model, dof)
    Mr = np.asarray(model.M @ r, dtype=float).ravel()
    total = float(r @ Mr)
    if not total > 0.0:
        raise ValueError(f"pattern={pattern!r} needs masses on the {dof} DOFs; the structure has none there "
                         "(add masses, or give the pattern as a load vector)")
    if pattern == "uniform":
        p = Mr
    elif pattern == "triangular":
        p = Mr * _heights(structure)
    else:
        p = r * np.asarray(model.M @ first_mode(model), dtype=float).ravel()
    resultant = float(r @ p)
    if resultant == 0.0:
        raise ValueError(f"pattern={pattern!r} has no resultant along {dof} (the first mode does not move the "
                         "masses that way, or every mass is at the base); give the pattern as a load vector")
    return p * (total / resultant)


def _heights(structure) -> np.ndarray:
    """Height (n,) of each free DOF's node above the lowest node (length; along y in 2-D, z in 3-D)."""
    coords = structure.coords
    up = vertical_axis(structure)
    base = min(float(xy[up]) for xy in coords.values())
    return np.array([float(coords[node][up]) - base for node, _ in structure.dofs.free])


def vertical_axis(structure) -> int:
    """The index of the vertical coordinate of a structure's nodes: 1 (y) in 2-D, 2 (z) in 3-D."""
    return 2 if len(structure.dofs.dof_names) == 6 else 1


def first_mode(model) -> np.ndarray:
    """The first mode shape ``phi_1`` (n,) of ``K phi = omega^2 M phi`` (largest entry 1 in size).

    DOFs without mass are condensed statically (``K* = K_mm - K_m0 K_00^-1 K_0m``) and their shape
    recovered as ``phi_0 = -K_00^-1 K_0m phi_m``.
    """
    K = model.K.toarray() if sp.issparse(model.K) else np.asarray(model.K, dtype=float)
    M = model.M.toarray() if sp.issparse(model.M) else np.asarray(model.M, dtype=float)
    mass = np.flatnonzero(np.diag(M) > 0)
    zero = np.setdiff1d(np.arange(K.shape[0]), mass)
    if mass.size == 0:
        raise ValueError("pattern='mode' needs masses: the structure has none")
    Kmm = K[np.ix_(mass, mass)]
    expand = np.zeros((zero.size, mass.size))
    if zero.size:
        expand = -np.linalg.solve(K[np.ix_(zero, zero)], K[np.ix_(zero, mass)])
        Kmm = Kmm + K[np.ix_(mass, zero)] @ expand
    _, phi_m = sla.eigh(0.5 * (Kmm + Kmm.T), M[np.ix_(mass, mass)], subset_by_index=(0, 0))
    phi = np.zeros(K.shape[0])
    phi[mass] = phi_m[:, 0]
    phi[zero] = expand @ phi_m[:, 0]
    return phi / phi[np.argmax(np.abs(phi))]
