"""Refusals: what :mod:`unilateral.opensees` does not represent, said at once and by name.

Every command, option, material or element outside the supported subset raises
:class:`OpenSeesRefused` when it is called, naming it, saying why the method of this library cannot
represent it and what comes nearest. Nothing outside the subset is approximated silently.
"""

from __future__ import annotations

__all__ = ["OpenSeesRefused", "refuse", "refused_command", "NOT_NEEDED", "REFUSED_COMMANDS"]


class OpenSeesRefused(ValueError):
    """An OpenSees command, option, material or element this library does not represent.

    Attributes
    ----------
    what : str
        The command or option refused (``"uniaxialMaterial('Steel02')"``).
    why : str
        Why the method cannot represent it.
    instead : str
        The nearest representable alternative.
    """

    def __init__(self, what, why, instead):
        self.what, self.why, self.instead = what, why, instead
        super().__init__(f"unilateral.opensees refuses {what}: {why}. Nearest alternative: {instead}")


def refuse(what, why, instead):
    """Raise :class:`OpenSeesRefused` for ``what`` with the reason ``why`` and the alternative ``instead``."""
    raise OpenSeesRefused(str(what), why, instead)


#: The commands accepted without effect, and why they are not needed.
NOT_NEEDED = {
    "constraints": "equalDOF and fix are eliminated exactly by a transformation of the DOFs",
    "numberer": "the DOFs are numbered by the model builder",
    "system": "the linear systems are solved by the library's own factorisations",
    "test": "each step solves the piecewise-linear problem exactly by one LCP: no iterations to test",
    "algorithm": "each step solves the piecewise-linear problem exactly by one LCP: no Newton iterations",
}

#: The elements, materials and commands refused by name: (why, instead).
REFUSED_MATERIALS = {
    "Series": "materials in series share one force: a composition of contacts and yield laws in series needs "
              "an internal deformation, not in the subset (use two zeroLength elements through a node between)",
    "Steel02": "the Giuffre-Menegotto-Pinto law is smooth (curved), not piecewise linear",
    "Concrete01": "concrete softening and degrading unloading are not a convex piecewise-linear law",
    "Concrete02": "concrete softening and degrading unloading are not a convex piecewise-linear law",
    "Hysteretic": "pinching and damage degrade the stiffness along the history",
    "Bilin": "deteriorating (IMK) laws degrade along the history",
    "ModIMKPeakOriented": "deteriorating (IMK) laws degrade along the history",
}


#: OpenSeesPy commands outside the subset, with why and what instead.
REFUSED_COMMANDS = {
    "section": ("fibre and other sections integrate nonlinear stress-strain laws", "elasticBeamColumn with "
                "zeroLength ElasticPP hinges"),
    "fiber": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "patch": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "layer": ("fibre sections integrate nonlinear stress-strain laws", "zeroLength ElasticPP hinges"),
    "beamIntegration": ("force- and displacement-based fibre elements are not in the subset",
                        "elasticBeamColumn"),
    "eigen": ("eigenvalue analysis is not in this slice", "unilateral.structure.modes on the built model"),
    "sp": ("imposed displacements are not in this slice", "a load, or a stiff support spring in the model"),
    "imposedMotion": ("multi-support excitation is not in this slice", "pattern('UniformExcitation', ...)"),
    "groundMotion": ("multi-support excitation is not in this slice", "pattern('UniformExcitation', ...)"),
    "nDMaterial": ("multi-dimensional materials are not in this slice", "uniaxial ENT, ElasticPP, ElasticPPGap"),
    "region": ("regions (for damping by region) are not in this slice", "rayleigh() for the whole model"),
    "modalDamping": ("modal damping is not in this slice of the OpenSees layer", "rayleigh(), or "
                     "unilateral.structure.Frame2D.modal_damping directly"),
    "printModel": ("printing the OpenSees domain is not in this slice", "getNodeTags, getEleTags, nodeCoord"),
}



def refused_command(name):
    """A function that refuses the OpenSees command ``name`` when called (:class:`OpenSeesRefused`)."""
    why, instead = REFUSED_COMMANDS.get(name, ("the command is not in the supported subset",
                                               "see docs/opensees.md for the supported commands"))

    def refused(*args, **kwargs):
        """Refuse the command (:class:`OpenSeesRefused`)."""
        refuse(f"{name}()", why, instead)

    refused.__name__ = name
    return refused
