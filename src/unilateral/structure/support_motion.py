"""Multiple-support excitation: a displacement history imposed on supported DOFs.

A supported DOF ``s`` of a frame is removed from ``u``; giving it a motion ``u_s(t)``
(:meth:`SupportMotions.support_motion`) strains every element attached to it by ``l_s u_s(t)``,
``l_s`` (ne,) the column of the compatibility ``e = L u_full`` at that DOF. For the free DOFs this
is an imposed strain varying in time (Liolios 1990, eqs. 13-16, with ``theta`` a function of time):

    theta(t) = theta_0 - sum_s l_s u_s(t)

so that ``G E theta`` is the load ``-K_fs u_s`` of the moving supports, ``B^T E theta`` moves the
gaps of the unilateral elements attached to them (a gap closing on a moving abutment), and the
element stresses ``sigma = E (G^T u - B v - theta)`` are the total ones. ``u`` is the **total**
motion (not relative to a ground), as OpenSees's ``MultipleSupport`` pattern gives it. With Kelvin
elements on a moving support the rate ``theta'(t) = -sum_s l_s u_s'(t)`` enters as well.

Damping that the free DOFs' equations cannot carry is refused rather than dropped: the
stiffness-proportional Rayleigh term (``a1 K``) and attached dashpots on a moving support would
load the structure by ``-C_fs u_s'``. Mass-proportional and modal damping act on the free DOFs
(absolute velocities) and are kept. The lumped masses of supported DOFs carry no equation, so the
support accelerations do not enter.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True)
class Motion:
    """The imposed motion of one supported DOF: ``displacement(t)`` (length) and, where known,
    ``velocity(t)`` (length/s; from the function's piecewise form when not given)."""

    node: object
    dof: str
    displacement: object
    velocity: object = None


class SupportStrains:
    """``theta(t) = theta_0 - L_s u_s(t)`` (ne,): the imposed strains of a frame with moving supports.

    Parameters
    ----------
    theta0 : (ne,) the constant imposed strains (gaps, slack, prestrains)
    L_s : (ne, s) csr, the strains of a unit motion of each moving supported DOF
    motions : tuple of :class:`Motion`, length s
    """

    def __init__(self, theta0, L_s, motions):
        self.theta0 = np.asarray(theta0, dtype=float)
        self.L_s = L_s
        self.motions = tuple(motions)

    def support_displacements(self, t) -> np.ndarray:
        """``u_s(t)`` (s,) for a scalar ``t``, or (N, s) for times ``t`` (N,)."""
        return _evaluate([m.displacement for m in self.motions], t)

    def __call__(self, t) -> np.ndarray:
        return self.theta0 - self.L_s @ self.support_displacements(float(t))


class SupportStrainRates:
    """``theta'(t) = -L_s u_s'(t)`` (ne,)."""

    def __init__(self, L_s, motions):
        self.L_s = L_s
        self.velocities = [m.velocity for m in motions]

    def __call__(self, t) -> np.ndarray:
        return -(self.L_s @ _evaluate(self.velocities, float(t)))


def _evaluate(functions, t) -> np.ndarray:
    t = np.asarray(t, dtype=float)
    values = [np.broadcast_to(np.asarray(f(t), dtype=float), t.shape) for f in functions]
    return np.stack(values, axis=-1)


class SupportMotions:
    """The :meth:`support_motion` of :class:`~unilateral.structure.Frame2D` and
    :class:`~unilateral.structure.Frame3D` (a mixin: the motions are kept until ``build``)."""

    def support_motion(self, node, dof, displacement, *, velocity=None) -> None:
        """Impose the displacement history ``displacement(t)`` (length) on the supported DOF
        ``dof`` of ``node``: multiple-support excitation, the response being the total motion.

        Parameters
        ----------
        node : a node with ``dof`` supported (:meth:`support`)
        dof : str, one of the frame's DOF names (``"ux"``, ``"uy"``, ``"rz"`` in 2-D)
        displacement : callable ``t -> float`` (length), e.g. a
            :class:`~unilateral.loads.Tabulated` record of the support's displacement (sampled at
            the step times, as OpenSees samples an imposed motion)
        velocity : callable ``t -> float`` (length/s), optional
            Needed only with Kelvin elements attached to the moving support; by default the
            derivative of ``displacement``'s piecewise form (a :class:`~unilateral.loads.TimeFunction`).

        Supports moving alike give the response of a uniform ground motion plus the rigid
        translation (``tests/test_support_motion.py``).
        """
        where = f"support_motion at node {node!r}"
        self._node(where, "node", node)
        if dof not in self._dof_names:
            raise ValueError(f"{where}: dof={dof!r} is not a DOF (valid: {', '.join(self._dof_names)})")
        if (node, dof) not in self._restrained:
            raise ValueError(f"{where}: {dof} is a free DOF; a support motion acts on a supported DOF "
                             f"(support({node!r}, {dof}=True) first)")
        for arg, f in (("displacement", displacement), ("velocity", velocity)):
            if f is not None and not callable(f):
                raise TypeError(f"{where}: {arg} must be a time function f(t), got {f!r}")
        motions = self.__dict__.setdefault("_support_motions", {})
        if (node, dof) in motions:
            raise ValueError(f"{where}: {dof} already has a support motion")
        if velocity is None:
            velocity = _derivative(displacement)
        motions[(node, dof)] = Motion(node, dof, displacement, velocity)


def _derivative(f):
    """The derivative of a time function with a piecewise form, else None."""
    form = getattr(f, "piecewise", lambda: None)()
    if form is None:
        return None
    return lambda t: form.evaluate(t, derivative=1)


def attach(frame, structure):
    """``structure`` with the support motions of ``frame`` in its imposed strains (or itself)."""
    motions = tuple(frame.__dict__.get("_support_motions", {}).values())
    if not motions:
        return structure
    _check_damping(frame, structure, motions)
    _check_ties(frame, motions)
    L_s = _strain_columns(structure, motions)
    nat = structure.natural
    rates = None
    if nat.E_v is not None and (nat.E_v @ L_s).nnz:
        missing = [m for m in motions if m.velocity is None]
        if missing:
            raise ValueError(f"support_motion at node {missing[0].node!r}: a Kelvin element on the moving support "
                             f"needs the velocity of {missing[0].dof}; give velocity= or a TimeFunction")
        rates = SupportStrainRates(L_s, motions)
    elif nat.E_v is not None:
        rates = SupportStrainRates(L_s, [dataclasses.replace(m, velocity=lambda t: 0.0) for m in motions])
    natural = dataclasses.replace(nat, theta=SupportStrains(nat.theta(0.0), L_s, motions), theta_rate=rates)
    return dataclasses.replace(structure, natural=natural)


def _check_damping(frame, structure, motions) -> None:
    where = f"support_motion at node {motions[0].node!r}"
    if structure.foundation is not None:
        raise ValueError(f"{where}: not available with a foundation on a soil medium")
    if (frame.__dict__.get("_rigid") or {}).get("contacts"):
        raise ValueError(f"{where}: not available with rigid contacts (their gaps are constant)")
    if structure.rayleigh and structure.rayleigh[1]:
        raise ValueError(f"{where}: stiffness-proportional Rayleigh damping (a1 = {structure.rayleigh[1]!r}) would "
                         "load the structure by -a1 K_fs u_s' through the moving support; use mass-proportional "
                         "(a1 = 0) or modal damping")
    moving = {(m.node, m.dof) for m in motions}
    for d in structure.dashpots:
        if moving & set(d.dofs):
            raise ValueError(f"{where}: the dashpot {d.name!r} is attached to a moving support; attach it to a free "
                             "node or use a Kelvin element (soil, gap with c=)")


def _check_ties(frame, motions) -> None:
    moving = {m.node for m in motions}
    for node in frame._coords:
        master = frame._master(node)
        while master is not None and master not in moving:
            master = frame._master(master)
        if master is not None:
            raise ValueError(f"support_motion at node {master!r}: node {node!r} is tied to the moving support "
                             "(rigid link or diaphragm); connect it by an element instead")


def _strain_columns(structure, motions) -> sp.csr_matrix:
    """``L_s`` (ne, s): the strains of a unit displacement of each moving supported DOF."""
    rows, cols, vals, start = [], [], [], 0
    column = {(m.node, m.dof): j for j, m in enumerate(motions)}
    for e in structure.elements:
        for c, key in enumerate(e.dofs):
            j = column.get(key)
            if j is not None:
                for r in np.flatnonzero(e.a[:, c]):
                    rows.append(start + r)
                    cols.append(j)
                    vals.append(e.a[r, c])
        start += e.E.shape[0]
    L_s = sp.csr_matrix((vals, (rows, cols)), shape=(start, len(motions)))
    idle = [m for j, m in enumerate(motions) if L_s[:, j].nnz == 0]
    if idle:
        raise ValueError(f"support_motion at node {idle[0].node!r}: no element is attached to {idle[0].dof}; "
                         "the motion would move nothing")
    return L_s


def support_displacement(structure, node, dof, sol) -> np.ndarray | None:
    """The imposed history (N+1,) of ``(node, dof)`` at the times ``sol.t``, or None if it does not move."""
    theta = structure.natural.theta
    if not isinstance(theta, SupportStrains):
        return None
    for j, m in enumerate(theta.motions):
        if (m.node, m.dof) == (node, dof):
            return np.asarray(theta.support_displacements(np.asarray(sol.t, dtype=float)))[..., j]
    return None

