"""Constraint families and their laws: contact, yield and friction in one convolutional LCP.

A :class:`~unilateral.model.Model` is a linear structure plus constraint families
(``Model(..., families=[...])``): :class:`Contact` (the paper's unilateral contact),
:class:`Yield` (plastic multipliers; :class:`Bearing`: the one-sided settlement of a soil spring's
bearing capacity), :class:`Friction` (Coulomb slips), :class:`RigidContact`
(contacts without compliance, ``H = 0``, in the force form) and :class:`SoilContact` (footings
on a soil given in the Laplace domain, :class:`~unilateral.soil.FoundationModel`, with
:class:`SoilShear` and :class:`SoilFriction` for footings that slide). The
methods see only the :class:`StepLaw` assembled from them (``model.law``), which turns each step's
LCP of the paper into the LCP of the mixed problem with the same matrix ``W0``.
"""

from .families import (Bearing, ConstraintFamily, Contact, Friction, RigidContact, SoilContact, SoilFriction,
                       SoilShear, Yield)
from .law import StepLaw, contact_law, default_families, step_law

__all__ = ["Bearing", "ConstraintFamily", "Contact", "Friction", "RigidContact", "SoilContact", "SoilFriction",
           "SoilShear", "StepLaw", "Yield", "contact_law",
           "default_families", "step_law"]
