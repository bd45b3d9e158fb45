"""Extensions: commands for what only this library has, in OpenSees's own style (tags, positional
numbers, ``'-flag'`` options).

==================================================  =============================================
``footing(tag, node, width, length, soil, ...)``    a rigid footing on a soil medium
                                                    (``Frame2D.foundation``): half-space, layered
                                                    soil, cones or Winkler-Kelvin patches; lifts
                                                    off, optionally slides with friction
``springFooting(tag, node, width, k, ...)``         a rigid footing on tensionless Winkler springs
                                                    that may yield (``Frame2D.spring_footing``)
``kelvinContact(tag, iNode, jNode, '-dir', d, ...)`` a spring and a dashpot acting only in contact
                                                    (``Frame2D.gap`` / ``Frame3D.gap`` with ``c``)
``rigidContact(tag, node, '-dir', d, ...)``          a rigid contact with the ground, Newton's
                                                    impact law (``Frame2D.contact``, Moreau-Jean)
``bilateral(flag)``                                 the bilateral reference: every unilateral
                                                    constraint held (``solve(..., bilateral=True)``)
==================================================  =============================================

The elements of the extensions are kept apart from the domain's OpenSees elements
(``Domain.extensions``); :mod:`.build` adds them to the frame (:func:`.extension_elements.add_to_frame`) and the session
answers ``eleForce``, ``eleResponse``, ``getEleTags`` and ``reactions`` for them
(:class:`ExtensionCommands`), and the ``Element`` recorders record them (:mod:`.recorders`). Their forces are the constraint reactions ``psi`` of the state the
analysis reached (the stepping's, or the static state's). Footings on a soil medium are analysed
by :mod:`.soil_analysis`.
"""

from __future__ import annotations

import numpy as np

from .extension_elements import PARSERS, KelvinContact
from .extension_results import end_forces, pick, response
from .refusals import refuse

__all__ = ["ExtensionCommands", "extended", "EXTENSION_COMMANDS"]

#: The extension commands (``docs/opensees.md``, section "Extensions").
EXTENSION_COMMANDS = ("footing", "springFooting", "kelvinContact", "rigidContact", "bilateral")


# ---------------------------------------------------------------------- the session's commands
class ExtensionCommands:
    """The extension commands and the queries of their elements, put into the session by :func:`extended`."""

    def _extension(self, command, tag, args):
        what = f"{command}({', '.join(map(repr, (tag, *args)))})"
        d = self.domain
        d._need_model(what)
        if isinstance(tag, bool) or not isinstance(tag, (int, np.integer, float)) or int(tag) != tag:
            refuse(what, f"the tag {tag!r} is not an integer", "an integer tag")
        tag = int(tag)
        if tag in d.elements or tag in d.extensions:
            refuse(what, f"element {tag} is already defined", "a new tag")
        d.extensions[tag] = PARSERS[command](d, what, args)
        d._changed()

    def footing(self, tag, *args):
        """``footing(tag, node, width, length, soil, *soilArgs, ...)``: a rigid footing on a soil medium."""
        self._extension("footing", tag, args)

    def springFooting(self, tag, *args):
        """``springFooting(tag, node, width, k, ...)``: a rigid footing on tensionless springs."""
        self._extension("springFooting", tag, args)

    def kelvinContact(self, tag, *args):
        """``kelvinContact(tag, iNode, jNode, '-dir', d, '-k', k, ...)``: a Kelvin contact."""
        self._extension("kelvinContact", tag, args)

    def rigidContact(self, tag, *args):
        """``rigidContact(tag, node, '-dir', d, ...)``: a rigid contact with the ground (Moreau-Jean)."""
        self._extension("rigidContact", tag, args)

    def bilateral(self, flag=True):
        """``bilateral(flag)``: the transient analyses hold every unilateral constraint at the state they
        start from (1), or not (0)."""
        if flag not in (0, 1, True, False):
            refuse(f"bilateral({flag!r})", f"flag={flag!r} is not 0 or 1", "bilateral(1) or bilateral(0)")
        self.analysis.bilateral = bool(flag)
        self.analysis.sim = None

    # ------------------------------------------------------------------ queries
    def getEleTags(self):
        """``getEleTags()``: the OpenSees elements, then those of the extensions."""
        return self._base_getEleTags() + list(self.domain.extensions)

    def eleForce(self, tag, dof=-1):
        """``eleForce(tag, dof)``; an extension's: see :func:`.extension_results.end_forces`."""
        if self.domain.extensions and _is_extension(self.domain, tag):
            return pick(end_forces(self.analysis, int(tag)), dof, f"eleForce({tag!r})")
        return self._base_eleForce(tag, dof)

    def eleResponse(self, tag, *args):
        """``eleResponse(tag, ...)``; an extension's: see :func:`.extension_results.response`."""
        if self.domain.extensions and _is_extension(self.domain, tag):
            return response(self.analysis, int(tag), *args)
        return self._base_eleResponse(tag, *args)

    def reactions(self, *args):
        """``reactions()``: the element forces of the extensions counted too."""
        code = self._base_reactions(*args)
        nf = self.domain.ndf
        for tag, element in self.domain.extensions.items():
            f = end_forces(self.analysis, tag)
            nodes = (element.i, element.j) if isinstance(element, KelvinContact) else (element.node,)
            f = f[:len(nodes) * nf]
            for k, node in enumerate(nodes):
                self.reactions_[node] = self.reactions_[node] + f[k * nf:(k + 1) * nf]
        return code

    def commands(self) -> dict:
        """The command table of the session with the extension commands."""
        table = self._base_commands()
        table.update({name: getattr(self, name) for name in EXTENSION_COMMANDS})
        return table


#: The session's methods the extensions extend (the original kept as ``_base_<name>``).
_EXTENDED = ("getEleTags", "eleForce", "eleResponse", "reactions", "commands")


def extended(cls):
    """The session class ``cls`` with the extension commands and the queries of their elements."""
    for name in _EXTENDED:
        setattr(cls, f"_base_{name}", getattr(cls, name))
        setattr(cls, name, getattr(ExtensionCommands, name))
    for name in (*EXTENSION_COMMANDS, "_extension"):
        setattr(cls, name, getattr(ExtensionCommands, name))
    return cls


def _is_extension(domain, tag) -> bool:
    try:
        return int(tag) in domain.extensions and int(tag) not in domain.elements
    except (TypeError, ValueError):
        return False
