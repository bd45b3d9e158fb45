"""Solvers for the linear complementarity problem (LCP).

Find ``v >= 0`` with ``w = W v + q >= 0`` and ``v . w = 0``, for ``W``
(m, m) and ``q`` (m,). One small LCP is solved per time step.

Solvers (``LCP_SOLVERS`` name -> class, ``get_lcp_solver(name, **options)``):

==============  ========================  ==========================================
name            class                     W must be
==============  ========================  ==========================================
``"bpp"``       BlockPrincipalPivoting    P-matrix (default; warm start, fastest)
``"lemke"``     Lemke                     P-matrix, or positive semidefinite
``"newton"``    SemismoothNewton          P-matrix ("fb"); SPD for merit "min"
``"pgs"``       ProjectedGaussSeidel      symmetric PSD with positive diagonal
``"enumerate"`` Enumeration               anything, m <= 20 (reference solver)
==============  ========================  ==========================================

Every solver returns an :class:`LCPResult` and never raises on failure
(``success=False`` and a ``message`` saying what to try); only malformed
input (and m > 20 for enumeration) raises ValueError.
"""

from .base import LCP_SOLVERS, LCPResult, LCPSolver, get_lcp_solver, lcp_error, solve_lcp
from .bpp import BlockPrincipalPivoting
from .enumeration import Enumeration
from .lemke import Lemke
from .newton import SemismoothNewton
from .pgs import ProjectedGaussSeidel

__all__ = [
    "LCP_SOLVERS",
    "BlockPrincipalPivoting",
    "Enumeration",
    "LCPResult",
    "LCPSolver",
    "Lemke",
    "ProjectedGaussSeidel",
    "SemismoothNewton",
    "get_lcp_solver",
    "lcp_error",
    "solve_lcp",
]
