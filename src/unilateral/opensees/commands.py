"""The session behind :mod:`unilateral.opensees`: one :class:`~.domain.Domain` and one
:class:`~.analysis.Analysis`, and the commands of OpenSeesPy as its methods."""

from __future__ import annotations

from .domain import Domain
from .extensions import extended
from .queries import element_force, element_response, nodal, nodal_reactions
from .recorders import parse_recorder
from .refusals import NOT_NEEDED, refuse
from .soil_analysis import ExtendedAnalysis as Analysis

__all__ = ["Session"]

_DOMAIN_COMMANDS = ("model", "node", "fix", "mass", "equalDOF", "rigidLink", "rigidDiaphragm",
                    "geomTransf", "uniaxialMaterial", "element",
                    "timeSeries", "pattern", "load", "eleLoad", "rayleigh", "loadConst", "setTime", "getTime")
_SESSION_COMMANDS = ("wipe", "integrator", "analyze", "wipeAnalysis", "nodeDisp", "nodeVel", "nodeAccel",
                     "nodeCoord", "getNodeTags", "getEleTags", "eleForce", "eleResponse", "reactions",
                     "nodeReaction", "recorder", "record", "remove")


@extended
class Session:
    """The state of one OpenSees interpreter: the model and its analysis."""

    def __init__(self):
        self.domain = Domain()
        self.analysis = Analysis(self.domain)
        self.reactions_ = {}
        self.settings = {}
        self.recorders = {}
        self.analysis.on_commit = self._record

    # ------------------------------------------------------------------ the command table
    def commands(self) -> dict:
        """``{OpenSees command name: callable}`` of this session (the module's and Tcl's commands)."""
        table = {name: getattr(self.domain, name) for name in _DOMAIN_COMMANDS}
        table.update({name: getattr(self, name) for name in _SESSION_COMMANDS})
        table.update({name: self.accepted(name) for name in NOT_NEEDED})
        table["analysis"] = self.analysis_
        return table

    # ------------------------------------------------------------------ whole session
    def wipe(self):
        """``wipe()``: remove the model, the loads, the state and the analysis."""
        self.remove("recorders")
        self.domain.__init__()
        self.analysis.wipe()
        self.reactions_ = {}
        self.settings = {}

    # ------------------------------------------------------------------ recorders
    def recorder(self, kind, *args):
        """``recorder('Node' | 'Element', '-file', name, ...)``: its tag (see :mod:`.recorders`)."""
        tag = max(self.recorders, default=-1) + 1
        self.recorders[tag] = parse_recorder(kind, args, self.domain)
        return tag

    def _record(self, t):
        for rec in self.recorders.values():
            rec.commit(self, t)

    def _flush(self):
        for rec in self.recorders.values():
            rec.flush()

    def record(self):
        """``record()``: every recorder records the current state."""
        self._record(self.domain.time)
        self._flush()

    def remove(self, what, *args):
        """``remove('recorders')``, ``remove('recorder', tag)``, ``remove('loadPattern', tag)``."""
        if what == "recorders":
            for rec in self.recorders.values():
                rec.close()
            self.recorders = {}
        elif what == "recorder" and args and int(args[0]) in self.recorders:
            self.recorders.pop(int(args[0])).close()
        elif what in ("loadPattern", "pattern") and args and int(args[0]) in self.domain.patterns:
            self.domain.patterns.pop(int(args[0]))
            self.domain.load_version += 1
        else:
            refuse(f"remove({what!r}, {', '.join(map(repr, args))})", "only recorders and defined load patterns "
                   "can be removed here", "remove('recorders'), remove('recorder', tag), remove('loadPattern', tag)")

    def wipeAnalysis(self):
        """``wipeAnalysis()``: remove the analysis settings; the model and its state stay."""
        self.analysis.wipe_analysis()

    # ------------------------------------------------------------------ accepted, not needed
    def accepted(self, command):
        """A command accepted without effect (see :data:`~.refusals.NOT_NEEDED`)."""
        def run(*args, **kwargs):
            """Record the arguments; 0."""
            self.settings[command] = args
            return 0
        run.__name__ = command
        run.__doc__ = f"``{command}(...)``: accepted, no effect: {NOT_NEEDED[command]}."
        return run

    # ------------------------------------------------------------------ analysis
    def integrator(self, kind, *args):
        """``integrator('Newmark', gamma, beta)`` or ``integrator('LoadControl', dLambda)``."""
        self.analysis.set_integrator(kind, *args)

    def analysis_(self, kind, *args):
        """``analysis('Static' | 'Transient')``."""
        self.analysis.set_analysis(kind, *args)

    def analyze(self, numIncr=1, dt=None, *args):
        """``analyze(numIncr, dt)``: 0 on success, negative on failure."""
        if args:
            refuse(f"analyze{(numIncr, dt) + args}", "variable time steps are not in the subset",
                   "analyze(numIncr, dt)")
        try:
            return self.analysis.analyze(numIncr, dt)
        finally:
            self._flush()                                # the recorders write the steps of this analyze

    # ------------------------------------------------------------------ queries
    def nodeDisp(self, tag, dof=-1):
        """``nodeDisp(tag, dof)``: a displacement, or the node's three."""
        return nodal(self.analysis, "u", tag, dof)

    def nodeVel(self, tag, dof=-1):
        """``nodeVel(tag, dof)``."""
        return nodal(self.analysis, "ud", tag, dof)

    def nodeAccel(self, tag, dof=-1):
        """``nodeAccel(tag, dof)`` (relative to the ground under a UniformExcitation)."""
        return nodal(self.analysis, "udd", tag, dof)

    def nodeCoord(self, tag, dim=-1):
        """``nodeCoord(tag, dim)``."""
        x = list(self.domain.nodes[int(tag)])
        return x if dim in (None, -1) else x[int(dim) - 1]

    def getNodeTags(self):
        """``getNodeTags()``."""
        return list(self.domain.nodes)

    def getEleTags(self):
        """``getEleTags()``."""
        return list(self.domain.elements)

    def eleForce(self, tag, dof=-1):
        """``eleForce(tag, dof)``: global end forces (see :mod:`.queries`)."""
        return element_force(self.analysis, tag, dof)

    def eleResponse(self, tag, *args):
        """``eleResponse(tag, 'force' | 'deformation' | ...)``."""
        return element_response(self.analysis, tag, *args)

    def reactions(self, *args):
        """``reactions()``: compute the nodal reactions for ``nodeReaction``."""
        self.reactions_ = nodal_reactions(self.analysis, *args)
        return 0

    def nodeReaction(self, tag, dof=-1):
        """``nodeReaction(tag, dof)``: the reaction computed by the last ``reactions()``."""
        tag = int(tag)
        if tag not in self.reactions_:
            refuse(f"nodeReaction({tag})", "reactions() has not been called since the node was defined",
                   "call reactions() first")
        values = self.reactions_[tag]
        return [float(x) for x in values] if dof in (None, -1) else float(values[int(dof) - 1])
