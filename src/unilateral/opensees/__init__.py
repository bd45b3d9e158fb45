"""OpenSeesPy's commands on this library's model: ``import unilateral.opensees as ops``.

A 2-D OpenSeesPy script of the supported subset runs unchanged but for its import: the commands
record the model (:mod:`.domain`), ``analyze`` builds it (:mod:`.build`) and steps it with a
:class:`unilateral.Simulation` (:mod:`.analysis`), and the queries answer in OpenSees's layout
and signs (:mod:`.queries`). What is outside the subset raises :class:`OpenSeesRefused` at once
(:mod:`.refusals`). See ``docs/opensees.md``.
"""

from __future__ import annotations

from .commands import Session
from .refusals import NOT_NEEDED, OpenSeesRefused, refuse

_session = Session()
_domain = _session.domain

# model building
wipe = _session.wipe
model = _domain.model
node = _domain.node
fix = _domain.fix
mass = _domain.mass
equalDOF = _domain.equalDOF
geomTransf = _domain.geomTransf
uniaxialMaterial = _domain.uniaxialMaterial
element = _domain.element
timeSeries = _domain.timeSeries
pattern = _domain.pattern
load = _domain.load
rayleigh = _domain.rayleigh
loadConst = _domain.loadConst
setTime = _domain.setTime
getTime = _domain.getTime
# analysis
constraints = _session.accepted("constraints")
numberer = _session.accepted("numberer")
system = _session.accepted("system")
test = _session.accepted("test")
algorithm = _session.accepted("algorithm")
integrator = _session.integrator
analysis = _session.analysis_
analyze = _session.analyze
wipeAnalysis = _session.wipeAnalysis
# queries
nodeDisp = _session.nodeDisp
nodeVel = _session.nodeVel
nodeAccel = _session.nodeAccel
nodeCoord = _session.nodeCoord
getNodeTags = _session.getNodeTags
getEleTags = _session.getEleTags
eleForce = _session.eleForce
eleResponse = _session.eleResponse
reactions = _session.reactions
nodeReaction = _session.nodeReaction

__all__ = ["OpenSeesRefused", "wipe", "model", "node", "fix", "mass", "equalDOF", "geomTransf",
           "uniaxialMaterial", "element", "timeSeries", "pattern", "load", "rayleigh", "loadConst", "setTime",
           "getTime", "constraints", "numberer", "system", "test", "algorithm", "integrator", "analysis",
           "analyze", "wipeAnalysis", "nodeDisp", "nodeVel", "nodeAccel", "nodeCoord", "getNodeTags",
           "getEleTags", "eleForce", "eleResponse", "reactions", "nodeReaction"]

#: OpenSeesPy commands outside the subset, with why and what instead.
_REFUSED_COMMANDS = {
    "section": ("fibre and other sections integrate nonlinear stress-strain laws", "elasticBeamColumn with "
                "zeroLength ElasticPP hinges"),
    "fiber": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "patch": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "layer": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "beamIntegration": ("force- and displacement-based fibre elements are not in the subset",
                        "elasticBeamColumn"),
    "recorder": ("recorders (files written during the analysis) are not in this slice",
                 "read nodeDisp, eleForce ... after each analyze(1, dt)"),
    "eigen": ("eigenvalue analysis is not in this slice", "unilateral.structure.modes on the built model"),
    "sp": ("imposed displacements are not in this slice", "a load, or a stiff support spring in the model"),
    "eleLoad": ("element loads are not in this slice", "equivalent nodal loads (load(node, ...))"),
    "rigidLink": ("rigid links are not in this slice of the OpenSees layer", "equalDOF, or "
                  "unilateral.structure.Frame2D.rigid_link directly"),
    "rigidDiaphragm": ("rigid diaphragms are 3-D and not in this slice", "equalDOF in the floor's direction"),
    "imposedMotion": ("multi-support excitation is not in this slice", "pattern('UniformExcitation', ...)"),
    "groundMotion": ("multi-support excitation is not in this slice", "pattern('UniformExcitation', ...)"),
    "nDMaterial": ("multi-dimensional materials are not in this slice", "uniaxial ENT, ElasticPP, ElasticPPGap"),
    "region": ("regions (for damping by region) are not in this slice", "rayleigh() for the whole model"),
    "modalDamping": ("modal damping is not in this slice of the OpenSees layer", "rayleigh(), or "
                     "unilateral.structure.Frame2D.modal_damping directly"),
    "printModel": ("printing the OpenSees domain is not in this slice", "getNodeTags, getEleTags, nodeCoord"),
}


def __getattr__(name):
    """Every other OpenSeesPy command: a function that refuses it when called."""
    if name.startswith("__"):
        raise AttributeError(name)
    why, instead = _REFUSED_COMMANDS.get(name, ("the command is not in the supported subset of this slice",
                                                "see docs/opensees.md for the supported commands"))

    def refused(*args, **kwargs):
        """Refuse the command (:class:`OpenSeesRefused`)."""
        refuse(f"{name}()", why, instead)

    refused.__name__ = name
    return refused
