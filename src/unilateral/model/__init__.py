"""The reduced problem of Liolios (1990), eqs. (15)-(16), at matrix level.

    M u'' + C u' + K u = q + F v + F_v v'
    psi = F^T u + F_v^T u' - H v - H_v v' - g
    psi <= 0,  v >= 0,  psi^T v = 0

``n`` structural degrees of freedom, ``m`` unilateral unknowns. ``F_v`` and ``H_v`` are the viscous
parts that Kelvin elements (``E(s) = E + s E_v``) add to ``F(s) = F + s F_v`` and
``H(s) = H + s H_v``; without Kelvin elements they are absent. In the Laplace domain
``D(s) = K + s C + s^2 M`` and the influence matrix is ``Lambda(s) = H(s) - F(s)^T D(s)^-1 F(s)``
(the paper prints a plus sign in eq. 23; the minus follows from eqs. 18-19).

:mod:`unilateral.model.stiff` puts a model with penalty-stiff elements in coordinates that separate
the stiff strains (:class:`~unilateral.model.stiff.StiffCoordinates`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .. import _validate as V
from ..constraints import default_families, step_law


class ConstantStrain:
    """Imposed strains that do not vary in time: ``theta(t) = value`` (ne,)."""

    def __init__(self, value):
        self.value = np.asarray(value, dtype=float)

    def __call__(self, t) -> np.ndarray:
        return self.value


@dataclass(frozen=True)
class NaturalForm:
    """The unassembled ("natural") description the model was built from (eqs. 1-9).

    Attributes
    ----------
    G : (n, ne) equilibrium matrix (``e = G^T u``)
    E : (ne, ne) elasticity matrix, symmetric positive definite
    B : (ne, m) maps unilateral deformations to strains (``mu = B v``)
    A : (m, m) unilateral interaction matrix
    r : (m,) resistances (capacities)
    theta : callable ``theta(t) -> (ne,)`` imposed strains
    E_v : (ne, ne) viscous elasticity matrix of Kelvin elements, or None
    theta_rate : callable ``theta'(t) -> (ne,)`` or None
    K_geometric : (n, n) sparse or None
        A stiffness the model's ``K`` has beside ``G E G^T`` and that no element strain carries (the
        geometric stiffness of P-Delta): whatever rebuilds ``K`` from this form adds it.
    """

    G: object
    E: object
    B: object
    A: np.ndarray
    r: np.ndarray
    theta: object
    E_v: object = None
    theta_rate: object = None
    K_geometric: object = None

    def imposed_strains(self, t) -> np.ndarray:
        """``theta`` at the times ``t`` (N,): (N, ne), or (ne,) when it is constant (broadcasts)."""
        if isinstance(self.theta, ConstantStrain):
            return self.theta.value
        return np.array([self.theta(tk) for tk in np.atleast_1d(t)])

    def stresses(self, t, u, v, udot=None, vdot=None) -> np.ndarray:
        """Element stresses ``sigma = E eps + E_v eps'`` with ``eps = G^T u - B v - theta``.

        Parameters
        ----------
        t : (N,) times;  u : (N, n);  v : (N, m);  udot, vdot : (N, n), (N, m) (needed with E_v)

        Returns
        -------
        sigma : (N, ne)
        """
        t = np.atleast_1d(t)
        eps = (self.G.T @ u.T).T - (self.B @ v.T).T - self.imposed_strains(t)
        sigma = (self.E @ eps.T).T
        if self.E_v is not None:
            if udot is None or vdot is None:
                raise ValueError("udot and vdot are required for stresses of Kelvin elements (E_v given)")
            eps_rate = (self.G.T @ udot.T).T - (self.B @ vdot.T).T
            if self.theta_rate is not None:
                eps_rate = eps_rate - np.array([self.theta_rate(tk) for tk in np.atleast_1d(t)])
            sigma = sigma + (self.E_v @ eps_rate.T).T
        return np.asarray(sigma)


#: The largest ``gap`` of :class:`Model` (length units; a matrix-level model has no size of its own to
#: scale it by): a gap is cancelled by the open contact's deformation, so the response moves by about
#: ``2.2e-16 gap k / K`` whether or not it closes (measured on two DOFs with a gap spring of k = 1e4,
#: response 0.145: 4.9e-11 of the peak at gap = 1e3, 7.8e-8 at 1e6, 4.9e-5 at 1e9, 2.8 % at 1e12,
#: 35 times at 1e15). The frames refuse clearances above ten times their size instead.
GAP_MAX = 1e5


class Model:
    """Linear structure with unilateral constraints, eqs. (15)-(16) of Liolios (1990).

    Parameters
    ----------
    M, K : (n, n) array_like or sparse
        Mass and stiffness; symmetric. ``M`` may be positive semidefinite (massless DOFs);
        ``K`` must be positive definite (the structure with every constraint bilateral is stable).
    F : (n, m) array_like or sparse
        Coupling of unilateral deformations into the equations of motion (``G E B``).
    H : (m, m) array_like
        ``A + B^T E B``; symmetric positive semidefinite.
    C : (n, n), optional
        Damping, symmetric positive semidefinite (default zero).
    g : (m,) array_like or callable ``g(t) -> (m,)``, optional
        Constraint offset ``B^T E theta + r`` (default zero). ``g`` alone shifts the constraint
        law only (a resistance or capacity ``r``); an imposed strain ``theta`` (a gap, a
        prestrain) also loads the structure by ``q_imposed = G E theta``, and the two must agree:
        give gaps by ``gap``, which sets both.
    F_v : (n, m), optional
        Viscous coupling of Kelvin elements (``G E_v B``).
    H_v : (m, m), optional
        Viscous part of H (``B^T E_v B``), symmetric positive semidefinite.
    q_imposed : (n,) array_like or callable ``q(t) -> (n,)``, optional
        Load equivalent to imposed strains (``G E theta``), added to the applied load.
    gap : (m,) array_like, optional
        Initial opening of each unilateral element, m (>= 0): the imposed strain ``theta = -gap``
        on the unilateral deformations, i.e. ``-H gap`` added to ``g`` and ``-F gap`` to
        ``q_imposed``, as :class:`~unilateral.structure.Frame2D` builds a soil element or a gap
        link with ``gap=`` (the element carries force only once the gap has closed).
    dof_names : sequence of n str, optional
    constraint_names : sequence of m str, optional
    families : sequence of ConstraintFamily, optional
        The laws of the unknowns (:mod:`unilateral.constraints`): :class:`~unilateral.constraints.Contact`
        (the paper's unilateral contact, the default for every unknown no family names),
        :class:`~unilateral.constraints.Yield` (plastic multipliers) and
        :class:`~unilateral.constraints.Friction` (Coulomb slips). Their step law is ``law``.
    on_soil : bool
        The structure rests on a soil (:meth:`unilateral.soil.FoundationModel.on`), which
        supports it: ``K`` may then be singular (semidefinite); default False (``K`` definite).
    """

    def __init__(self, M, K, F, H, C=None, g=None, *, F_v=None, H_v=None, q_imposed=None, gap=None,
                 dof_names=None, constraint_names=None, natural: NaturalForm | None = None,
                 families=None, on_soil=False, _owned=frozenset()):
        # _owned (internal, :meth:`from_natural`): the names of the matrices the caller has just
        # computed and hands over; they are kept as given instead of copied (the same checks)
        self.K = V.as_matrix("K", K, (None, None), copy="K" not in _owned)
        n = self.K.shape[0]
        if self.K.shape != (n, n):
            raise ValueError(f"K must be square, got shape {self.K.shape}")
        self.M = V.as_matrix("M", M, (n, n))
        self.C = None if C is None else V.as_matrix("C", C, (n, n), copy="C" not in _owned)
        self.F = V.as_matrix("F", F, (n, None), copy="F" not in _owned)
        m = self.F.shape[1]
        self.H = V.as_matrix("H", H, (m, m), allow_sparse=False, copy="H" not in _owned)
        self.F_v = None if F_v is None else V.as_matrix("F_v", F_v, (n, m), copy="F_v" not in _owned)
        self.H_v = None if H_v is None else V.as_matrix("H_v", H_v, (m, m), allow_sparse=False,
                                                        copy="H_v" not in _owned)
        diagonal_H = V.is_diagonal(self.H)         # (one look at H's pattern for both checks)
        for name in ("M", "K", "C", "H", "H_v"):
            if getattr(self, name) is not None:
                V.check_symmetric(name, getattr(self, name), diagonal=name == "H" and diagonal_H)
        V.check_psd("H", self.H, diagonal=diagonal_H)
        if self.H_v is not None:
            V.check_psd("H_v", self.H_v)
        _check_diagonal_nonnegative("M", self.M)
        _check_diagonal_nonnegative("K", self.K, strict=True)
        check_definite("K", self.K, strict=not on_soil)
        check_definite("M", self.M, strict=False)
        self.g, self.g_is_constant = V.time_function("g", g, m)
        self.q_imposed, self.q_imposed_is_constant = V.time_function("q_imposed", q_imposed, n)
        if gap is not None:
            self._add_gap(V.as_vector("gap", gap, m))
        self.dof_names = checked_names("dof_names", dof_names, n, "u", strings="dof_names" in _owned)
        self.constraint_names = checked_names("constraint_names", constraint_names, m, "c")
        self.natural = natural
        self.families = list(families) if families is not None else default_families(m)
        self.law = step_law(self.families, m)
        if gap is not None and np.any(gap_rate := (self.law.rate & (np.asarray(gap) != 0))):
            raise ValueError(f"gap[{int(np.argmax(gap_rate))}] is given for a yield or friction unknown; "
                             "gaps apply to contacts")

    def _add_gap(self, gap: np.ndarray) -> None:
        """Add the imposed strain ``theta = -gap`` of the unilateral elements to ``g`` and ``q_imposed``."""
        bad = np.flatnonzero(gap < 0)
        if bad.size:
            raise ValueError(f"gap[{bad[0]}] = {float(gap[bad[0]])!r} is negative; a gap is an opening >= 0 "
                             "(an overlap is an imposed strain: give g and q_imposed)")
        big = np.flatnonzero(gap > GAP_MAX)
        if big.size:
            raise ValueError(f"gap[{big[0]}] = {float(gap[big[0]])!r} exceeds {GAP_MAX:g} (length units): a gap is an "
                             "imposed strain that an open contact cancels (v = e + gap), and double precision carries "
                             f"the response only to about 2.2e-16 * gap; give gap <= {GAP_MAX:g}, or leave the "
                             "contact out if it never closes")
        dg = -(self.H @ gap)
        dq = -np.asarray(self.F @ gap, dtype=float).ravel()
        for name, delta in (("g", dg), ("q_imposed", dq)):
            f, constant = getattr(self, name), getattr(self, f"{name}_is_constant")
            if constant:
                value = f(0.0) + delta
                setattr(self, name, lambda t, _v=value: _v)
            else:
                setattr(self, name, lambda t, _f=f, _d=delta: _f(t) + _d)

    # ------------------------------------------------------------------ sizes and flags
    #: The kind of problem, as the methods know it (:attr:`unilateral.methods.Method.solves`).
    kind = "matrices"

    @property
    def n(self) -> int:
        """Number of structural degrees of freedom."""
        return self.K.shape[0]

    @property
    def m(self) -> int:
        """Number of unilateral unknowns."""
        return self.F.shape[1]

    @property
    def sparse(self) -> bool:
        return sp.issparse(self.K)

    @property
    def viscous(self) -> bool:
        """True if the constraints carry Kelvin (viscous) terms F_v or H_v."""
        return self.F_v is not None or self.H_v is not None

    # ------------------------------------------------------------------ Laplace-domain pieces
    def D(self, s):
        """Dynamic stiffness ``D(s) = K + s C + s^2 M`` for a scalar ``s`` (real or complex)."""
        out = self.K + (s * s) * self.M
        if self.C is not None:
            out = out + s * self.C
        return out

    def F_of(self, s):
        """``F(s) = F + s F_v``, shape (n, m)."""
        return self.F if self.F_v is None else self.F + s * self.F_v

    def H_of(self, s) -> np.ndarray:
        """``H(s) = H + s H_v``, shape (m, m)."""
        return self.H if self.H_v is None else self.H + s * self.H_v

    def damping(self):
        """C, or a zero matrix of the right kind if the model is undamped."""
        if self.C is not None:
            return self.C
        return sp.csr_matrix((self.n, self.n)) if self.sparse else np.zeros((self.n, self.n))

    # ------------------------------------------------------------------ the natural form
    @classmethod
    def from_natural(cls, G, E, B, *, M, A=None, r=None, theta=None, C=None, E_v=None,
                     theta_rate=None, dof_names=None, constraint_names=None, families=None,
                     on_soil=False) -> Model:
        """Assemble the reduced problem from the unassembled structure, eqs. (13)-(16).

        ``K = G E G^T``, ``F = G E B``, ``H = A + B^T E B``, ``g = B^T E theta + r``, and the
        imposed-strain load ``G E theta`` (eq. 14). With Kelvin elements (``E_v``), by the
        correspondence principle ``E -> E + s E_v``: ``C += G E_v G^T``, ``F_v = G E_v B``,
        ``H_v = B^T E_v B``, and the rates of ``theta`` enter ``g`` and the load.

        Parameters
        ----------
        G : (n, ne) equilibrium matrix; the compatibility is ``e = G^T u``
        E : (ne, ne) elasticity matrix, symmetric positive definite
        B : (ne, m) transformation of unilateral deformations into strains, ``mu = B v``
        M : (n, n) mass matrix
        A : (m, m) unilateral interaction matrix, symmetric PSD (default zero)
        r : (m,) resistances (ultimate capacities), ``r >= 0`` (default zero)
        theta : (ne,) or callable ``theta(t) -> (ne,)``, imposed strains (default zero)
        C : (n, n) structural damping (default zero)
        E_v : (ne, ne) viscous elasticity of Kelvin elements, symmetric PSD (default none)
        theta_rate : callable ``theta'(t) -> (ne,)``; required when ``theta`` is a function of
            time and ``E_v`` is given
        families : sequence of ConstraintFamily, optional (see :class:`Model`)
        on_soil : bool, optional (see :class:`Model`)
        """
        G = V.as_matrix("G", G, (None, None))
        n, ne = G.shape
        E = V.as_matrix("E", E, (ne, ne))
        B = V.as_matrix("B", B, (ne, None))
        m = B.shape[1]
        V.check_symmetric("E", E)
        _check_diagonal_nonnegative("E", E, strict=True)
        a_zero = A is None
        if a_zero:
            A = np.zeros((m, m))                # symmetric and semidefinite: nothing to check
        else:
            A = V.as_matrix("A", A, (m, m), allow_sparse=False)
            V.check_symmetric("A", A)
            V.check_psd("A", A)
        r = np.zeros(m) if r is None else V.as_vector("r", r, m)
        if np.any(r < 0):
            i = int(np.argmax(r < 0))
            raise ValueError(f"r must be >= 0 (resistances); r[{i}] = {float(r[i])!r}")
        theta_f, theta_const = V.time_function("theta", theta, ne)
        if E_v is not None:
            E_v = V.as_matrix("E_v", E_v, (ne, ne))
            V.check_symmetric("E_v", E_v)
            _check_diagonal_nonnegative("E_v", E_v)
        rate_f = None
        if theta_rate is not None:
            rate_f, _ = V.time_function("theta_rate", theta_rate, ne)
        elif E_v is not None and not theta_const:
            raise ValueError(
                "theta_rate is required when theta is a function of time and E_v is given "
                "(Kelvin elements respond to the rate of imposed strains)"
            )

        GE = G @ E
        K = GE @ G.T
        F = _dense_if_small(GE @ B)
        BtE = B.T @ E
        H = _plus_dense(None if a_zero else A, BtE @ B)    # (B.T @ E @ B, left to right)
        BtE = _dense_if_small(BtE)
        q_imposed = _load_of(GE, theta_f, theta_const)
        g = _offset_of(BtE, theta_f, theta_const, r)
        owned = {"K", "F", "H"}                 # computed here: handed to __init__ without a copy
        kelvin = dict(C=C, F_v=None, H_v=None, q_imposed=q_imposed, g=g)
        if E_v is not None:
            owned |= {"C", "F_v", "H_v"}
            kelvin = _kelvin_terms(G, B, E_v, rate_f, C=C, q_imposed=q_imposed, g=g)
        natural = NaturalForm(G=G, E=E, B=B, A=A, r=r, theta=theta_f, E_v=E_v, theta_rate=rate_f)
        return cls(M=M, K=K, F=F, H=H, **kelvin, dof_names=dof_names, constraint_names=constraint_names,
                   natural=natural, families=families, on_soil=on_soil, _owned=frozenset(owned))

    def __repr__(self) -> str:
        kind = "sparse" if self.sparse else "dense"
        visc = ", Kelvin constraints" if self.viscous else ""
        laws = "" if self.law.trivial else ", " + ", ".join(
            f"{self.law.kinds.count(k)} {k}" for k in ("contact", "yield", "friction") if k in self.law.kinds)
        return f"Model(n={self.n}, m={self.m}, {kind}{visc}{laws})"


# ---------------------------------------------------------------------- helpers
def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)


def _plus_dense(A: np.ndarray | None, S) -> np.ndarray:
    """``A + S`` dense, ``S`` sparse or dense (the same sums; with a zero ``A``, ``S`` alone), a new
    array. ``A=None``: a zero ``A``, known without looking at it (the sums of a zero array)."""
    if not sp.issparse(S):
        return np.asarray(S, dtype=float) + 0.0 if A is None else A + np.asarray(S, dtype=float)
    out = S.toarray(order="C")
    if A is not None and A.any():       # (a zero A: its pages are never touched)
        out += A
    return out


def _dense_if_small(A, limit=2_000_000):
    """Keep a sparse product sparse only when its dense form would be large."""
    if sp.issparse(A) and A.shape[0] * A.shape[1] <= limit:
        return A.toarray()
    return A


def _load_of(GE, theta_f, constant):
    if constant:
        return np.asarray(GE @ theta_f(0.0)).ravel()
    return lambda t: np.asarray(GE @ theta_f(t)).ravel()


def _offset_of(BtE, theta_f, constant, r):
    if constant:
        return np.asarray(BtE @ theta_f(0.0)).ravel() + r
    return lambda t: np.asarray(BtE @ theta_f(t)).ravel() + r



def _kelvin_terms(G, B, E_v, rate_f, *, C, q_imposed, g) -> dict:
    """The Kelvin elements' part of :meth:`Model.from_natural` (the correspondence ``E -> E + s E_v``):
    ``C += G E_v G^T``, ``F_v = G E_v B``, ``H_v = B^T E_v B`` and, with imposed strains varying in
    time, their rates in ``q_imposed`` and ``g``. Returns the keywords ``C, F_v, H_v, q_imposed, g``."""
    n = G.shape[0]
    GEv = G @ E_v
    C_v = GEv @ G.T
    C = C_v if C is None else V.as_matrix("C", C, (n, n)) + C_v
    if rate_f is not None:
        BtEv = _dense_if_small(B.T @ E_v)
        q_imposed = _sum(q_imposed, lambda t: np.asarray(GEv @ rate_f(t)).ravel())
        g = _sum(g, lambda t: np.asarray(BtEv @ rate_f(t)).ravel())
    return dict(C=C, F_v=_dense_if_small(GEv @ B), H_v=_dense(B.T @ E_v @ B), q_imposed=q_imposed, g=g)

def _sum(a, f):
    """Sum of a constant-or-callable and a callable, as a callable."""
    if callable(a):
        return lambda t: a(t) + f(t)
    return lambda t: a + f(t)


def checked_names(arg, names, size, prefix, strings=False):
    """``names`` as a list of ``size`` unique str (``strings``: a new list of str already), or
    ``prefix0``, ``prefix1``, ... for None."""
    if names is None:
        return [f"{prefix}{i}" for i in range(size)]
    if not (strings and type(names) is list):
        names = list(map(str, names))
    if len(names) != size:
        raise ValueError(f"{arg} must have {size} entries, got {len(names)}")
    if len(set(names)) == size:
        return names
    seen = set()
    for name in names:
        if name in seen:
            raise ValueError(f"{arg} has the name {name!r} twice; names must be unique")
        seen.add(name)
    return names


#: Dense matrices up to this size are checked for definiteness by their eigenvalues.
DEFINITENESS_DENSE_MAX_N = 2000


def check_definite(name, A, *, strict):
    """Raise if the symmetric ``A`` is indefinite (``strict``: also if singular).

    Dense matrices up to :data:`DEFINITENESS_DENSE_MAX_N`: the smallest eigenvalue. Sparse ones: the
    inertia of ``P A P^T = L D L^T`` from a symmetric-mode sparse LU without pivoting off the
    diagonal (Sylvester's law: the signs of ``D`` are those of the eigenvalues); a factorisation
    that breaks down is left to the later solves, which report it.
    """
    n = A.shape[0]
    if n == 0:
        return
    need = "positive definite" if strict else "positive semidefinite"
    if not sp.issparse(A):
        if n > DEFINITENESS_DENSE_MAX_N:
            return
        eig = np.linalg.eigvalsh(A)
        # eigenvalues are accurate to about n eps max|eig|: penalty-stiff models (cond 1e13) pass
        limit = 10 * n * np.finfo(float).eps * max(np.max(np.abs(eig)), np.finfo(float).tiny)
        if eig[0] < -limit or (strict and eig[0] <= limit):
            raise ValueError(f"{name} must be symmetric {need}; its smallest eigenvalue is {eig[0]:.3g} "
                             f"(largest {eig[-1]:.3g})")
        return
    if not strict:
        return           # a sparse M with massless DOFs has no LDL^T; its diagonal was checked
    banded = _banded_upper(A)
    if banded is not None:
        import scipy.linalg as sla

        try:
            sla.cholesky_banded(banded, overwrite_ab=True, check_finite=False)
        except sla.LinAlgError as exc:
            raise ValueError(f"{name} must be symmetric {need}; its Cholesky factorisation fails: the "
                             f"{exc} (an unstable or indefinite structure)") from None
        return
    import scipy.sparse.linalg as spla
    try:
        lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
    except RuntimeError:
        return
    d = lu.U.diagonal()
    if np.any(d <= 0):
        raise ValueError(f"{name} must be symmetric {need}; its LDL^T factorisation has {int(np.sum(d <= 0))} "
                         "nonpositive pivots (an unstable or indefinite structure)")


#: A sparse matrix whose nonzeros lie within this many diagonals of the main one is checked for
#: definiteness by a banded Cholesky factorisation (``n b^2`` operations, no ordering): a beam or a
#: chain of elements numbered along it.
DEFINITENESS_BANDED_MAX = 16


def _banded_upper(A):
    """The upper band of the sparse symmetric ``A`` in LAPACK's storage ``(b + 1, n)`` (row ``b`` the
    diagonal), or None if its half-bandwidth ``b`` exceeds :data:`DEFINITENESS_BANDED_MAX`."""
    A = A.tocsr() if A.format != "csr" else A
    if not A.has_canonical_format:
        return None
    n = A.shape[0]
    rows = np.repeat(np.arange(n), np.diff(A.indptr))
    offset = A.indices - rows                                    # column - row
    if offset.size == 0 or np.abs(offset).max() > DEFINITENESS_BANDED_MAX:
        return None
    b = int(offset.max(initial=0))
    upper = offset >= 0
    band = np.zeros((b + 1, n))
    band[b - offset[upper], A.indices[upper]] = A.data[upper]
    return band


def _check_diagonal_nonnegative(name, A, *, strict=False):
    """Cheap necessary condition for (semi)definiteness: the diagonal is (positive) nonnegative."""
    d = A.diagonal() if sp.issparse(A) else np.diag(A)
    bad = np.flatnonzero(d <= 0) if strict else np.flatnonzero(d < 0)
    if bad.size:
        i = int(bad[0])
        need = "positive" if strict else "nonnegative"
        raise ValueError(
            f"{name} must have a {need} diagonal ({name} is a stiffness/mass-type matrix); "
            f"{name}[{i}, {i}] = {float(d[i])!r}"
        )


#: Set-up entries kept per model by :func:`remembered` (the oldest goes first).
SETUP_KEEP = 8


def remembered(model, key, build):
    """``build()``, or the value it gave for ``key`` on this ``model`` before (exceptions are not kept).

    Set-up kept on a model between solves: a batch solves one model variant under many records and
    scale factors (an IDA), and its static state under gravity and the poles of its kernel are the
    same every time. They are kept on the model object (a model is treated as immutable once built,
    as a soil keeps its weights), at most :data:`SETUP_KEEP` entries per model.
    """
    cache = model.__dict__.setdefault("_setup_cache", {})
    if key not in cache:
        value = build()
        if len(cache) >= SETUP_KEEP:
            cache.pop(next(iter(cache)))
        cache[key] = value
    return cache[key]
