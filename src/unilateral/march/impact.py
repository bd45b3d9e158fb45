"""A velocity-level impact law for rigid contacts: the Moreau-Jean time stepping with Newton's law,
and impacts located within the step.

The position-level LCP of ``method="direct"`` holds the opening of a rigid contact at zero at the
end of a step, and what that does to the velocity depends on the rule (BDF1: a plastic impact,
the trapezoidal rule: a bounce; ``docs/rocking.md``). Here the contacts act on the *velocity*
(Moreau 1988, Jean 1999). A step of length ``h`` is the theta-method on
``M u'' + C u' + K u = q + N lambda`` with the impulses ``P = h lambda`` of the step:

    M (v1 - v0) = h (q_th - C v_th - K u_th) + N P,     u1 = u0 + h v_th,
    x_th = (1 - th) x0 + th x1,

and every contact ``j`` of the step's active set obeys Newton's impact law in complementarity
with its impulse:

    U_j = N_j^T v1 + e_j N_j^T v0 >= 0,   P_j >= 0,   U_j P_j = 0

(``e`` the coefficients of restitution). A persistent contact keeps ``N^T v = 0``, so its opening
does not drift (linear constraints).

**Impacts located within the step** (``locate=True``, the default). The active set of a step is
the contacts that touch at its start and do not separate. If the step so taken ends with another
contact penetrating, the time ``tau`` at which its opening reaches zero is the root of the opening
of the partial step of length ``tau`` (bracketed, then the Illinois method to ``1e-14`` of the
length scale); the state is advanced to ``tau``, the impact is applied there as a jump of the
velocity (the impact LCP ``v+ = v- + X P``, ``X = M^-1 N`` with massless DOFs condensed,
``U = N^T v+ + e N^T v- >= 0`` on every contact that touches), and the rest of the step is taken
the same way, landing back on the grid. An accumulation of impacts (Zeno: a ball bouncing to
rest) is cut by holding a contact whose rebound would return within a step (``2 e |U-| < dt a``
with ``a`` the normal acceleration that pulls it back: the impact is then plastic, ``e = 0``);
after ``max_events`` impacts in one step the rest of the step is taken by the plain rule. ``locate=False``
is the plain Moreau-Jean scheme: the active set is the contacts whose opening predicted at
mid-step, ``N^T (u0 + h v0 / 2) - g``, is not positive, and an impact is applied at the end of the
step in which the contact arrives (first order in the impact's effect).

**Redundant contacts.** Where more contacts close than the DOFs they move (a 3-D box's four
corners on ``uz``, ``rx``, ``ry``), the LCP's matrix is singular and its impulses are not unique
(the velocities are): :func:`spread` takes the least-norm member of the solution set (a box at rest
carries ``W / 4`` on each corner), so that a vertex solution's unloaded corner does not show as a
contact change. Contacts that are never redundant (every 2-D case) keep the LCP's solution.

**Energy.** With ``x_th`` as above, every step satisfies exactly

    Delta (v^T M v / 2 + u^T K u / 2) = h q_th^T v_th - h v_th^T C v_th + P^T N^T v_th
                                         - (th - 1/2) (Delta v^T M Delta v + Delta u^T K Delta u)

and a located impact ``Delta (v^T M v / 2) = P^T N^T (v+ + v-) / 2``. The march accumulates the
terms: the external work, the damping, the energy lost at impacts ``-P^T N^T v_bar`` (zero for a
persistent contact; ``(1 - e^2)`` times the normal kinetic energy ``(N^T v-)^2 / (2 N^T X)`` at a
located impact on one contact) and the numerical dissipation (zero for ``th = 1/2``), so that the
balance closes to round-off (:mod:`unilateral.analysis.rigid`).

**Friction** (contacts with ``mu > 0``): Coulomb's law on the tangential impulses, in the same
velocity-level LCP. The friction cone of a contact is a polygon on its tangent axes (one axis
``t`` in 2-D: the segment ``|Pt| <= mu P``; ``t1``, ``t2`` in 3-D: the polygon of ``facets``
facets circumscribing Coulomb's circle, :func:`~unilateral.constraints.families.friction_polygon`)
spanned by its generators ``g_k`` (the polygon's vertices): ``Pt = sum_k beta_k g_k``,
``beta >= 0``, with the slip rate ``lam`` of the contact (Stewart and Trinkle's form)

    g_k^T T^T v1 + lam >= 0  _|_  beta_k >= 0,        mu P - sum_k beta_k >= 0  _|_  lam >= 0,

the principle of maximal dissipation over the polygon: a contact sticks (``T^T v1 = 0``) with
``Pt`` in it, or slides with ``Pt`` on its boundary where the slip ``T^T v1`` is in the normal
cone. Lemke's method solves this LCP (copositive: it terminates with a solution). The friction
work ``-Pt^T T^T v_th`` of each step (and at impacts, in their loss) joins the balance.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..linalg import dense
from .step_log import StepLog

#: The energy terms the march accumulates, in the order of :attr:`MoreauJeanMarch.work`.
WORK_TERMS = ("external_work", "damping", "impact_loss", "numerical_dissipation", "friction_work")
#: Relative tolerance of "touching" (opening) and "at rest" (normal velocity).
OPEN_TOL, VELOCITY_TOL = 1e-11, 1e-10


@dataclasses.dataclass
class ImpactSystem:
    """The matrices of a model with rigid contacts only, as the march uses them.

    Attributes
    ----------
    M, K, C : (n, n) mass, stiffness (of the structure without its rigid contacts), damping
    N : (n, m) the contacts' normals (``F``);  e : (m,) coefficients of restitution
    g : callable ``g(t) -> (m,)`` (opening ``N^T u - g``);  q : callable ``q(t) -> (n,)`` load
    X : (n, m) the velocity jump of a unit impulse on each contact (``M^-1 N``, massless DOFs
        condensed statically)
    T : (n, m) one tangent per contact (zero columns without friction), or None; replaced by the
        cones' tangent axes ``cones.T`` (n, R)
    mu : (m,) Coulomb's coefficients (0: no friction)
    cones : FrictionCones of the contacts with friction, or None (from ``T``: one tangent each)
    """

    M: np.ndarray
    K: np.ndarray
    C: np.ndarray
    N: np.ndarray
    e: np.ndarray
    g: object
    q: object
    X: np.ndarray = None
    T: np.ndarray = None
    mu: np.ndarray = None
    cones: FrictionCones = None

    def __post_init__(self):
        n, m = self.N.shape
        if self.X is None:
            self.X = inertia_solve(self.M, self.K, self.N)
        if self.mu is None or not np.any(self.mu > 0):
            self.mu, self.cones = np.zeros(m), None
        if self.cones is None:
            self.cones = FrictionCones.build(n, [(j, self.T[:, j:j + 1], 2) for j in np.flatnonzero(self.mu > 0)])
        self.T, self.D = self.cones.T, self.cones.T @ self.cones.G
        self.XD = inertia_solve(self.M, self.K, self.D) if self.D.shape[1] else np.zeros((n, 0))

    def opening(self, u, t) -> np.ndarray:
        return self.N.T @ u - self.g(t)


@dataclasses.dataclass
class FrictionCones:
    """The friction cones of the contacts with friction on the DOFs (see the module).

    Attributes
    ----------
    T : (n, R) the contacts' tangent axes (one per 2-D contact, ``t1``, ``t2`` per 3-D contact)
    axis_of : (R,) the contact (index in ``0..m-1``) of each axis
    G : (R, L) the generators of the cones (their vertices for ``mu P = 1``) on the axes
    of : (L,) the contact of each generator
    normals : (Q, R) the unit outward normals of the cones' facets (at distance ``mu P``)
    normal_of : (Q,) the contact of each facet
    """

    T: np.ndarray
    axis_of: np.ndarray
    G: np.ndarray
    of: np.ndarray
    normals: np.ndarray
    normal_of: np.ndarray

    @classmethod
    def build(cls, n, contacts) -> FrictionCones:
        """The cones of ``contacts``, a list of ``(j, axes (n, r), facets)`` (contact ``j``, its
        tangent axes, the facets of its polygon: 2 for one axis); the generators ordered by their
        number within the cone, then by contact (2-D: every ``+t``, then every ``-t``)."""
        from ..constraints.families import friction_polygon

        contacts = sorted(contacts, key=lambda c: c[0])
        T = np.column_stack([c[1] for c in contacts]) if contacts else np.zeros((n, 0))
        axis_of = np.concatenate([[c[0]] * c[1].shape[1] for c in contacts]).astype(int) if contacts else \
            np.zeros(0, dtype=int)
        polygons = [friction_polygon(int(c[2])) for c in contacts]
        start = np.cumsum([0] + [c[1].shape[1] for c in contacts])
        order = sorted((k, i) for i, (_, gens) in enumerate(polygons) for k in range(len(gens)))
        G = np.zeros((T.shape[1], len(order)))
        for col, (k, i) in enumerate(order):
            G[start[i]:start[i + 1], col] = polygons[i][1][k]
        normals = np.zeros((sum(len(p[0]) for p in polygons), T.shape[1]))
        rows = np.cumsum([0] + [len(p[0]) for p in polygons])
        for i, (d, _) in enumerate(polygons):
            normals[rows[i]:rows[i + 1], start[i]:start[i + 1]] = d
        normal_of = np.concatenate([[c[0]] * len(p[0]) for c, p in zip(contacts, polygons)]).astype(int) \
            if contacts else np.zeros(0, dtype=int)
        of = np.array([contacts[i][0] for _, i in order], dtype=int)
        return cls(T=T, axis_of=axis_of, G=G, of=of, normals=normals, normal_of=normal_of)

    def outside(self, Pt, P, mu, rtol=1e-9) -> bool:
        """Whether a tangential force (or impulse) ``Pt`` (R,) on the axes lies outside the cone of
        its normal force ``P`` (m,): ``d . Pt > mu P (1 + rtol)`` on a facet."""
        bound = mu[self.normal_of] * P[self.normal_of]
        return bool(np.any(self.normals @ Pt > bound * (1.0 + rtol) + 1e-300))


def inertia_solve(M, K, R) -> np.ndarray:
    """``M^-1 R`` (n, k) on the DOFs with mass; the DOFs without (a massless rotation of a beam's
    end) follow by the static condensation ``x_0 = -K00^-1 K0m x_m``, the forces on them carried
    onto the others, ``R_m - K_m0 K00^-1 R_0``."""
    R = np.asarray(R, dtype=float)
    mass = np.diag(M) > 0
    if mass.all():
        return np.linalg.solve(M, R)
    K00 = K[np.ix_(~mass, ~mass)]
    out = np.zeros_like(R)
    out[mass] = np.linalg.solve(M[np.ix_(mass, mass)], R[mass] - K[np.ix_(mass, ~mass)] @ np.linalg.solve(K00, R[~mass]))
    out[~mass] = -np.linalg.solve(K00, K[np.ix_(~mass, mass)] @ out[mass])
    return out


def forces_at_rest(system, u, udot, t=0.0) -> tuple[np.ndarray, np.ndarray]:
    """``(lam (m,), accel (n,))``: the contact forces of the touching rigid contacts at rest
    (opening and normal velocity zero to the tolerances) that the acceleration-level LCP gives,
    ``w = N_A^T u'' >= 0``, ``lam_A >= 0``, ``w^T lam_A = 0``, with
    ``M u'' = q(t) - K u - C u' + N lam``, and the acceleration ``u''`` (massless DOFs condensed)."""
    from ..lcp import get_lcp_solver

    s = system
    f = np.asarray(s.q(t), dtype=float) - s.K @ u - s.C @ udot
    length = 1.0 + float(np.max(np.abs(u), initial=0.0)) + float(np.max(np.abs(s.g(t)), initial=0.0))
    speed = 1.0 + float(np.max(np.abs(udot), initial=0.0))
    touching = np.flatnonzero((s.opening(u, t) <= OPEN_TOL * length) & (np.abs(s.N.T @ udot) <= VELOCITY_TOL * speed))
    lam = np.zeros(s.N.shape[1])
    X = inertia_solve(s.M, s.K, np.column_stack([f, s.N[:, touching]]))
    if touching.size:
        NA = s.N[:, touching]
        res = get_lcp_solver("bpp").solve(NA.T @ X[:, 1:], NA.T @ X[:, 0])
        if not res.success:
            raise ValueError("no contact forces hold the initial state: " + res.message)
        lam_A = spread(NA.T @ X[:, 1:], NA.T @ X[:, 0], res.v)
        lam[touching] = lam_A
        return lam, X[:, 0] + X[:, 1:] @ lam_A
    return lam, X[:, 0]


class MoreauJeanMarch:
    """The Moreau-Jean march of an :class:`ImpactSystem` (see the module).

    Parameters
    ----------
    system : ImpactSystem;  dt : time step, s;  N : number of steps
    u0, udot0 : (n,) initial state;  theta : 1/2 .. 1;  solver : LCPSolver of the impulses
    locate : locate the impacts within the step;  max_events : most impacts located in one step
    bilateral : hold every contact at its initial opening (impulses of either sign, no impact):
        the "without uplift" reference

    Attributes (after :meth:`run`)
    ------------------------------
    u, udot : (N+1, n);  P : (N+1, m) the impulses of each step (force time);
    work : (N+1, 4) cumulative :data:`WORK_TERMS`;  events : list of dict (``time``, ``contacts``,
    ``impulses``, ``before``, ``after`` normal velocities of the contacts struck, ``loss`` the
    energy lost, ``udot_before``, ``udot_after`` (n,) the velocities);  log : StepLog
    """

    def __init__(self, system, dt, N, u0, udot0, *, theta=0.5, solver=None, locate=True, max_events=16,
                 bilateral=False):
        from ..lcp import get_lcp_solver

        self.s, self.dt, self.N, self.theta = system, float(dt), int(N), float(theta)
        self.solver, self.locate, self.max_events = solver or get_lcp_solver("bpp"), locate, int(max_events)
        self.bilateral = bool(bilateral)
        n, m = system.N.shape
        self.u, self.udot = np.zeros((N + 1, n)), np.zeros((N + 1, n))
        self.u[0], self.udot[0] = u0, udot0
        self.P, self.work = np.zeros((N + 1, m)), np.zeros((N + 1, len(WORK_TERMS)))
        self.events, self.unlocated_steps, self.done = [], 0, 0
        try:
            closed = forces_at_rest(system, self.u[0], self.udot[0])[0] > 0
        except ValueError:
            closed = np.zeros(m, dtype=bool)
        self.log = StepLog(m, closed)
        self.length = 1.0 + float(np.max(np.abs(u0), initial=0.0)) + float(np.max(np.abs(system.g(0.0)), initial=0.0))
        self._lu = {}

    # ------------------------------------------------------------------ one sub-step
    def _factor(self, h):
        lu = self._lu.get(h)
        if lu is None:
            s, th = self.s, self.theta
            W = np.linalg.inv(s.M + th * h * s.C + th * th * h * h * s.K)     # n is small: one product a step
            lu = (W, W @ s.N, W @ s.D)
            if h == self.dt:
                self._lu[h] = lu
        return lu

    def substep(self, u, v, t, h, active):
        """``(u1, v1, P (m,), work (4,), message)`` of a theta step of length ``h`` from ``(u, v)``
        at ``t`` with Newton's law on the contacts ``active`` (indices)."""
        s, th = self.s, self.theta
        W, WN, WD = self._factor(h)
        q = np.asarray(s.q(t + th * h), dtype=float)
        v1 = W @ (s.M @ v - h * (1 - th) * (s.C @ v) - h * (s.K @ (u + th * (1 - th) * h * v)) + h * q)
        P, Pt, message = np.zeros(s.N.shape[1]), np.zeros(s.T.shape[1]), ""
        if active.size:
            v1, P, Pt, message = self._contacts(v1, WN, WD, active, s.e[active] * (s.N[:, active].T @ v))
        u1 = u + h * ((1 - th) * v + th * v1)
        vth, du, dv = (1 - th) * v + th * v1, u1 - u, v1 - v
        work = np.array([h * q @ vth, h * vth @ (s.C @ vth), -P @ (s.N.T @ vth),
                         (th - 0.5) * (dv @ (s.M @ dv) + du @ (s.K @ du)), -Pt @ (s.T.T @ vth)])
        return u1, v1, P, work, message

    def _contacts(self, v, GN, GD, active, shift):
        """``(v1, P (m,), Pt (R,), message)``: the impulses of the contacts ``active`` from the free
        velocity ``v``, ``GN`` (n, m), ``GD`` (n, L) the velocity responses of unit normal impulses
        and of unit impulses along the cones' generators: Newton's law ``U = N^T v1 + shift >= 0``
        complementary to ``P >= 0``, and on the contacts with friction Coulomb's law in its
        polygonal cone (the LCP of ``P``, the generators' ``beta`` and the slip rates ``lam``, see
        the module; Lemke's method); ``Pt`` the tangential impulses on the axes ``T``."""
        s, m = self.s, self.s.N.shape[1]
        P, Pt = np.zeros(m), np.zeros(s.T.shape[1])
        NA = s.N[:, active]
        F = active[s.mu[active] > 0]
        if F.size == 0:
            p, message = self._lcp(NA.T @ GN[:, active], NA.T @ v + shift)
            P[active] = p
            return v + GN[:, active] @ p, P, Pt, message
        gens = np.flatnonzero(np.isin(s.cones.of, F))
        DF, k, L, f = s.D[:, gens], active.size, gens.size, F.size
        Eg = (s.cones.of[gens][:, None] == F[None, :]).astype(float)                # generator of contact
        Emu = (active[None, :] == F[:, None]).astype(float) * s.mu[F][:, None]       # mu P_n of F
        A = np.block([[NA.T @ GN[:, active], NA.T @ GD[:, gens], np.zeros((k, f))],
                      [DF.T @ GN[:, active], DF.T @ GD[:, gens], Eg], [Emu, -Eg.T, np.zeros((f, f))]])
        res = friction_lcp(A, np.concatenate([NA.T @ v + shift, DF.T @ v, np.zeros(f)]))
        self.log.iterations += res.iterations
        self.log.max_error = max(self.log.max_error, res.error)
        x = spread_friction(NA, DF, Eg, Emu, res.v, res.w) if res.success else res.v
        P[active], beta = x[:k], x[k:k + L]
        Pt = s.cones.G[:, gens] @ beta
        return v + GN[:, active] @ P[active] + GD[:, gens] @ beta, P, Pt, "" if res.success else res.message

    def impact(self, u, v, t, touching):
        """``(v+, P (m,), loss, message)``: the jump of the velocity at an impact at ``t`` on the
        contacts ``touching`` (indices), Newton's law on each; a contact whose rebound would return
        within a step (``2 e |U| < dt a``, ``a`` the normal acceleration pulling it back: an
        accumulation of impacts) is held, ``e = 0`` (the Zeno rule)."""
        s = self.s
        NA = s.N[:, touching]
        U = NA.T @ v
        e = s.e[touching].copy()
        if np.any(e > 0):
            a = NA.T @ inertia_solve(s.M, s.K, (np.asarray(s.q(t), dtype=float) - s.K @ u - s.C @ v)[:, None])[:, 0]
            e[(U < 0) & (a < 0) & (2.0 * e * np.abs(U) < -a * self.dt)] = 0.0
        v1, P, Pt, message = self._contacts(v, s.X, s.XD, touching, e * U)
        p = P[touching]
        loss = -0.5 * (P @ (s.N.T @ (v + v1)) + Pt @ (s.T.T @ (v + v1)))
        self.events.append({"time": float(t), "contacts": [int(j) for j in touching[p > 0]],
                            "impulses": p[p > 0].tolist(), "before": U[p > 0].tolist(),
                            "after": (NA.T @ v1)[p > 0].tolist(), "loss": float(loss),
                            "udot_before": v.copy(), "udot_after": v1.copy()})
        return v1, P, loss, message

    def _lcp(self, A, b):
        if self.bilateral:                          # every contact held: an impulse of either sign
            return np.linalg.solve(A, -b), ""
        if b.size <= 2 and self.solver.name == "bpp":
            return _small_lcp(A, b), ""
        res = self.solver.solve(A, b)
        if not res.success:
            from ..lcp import get_lcp_solver

            res = get_lcp_solver("lemke").solve(A, b)
        self.log.iterations += res.iterations
        self.log.max_iterations = max(self.log.max_iterations, res.iterations)
        self.log.max_error = max(self.log.max_error, res.error)
        return spread(A, b, res.v), "" if res.success else res.message

    # ------------------------------------------------------------------ the step
    def _touching(self, u, t) -> np.ndarray:
        return self.s.opening(u, t) <= OPEN_TOL * self.length

    def step(self, k) -> str:
        """Advance from step ``k`` to ``k + 1``; "" or why it failed."""
        t = k * self.dt
        if self.bilateral:
            u, v, P, work, message = self.substep(self.u[k], self.udot[k], t, self.dt, np.arange(self.s.N.shape[1]))
        else:
            u, v, P, work, message = self._located(self.u[k], self.udot[k], t)
        if message:
            return f"the LCP of step {k + 1} (t = {t:.9g}) failed: {message}"
        self.u[k + 1], self.udot[k + 1], self.P[k + 1] = u, v, P
        self.work[k + 1] = self.work[k] + work
        closed = P > 0
        self.log.contact_changes += int(np.count_nonzero(closed != self.log.active))
        self.log.active = closed
        return ""

    def _located(self, u, v, t):
        """``(u, v, P, work, message)`` of the step from ``(u, v)`` at ``t``, its impacts located
        (or at the end of the step, ``locate=False``)."""
        s, left, events = self.s, self.dt, 0
        P, work = np.zeros(s.N.shape[1]), np.zeros(len(WORK_TERMS))
        while True:
            touching = self._touching(u, t)
            vtol = VELOCITY_TOL * (1.0 + float(np.max(np.abs(v), initial=0.0)))
            U = s.N.T @ v
            if self.locate and np.any(touching & (U < -vtol)):
                v, p, loss, message = self.impact(u, v, t, np.flatnonzero(touching))
                if message:
                    return u, v, P, work, f"the impact LCP at t = {t:.9g}: {message}"
                P, work[2] = P + p, work[2] + loss
                U = s.N.T @ v
            held = touching & (U <= vtol)
            if not self.locate or events >= self.max_events:
                self.unlocated_steps += int(self.locate)
                mid = s.opening(u + 0.5 * left * v, t + left) <= 0.0
                u, v, p, w, message = self.substep(u, v, t, left, np.flatnonzero(held | mid))
                return u, v, P + p, work + w, message
            u1, v1, p, w, message = self.substep(u, v, t, left, np.flatnonzero(held))
            into = ~held & (s.opening(u1, t + left) < -OPEN_TOL * self.length)
            if message or not into.any():
                return u1, v1, P + p, work + w, message
            tau = self._event_time(u, v, t, left, held, into)
            if tau >= left * (1.0 - 1e-12):        # at the end of the step: the next step's impact
                return u1, v1, P + p, work + w, message
            u, v, p, w, message = self.substep(u, v, t, tau, np.flatnonzero(held))
            P, work, t, left, events = P + p, work + w, t + tau, left - tau, events + 1
            if message:
                return u, v, P, work, message

    def _event_time(self, u, v, t, h, held, into) -> float:
        """The time ``tau`` in ``(0, h)`` at which the first of the contacts ``into`` (penetrating
        at ``h``) reaches zero opening, on the partial steps of length ``tau``."""
        active = np.flatnonzero(held)
        f = lambda tau: float(np.min(self.s.opening(self.substep(u, v, t, tau, active)[0], t + tau)[into]))
        lo, hi = 0.0, h
        f_lo, f_hi = float(np.min(self.s.opening(u, t)[into])), f(h)
        tol = 1e-14 * self.length
        while f_lo <= tol:                         # a contact that just separated: bracket off zero
            mid = 0.5 * (lo + hi)
            f_mid = f(mid)
            if f_mid > tol:
                lo, f_lo = mid, f_mid
            else:
                hi, f_hi = mid, f_mid
            if hi - lo <= 1e-15 * h:
                return hi
        side = 0
        for _ in range(100):                       # Illinois
            tau = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
            f_tau = f(tau)
            if abs(f_tau) <= tol or hi - lo <= 1e-15 * h:
                return tau
            if f_tau > 0:
                lo, f_lo = tau, f_tau
                f_hi, side = (0.5 * f_hi, 1) if side == 1 else (f_hi, 1)
            else:
                hi, f_hi = tau, f_tau
                f_lo, side = (0.5 * f_lo, -1) if side == -1 else (f_lo, -1)
        return tau

    def run(self, K=None) -> int:
        """March to step ``K`` (default ``N``) or to the step that fails; the last step done."""
        for k in range(self.done, self.N if K is None else K):
            message = self.step(k)
            if message:
                self.log.failure = message
                break
            self.done = k + 1
        return self.done


#: Relative sizes of the perturbations of ``b`` with which :func:`friction_lcp` retries Lemke's method.
PERTURBATIONS = (1e-14, 1e-13, 1e-12, 1e-11, 1e-10)


def friction_lcp(A, b):
    """The :class:`~unilateral.lcp.LCPResult` of the friction LCP ``w = A x + b`` by Lemke's method.

    The LCP of a box on four corners is degenerate: its four corners' normals and their cones'
    generators span three DOFs each (a singular Delassus block) and the symmetric corners tie in
    the ratio tests, where round-off may lead Lemke's method onto a secondary ray. Then it is
    retried on ``b`` perturbed by a fixed pseudo-random vector of :data:`PERTURBATIONS` times
    ``1 + max |b|``, and the complementary basis it ends on is solved with ``b`` itself: the
    solution kept if its error (:func:`~unilateral.lcp.lcp_error`) is within Lemke's ``tol``."""
    from ..lcp import LCPResult, get_lcp_solver, lcp_error
    from ..lcp.base import PrincipalSystems

    lemke = get_lcp_solver("lemke")
    res = lemke.solve(A, b)
    if res.success:
        return res
    pivots, scale = res.iterations, 1.0 + float(np.max(np.abs(b), initial=0.0))
    noise = np.random.default_rng(20240611).uniform(0.5, 1.0, b.size)
    for size in PERTURBATIONS:
        trial = lemke.solve(A, b + size * scale * noise)
        pivots += trial.iterations
        if not trial.success:
            continue
        x = PrincipalSystems(A, b).solve(trial.active)
        x[(x < 0) & (x >= -lemke.tol * scale)] = 0.0
        w = A @ x + b
        error = lcp_error(x, w, b)
        if error <= lemke.tol and x.min() >= 0.0:
            return LCPResult(x, w, trial.active, pivots, error, True, f"Lemke on b perturbed by {size:g}")
    return res


def spread(A, b, p) -> np.ndarray:
    """The least-norm impulses (or forces) ``p' >= 0`` of the LCP ``w = A p + b`` with the same ``w``
    as its solution ``p`` (k,), where ``A`` (k, k; symmetric positive semidefinite) is singular on the
    contacts that close (``w = 0``): more contacts than the DOFs they move (a 3-D box's four corners
    on ``uz``, ``rx``, ``ry``), whose LCP solution is one vertex of a set of equal motions. The
    least-norm member ``p_S + null(A_SS)`` spreads them as the symmetry does (four equal corners at
    rest); ``p`` itself where ``A_SS`` has full rank (every 2-D case) or the spread has a negative
    entry."""
    scale = 1.0 + float(np.max(np.abs(b), initial=0.0))
    S = np.flatnonzero(A @ p + b <= 1e-12 * scale)
    if S.size < 2:
        return p
    A_SS = A[np.ix_(S, S)]
    x, _, rank, _ = np.linalg.lstsq(A_SS, A_SS @ p[S], rcond=1e-10)
    if rank == S.size or x.min() < -1e-12 * (1.0 + float(np.abs(p).max())):
        return p
    out = np.zeros_like(p)
    out[S] = np.maximum(x, 0.0)
    return out


def spread_friction(NA, DF, Eg, mu, x, w) -> np.ndarray:
    """The least-norm solution ``x' = (P', beta', lam)`` of the friction LCP with the same normal and
    tangential impulses on the DOFs as its solution ``x = (P, beta, lam)``, as :func:`spread` does
    without friction: ``NA P' = NA P``, ``DF beta' = DF beta`` on the contacts and generators that
    close (``w = 0``), ``sum beta' = mu P'`` on the contacts that slide (``lam > 0``), taken where it
    is admissible (``x' >= 0``, ``sum beta' <= mu P'`` on those that stick) and not unique (a box's
    four corners: ``W / 4`` on each corner of a box at rest or sliding); ``x`` otherwise.

    ``NA`` (n, k), ``DF`` (n, L) the normals and the generators on the DOFs, ``Eg`` (L, f) the
    contact of each generator, ``mu`` (f, k) ``mu`` on the position of each contact with friction
    among the ``k`` (the LCP's block), ``x``, ``w`` (k + L + f,) the LCP's solution."""
    n, k, L = NA.shape[0], NA.shape[1], DF.shape[1]
    P, beta, lam = x[:k], x[k:k + L], x[k + L:]
    tol = 1e-12 * (1.0 + float(np.max(np.abs(w), initial=0.0)))
    Sn, Sg = np.flatnonzero(w[:k] <= tol), np.flatnonzero(w[k:k + L] <= tol)
    slide = lam > 0
    E = np.zeros((2 * n + mu.shape[0], Sn.size + Sg.size))
    E[:n, :Sn.size], E[n:2 * n, Sn.size:] = NA[:, Sn], DF[:, Sg]
    E[2 * n:, :Sn.size], E[2 * n:, Sn.size:] = -mu[:, Sn], Eg[Sg].T          # sum beta - mu P per contact
    E[2 * n:][~slide] = 0.0                          # sticking contacts: an inequality, checked below
    rhs = np.concatenate([NA @ P, DF @ beta, np.zeros(mu.shape[0])])
    y, _, rank, _ = np.linalg.lstsq(E, rhs, rcond=1e-10)
    if rank == E.shape[1]:
        return x
    out = x.copy()
    out[:k], out[k:k + L] = 0.0, 0.0
    out[Sn], out[k + Sg] = y[:Sn.size], y[Sn.size:]
    P1, beta1 = out[:k], out[k:k + L]
    small = 1e-12 * (1.0 + float(np.abs(x).max()))
    if (np.abs(E @ y - rhs).max() > small or out[:k + L].min() < -small
            or np.any(Eg.T @ beta1 - mu @ P1 > small)):
        return x
    out[:k + L] = np.maximum(out[:k + L], 0.0)
    return out


def _small_lcp(A, b) -> np.ndarray:
    """The solution of ``w = A p + b >= 0, p >= 0, w^T p = 0`` for one or two unknowns and a
    positive definite ``A``, by enumeration of the active sets (exact)."""
    if b.size == 1:
        return np.array([max(0.0, -b[0] / A[0, 0])])
    if b[0] >= 0 and b[1] >= 0:
        return np.zeros(2)
    for i, j in ((0, 1), (1, 0)):
        p = -b[i] / A[i, i]
        if p > 0 and A[j, i] * p + b[j] >= 0:
            out = np.zeros(2)
            out[i] = p
            return out
    return np.linalg.solve(A, -b)


def system_of(model, load, dt) -> ImpactSystem:
    """The :class:`ImpactSystem` of a matrix ``model`` with rigid contacts only and a ``load``
    (None, a callable ``q(t)`` such as a LoadHistory, or an array (N+1, n) at ``t_k = k dt``,
    interpolated linearly); the imposed-strain load ``model.q_imposed(t)`` is added."""
    e, mu, cones = np.zeros(model.m), np.zeros(model.m), []
    for family in model.families:
        if family.impact_law:
            e[family.indices], mu[family.indices] = family.restitution, family.mu
            cones += [(int(j), family.tangent_axes(p), int(family.facets[p]))
                      for p, j in enumerate(family.indices) if family.mu[p] > 0]
    if load is None:
        q = model.q_imposed
    elif callable(load):
        q = lambda t: np.asarray(load(t), dtype=float) + model.q_imposed(t)
    else:
        table = np.asarray(load, dtype=float)
        times = np.arange(table.shape[0]) * dt
        q = lambda t: np.array([np.interp(t, times, c) for c in table.T]) + model.q_imposed(t)
    M, K = dense(model.M), dense(model.K)
    return ImpactSystem(M=M, K=K, C=dense(model.damping()), N=dense(model.F), e=e, g=model.g, q=q, mu=mu,
                        cones=FrictionCones.build(model.n, cones))


def moreau_jean(model, load, *, dt, t_end, u0, udot0=None, e=None, theta=0.5, locate=True):
    """March ``model`` with rigid contacts by the Moreau-Jean scheme (see the module): the march
    behind ``method="moreau-jean"`` (:class:`~unilateral.methods.MoreauJean`), without its checks.

    Parameters
    ----------
    model : Model whose unknowns are all rigid contacts
    load : None, callable ``q(t) -> (n,)`` (a LoadHistory) or array (N+1, n), force
    dt, t_end : s;  u0, udot0 : (n,) (length, length/s)
    e : coefficient of restitution of every contact, or None (the contacts' own)
    theta : 1/2 .. 1;  locate : locate the impacts within the step

    Returns
    -------
    MoreauJeanMarch, marched to the end (or to the step that failed)
    """
    system = system_of(model, load, dt)
    if e is not None:
        system.e = np.full(model.m, float(e))
    N = int(round(t_end / dt))
    udot0 = np.zeros(model.n) if udot0 is None else np.asarray(udot0, dtype=float)
    march = MoreauJeanMarch(system, dt, N, np.asarray(u0, dtype=float), udot0, theta=theta, locate=locate)
    march.run()
    return march
