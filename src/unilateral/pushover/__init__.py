"""Static pushover by path-following of the parametric LCP (Maier's incremental analysis).

:func:`pushover` puts a structure (a :class:`~unilateral.structure.Frame2D`, its
:class:`~unilateral.structure.Structure` or a :class:`unilateral.Model`) under gravity, then under
``lambda`` times a lateral pattern, and follows the static path ``K u = q_g + lambda p + F v``,
``psi = F^T u - H v - g`` with the model's constraint laws (contacts, plastic hinges and links,
friction) from event to event, each event exactly: the path of perfectly plastic or linearly
hardening laws and contacts is piecewise linear in ``lambda``. Under displacement control the load
factor is free and the control DOF prescribed (plateaus, softening with P-Delta); under load
control the path stops at a mechanism. Plane (``Frame2D``) and space (``Frame3D``) frames.

Modules: :mod:`~unilateral.pushover.problem` (the parametric LCP condensed on ``v``),
:mod:`~unilateral.pushover.rates` (the rate problem at an event), :mod:`~unilateral.pushover.path`
(event to event), :mod:`~unilateral.pushover.patterns` (load patterns),
:mod:`~unilateral.pushover.control` (the control DOF), :mod:`~unilateral.pushover.result`
(:class:`PushoverResult`, :class:`Event`), :mod:`~unilateral.pushover.api` (:func:`pushover`),
:mod:`~unilateral.pushover.geometry` (P-Delta: the consistent or string geometric stiffness of the
gravity's axial forces), :mod:`~unilateral.pushover.files` (a pushover from a model file,
``[analysis] type = "pushover"``, and its outputs). A ``target`` may be a list: a cyclic history.
See ``docs/pushover.md``.
"""

from .api import CONTROLS, pushover
from .patterns import PATTERNS, first_mode, load_pattern
from .result import Event, PushoverResult

__all__ = ["CONTROLS", "PATTERNS", "Event", "PushoverResult", "first_mode", "load_pattern", "pushover"]
