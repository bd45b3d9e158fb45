"""unilateral: dynamics of structures with unilateral constraints.

The method of A. A. Liolios, "A Laplace transform aided numerical approach to dynamic unilateral
contact problems" (1990): the problem is reduced to the unilateral unknowns only,
``psi(t) = psiL(t) - (Lambda * v)(t)``, a convolutional linear complementarity problem solved
step by step with one small LCP per time step.

Entry points: :class:`Model` (matrices or the natural form), :class:`KernelModel` (a kernel
``Lambda(s)`` and ``psiL``, or a time-domain kernel ``Lambda(t)``, :class:`TimeKernel`, e.g.
by numerical Laplace inversion, :func:`invert_laplace`), and :func:`solve` (loads as callables,
arrays or a :class:`LoadHistory`). Structures are built with :class:`unilateral.structure.Frame2D`
or read from model files (:func:`unilateral.modelfile.load_model_file`); :class:`Simulation` advances
an analysis step by step (``step``, ``advance``, ``advance_to``, ``state``, ``solution``);
:func:`run` analyses a model file in memory (an :class:`Analysis`: the summary, the solutions, every
result as an xarray Dataset, the figures; ``save(folder)`` or ``out=`` writes what ``unilateral run``
writes), and :func:`results_dataset` gives the results Dataset of solutions of a structure.

The names are imported lazily, on first use: ``import unilateral`` (and the command line's
``--help``) does not import numpy, scipy, xarray or matplotlib.
"""

import sys
import types
from importlib import import_module

__version__ = "0.1.0"

#: The names of the registries, listed here so that the command line and the model-file schema
#: check a name without importing the solvers (numpy, scipy): ``unilateral.methods.MATRIX_METHOD_NAMES``,
#: ``unilateral.rules.RULES`` (in its order) and ``unilateral.lcp.LCP_SOLVERS`` (sorted).
#: ``tests/test_prompt.py`` checks them against the registries.
_MATRIX_METHOD_NAMES = ("auto", "cq", "modal", "direct", "event", "moreau-jean")
_RULE_NAMES = ("bdf1", "bdf2", "trapezoidal", "newmark", "hht")
_LCP_NAMES = ("bpp", "enumerate", "lemke", "newton", "pgs")

#: Public name -> the module that defines it.
_LAZY = {
    **dict.fromkeys(("CallableKernel", "KernelModel", "MatrixKernel", "PoleResidueKernel", "TimeKernel",
                     "TimeKernelModel", "cq_weights", "invert_laplace", "time_kernel_weights"),
                    "unilateral.kernels"),
    **dict.fromkeys(("LCP_SOLVERS", "LCPResult", "LCPSolver", "get_lcp_solver", "solve_lcp"), "unilateral.lcp"),
    "LoadHistory": "unilateral.loads",
    **dict.fromkeys(("FoundationModel", "SoilFlexibility"), "unilateral.soil"),
    **dict.fromkeys(("METHODS", "solve_time_kernel"), "unilateral.methods"),
    **dict.fromkeys(("Model", "NaturalForm"), "unilateral.model"),
    **dict.fromkeys(("Solution", "State"), "unilateral.result"),
    **dict.fromkeys(("BDF", "HHT", "Newmark", "get_rule"), "unilateral.rules"),
    **dict.fromkeys(("Simulation", "solve"), "unilateral.solve"),
    **dict.fromkeys(("SizePolicy", "size_policy"), "unilateral.march.policy"),
    **dict.fromkeys(("Analysis", "results_dataset", "run"), "unilateral.analysis.memory"),
}
_ALIASES: dict = {}

__all__ = sorted(_LAZY)


def __getattr__(name):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'unilateral' has no attribute {name!r}")
    value = getattr(import_module(module), _ALIASES.get(name, name))
    globals()[name] = value         # later lookups skip __getattr__
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))


class _Package(types.ModuleType):
    """The package module: ``unilateral.solve`` stays the function when the submodule
    ``unilateral.solve`` is imported (the import system would bind the module to the name)."""

    def __setattr__(self, name, value):
        if name == "solve" and isinstance(value, types.ModuleType):
            value = value.solve
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
