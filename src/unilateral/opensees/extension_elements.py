"""The elements of the extensions (:mod:`.extensions`): their records, their parsing from the
commands' arguments (tags, positional numbers, ``'-flag'`` options, each refused by name when
invalid) and the elements of ``Frame2D``/``Frame3D`` they become (:func:`add_to_frame`)."""


from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .materials import DIRECTIONS
from .refusals import refuse

__all__ = ["Footing", "SpringFooting", "KelvinContact", "RigidContact", "add_to_frame", "PARSERS"]

_SOILS = {"halfspace": ("Vs", "nu", "rho"), "cones": ("Vs", "nu", "rho"), "layered": ("Vs", "nu", "rho"),
          "winkler": ("k", "c")}
_FOOTING = ("footing(tag, node, width, length, 'halfspace' | 'cones', Vs, nu, rho, ['-patches', n, '-gap', g, "
            "'-damping', D, '-horizontal', 'support' | 'cone' | 'none', '-mu', mu, '-layer', h, Vs, nu, rho])")
_SPRING = "springFooting(tag, node, width, k, ['-length', L, '-c', c, '-springs', n, '-qult', q, '-gap', g])"
_RIGID = "rigidContact(tag, node, '-dir', d, ['-gap', g, '-mu', mu, '-e', e])"
_KELVIN = "kelvinContact(tag, iNode, jNode, '-dir', d, '-k', k, ['-c', c, '-gap', g, '-mu', mu, '-kt', kt])"


@dataclass
class Footing:
    """``footing``: a rigid footing under ``node`` on a soil medium (``Frame2D.foundation``)."""

    node: int
    width: float
    length: float
    soil: dict
    patches: int = 3
    gap: float = 0.0
    horizontal: str = "support"
    mu: float = None

    def add(self, fr, name):
        """Add the footing to the frame ``fr``."""
        fr.foundation(name, self.node, width=self.width, length=self.length, soil=self.soil, patches=self.patches,
                      gap=self.gap, horizontal=self.horizontal, mu=self.mu)


@dataclass
class SpringFooting:
    """``springFooting``: a rigid footing under ``node`` on tensionless springs (``Frame2D.spring_footing``)."""

    node: int
    width: float
    k: float
    length: float = 1.0
    c: float = 0.0
    springs: int = 8
    q_ult: float = None
    gap: float = 0.0

    def add(self, fr, name):
        """Add the footing (its nodes ``name.<j>`` and springs) to the frame ``fr``."""
        fr.spring_footing(name, self.node, width=self.width, k=self.k, length=self.length, c=self.c,
                          springs=self.springs, q_ult=self.q_ult, gap=self.gap)


@dataclass
class KelvinContact:
    """``kelvinContact``: a spring ``k`` and a dashpot ``c`` in parallel between ``i`` and ``j`` along the
    DOF ``direction`` (1..ndf), acting only in contact (``Frame2D.gap``)."""

    i: int
    j: int
    direction: int
    k: float
    c: float = 0.0
    gap: float = 0.0
    mu: float = None
    kt: float = None
    dofs: dict = field(default_factory=dict)

    def add(self, fr, name):
        """Add the contact to the frame ``fr``."""
        fr.gap(name, self.i, self.j, self.k, gap=self.gap, c=self.c, direction=self.dofs[self.direction],
               mu=self.mu, kt=self.kt)


@dataclass
class RigidContact:
    """``rigidContact``: a rigid contact of ``node`` with the fixed ground along the translation
    ``direction`` (1..ndm), opening ``gap``, Coulomb's ``mu`` and Newton's ``restitution``
    (``Frame2D.contact``)."""

    node: int
    direction: int
    gap: float = 0.0
    mu: float = None
    restitution: float = 0.0
    dofs: dict = field(default_factory=dict)

    def add(self, fr, name):
        """Add the contact to the frame ``fr``."""
        fr.contact(name, self.node, direction=self.dofs[self.direction], gap=self.gap, mu=self.mu,
                   restitution=self.restitution)


def add_to_frame(fr, domain) -> None:
    """Add the extension elements of ``domain`` to the frame ``fr`` (named ``x<tag>``)."""
    for tag, element in getattr(domain, "extensions", {}).items():
        element.add(fr, f"x{tag}")


# ---------------------------------------------------------------------- parsing
_BOUNDS = {">0": "> 0", ">=0": ">= 0"}


def _number(what, name, value, bound=None):
    """``value`` as a float, checked against ``bound`` (``">0"``, ``">=0"``)."""
    if isinstance(value, (bool, str)) or value is None:
        refuse(what, f"{name}={value!r} is not a number", f"a number for {name}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        refuse(what, f"{name}={value!r} is not a number", f"a number for {name}")
    if not np.isfinite(x) or (bound == ">0" and not x > 0) or (bound == ">=0" and not x >= 0):
        refuse(what, f"{name}={value!r} is not valid", f"a finite number {_BOUNDS[bound]} for {name}"
               if bound else f"a finite number for {name}")
    return x


def _options(what, rest, valid, usage):
    """``{flag: [values]}`` of the ``'-flag', values...`` in ``rest``; an unknown flag refused."""
    out = {}
    rest = list(rest)
    while rest:
        flag = rest.pop(0)
        if not isinstance(flag, str) or flag not in valid:
            refuse(f"{what} {flag!r}", f"the option is not valid; valid: {', '.join(map(repr, valid))}", usage)
        values = []
        while rest and not (isinstance(rest[0], str) and rest[0].startswith("-")):
            values.append(rest.pop(0))
        out.setdefault(flag, []).append(values)
    return out


def _one(what, opts, flag, name, bound=None, default=None):
    """The single number of ``flag`` (its last use), or ``default``."""
    if flag not in opts:
        return default
    values = opts[flag][-1]
    if len(values) != 1:
        refuse(f"{what} {flag!r}", f"{name} takes one value, got {values!r}", f"{flag!r}, {name}")
    return _number(what, name, values[0], bound)


def _node(what, domain, name, value):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float)) or int(value) != value:
        refuse(what, f"{name}={value!r} is not an integer tag", "the tag of a defined node")
    if int(value) not in domain.nodes:
        refuse(what, f"{name}={int(value)}: node {int(value)} is not defined", "define the node first")
    return int(value)


def parse_footing(domain, what, args) -> Footing:
    """The :class:`Footing` of ``footing(tag, *args)``."""
    if domain.ndm != 2:
        refuse(what, "a footing on a soil medium is a 2-D extension here (Frame3D.foundation is not mapped yet)",
               "model('basic', '-ndm', 2, '-ndf', 3), or Frame3D.foundation in Python")
    if len(args) < 4:
        refuse(what, "node, width, length and the soil are needed", _FOOTING)
    node = _node(what, domain, "node", args[0])
    width, length = _number(what, "width", args[1], ">0"), _number(what, "length", args[2], ">0")
    kind = args[3]
    if kind not in _SOILS:
        refuse(what, f"the soil {kind!r} is not valid; valid: {', '.join(map(repr, _SOILS))}", _FOOTING)
    names = _SOILS[kind]
    params = list(args[4:4 + len(names)])
    if len(params) != len(names) or any(isinstance(p, str) for p in params):
        refuse(what, f"the soil {kind!r} takes {', '.join(names)}, got {params!r}",
               f"footing(tag, node, width, length, {kind!r}, {', '.join(names)}, ...)")
    valid = ("-patches", "-gap", "-damping", "-horizontal", "-mu", "-layer")
    opts = _options(what, args[4 + len(names):], valid, _FOOTING)
    spec = _soil_spec(what, kind, names, params, opts)
    patches = _one(what, opts, "-patches", "n", ">0", 3)
    if int(patches) != patches or not 1 <= patches <= 400:
        refuse(f"{what} '-patches'", f"n={patches!r} is not an integer in 1..400", "'-patches', 4")
    mu = _one(what, opts, "-mu", "mu", ">=0")
    horizontal = "soil" if mu is not None else "support"
    if "-horizontal" in opts:
        values = opts["-horizontal"][-1]
        if len(values) != 1 or values[0] not in ("support", "cone", "none"):
            refuse(f"{what} '-horizontal'", f"{values!r} is not valid; valid: 'support', 'cone', 'none' (a "
                   "footing that slides on the soil takes '-mu', mu instead)", "'-horizontal', 'support'")
        if mu is not None:
            refuse(what, "'-mu' makes the footing slide on the soil; '-horizontal' restrains it otherwise",
                   "one of '-mu', mu or '-horizontal', kind")
        horizontal = values[0]
    return Footing(node, width, length, spec, int(patches), _one(what, opts, "-gap", "g", None, 0.0), horizontal, mu)


def _soil_spec(what, kind, names, params, opts) -> dict:
    """The soil of a footing as a dict of :class:`~unilateral.structure.foundation.SoilSpec`."""
    values = {name: _number(what, name, p, ">=0" if name in ("c", "nu") else ">0") for name, p in zip(names, params)}
    damping = _one(what, opts, "-damping", "D", ">=0", 0.0)
    if kind == "winkler":
        if "-damping" in opts or "-layer" in opts:
            refuse(what, "a Winkler-Kelvin soil has its dashpot c, no material damping or layers", _FOOTING)
        return {"model": "winkler-kelvin", "k": values["k"], "c": values["c"]}
    spec = {"model": kind, **values, "damping": damping}
    if kind == "cones" and damping:
        refuse(f"{what} '-damping'", f"D={damping!r}: Wolf's cones have no material damping", "'-damping', 0")
    layers = opts.get("-layer", [])
    if kind != "layered" and layers:
        refuse(f"{what} '-layer'", "layers belong to the soil 'layered'", "footing(..., 'layered', Vs, nu, rho, "
               "'-layer', h, Vs, nu, rho)")
    if kind == "layered":
        if not layers:
            refuse(what, "a layered soil needs at least one '-layer', h, Vs, nu, rho (from the surface down)",
                   _FOOTING)
        spec["layers"] = []
        for values in layers:
            if len(values) != 4:
                refuse(f"{what} '-layer'", f"a layer takes h, Vs, nu, rho, got {values!r}", "'-layer', h, Vs, nu, rho")
            h, vs, nu, rho = (_number(what, n, v, ">=0" if n == "nu" else ">0")
                              for n, v in zip(("h", "Vs", "nu", "rho"), values))
            spec["layers"].append({"thickness": h, "Vs": vs, "nu": nu, "rho": rho, "damping": damping})
    return spec


def parse_spring_footing(domain, what, args) -> SpringFooting:
    """The :class:`SpringFooting` of ``springFooting(tag, *args)``."""
    if domain.ndm != 2:
        refuse(what, "a footing on springs is a 2-D extension here", "model('basic', '-ndm', 2, '-ndf', 3)")
    if len(args) < 3:
        refuse(what, "node, width and k are needed", _SPRING)
    node = _node(what, domain, "node", args[0])
    width, k = _number(what, "width", args[1], ">0"), _number(what, "k", args[2], ">0")
    opts = _options(what, args[3:], ("-length", "-c", "-springs", "-qult", "-gap"), _SPRING)
    springs = _one(what, opts, "-springs", "n", ">0", 8)
    if int(springs) != springs:
        refuse(f"{what} '-springs'", f"n={springs!r} is not an integer", "'-springs', 8")
    return SpringFooting(node, width, k, _one(what, opts, "-length", "L", ">0", 1.0), _one(what, opts, "-c", "c", ">=0", 0.0),
                         int(springs), _one(what, opts, "-qult", "q", ">0"), _one(what, opts, "-gap", "g", None, 0.0))


def parse_kelvin(domain, what, args) -> KelvinContact:
    """The :class:`KelvinContact` of ``kelvinContact(tag, *args)``."""
    if len(args) < 2:
        refuse(what, "the nodes are missing", _KELVIN)
    i, j = _node(what, domain, "iNode", args[0]), _node(what, domain, "jNode", args[1])
    if i == j:
        refuse(what, f"iNode = jNode = {i}", "two different nodes (the contact's two sides)")
    opts = _options(what, args[2:], ("-dir", "-k", "-c", "-gap", "-mu", "-kt"), _KELVIN)
    dofs = DIRECTIONS[domain.ndf]
    direction = _one(what, opts, "-dir", "d")
    translations = range(1, domain.ndm + 1)
    if direction is None or direction not in translations:
        refuse(f"{what} '-dir'", f"d={direction!r} is not a translation 1..{domain.ndm}", "'-dir', 1")
    k = _one(what, opts, "-k", "k", ">0")
    if k is None:
        refuse(what, "the stiffness '-k' is missing", _KELVIN)
    mu, kt = _one(what, opts, "-mu", "mu", ">=0"), _one(what, opts, "-kt", "kt", ">0")
    if (mu is None) != (kt is None):
        refuse(what, f"friction needs both '-mu' and '-kt' (got mu={mu!r}, kt={kt!r})", "'-mu', mu, '-kt', kt")
    if mu is not None and domain.ndm == 3:
        refuse(f"{what} '-mu'", "friction of a 3-D Kelvin contact (a polygonal cone) is not mapped here",
               "a 2-D model, or Frame3D.gap(..., mu=, kt=) in Python")
    return KelvinContact(i, j, int(direction), k, _one(what, opts, "-c", "c", ">=0", 0.0),
                         _one(what, opts, "-gap", "g", ">=0", 0.0), mu, kt, dofs)


def parse_rigid(domain, what, args) -> RigidContact:
    """The :class:`RigidContact` of ``rigidContact(tag, *args)``."""
    if domain.ndm != 2:
        refuse(what, "a rigid contact is a 2-D extension here", "model('basic', '-ndm', 2, '-ndf', 3), or "
               "Frame3D.contact in Python")
    if not args:
        refuse(what, "the node is missing", _RIGID)
    node = _node(what, domain, "node", args[0])
    opts = _options(what, args[1:], ("-dir", "-gap", "-mu", "-e"), _RIGID)
    direction = _one(what, opts, "-dir", "d")
    if direction is None or direction not in (1, 2):
        refuse(f"{what} '-dir'", f"d={direction!r} is not a translation 1..2", "'-dir', 2")
    e = _one(what, opts, "-e", "e", ">=0", 0.0)
    if e > 1:
        refuse(f"{what} '-e'", f"e={e!r} is not in [0, 1] (Newton's coefficient of restitution)", "'-e', 0.5")
    return RigidContact(node, int(direction), _one(what, opts, "-gap", "g", ">=0", 0.0), _one(what, opts, "-mu", "mu", ">=0"),
                        e, DIRECTIONS[domain.ndf])


#: The parser of each element command.
PARSERS = {"footing": parse_footing, "springFooting": parse_spring_footing, "kelvinContact": parse_kelvin,
           "rigidContact": parse_rigid}


