"""Refusals: what :mod:`unilateral.opensees` does not represent, said at once and by name.

Every command, option, material or element outside the supported subset raises
:class:`OpenSeesRefused` when it is called, naming it, saying why the method of this library cannot
represent it and what comes nearest. Nothing outside the subset is approximated silently.
"""

from __future__ import annotations

__all__ = ["OpenSeesRefused", "refuse", "NOT_NEEDED"]


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
    raise OpenSeesRefused(what, why, instead)


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
    "Steel01": "a bilinear steel with isotropic hardening is not a piecewise-linear law with constant "
               "yield forces",
    "Steel02": "the Giuffre-Menegotto-Pinto law is smooth (curved), not piecewise linear",
    "Concrete01": "concrete softening and degrading unloading are not a convex piecewise-linear law",
    "Concrete02": "concrete softening and degrading unloading are not a convex piecewise-linear law",
    "Hysteretic": "pinching and damage degrade the stiffness along the history",
    "Bilin": "deteriorating (IMK) laws degrade along the history",
    "ModIMKPeakOriented": "deteriorating (IMK) laws degrade along the history",
}
