"""``method="auto"``: the policy that picks the fastest correct method, and says why."""

from __future__ import annotations

import functools

from ..kernels import KernelModel
from ..lcp import BlockPrincipalPivoting
from ..march.policy import current_policy
from ..model import Model
from ..soil.foundation_model import FoundationModel
from .cq import CQ
from .direct import Direct
from .modal import FoundationPolesRefused, Modal, PolesRefused
from .time_kernel import TimeKernelMethod


@functools.singledispatch
def choose_method(model, rule, solver, options):
    """The method of ``method="auto"`` and the reason (measured in the benchmark suite).

    One rule per model class (registered below; a new model class registers its own).

    Parameters
    ----------
    model : Model, KernelModel or FoundationModel
    rule : Rule
    solver : LCPSolver
    options : dict of method name -> options given (``cq_options`` and the like)

    Returns
    -------
    method : Method (an instance) ; reason : str
    """
    raise TypeError(f"method='auto' has no rule for a {type(model).__name__}")


@choose_method.register
def _(model: KernelModel, rule, solver, options):
    if model.domain == "time":
        return TimeKernelMethod(), "a KernelModel of a TimeKernel is solved by product integration of its Lambda(t)"
    return CQ(**options.get("cq", {})), "a KernelModel is solved by convolution quadrature of its Lambda(s)"


@choose_method.register
def _(model: Model, rule, solver, options):
    if "cq" in options:
        return CQ(**options["cq"]), "cq_options were given"
    if "modal" in options:
        return Modal(**options["modal"]), "modal_options were given"
    if "direct" in options:
        return Direct(**options["direct"]), "direct_options were given"
    policy = current_policy()
    small = model.n <= policy.dense_stepping_max_n and model.m <= policy.full_space_min_m
    bpp = isinstance(solver, BlockPrincipalPivoting)
    if small and bpp and model.m and type(rule).__module__ == "unilateral.rules":
        return Direct(), ("small model: compiled direct stepping (a dense LU of D_eff, the condensed LCP) "
                          "is the fastest end to end, half the time of modal's march and two linear sweeps")
    if small and rule.supports_cq and bpp and model.m:
        return Modal(), ("small model with a rule of its own: the compiled CLCP march with the exact "
                         "recursive history and compiled linear sweeps")
    full = model.sparse and model.law.trivial and (model.m > policy.full_space_min_m
                                                        or model.n > policy.compiled_max_n)
    space = "the LCP in the full sparse space" if full else "the condensed LCP"
    return Direct(), f"direct stepping ({space}) is the fastest end to end for this model"


@choose_method.register
def _(model: FoundationModel, rule, solver, options):
    """cq or modal for a FoundationModel (the dual CLCP in the contact forces)."""
    if "cq" in options:
        return CQ(**options["cq"]), "cq_options were given"
    if "modal" in options:
        return Modal(**options["modal"]), "modal_options were given"
    if model.soil.is_rational and rule.supports_cq:
        return Modal(), ("a foundation on a rational soil: the recursive history of the poles of the "
                         "structure and the soil costs O(r m) per step")
    return CQ(), "a foundation on a soil given by Phi(s): convolution quadrature of the dual kernel"


def fallback(exc):
    """The method and reason to use when the auto choice was refused by ``exc``, or None."""
    if isinstance(exc, FoundationPolesRefused):
        return CQ(), f"modal refused ({exc}), cq used instead"
    if isinstance(exc, PolesRefused):
        return Direct(), f"modal refused ({exc}), direct used instead"
    return None
