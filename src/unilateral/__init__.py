"""unilateral: dynamics of structures with unilateral constraints.

The method of A. A. Liolios, "A Laplace transform aided numerical approach to dynamic unilateral
contact problems" (1990): the problem is reduced to the unilateral unknowns only,
``psi(t) = psiL(t) - (Lambda * v)(t)``, a convolutional linear complementarity problem solved
step by step with one small LCP per time step.

Entry points: :class:`Model` (matrices or the natural form), :class:`KernelModel` (a kernel
``Lambda(s)`` and ``psiL``), :func:`solve`.
"""

from .cq import cq_weights
from .kernel_model import KernelModel
from .kernels import CallableKernel, MatrixKernel
from .lcp import LCP_SOLVERS, LCPResult, LCPSolver, get_lcp_solver, solve_lcp
from .model import Model, NaturalForm
from .result import Solution
from .rules import BDF, HHT, Newmark, get_rule
from .solve import METHODS, solve

__version__ = "0.1.0"

__all__ = [
    "BDF", "CallableKernel", "HHT", "KernelModel", "LCPResult", "LCPSolver", "LCP_SOLVERS",
    "METHODS", "MatrixKernel", "Model", "NaturalForm", "Newmark", "Solution", "cq_weights",
    "get_lcp_solver", "get_rule", "solve", "solve_lcp",
]
