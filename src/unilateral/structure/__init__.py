"""Build structures in natural form: a 2-D frame builder with unilateral elements.

:class:`Frame2D` collects nodes, supports, rigid links, beams, bars, springs, dashpots, masses and
the unilateral elements of Liolios (1990) — tensionless soil, pounding gaps and slack cables, with
Coulomb friction on contacts — with yield links, plastic hinges and sliders, and
:meth:`Frame2D.build` assembles them (sparse) into a :class:`Structure`: the natural form
``G, E, B, A, r, theta`` (and ``E_v`` of Kelvin elements), ``M``, ``C`` and the :class:`DofMap`.
:meth:`Structure.to_model` gives the :class:`unilateral.Model` for :func:`unilateral.solve`.

:func:`liolios1990` builds the paper's numerical example.
"""

from .dofs import DofMap
from .examples import liolios1990, winkler_beam
from .frame import Frame2D, Structure
from .frame3d import Frame3D, Structure3D

__all__ = ["DofMap", "Frame2D", "Frame3D", "Structure", "Structure3D", "liolios1990", "winkler_beam"]
