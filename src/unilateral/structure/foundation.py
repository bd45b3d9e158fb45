"""A footing of a :class:`~unilateral.structure.Frame2D` resting on a soil medium (``Frame2D.foundation``).

The frame is the structure of a :class:`~unilateral.soil.FoundationModel`: its ``M, K, C`` without the
soil, ``T`` (n, m) the upward displacement of the footing at each contact patch, ``Phi(s)`` the soil's
flexibility of the patches (``docs/theory.md``, section 12). Two footings:

* **rigid** (``node`` only): the reference ``node`` carries ``uy`` and ``rz``; ``patches`` strips
  across the ``width`` (the frame's x), each as long as the footing (``length``, out of plane), at
  ``x_j`` from the node: ``T[:, j] = e_uy + x_j e_rz``;
* **flexible** (``nodes=[...]``): one patch per node of a footing beam, centred on the node, twice
  as wide as the nearer end of its tributary strip (default ``width``: the span of the nodes plus
  one mean spacing, so that equally spaced nodes get equal patches that cover the footing);
  ``T[:, j] = e_uy`` of node ``j``.

The soil (``soil=``): a :class:`~unilateral.soil.SoilFlexibility` of the patches, a
:class:`SoilSpec`, or a dict of its fields: ``model`` ``"halfspace"`` (the rigorous (visco)elastic
half-space), ``"cones"`` (Wolf's cones with Boussinesq coupling) or ``"winkler-kelvin"`` (the paper's
tensionless spring ``k`` and dashpot ``c`` per patch); ``G`` or ``Vs``, ``nu``, ``rho``, ``damping``.

``"cones"`` is Wolf's (1994) vertical cone of the disc with the footing's area (spring ``K``,
radiation dashpot ``C = rho c A``, trapped mass if ``nu > 1/3``) spread over the patches in
proportion to their areas: a bed of uncoupled, rational (``method="modal"``) cone elements whose
totals are the footing's vertical cone; its rocking stiffness is that of a Winkler bed (for the
10 m square footing on 4 strips 0.47 of the rocking cone's). The coupled
:meth:`SoilFlexibility.cones <unilateral.soil.SoilFlexibility.cones>` (Boussinesq decay with a wave
delay between patches) can be given as ``soil`` directly, but it is not passive: with the contacts
held (the bilateral case) the march of the example's tower on 2 to 4 strips grows without bound
(to 1e7 m and beyond), at every time step tried; it is not used here.

The horizontal restraint (``horizontal=``): the contact is vertical only (relaxed: no shear
tractions), so the footing needs a horizontal restraint of its own: ``"support"`` (default: ``ux``
of the reference node supported, as in the paper's example), ``"cone"`` (a bilateral horizontal
spring ``K = 8 G r0 / (2 - nu)`` and dashpot ``C = rho Vs pi r0^2`` of Wolf's horizontal cone of the
disc of equal area, attached to the reference node: the footing is assumed not to slide, also when
it lifts off partly) or ``"none"`` (the frame restrains it otherwise), or ``"soil"``: the footing rests on the soil
horizontally too and **slides** - each patch carries a horizontal force through the soil's
horizontal and vertical flexibility (on a half-space or a layered soil the x-z Green's tensor with
the coupling of a compressible solid; Wolf's horizontal cone spread over the patches by area for
``"cones"``; springs ``kx`` and dashpots ``cx`` per patch for ``"winkler-kelvin"``), limited by
Coulomb friction ``|f| <= mu c`` (``mu=`` of the footing): an open patch carries none, so the footing
rocks, lifts and slides at once (:class:`~unilateral.soil.FoundationModel` with ``Tx``, ``mu``).
Every footing of a frame then takes ``horizontal="soil"``.

Units: any consistent set; with kN, m, s: ``G`` in kPa, ``rho`` in t/m^3, ``k`` in kN/m,
``c`` in kN s/m.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass, fields

import numpy as np
import scipy.sparse as sp

__all__ = ["HORIZONTAL", "SOIL_MODELS", "Footings", "Foundation", "SoilSpec", "soil_flexibility"]

SOIL_MODELS = ("halfspace", "layered", "cones", "winkler-kelvin")
#: Soils whose patches interact through the ground (one flexibility for every footing on them).
COUPLED_SOILS = ("halfspace", "layered")
HORIZONTAL = ("support", "cone", "none", "soil")


@dataclass(frozen=True)
class SoilSpec:
    """The soil under a footing, by its material (all in the frame's consistent units).

    Attributes
    ----------
    model : {"halfspace", "layered", "cones", "winkler-kelvin"}
        The rigorous half-space, horizontal layers over it (:class:`~unilateral.soil.Layered`),
        the footing's vertical cone spread over the patches, or the paper's Kelvin elements (see
        :mod:`unilateral.structure.foundation`).
    G : float, force/length^2
        Shear modulus (or give ``Vs``; ``G = rho Vs^2``).
    Vs : float, length/time
        Shear-wave speed.
    nu : float in [0, 0.5)
    rho : float, mass/length^3 (force time^2/length^4)
    damping : float >= 0
        Material damping ratio of the half-space (constant Q, :class:`~unilateral.soil.HalfSpace`);
        0 for the cones (they have none).
    k : float or sequence of m floats, force/length
        ``"winkler-kelvin"``: the spring of each patch (one number: the same for every patch).
    c : float or sequence of m floats, force time/length
        ``"winkler-kelvin"``: the dashpot of each patch (default 0).
    kx, cx : float or sequence of m floats
        ``"winkler-kelvin"`` with ``horizontal="soil"``: the horizontal spring (force/length) and
        dashpot (force time/length) of each patch.
    layers : sequence of dict, optional
        ``"layered"``: the layers from the surface down, each ``thickness``, ``G`` or ``Vs``,
        ``nu``, ``rho``, ``damping``; the half-space under them is ``G`` or ``Vs``, ``nu``, ``rho``,
        ``damping`` of this spec, or a rigid base with ``base="rigid"``.
    base : {"halfspace", "rigid"}
        ``"layered"``: what the layers rest on.
    """

    model: str
    G: float | None = None
    Vs: float | None = None
    nu: float | None = None
    rho: float | None = None
    damping: float = 0.0
    k: object = None
    c: object = 0.0
    kx: object = None
    cx: object = 0.0
    layers: object = None
    base: str = "halfspace"

    @classmethod
    def from_dict(cls, data: dict, where: str = "soil") -> SoilSpec:
        """A SoilSpec from a dict of its fields; unknown keys are named in the error."""
        if not isinstance(data, dict):
            raise TypeError(f"{where} must be a SoilFlexibility, a SoilSpec or a dict with 'model', got {data!r}")
        names = [f.name for f in fields(cls)]
        unknown = [key for key in data if key not in names]
        if unknown:
            raise ValueError(f"{where}: unknown key(s) {', '.join(map(repr, unknown))}; valid: {', '.join(names)}")
        if "model" not in data:
            raise ValueError(f"{where}: 'model' is missing; valid: {', '.join(map(repr, SOIL_MODELS))}")
        return cls(**data)

    def shear_modulus(self, where="soil") -> float:
        """``G`` (given, or ``rho Vs^2``)."""
        if (self.G is None) == (self.Vs is None):
            raise ValueError(f"{where}: give either G or Vs (not both, not neither) for model={self.model!r}; "
                             f"got G={self.G!r}, Vs={self.Vs!r}")
        rho = _positive(where, "rho", self.rho)
        if self.G is not None:
            return _positive(where, "G", self.G)
        vs = _positive(where, "Vs", self.Vs)
        G = rho * vs * vs
        if not 0.0 < G < np.inf:
            raise ValueError(f"{where}: Vs={self.Vs!r} with rho={self.rho!r} gives the shear modulus "
                             f"G = rho Vs^2 = {G:g}; give a Vs for which it is a finite number > 0")
        return G

    def poisson(self, where="soil") -> float:
        if isinstance(self.nu, bool) or not isinstance(self.nu, numbers.Real) or not 0.0 <= self.nu < 0.5:
            raise ValueError(f"{where}: nu={self.nu!r} is not valid; give Poisson's ratio in [0, 0.5)")
        return float(self.nu)


def soil_flexibility(soil, patches, where="soil", components="z"):
    """The :class:`~unilateral.soil.SoilFlexibility` of ``patches`` for ``soil``.

    Parameters
    ----------
    soil : SoilFlexibility, SoilSpec or dict
        A SoilFlexibility must have one contact per patch (``components="xz"``: two, x then z).
    patches : RectangularPatches
        ``m`` patches (contact order).
    where : str
        The name used in error messages.
    components : {"z", "xz"}
        Vertical only, or the x rows of the patches then their z rows (footings that slide).

    Returns
    -------
    soil : SoilFlexibility
    spec : SoilSpec or None
    """
    from ..soil.flexibility import SoilFlexibility

    rows = len(components) * patches.m
    if isinstance(soil, SoilFlexibility):
        if soil.m != rows:
            raise ValueError(f"{where}: the SoilFlexibility has m = {soil.m} rows but the footing has "
                             f"{patches.m} patches" + (" and slides (x then z rows: 2 per patch)" if rows > patches.m
                                                       else "") + "; build it for these patches")
        return soil, None
    spec = soil if isinstance(soil, SoilSpec) else SoilSpec.from_dict(soil, where)
    if spec.model not in SOIL_MODELS:
        raise ValueError(f"{where}: model={spec.model!r} is not valid; valid: {', '.join(map(repr, SOIL_MODELS))}")
    m = patches.m
    if spec.model == "winkler-kelvin":
        return _winkler_kelvin(spec, m, where, components), spec
    if spec.kx is not None or spec.cx not in (None, 0, 0.0):
        raise ValueError(f"{where}: kx and cx are for model='winkler-kelvin'; remove them for model={spec.model!r}")
    if spec.model == "layered":
        return SoilFlexibility.halfspace(layered_soil(spec, where), patches, components=components), spec
    if spec.layers is not None or spec.base != "halfspace":
        raise ValueError(f"{where}: layers and base are for model='layered'; remove them for model={spec.model!r}")
    if spec.k is not None or (spec.c not in (None, 0, 0.0)):
        raise ValueError(f"{where}: k and c are for model='winkler-kelvin'; model={spec.model!r} takes G or Vs, "
                         "nu, rho (and damping)")
    G, nu = spec.shear_modulus(where), spec.poisson(where)
    rho = _positive(where, "rho", spec.rho)
    damping = spec.damping
    if isinstance(damping, bool) or not isinstance(damping, numbers.Real) or not 0.0 <= damping < 1.0:
        raise ValueError(f"{where}: damping={damping!r} is not valid; give a damping ratio in [0, 1)")
    if spec.model == "cones":
        if damping:
            raise ValueError(f"{where}: damping={damping!r}: the cones have no material damping; use "
                             "model='halfspace' for a damped soil, or damping = 0")
        return _cones(patches, G, nu, rho, components), spec
    from ..soil.halfspace import HalfSpace

    return SoilFlexibility.halfspace(HalfSpace(G, nu, rho, float(damping)), patches, components=components), spec


def _winkler_kelvin(spec, m, where, components):
    """The Kelvin springs of a ``"winkler-kelvin"`` soil spec (``k``, ``c`` per patch; with
    ``components="xz"`` also ``kx``, ``cx``, the x rows first)."""
    from ..soil.flexibility import SoilFlexibility

    for key in ("G", "Vs", "nu", "rho"):
        if getattr(spec, key) is not None:
            raise ValueError(f"{where}: {key}={getattr(spec, key)!r} is not used by model='winkler-kelvin' "
                             "(give k and c per patch), remove it")
    if spec.damping:
        raise ValueError(f"{where}: damping={spec.damping!r} is not used by model='winkler-kelvin' (give c)")
    if spec.k is None:
        raise ValueError(f"{where}: model='winkler-kelvin' needs k, the spring of each patch [force/length]")
    k = _per_patch(where, "k", spec.k, m, ">0")
    c = _per_patch(where, "c", spec.c, m, ">=0")
    if components == "xz":
        if spec.kx is None:
            raise ValueError(f"{where}: a footing that slides on model='winkler-kelvin' needs kx, the horizontal "
                             "spring of each patch [force/length] (and cx, its dashpot)")
        k = np.concatenate([_per_patch(where, "kx", spec.kx, m, ">0"), k])
        c = np.concatenate([_per_patch(where, "cx", spec.cx, m, ">=0"), c])
    elif spec.kx is not None or spec.cx not in (None, 0, 0.0):
        raise ValueError(f"{where}: kx and cx are for a footing with horizontal='soil'; remove them")
    return SoilFlexibility.kelvin(k, c)


def _cones(patches, G, nu, rho, components):
    """Wolf's cones of the whole footing (vertical; with ``components="xz"`` horizontal first),
    shared among the patches by area."""
    from ..soil.cones import Cone, cone
    from ..soil.flexibility import SoilFlexibility

    areas = patches.areas
    share = areas / areas.sum()
    r0 = float(np.sqrt(areas.sum() / np.pi))
    motions = ("horizontal", "vertical") if components == "xz" else ("vertical",)
    cones = []
    for motion in motions:
        whole = cone(motion, G, nu, rho, r0)
        cones += [Cone(motion, whole.K * w, whole.C * w, whole.dM * w, 0.0, whole.z0, whole.c) for w in share]
    flex = SoilFlexibility.impedances(cones)
    flex.description = (f"the footing's {' and '.join(motions)} cones (G={G:g}, nu={nu:g}, rho={rho:g}) over "
                        f"{patches.m} patches by area")
    return flex


def layered_soil(spec: SoilSpec, where="soil"):
    """The :class:`~unilateral.soil.Layered` soil of a ``"layered"`` spec."""
    from ..soil.halfspace import HalfSpace
    from ..soil.layered import Layered

    if not isinstance(spec.layers, (list, tuple)) or not spec.layers:
        raise ValueError(f"{where}: model='layered' needs layers, a list of tables with thickness, G or Vs, nu, "
                         f"rho (and damping), from the surface down; got layers={spec.layers!r}")
    if spec.k is not None or (spec.c not in (None, 0, 0.0)):
        raise ValueError(f"{where}: k and c are for model='winkler-kelvin'; remove them for model='layered'")
    if spec.base not in ("halfspace", "rigid"):
        raise ValueError(f"{where}: base={spec.base!r} is not valid; valid: 'halfspace' (G or Vs, nu, rho, damping "
                         "of the soil table) or 'rigid'")
    layers = [dict(layer) for layer in spec.layers]
    for k, layer in enumerate(layers):
        if isinstance(layer.get("nu"), numbers.Real) and not layer["nu"] < 0.5:
            raise ValueError(f"{where}: layers[{k}]['nu'] = {layer['nu']!r}: the layered soil is compressible; "
                             "give nu in [0, 0.5)")
    if spec.base == "rigid":
        given = [key for key in ("G", "Vs", "nu", "rho") if getattr(spec, key) is not None]
        if given or spec.damping:
            raise ValueError(f"{where}: base='rigid' takes no half-space ({', '.join(given) or 'damping'} given): "
                             "remove them, or use base='halfspace'")
        try:
            return Layered(layers, None)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{where}: {exc}") from None
    damping = spec.damping
    if isinstance(damping, bool) or not isinstance(damping, numbers.Real) or not 0.0 <= damping < 1.0:
        raise ValueError(f"{where}: damping={damping!r} is not valid; give a damping ratio in [0, 1)")
    base = HalfSpace(spec.shear_modulus(where), spec.poisson(where), _positive(where, "rho", spec.rho), float(damping))
    try:
        return Layered(layers, base)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}: {exc}") from None


@dataclass(frozen=True, eq=False)
class Foundation:
    """A footing on a soil medium, as attached by :meth:`Frame2D.foundation`.

    Attributes
    ----------
    name : str
    node : the reference node (rigid: the footing's node; flexible: where ``horizontal`` acts)
    nodes : tuple of contact nodes (flexible), or None (rigid)
    width, length : float, length
    patches : RectangularPatches
        Patch centres in the frame's x (absolute; y = 0 along the footing's length).
    soil : SoilFlexibility
    spec : SoilSpec or None
    horizontal : str
    gap : (m,) opening at ``u = 0`` with the soil unloaded
    contact_names : tuple of m str
    y : float, elevation of the footing (length)
    mu : float or None, the friction coefficient on the soil (``horizontal="soil"``)
    """

    name: str
    node: object
    nodes: tuple | None
    width: float
    length: float
    patches: object
    soil: object
    spec: SoilSpec | None
    horizontal: str
    gap: np.ndarray
    contact_names: tuple
    y: float = 0.0
    mu: float | None = None

    @property
    def m(self) -> int:
        """Number of contact patches."""
        return self.patches.m

    @property
    def rigid(self) -> bool:
        return self.nodes is None

    @property
    def sliding(self) -> bool:
        """The footing rests on the soil horizontally and slides (``horizontal="soil"``)."""
        return self.horizontal == "soil"

    def contact_nodes(self) -> list:
        """The node each contact force acts on (the reference node for a rigid footing)."""
        return [self.node] * self.m if self.rigid else list(self.nodes)

    def moved_rows(self, coords) -> list[tuple]:
        """Per contact: ``[(node, dof, factor), ...]`` with ``z_f = sum factor * u(node, dof)``."""
        if self.rigid:
            x0 = float(coords[self.node][0])
            return [[(self.node, "uy", 1.0), (self.node, "rz", float(x) - x0)]
                    for x in self.patches.centres[:, 0]]
        return [[(node, "uy", 1.0)] for node in self.nodes]

    def shear_rows(self) -> list[tuple]:
        """Per contact: ``[(node, "ux", 1.0)]``, the footing's horizontal displacement at the patch (its
        base, at the node's elevation)."""
        return [[(node, "ux", 1.0)] for node in self.contact_nodes()]

    def T(self, dofs, coords) -> np.ndarray:
        """``T`` (n, m): upward displacement of the footing at each patch, ``z_f = T^T u``."""
        return _rows_matrix(dofs, self.moved_rows(coords), self.m)

    def Tx(self, dofs) -> np.ndarray:
        """``Tx`` (n, m): horizontal displacement of the footing at each patch, ``x_f = Tx^T u``."""
        return _rows_matrix(dofs, self.shear_rows(), self.m)

    def constraint_coords(self) -> dict:
        """Coordinates along ``constraint`` for ``results.nc``: x, y of each patch, kind, gap (of its
        contact; a footing that slides: of its shears and slips too, with :meth:`Footings.constraint_coords`)."""
        return {"constraint_x": ("constraint", [float(x) for x in self.patches.centres[:, 0]]),
                "constraint_y": ("constraint", [float(self.y)] * self.m),
                "constraint_kind": ("constraint", ["foundation"] * self.m),
                "constraint_gap": ("constraint", [float(g) for g in self.gap])}

    # ------------------------------------------------------------------ results of a solution
    def ground_reactions(self, structure, c, h=None) -> tuple[dict, dict]:
        """The soil's forces on the structure, per contact: ``(fx, fy, mz)`` (N+1, 3) and the node.

        ``c`` (N+1, m) are the footing's compressive contact forces, ``h`` (N+1, m) the soil's
        horizontal forces on the footing (a footing that slides; else none). Each acts at its patch
        centre, at the footing's base; it is reported at the node it acts on (``contact_nodes``) with
        the moment ``(x_j - x_node) c_j`` of the offset, so that base forces and overturning
        moments about any point come out right.
        """
        forces, at = {}, {}
        for j, node in enumerate(self.contact_nodes()):
            f = np.zeros((c.shape[0], 3))
            f[:, 1] = c[:, j]
            if h is not None:
                f[:, 0] = h[:, j]
            f[:, 2] = (float(self.patches.centres[j, 0]) - float(structure.coords[node][0])) * c[:, j]
            forces[self.contact_names[j]] = f
            at[self.contact_names[j]] = node
        return forces, at


class Footings:
    """All the footings of a frame on one soil: their patches share one flexibility ``Phi(s)``.

    On a half-space (or a layered soil) every patch of every footing is coupled to every other
    through the ground (structure-soil-structure interaction); footings on cones or on Winkler-Kelvin
    beds are uncoupled (a block-diagonal ``Phi``). The soil contacts follow the frame's own
    constraints in the model and its solutions: ``first`` is their number.

    Attributes
    ----------
    footings : tuple of Foundation
    soil : SoilFlexibility of all ``m`` patches (footing by footing, in the order attached)
    first : int, the index of the first soil contact among the model's constraints
    """

    def __init__(self, footings, first=0):
        self.footings = tuple(footings)
        self.first = int(first)
        self.sliding = self.footings[0].sliding
        if any(f.sliding != self.sliding for f in self.footings):
            raise ValueError(f"foundations {', '.join(repr(f.name) for f in self.footings)}: footings that slide "
                             "(horizontal='soil') and footings held otherwise cannot be mixed in one frame; give "
                             "every footing horizontal='soil', or none")
        self.mu = np.concatenate([np.full(f.m, f.mu if f.sliding else 0.0) for f in self.footings])
        self.soil = _group_soil(self.footings)
        self.patches = _concat_patches([f.patches for f in self.footings])
        self.gap = np.concatenate([f.gap for f in self.footings])
        self.contact_names = tuple(name for f in self.footings for name in f.contact_names)

    @property
    def m(self) -> int:
        """Number of contact patches of all footings."""
        return self.patches.m

    @property
    def name(self) -> str:
        return ", ".join(f.name for f in self.footings)

    def __len__(self) -> int:
        return len(self.footings)

    def contact_nodes(self) -> list:
        return [node for f in self.footings for node in f.contact_nodes()]

    def moved_rows(self, coords) -> list:
        return [row for f in self.footings for row in f.moved_rows(coords)]

    def T(self, dofs, coords) -> np.ndarray:
        """``T`` (n, m) of all patches."""
        return np.hstack([f.T(dofs, coords) for f in self.footings])

    def Tx(self, dofs) -> np.ndarray:
        """``Tx`` (n, m) of all patches (footings that slide)."""
        return np.hstack([f.Tx(dofs) for f in self.footings])

    def constraint_coords(self) -> dict:
        """x, y, kind and gap of each patch along ``constraint`` (after the frame's own constraints); a
        footing that slides: its contacts, then its shears (kind ``"foundation_shear"``) and its
        slip pairs (``"foundation_slip"``), each at its patch."""
        parts = [f.constraint_coords() for f in self.footings]
        out = {key: [x for p in parts for x in p[key][1]] for key in parts[0]}
        if self.sliding:
            x, y, gap = out["constraint_x"], out["constraint_y"], out["constraint_gap"]
            out = {"constraint_x": x + x + [a for a in x for _ in "+-"],
                   "constraint_y": y + y + [a for a in y for _ in "+-"],
                   "constraint_kind": out["constraint_kind"] + ["foundation_shear"] * self.m
                   + ["foundation_slip"] * (2 * self.m),
                   "constraint_gap": gap + [0.0] * (3 * self.m)}
        return {key: ("constraint", value) for key, value in out.items()}

    def contact_forces(self, sol) -> np.ndarray:
        """Compressive contact forces ``c = -psi`` (N+1, m) of a solution (force)."""
        return -np.asarray(sol.psi, dtype=float)[:, self.first:self.first + self.m]

    def shear_forces(self, sol) -> np.ndarray | None:
        """The soil's horizontal forces on the footings (N+1, m) (force, +x), or None if they do not slide."""
        if not self.sliding:
            return None
        return np.asarray(sol.psi, dtype=float)[:, self.first + self.m:self.first + 2 * self.m]

    def slips(self, sol) -> np.ndarray | None:
        """The net slip ``s+ - s-`` (N+1, m) of each patch on the soil (length, +x), or None."""
        if not self.sliding:
            return None
        return np.asarray(sol.v, dtype=float)[:, self.first + self.m:self.first + 2 * self.m]

    def contact_load(self, structure, sol) -> np.ndarray:
        """``T c + Tx h`` (N+1, n): the load of the soil's forces on the structure."""
        out = self.contact_forces(sol) @ self.T(structure.dofs, structure.coords).T
        if self.sliding:
            out = out + self.shear_forces(sol) @ self.Tx(structure.dofs).T
        return out

    def ground_reactions(self, structure, sol) -> tuple[dict, dict]:
        """The soil's forces on the structure per contact, as :meth:`Foundation.ground_reactions`."""
        c = self.contact_forces(sol)
        h = self.shear_forces(sol)
        forces, at = {}, {}
        start = 0
        for f in self.footings:
            got, where = f.ground_reactions(structure, c[:, start:start + f.m],
                                            None if h is None else h[:, start:start + f.m])
            forces |= got
            at |= where
            start += f.m
        return forces, at


def _rows_matrix(dofs, rows, m) -> np.ndarray:
    """(n, m): column ``j`` is ``sum factor * e(node, dof)`` over ``rows[j]``."""
    out = np.zeros((dofs.n, m))
    for j, terms in enumerate(rows):
        for node, dof, factor in terms:
            if factor:
                out[:, j] += factor * dofs.T[dofs.full_index(node, dof)].toarray().ravel()
    return out


def _concat_patches(parts):
    from ..soil.patches import RectangularPatches

    return RectangularPatches(np.vstack([p.centres for p in parts]), np.vstack([p.sizes for p in parts]))


def shared_medium(footings, elevation: str) -> bool:
    """True if the footings rest on one half-space or layered soil (their patches interact through
    it); raise ``ValueError`` unless all do, on the same material and at one ``elevation`` (the name
    of the vertical coordinate: ``"y"`` in 2-D, ``"z"`` in 3-D)."""
    specs = [f.spec for f in footings]
    coupled = [s is not None and s.model in COUPLED_SOILS for s in specs]
    if not any(coupled):
        return False
    names = ", ".join(repr(f.name) for f in footings)
    if not all(coupled) or len({_material(s) for s in specs}) > 1:
        raise ValueError(f"foundations {names}: footings on a half-space or a layered soil share that soil "
                         "(their patches interact through the ground): give every footing the same soil, "
                         f"got {[_material(s) if s else 'a SoilFlexibility' for s in specs]}")
    if len({round(f.y, 9) for f in footings}) > 1:
        raise ValueError(f"foundations {names}: footings on one soil medium lie on its surface, at one "
                         f"elevation; got {elevation} = {sorted({f.y for f in footings})}")
    return True


def _group_soil(footings):
    """One flexibility of all the footings' patches (see :class:`Footings`)."""
    from ..soil.flexibility import SoilFlexibility

    if len(footings) == 1:
        return footings[0].soil
    specs = [f.spec for f in footings]
    if shared_medium(footings, "y"):
        return soil_flexibility(specs[0], _concat_patches([f.patches for f in footings]),
                                f"foundation {footings[0].name!r}: soil", "xz" if footings[0].sliding else "z")[0]
    soil = SoilFlexibility.block_diagonal([f.soil for f in footings])
    if not footings[0].sliding:
        return soil
    # each footing's rows are its x then its z rows: all x rows first, then all z rows
    starts = np.cumsum([0] + [2 * f.m for f in footings])
    order = [a + j for a, f in zip(starts, footings) for j in range(f.m)]
    return soil.permuted(order + [a + f.m + j for a, f in zip(starts, footings) for j in range(f.m)])


def _material(spec):
    return (spec.model, spec.G, spec.Vs, spec.nu, spec.rho, spec.damping, repr(spec.layers), spec.base)


def _check_overlap(footings, new, where):
    """Raise if the new footing's plan overlaps a footing already attached at the same elevation."""
    lo, hi = new.patches.centres[:, 0] - 0.5 * new.patches.sizes[:, 0], \
        new.patches.centres[:, 0] + 0.5 * new.patches.sizes[:, 0]
    for other in footings:
        if abs(other.y - new.y) > 1e-9 * max(1.0, abs(new.y)):
            continue
        olo = other.patches.centres[:, 0] - 0.5 * other.patches.sizes[:, 0]
        ohi = other.patches.centres[:, 0] + 0.5 * other.patches.sizes[:, 0]
        overlap = min(hi.max(), ohi.max()) - max(lo.min(), olo.min())
        if overlap > 1e-9 * max(new.width, other.width):
            raise ValueError(f"{where}: the footing (x from {lo.min():g} to {hi.max():g}) overlaps footing "
                             f"{other.name!r} (x from {olo.min():g} to {ohi.max():g}) by {overlap:g}; footings "
                             "on the ground must not overlap")


def structural_solution(sol, first=0):
    """A view of a foundation model's solution for the frame's results: the frame's own constraints.

    The frame's end forces, supports, accelerations and energies are those of
    ``M u'' + C u' + K u = q + F v + T c`` with the soil's contact forces as a load
    (:meth:`Footings.contact_load`); ``first`` is the number of the frame's own constraints (its
    unilateral, yielding and friction elements), whose columns are kept.
    """
    from ..result import Solution

    keep = lambda a: None if a is None else np.asarray(a)[:, :first]
    return Solution(t=sol.t, v=keep(sol.v), psi=keep(sol.psi), psiL=keep(sol.psiL), u=sol.u, udot=sol.udot,
                    success=sol.success, message=sol.message, stats=dict(sol.stats), dof_names=sol.dof_names,
                    constraint_names=list(sol.constraint_names)[:first])


def build_foundation(*, name, node, nodes, width, length, soil, patches, horizontal, gap, coords,
                     mu=None) -> Foundation:
    """Check the arguments of :meth:`Frame2D.foundation` and make the :class:`Foundation`."""
    from ..soil.patches import RectangularPatches, strips

    where = f"foundation {name!r}"
    length = _positive(where, "length", length)
    horizontal = horizontal if isinstance(horizontal, str) else repr(horizontal)
    if horizontal not in HORIZONTAL:
        raise ValueError(f"{where}: horizontal={horizontal!r} is not valid; valid: {', '.join(map(repr, HORIZONTAL))}")
    if horizontal == "soil":
        if isinstance(mu, bool) or not isinstance(mu, numbers.Real) or not (np.isfinite(mu) and mu >= 0):
            raise ValueError(f"{where}: horizontal='soil' needs mu, the friction coefficient of the footing on the "
                             f"soil (a finite number >= 0; a large one for a footing that does not slide), got "
                             f"mu={mu!r}")
        mu = float(mu)
    elif mu is not None:
        raise ValueError(f"{where}: mu={mu!r} is for a footing that slides on the soil; give horizontal='soil' "
                         f"(now {horizontal!r}) or remove mu")
    if nodes is None:
        width = _positive(where, "width", width)
        if isinstance(patches, bool) or not isinstance(patches, numbers.Integral) or not 1 <= patches <= 400:
            raise ValueError(f"{where}: patches={patches!r} is not valid; give the number of strips across "
                             "the width, an integer from 1 to 400")
        x0, y0 = coords[node]
        local = strips(width, length, int(patches))
        pts = RectangularPatches(local.centres + np.array([x0, 0.0]), local.sizes)
        names = tuple(f"{name}.{j + 1}" for j in range(pts.m))
        contact_nodes = None
    else:
        nodes = list(nodes)
        if patches is not None:
            raise ValueError(f"{where}: patches={patches!r}: a flexible footing has one patch per node of "
                             "nodes; remove patches")
        if len(nodes) < 2:
            raise ValueError(f"{where}: nodes={nodes!r}: a flexible footing needs at least two nodes (one "
                             "patch each); give node only for a rigid footing")
        if len(set(map(repr, nodes))) != len(nodes):
            raise ValueError(f"{where}: nodes={nodes!r} lists a node twice")
        xy = np.array([coords[n] for n in nodes], dtype=float)
        order = np.argsort(xy[:, 0])
        if np.any(np.diff(xy[order, 0]) <= 0):
            raise ValueError(f"{where}: nodes={nodes!r}: two nodes have the same x; the footing's nodes must "
                             "lie at distinct x along the width")
        if np.ptp(xy[:, 1]) > 1e-9 * max(1.0, np.abs(xy[:, 1]).max()):
            raise ValueError(f"{where}: nodes={nodes!r} are not at one elevation (y from {xy[:, 1].min():g} to "
                             f"{xy[:, 1].max():g}); a footing lies on the ground surface")
        nodes = [nodes[i] for i in order]
        x = xy[order, 0]
        span = x[-1] - x[0]
        # default: one node spacing beyond the span, so that equally spaced nodes get equal patches
        width = span * len(nodes) / (len(nodes) - 1) if width is None else _positive(where, "width", width)
        if width < span * (1 - 1e-12):
            raise ValueError(f"{where}: width={width!r} is smaller than the span of the nodes ({span:g}); give "
                             "a width larger than the span, or omit it (the span plus one mean node spacing)")
        centre = 0.5 * (x[0] + x[-1])
        edges = np.concatenate([[centre - 0.5 * width], 0.5 * (x[1:] + x[:-1]), [centre + 0.5 * width]])
        lo, hi = edges[:-1], edges[1:]
        # each patch centred on its node: the narrower side of its tributary strip, twice
        half = np.minimum(x - lo, hi - x)
        if np.any(half <= 0):
            raise ValueError(f"{where}: a node lies on the footing's edge with width={width!r}; give a width "
                             "larger than the span of the nodes so that each edge node has a patch")
        pts = RectangularPatches(np.column_stack([x, np.zeros_like(x)]), np.column_stack([2 * half,
                                                                                          np.full_like(x, length)]))
        names = tuple(f"{name}.{n}" for n in nodes)
        contact_nodes = tuple(nodes)
        y0 = xy[0, 1]
    flex, spec = soil_flexibility(soil, pts, f"{where}: soil", "xz" if horizontal == "soil" else "z")
    return Foundation(name=name, node=node, nodes=contact_nodes, width=float(width), length=length, patches=pts,
                      soil=flex, spec=spec, horizontal=horizontal, gap=patch_gaps(where, gap, pts.m),
                      contact_names=names, y=float(y0), mu=mu)


def patch_gaps(where, gap, m) -> np.ndarray:
    """The opening of each of ``m`` patches at ``u = 0`` from ``gap`` (a number or ``m`` numbers)."""
    out = np.broadcast_to(np.asarray(gap, dtype=float), (m,)).copy() if np.ndim(gap) == 0 else \
        np.asarray(gap, dtype=float)
    if out.shape != (m,) or not np.all(np.isfinite(out)):
        raise ValueError(f"{where}: gap={gap!r} must be a finite number or one number per patch ({m})")
    return out


def check_patch_gaps(footings, coords) -> None:
    """Refuse a footing patch's gap that double precision cannot carry beside the frame's size
    (:func:`~unilateral.structure.elements.clearance_bound`): the openings of every patch enter the
    step's LCP beside those of the patches in contact, whose round-off then grows with the largest
    (measured on two footings on cones, one patch open by ``gap``: the response moves by 1e-11 of its
    peak at gap = 1e3 m, 6.7e-9 at 1e6 m, 3.9 % at 1e9 m and 76 times at 1e15 m)."""
    from .elements import CLEARANCE_MAX_RATIO, clearance_bound

    bound, size = clearance_bound(coords)
    for f in footings:
        j = int(np.argmax(np.abs(f.gap))) if f.m else 0
        if f.m and abs(float(f.gap[j])) > bound:
            raise ValueError(f"foundation {f.name!r}: gap = {float(f.gap[j])!r} (patch {j + 1}) exceeds "
                             f"{CLEARANCE_MAX_RATIO:g} times the size of the frame ({size}): double precision carries "
                             f"the contacts beside it only to about 2.2e-16 * gap; give |gap| <= {bound:.6g}, or leave "
                             "the footing out if it never touches the soil")


def horizontal_cone(fnd: Foundation, where: str) -> tuple[float, float]:
    """``(K, C)`` of Wolf's horizontal cone of the disc with the footing's area."""
    from ..soil.cones import cone

    spec = fnd.spec
    if spec is None or spec.model == "winkler-kelvin":
        raise ValueError(f"{where}: horizontal='cone' needs the soil's G (or Vs), nu and rho (model 'halfspace' "
                         "or 'cones'); use horizontal='support' or add a spring and a dashpot")
    r0 = float(np.sqrt(fnd.width * fnd.length / np.pi))
    c = cone("horizontal", spec.shear_modulus(where), spec.poisson(where), spec.rho, r0)
    return float(c.K), float(c.C)


def to_foundation_model(structure, model=None):
    """The :class:`~unilateral.soil.FoundationModel` of a frame with footings on a soil medium.

    ``model`` is the frame's own :class:`~unilateral.model.Model` (its unilateral, yielding and
    friction elements), or None for a frame without any: the footings' contacts then are the
    model's only constraints.
    """
    from ..soil.foundation_model import FoundationModel

    fnd = structure.foundation
    T = fnd.T(structure.dofs, structure.coords)
    slide = dict(Tx=fnd.Tx(structure.dofs), mu=fnd.mu) if fnd.sliding else {}
    if model is not None:
        if structure.n > 2000:
            T = sp.csr_matrix(T)
            slide = {key: sp.csr_matrix(value) if key == "Tx" else value for key, value in slide.items()}
        return FoundationModel.on(model, T, fnd.soil, gap=fnd.gap, contact_names=list(fnd.contact_names), **slide)
    nat = structure.natural
    if np.any(nat.theta(0.0)):
        raise ValueError("the frame has imposed strains (axial_strain, curvature) and a foundation on a soil "
                         "medium: give them as loads")
    K = (nat.G @ nat.E @ nat.G.T).tocsr()
    if structure.geometric is not None:            # P-Delta: the gravity's axial forces on the soil's springs
        K = (K + structure.geometric).tocsr()
    dense = structure.n <= 2000
    M, C = structure.M, structure.C
    if dense:
        K, M = K.toarray(), M.toarray()
        C = None if C is None else C.toarray()
    else:
        T = sp.csr_matrix(T)
        slide = {key: sp.csr_matrix(value) if key == "Tx" else value for key, value in slide.items()}
    return FoundationModel(M, K, T, fnd.soil, C=C, gap=fnd.gap, dof_names=structure.dofs.names,
                           contact_names=list(fnd.contact_names), K_geometric=structure.geometric, **slide)


def _positive(where, arg, value) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not np.isfinite(value) or value <= 0:
        raise ValueError(f"{where}: {arg}={value!r} is not valid; give a finite number > 0")
    return float(value)


def _per_patch(where, arg, value, m, bound) -> np.ndarray:
    values = [value] * m if isinstance(value, numbers.Real) and not isinstance(value, bool) else value
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.shape != (m,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{where}: {arg}={value!r} is not valid; give one number or a list of {m} numbers "
                         "(one per patch)")
    bad = arr <= 0 if bound == ">0" else arr < 0
    if np.any(bad):
        raise ValueError(f"{where}: {arg}={value!r} is not valid; every value must be {bound[0]} {bound[1:]}")
    return arr
