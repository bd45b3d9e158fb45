"""Methods: the ways of solving a unilateral problem, chosen by name from :data:`METHODS`.

=================  ==========================================================================
name               method
=================  ==========================================================================
``"cq"``           :class:`CQ`: the CLCP (eq. 27) with convolution-quadrature weights of
                   ``Lambda(s)``; matrix models and :class:`~unilateral.kernels.KernelModel`
``"modal"``        :class:`Modal`: the same CLCP with the exact recursive history from the
                   poles and residues of ``Lambda(s)``, O(r m) per step
``"direct"``       :class:`Direct`: the full model stepped with the rule, one LCP per step
``"time-kernel"``  :class:`TimeKernelMethod`: product integration of a time-domain kernel
``"event"``        :class:`Event`: exact integration from contact change to contact change
``"moreau-jean"``  :class:`MoreauJean`: rigid contacts with Newton's impact law at the velocity
                   level, impacts located within the step
``"auto"``         not a class: :func:`choose_method` picks one of the above and says why
=================  ==========================================================================

Each method is one class with one entry, ``solve(model, load, initial, disc, run)``, taking the
:class:`~unilateral.discretization.Discretization` and the
:class:`~unilateral.run_context.RunContext`. To add a method: write one module here with a
subclass of :class:`Method` and add one line to :data:`METHODS`; ``unilateral.solve``, the
model files and the command line then accept its name (see ``docs/architecture.md``).
"""

from .. import _validate as V
from .auto import choose_method
from .base import Method
from .cq import CQ
from .direct import Direct
from .event import Event
from .modal import Modal
from .moreau_jean import MoreauJean
from .time_kernel import TimeKernelMethod, solve_time_kernel

#: The registry: name -> Method subclass.
METHODS = {"cq": CQ, "modal": Modal, "direct": Direct, "time-kernel": TimeKernelMethod, "event": Event,
           "moreau-jean": MoreauJean}
#: Every name ``method=`` accepts.
METHOD_NAMES = ("auto", *METHODS)
#: The names that solve a matrix :class:`~unilateral.model.Model` (model files, the command line).
MATRIX_METHOD_NAMES = ("auto", *(name for name, cls in METHODS.items() if "matrices" in cls.solves))


def get_method(method, options=None):
    """A :class:`Method` instance from a registry name, a Method subclass or an instance.

    Parameters
    ----------
    method : str, type or Method (not ``"auto"``: see :func:`choose_method`)
    options : dict, optional
        The method's options (e.g. ``cq_options``); not allowed with an instance.
    """
    if isinstance(method, Method):
        if options:
            raise ValueError(f"options were given for a method instance {method!r}; pass them to its constructor")
        return method
    if isinstance(method, type) and issubclass(method, Method):
        return method(**(options or {}))
    if isinstance(method, str):
        name = V.choice("method", method, METHOD_NAMES)
        if name == "auto":
            raise ValueError("method='auto' is a policy, not a class: use choose_method")
        return METHODS[name](**(options or {}))
    raise TypeError(f"method must be a name ({', '.join(map(repr, METHOD_NAMES))}), a Method subclass "
                    f"or a Method instance; got {V.describe(method)}")


__all__ = ["CQ", "Direct", "Event", "MATRIX_METHOD_NAMES", "METHODS", "METHOD_NAMES", "Method", "Modal", "MoreauJean", "TimeKernelMethod", "choose_method",
           "get_method", "solve_time_kernel"]
