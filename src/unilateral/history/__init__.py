"""Histories: how the convolution sum ``h_n = sum_{j=1..n} W_j dv_{n-j}`` of the CLCP is evaluated.

Every history has ``value(n) -> (m,)`` (the sum at step n, before ``dv_n`` is known) and
``push(n, dv_n)``; the march (:mod:`unilateral.march`) calls them once per step.

=================  =========================================================================
module             history
=================  =========================================================================
``naive``          :class:`NaiveHistory`: direct summation of stored weights, O(n m^2) per step
``fft_blocked``    :class:`FFTBlockedHistory`: Hairer-Lubich-Schlichte blocking, O(m^2 N log^2 N)
                   in all
``recursive``      :class:`RecursiveHistory`: one scalar recursion per pole of a
                   :class:`~unilateral.kernels.PoleResidueKernel`, O(r m) per step, exact
``restricted``     :class:`RestrictedHistory`: any of the above on the unknowns that the weights
                   ``W_1 .. W_N`` couple (the slips of sliding footings have none)
=================  =========================================================================

A new way of summing the history is one module here with those two methods, and one entry in
:data:`HISTORIES` if it works from stored weights ``W (N+1, m, m)``.
"""

from .fft_blocked import FFTBlockedHistory
from .naive import NaiveHistory
from .recursive import LinearRecursion, RecursiveHistory
from .restricted import RestrictedHistory, coupled_unknowns, history_on_coupled_unknowns

#: Histories built from stored weights ``W (N+1, m, m)``, by name (``cq_options["history"]``).
HISTORIES = {"naive": NaiveHistory, "fft": FFTBlockedHistory}

__all__ = ["FFTBlockedHistory", "HISTORIES", "LinearRecursion", "NaiveHistory", "RecursiveHistory",
           "RestrictedHistory", "coupled_unknowns", "history_on_coupled_unknowns"]
