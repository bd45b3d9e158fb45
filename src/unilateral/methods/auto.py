"""``method="auto"``: the policy that picks the fastest correct method, and says why."""

from __future__ import annotations

from ..lcp import BlockPrincipalPivoting
from ..march.policy import current_policy
from .cq import CQ
from .direct import Direct
from .modal import Modal
from .moreau_jean import MoreauJean
from .time_kernel import TimeKernelMethod


def choose_method(model, rule, solver, options):
    """The method of ``method="auto"`` and the reason (measured in the benchmark suite).

    One rule per kind of problem (:data:`RULES`, by the problem's ``kind``; a new kind adds its own).

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
    choose = RULES.get(getattr(model, "kind", None))
    if choose is None:
        raise TypeError(f"method='auto' has no rule for a {type(model).__name__}")
    return choose(model, rule, solver, options)


def _kernel(model, rule, solver, options):
    if model.domain == "time":
        return TimeKernelMethod(), "a KernelModel of a TimeKernel is solved by product integration of its Lambda(t)"
    return CQ(**options.get("cq", {})), "a KernelModel is solved by convolution quadrature of its Lambda(s)"


def _matrices(model, rule, solver, options):
    if "cq" in options:
        return CQ(**options["cq"]), "cq_options were given"
    if "modal" in options:
        return _modal_or(Modal(**options["modal"]), "modal_options were given", model, Direct(), "direct")
    if "direct" in options:
        return Direct(**options["direct"]), "direct_options were given"
    if model.m and MoreauJean().applies(model, rule) is None:
        return MoreauJean(), "every unknown is a rigid contact: Newton's impact law, impacts located in the step"
    policy = current_policy()
    small = model.n <= policy.dense_stepping_max_n and model.m <= policy.full_space_min_m
    bpp = isinstance(solver, BlockPrincipalPivoting)
    if small and bpp and model.m and type(rule).__module__ == "unilateral.rules":
        return Direct(), ("small model: compiled direct stepping (a dense LU of D_eff, the condensed LCP) "
                          "is the fastest end to end, half the time of modal's march and two linear sweeps")
    if small and rule.supports_cq and bpp and model.m:
        return _modal_or(Modal(), "small model with a rule of its own: the compiled CLCP march with the exact "
                         "recursive history and compiled linear sweeps", model, Direct(), "direct")
    full = model.sparse and model.law.trivial and (model.m > policy.full_space_min_m
                                                        or model.n > policy.compiled_max_n)
    space = "the LCP in the full sparse space" if full else "the condensed LCP"
    return Direct(), f"direct stepping ({space}) is the fastest end to end for this model"


def _foundation(model, rule, solver, options):
    """cq or modal for a FoundationModel (the dual CLCP in the contact forces)."""
    if "cq" in options:
        return CQ(**options["cq"]), "cq_options were given"
    if "modal" in options:
        return _modal_or(Modal(**options["modal"]), "modal_options were given", model, CQ(), "cq")
    if model.soil.is_rational and rule.supports_cq:
        return _modal_or(Modal(), "a foundation on a rational soil: the recursive history of the poles of the "
                         "structure and the soil costs O(r m) per step", model, CQ(), "cq")
    return CQ(), "a foundation on a soil given by Phi(s): convolution quadrature of the dual kernel"


#: The rule of ``method="auto"`` for each kind of problem.
RULES = {"matrices": _matrices, "foundation": _foundation, "laplace kernel": _kernel, "time kernel": _kernel}


def _modal_or(modal, reason, model, other, name):
    """``modal`` and ``reason`` if the poles of ``model``'s kernel exist (:meth:`Modal.refusal`),
    else ``other`` with the reason modal was refused."""
    why_not = modal.refusal(model)
    if why_not is None:
        return modal, reason
    return other, f"modal refused ({why_not}), {name} used instead"
