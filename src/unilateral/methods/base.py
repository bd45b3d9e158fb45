"""The interface of a solution method: :class:`Method`."""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

from .stepping import SolvedRun


#: The kinds of problem in words (messages).
KIND_NAMES = {"matrices": "a Model", "foundation": "a FoundationModel",
              "laplace kernel": "a KernelModel of Lambda(s)", "time kernel": "a KernelModel of a TimeKernel"}
#: The method that solves each kind of problem without matrices.
USE_FOR = {"cq": "laplace kernel", "time-kernel": "time kernel"}


class Method(ABC):
    """A way of solving the unilateral problem on a time grid.

    Subclasses set :attr:`name`, :attr:`models` and :attr:`options` and implement :meth:`solve`.
    An instance carries the method's own options (e.g. the history of ``cq``); everything else
    comes in the :class:`~unilateral.discretization.Discretization` and the
    :class:`~unilateral.run_context.RunContext`.

    Parameters
    ----------
    **options
        The method's options, by the names in :attr:`options`; anything else is refused.
    """

    #: Registry name (``solve(..., method=name)``).
    name: ClassVar[str] = ""
    #: The kinds of problem the method solves (a problem's ``kind``: ``"matrices"`` for a
    #: :class:`~unilateral.model.Model`, ``"foundation"`` for a
    #: :class:`~unilateral.soil.FoundationModel`, ``"laplace kernel"`` and ``"time kernel"`` for a
    #: :class:`~unilateral.kernels.KernelModel`).
    solves: ClassVar[frozenset[str]] = frozenset({"matrices"})
    #: Option names accepted by the constructor.
    options: ClassVar[tuple[str, ...]] = ()
    #: Only rules with a convolution-quadrature form (BDF1, BDF2, trapezoidal).
    cq_rules_only: ClassVar[bool] = True
    def __init__(self, **options):
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            valid = ", ".join(repr(k) for k in self.options) or "none"
            raise ValueError(f"{self.option_name} has unknown keys {unknown}; valid keys: {valid}")
        self.config = dict(options)

    @property
    def option_name(self) -> str:
        """How the options are called in messages (``cq_options`` and the like)."""
        return f"{self.name.replace('-', '_')}_options"

    def applies(self, model, rule) -> str | None:
        """None if this method solves ``model`` with ``rule``; otherwise the reason it does not."""
        kind = getattr(model, "kind", None)
        if kind not in self.solves:
            takes = " or ".join(KIND_NAMES[k] for k in sorted(self.solves))
            given = KIND_NAMES.get(kind, f"a {type(model).__name__}")
            use = [name for name, k in USE_FOR.items() if k == kind]
            hint = f": use method={use[0]!r}" if use and use[0] != self.name else ""
            return f"method={self.name!r} solves {takes}, not {given}{hint}"
        if self.cq_rules_only and not rule.supports_cq:
            return (f"rule={rule.name!r} has no convolution-quadrature form; valid for method={self.name!r}: "
                    "'bdf1', 'bdf2', 'trapezoidal' (use method='direct' for Newmark and HHT)")
        return None

    def by_kind(self, model, disc, routes: dict):
        """The route of ``model``'s ``kind`` among ``routes`` (kind -> callable), for a method that
        solves several kinds; ``TypeError`` with the reason of :meth:`applies` if it has none."""
        route = routes.get(getattr(model, "kind", None))
        if route is None:
            raise TypeError(self.applies(model, disc.rule) or f"method={self.name!r} does not solve {model!r}")
        return route

    def refusal(self, model) -> str | None:
        """None, or why this method cannot solve ``model`` after all: a check that costs more than
        :meth:`applies` (e.g. the poles of ``modal``), made for the method chosen only."""
        return None

    def check(self, model, rule) -> None:
        """Raise ``ValueError`` if this method cannot solve ``model`` with ``rule`` (:meth:`applies`)."""
        reason = self.applies(model, rule)
        if reason is not None:
            raise ValueError(reason)

    def memory_estimate(self, model, disc) -> dict:
        """Bytes the run will hold, by what: ``{"histories of ...": bytes, ...}`` (a lower bound).

        The default counts the output histories: ``u`` and ``udot`` (n each), ``v``, ``psi`` and
        ``psiL`` (m each) at every step.
        """
        n = getattr(model, "n", 0)
        return {f"the histories of u, udot, v, psi, psiL (n = {n}, m = {model.m})":
                8.0 * (disc.N + 1) * (2 * n + 3 * model.m)}

    @abstractmethod
    def solve(self, model, load, initial, disc, run):
        """Solve ``model`` under ``load`` from ``initial`` on ``disc``; return a Solution.

        Parameters
        ----------
        model : the problem (a class of :attr:`models`)
        load : callable ``q(t) -> (n,)``, array (N+1, n), LoadHistory or None
        initial : "static", "rest" or dict of ``u0``, ``udot0``, ``v0``
        disc : Discretization
        run : RunContext
        """

    def start(self, model, load, initial, disc, run):
        """The run of ``model`` begun at step 0, advanced on request (same arguments as :meth:`solve`).

        The default marches all steps in one call of :meth:`solve` at the first request
        (:class:`~unilateral.methods.stepping.SolvedRun`); a method that can step overrides it and
        returns a run that performs its steps as they are asked for (:class:`Direct`).
        """
        return SolvedRun(lambda: self.solve(model, load, initial, disc, run), disc.N)

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.config.items())
        return f"{type(self).__name__}({args})"
