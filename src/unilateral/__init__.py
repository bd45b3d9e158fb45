"""unilateral: dynamics of structures with unilateral constraints.

The method of A. A. Liolios, "A Laplace transform aided numerical approach to dynamic unilateral
contact problems" (1990): the problem is reduced to the unilateral unknowns only,
``psi(t) = psiL(t) - (Lambda * v)(t)``, a convolutional linear complementarity problem solved
step by step with one small LCP per time step.

Entry points: :class:`Model` (matrices or the natural form), :class:`KernelModel` (a kernel
``Lambda(s)`` and ``psiL``), :class:`TimeKernelModel` (a time-domain kernel ``Lambda(t)``, e.g.
by numerical Laplace inversion, :func:`invert_laplace`), and :func:`solve` (loads as callables,
arrays or a :class:`LoadHistory`). Structures are built with :class:`unilateral.structure.Frame2D`
or read from model files (:func:`unilateral.modelfile.load_model_file`).
"""

from .kernels import (CallableKernel, KernelModel, MatrixKernel, PoleResidueKernel, TimeKernel,
                      TimeKernelModel, cq_weights, invert_laplace, time_kernel_weights)
from .lcp import LCP_SOLVERS, LCPResult, LCPSolver, get_lcp_solver, solve_lcp
from .loads import LoadHistory
from .methods import METHODS, solve_time_kernel
from .model import Model, NaturalForm
from .result import Solution
from .rules import BDF, HHT, Newmark, get_rule
from .solve import solve

__version__ = "0.1.0"

__all__ = [
    "BDF", "CallableKernel", "HHT", "KernelModel", "LCPResult", "LCPSolver", "LCP_SOLVERS",
    "LoadHistory", "METHODS", "MatrixKernel", "Model", "NaturalForm", "Newmark", "PoleResidueKernel",
    "Solution", "TimeKernel", "TimeKernelModel", "cq_weights", "get_lcp_solver", "get_rule",
    "invert_laplace", "solve", "solve_lcp", "solve_time_kernel", "time_kernel_weights",
]
