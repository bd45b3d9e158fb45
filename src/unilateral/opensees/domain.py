"""The model being built by an OpenSees script: nodes, fixities, masses, ties, transformations,
materials, elements, time series, patterns, Rayleigh factors and the domain time.

The commands only record and check; :mod:`.build` turns the record into a
:class:`~unilateral.Model` when an analysis needs it. :attr:`Domain.version` counts the changes of
the structure, :attr:`Domain.load_version` those of the loads, so that an analysis knows when to
rebuild.
"""

from __future__ import annotations

import numpy as np

from .composites import COMPOSITES, parse_composite
from .elements import parse_element
from .eleloads import parse_element_load
from .materials import parse_material
from .refusals import refuse
from .series import parse_pattern, parse_series

__all__ = ["Domain"]


def _tag(what, value):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float)) or int(value) != value:
        refuse(what, f"the tag {value!r} is not an integer", "an integer tag")
    return int(value)


class Domain:
    """The record of the model-building commands of one OpenSees session."""

    def __init__(self):
        self.ndm = self.ndf = None
        self.nodes, self.fixes, self.masses, self.ties, self.rigid = {}, {}, {}, [], []
        self.transforms, self.materials, self.elements = {}, {}, {}
        self.series, self.patterns, self.current = {}, {}, None
        self.damping = None
        self.extensions = {}                         # tag -> an extension element (.extensions)
        self.time = 0.0
        self.version = self.load_version = 0

    def _changed(self, loads=False):
        if loads:
            self.load_version += 1
        else:
            self.version += 1

    def _need_model(self, what):
        if self.ndm is None:
            refuse(what, "no model is defined", "model('basic', '-ndm', 2, '-ndf', 3) first")

    # ------------------------------------------------------------------ the structure
    def model(self, kind, *args):
        """``model('basic', '-ndm', 2, '-ndf', 3)``."""
        what = f"model({kind!r}, {', '.join(map(repr, args))})"
        if kind not in ("basic", "Basic", "BasicBuilder", "basicBuilder"):
            refuse(what, "only the basic model builder is in this slice", "model('basic', '-ndm', 2, '-ndf', 3)")
        opts = dict(zip(args[0::2], args[1::2]))
        ndm = int(opts.get("-ndm", 0))
        ndf = int(opts.get("-ndf", 3 if ndm == 2 else 6))
        if (ndm, ndf) not in ((2, 3), (3, 6)):
            refuse(what, "only frames with rotations are in the subset: plane (ux, uy, rz) or space (ux, uy, uz, "
                   "rx, ry, rz)", "model('basic', '-ndm', 2, '-ndf', 3) or model('basic', '-ndm', 3, '-ndf', 6)")
        self.ndm, self.ndf = ndm, ndf
        self._changed()

    def node(self, tag, *args):
        """``node(tag, x, y, '-mass', mx, my, mz)``."""
        what = f"node({tag!r})"
        self._need_model(what)
        tag = _tag(what, tag)
        if tag in self.nodes:
            refuse(what, f"node {tag} is already defined", "a new tag")
        nd, nf = self.ndm, self.ndf
        coords = [a for a in args[:nd]]
        if len(coords) != nd or any(isinstance(c, str) for c in coords):
            refuse(what, f"a node of a {nd}-D model needs {nd} coordinates", f"node(tag, {', '.join('xyz'[:nd])})")
        rest = list(args[nd:])
        self.nodes[tag] = tuple(float(c) for c in coords)
        if rest:
            if rest[0] != "-mass" or len(rest) != 1 + nf:
                refuse(f"{what} {rest[0]!r}", "the option is not in the subset",
                       f"node(tag, {', '.join('xyz'[:nd])}, '-mass', {nf} masses)")
            self.mass(tag, *rest[1:])
        self._changed()

    def fix(self, tag, *flags):
        """``fix(tag, fx, fy, frz)`` (1: fixed)."""
        what = f"fix({tag!r})"
        tag = _tag(what, tag)
        if tag not in self.nodes:
            refuse(what, f"node {tag} is not defined", "define the node first")
        self._need_model(what)
        if len(flags) != self.ndf or any(f not in (0, 1) for f in flags):
            refuse(what, f"the flags {flags!r} must be {self.ndf} 0 or 1", f"fix(tag, {', '.join(['1'] * self.ndf)})")
        old = self.fixes.get(tag, (0,) * self.ndf)
        self.fixes[tag] = tuple(int(a or b) for a, b in zip(old, flags))
        self._changed()

    def mass(self, tag, *values):
        """``mass(tag, mx, my, mz)``: lumped nodal masses (replace the node's masses, as OpenSees)."""
        what = f"mass({tag!r})"
        tag = _tag(what, tag)
        if tag not in self.nodes:
            refuse(what, f"node {tag} is not defined", "define the node first")
        self._need_model(what)
        if len(values) != self.ndf:
            refuse(what, f"{len(values)} values; a node has {self.ndf} DOFs", f"mass(tag, {self.ndf} values)")
        values = tuple(float(v) for v in values)
        if min(values) < 0:
            refuse(what, f"negative mass {values}", "masses >= 0")
        self.masses[tag] = values
        self._changed()

    def equalDOF(self, master, slave, *dofs):
        """``equalDOF(rNode, cNode, *dofs)``: the DOFs ``dofs`` of ``slave`` equal those of ``master``."""
        what = f"equalDOF({master!r}, {slave!r})"
        master, slave = _tag(what, master), _tag(what, slave)
        for node in (master, slave):
            if node not in self.nodes:
                refuse(what, f"node {node} is not defined", "define the nodes first")
        if master == slave or not dofs or any(d not in range(1, self.ndf + 1) for d in dofs):
            refuse(what, f"the DOFs {dofs!r} must be among 1..{self.ndf} of two different nodes", "equalDOF(r, c, 1, 2)")
        self.ties.append((master, slave, tuple(int(d) for d in dofs)))
        self._changed()

    def rigidLink(self, kind, master, slave):
        """``rigidLink('beam' | 'bar', rNode, cNode)``: ``beam`` moves ``cNode`` with ``rNode`` as a rigid
        body (all DOFs); ``bar`` makes their translations equal (an equalDOF of the translations)."""
        what = f"rigidLink({kind!r}, {master!r}, {slave!r})"
        self._need_model(what)
        master, slave = _tag(what, master), _tag(what, slave)
        for node in (master, slave):
            if node not in self.nodes:
                refuse(what, f"node {node} is not defined", "define the nodes first")
        if kind == "bar":
            self.equalDOF(master, slave, *range(1, self.ndm + 1))
            return
        if kind != "beam":
            refuse(what, f"the kind {kind!r} is not 'beam' or 'bar'", "rigidLink('beam', r, c)")
        self.rigid.append(("link", master, (slave,)))
        self._changed()

    def rigidDiaphragm(self, perp, master, *slaves):
        """``rigidDiaphragm(3, rNode, *cNodes)``: a rigid floor in the plane z = z of ``rNode``."""
        what = f"rigidDiaphragm({perp!r}, {master!r}, ...)"
        self._need_model(what)
        if self.ndm != 3 or perp != 3:
            refuse(what, "only floors perpendicular to z (perpDirn 3) of a 3-D model are in the subset",
                   "rigidDiaphragm(3, ...) in model('basic', '-ndm', 3, '-ndf', 6); equalDOF in 2-D")
        tags = [_tag(what, t) for t in (master, *slaves)]
        for node in tags:
            if node not in self.nodes:
                refuse(what, f"node {node} is not defined", "define the nodes first")
        self.rigid.append(("diaphragm", tags[0], tuple(tags[1:])))
        self._changed()

    def geomTransf(self, kind, tag, *args):
        """``geomTransf('Linear', tag)`` (3-D: ``tag, vecxz_x, vecxz_y, vecxz_z``), ``geomTransf('PDelta',
        tag)`` (the same arguments; the string stiffness of the axial forces, :mod:`.pdelta`);
        ``Corotational`` is refused."""
        what = f"geomTransf({kind!r}, {tag!r})"
        self._need_model(what)
        if kind == "Corotational":
            refuse(what, "large rotations (corotational kinematics) make the structure geometrically nonlinear; "
                   "the method needs a linear structure", "geomTransf('Linear', tag)")
        if kind not in ("Linear", "PDelta"):
            refuse(what, "only the Linear and PDelta transformations are in this slice",
                   "geomTransf('Linear', tag)")
        vecxz = None
        if self.ndm == 3:
            if len(args) < 3 or any(isinstance(a, str) for a in args[:3]):
                refuse(what, "a 3-D transformation needs its vecxz", "geomTransf('Linear', tag, vx, vy, vz)")
            vecxz, args = tuple(float(a) for a in args[:3]), args[3:]
        if args:
            refuse(f"{what} {args[0]!r}", "joint offsets (rigid end zones) are not in the subset",
                   "geomTransf('Linear', tag) and a rigidLink('beam', ...) for an offset")
        self.transforms[_tag(what, tag)] = (kind, vecxz)

    def uniaxialMaterial(self, kind, tag, *args):
        """``uniaxialMaterial(kind, tag, ...)``: Elastic, ENT, ElasticPP, ElasticPPGap."""
        what = f"uniaxialMaterial({kind!r}, {tag!r})"
        tag = _tag(what, tag)
        if kind in COMPOSITES:
            self.materials[tag] = parse_composite(kind, args, self.materials)
        else:
            self.materials[tag] = parse_material(kind, args)

    def element(self, kind, tag, *args):
        """``element(kind, tag, ...)``: elasticBeamColumn, zeroLength."""
        what = f"element({kind!r}, {tag!r})"
        self._need_model(what)
        tag = _tag(what, tag)
        if tag in self.elements:
            refuse(what, f"element {tag} is already defined", "a new tag")
        self.elements[tag] = parse_element(kind, args, self)
        self._changed()

    # ------------------------------------------------------------------ loads
    def timeSeries(self, kind, tag, *args):
        """``timeSeries('Constant'|'Linear'|'Path', tag, ...)``."""
        what = f"timeSeries({kind!r}, {tag!r})"
        self.series[_tag(what, tag)] = parse_series(kind, args)
        self._changed(loads=True)

    def pattern(self, kind, tag, *args):
        """``pattern('Plain', tag, tsTag)`` or ``pattern('UniformExcitation', tag, dir, '-accel', tsTag)``."""
        what = f"pattern({kind!r}, {tag!r})"
        tag = _tag(what, tag)
        if tag in self.patterns:
            refuse(what, f"pattern {tag} is already defined", "a new tag")
        pattern = parse_pattern(kind, args, self.series)
        if pattern.direction is not None and pattern.direction > self.ndm:
            refuse(f"{what} direction {pattern.direction}", "a ground rotation is not a rigid ground translation",
                   f"a direction 1..{self.ndm}")
        self.patterns[tag] = pattern
        self.current = tag
        self._changed(loads=True)

    def load(self, tag, *values):
        """``load(node, Fx, Fy, Mz)`` in the last pattern defined (a Plain one)."""
        what = f"load({tag!r})"
        tag = _tag(what, tag)
        if self.current is None or self.patterns[self.current].kind != "Plain":
            refuse(what, "nodal loads belong to a Plain pattern", "pattern('Plain', tag, tsTag) before load()")
        if tag not in self.nodes:
            refuse(what, f"node {tag} is not defined", "define the node first")
        if len(values) != self.ndf or any(isinstance(v, str) for v in values):
            refuse(what, f"{values!r}: a node takes {self.ndf} values", f"load(node, {self.ndf} values)")
        self.patterns[self.current].loads.append((tag, np.array([float(v) for v in values])))
        self._changed(loads=True)

    def eleLoad(self, *args):
        """``eleLoad('-ele', *tags, '-type', '-beamUniform', Wy[, Wx])`` in the last pattern defined (a
        Plain one), on 2-D elasticBeamColumn elements (:mod:`.eleloads`)."""
        what = f"eleLoad({', '.join(map(repr, args))})"
        if self.current is None or self.patterns[self.current].kind != "Plain":
            refuse(what, "element loads belong to a Plain pattern", "pattern('Plain', tag, tsTag) before eleLoad()")
        if self.ndm != 2:
            refuse(what, "element loads of a 3-D model are not in this slice", "nodal loads")
        self.patterns[self.current].element_loads.extend(parse_element_load(self, args))
        self._changed(loads=True)

    def rayleigh(self, alphaM, betaK, betaKinit, betaKcomm):
        """``rayleigh(alphaM, betaK, betaKinit, betaKcomm)``: on the nodes and elements defined now."""
        factors = tuple(float(x) for x in (alphaM, betaK, betaKinit, betaKcomm))
        if min(factors) < 0:
            refuse(f"rayleigh{factors}", "negative damping factors", "factors >= 0")
        self.damping = (factors, frozenset(self.nodes), frozenset(self.elements))
        self._changed()

    def loadConst(self, *args):
        """``loadConst('-time', t)``: every pattern keeps its current factor; the time is set to ``t``."""
        for p in self.patterns.values():
            if p.frozen is None:
                p.frozen = float(p.factor * self.series[p.series](np.array([self.time]))[0])
        if args:
            if args[0] != "-time" or len(args) != 2:
                refuse(f"loadConst{args}", "the arguments are not in the subset", "loadConst('-time', 0.0)")
            self.time = float(args[1])
        self._changed(loads=True)

    def setTime(self, t):
        """``setTime(t)``: the domain time."""
        self.time = float(t)

    def getTime(self):
        """``getTime()``: the domain time."""
        return self.time
