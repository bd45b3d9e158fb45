"""Kernels: how the influence matrix ``Lambda`` of the convolutional LCP is represented.

A model becomes a kernel; a kernel gives convolution weights or a history (:mod:`unilateral.history`).

=======================  ==========================================================================
module                   content
=======================  ==========================================================================
``base``                 :class:`Kernel` (``kernel(s) -> (L, m, m)``) and :class:`CallableKernel`
                         (a user's ``Lambda(s)``)
``matrix``               :class:`MatrixKernel`: ``Lambda(s) = H(s) - F(s)^T D(s)^-1 F(s)`` of a
                         :class:`~unilateral.model.Model`, and the load transfer ``F^T D^-1``
``pole_residue``         :class:`PoleResidueKernel`: ``Lambda0 + s P1 + sum_k R_k s/(p_k (s - p_k))``,
                         built from all poles (``poles_dense``) or the lowest modes with a static
                         correction (``poles_truncated``)
``time_domain``          :class:`TimeKernel`: ``Lambda_inf delta + Lambda_rate delta' + Lambda_r(t)``
                         and its product-integration weights
``laplace_inversion``    :func:`invert_laplace` (de Hoog, Durbin), used to build time-domain kernels
``cq_weights``           :func:`cq_weights`: convolution-quadrature weights of any kernel by FFT
``kernel_model``         :class:`KernelModel` (its kernel in the Laplace or the time domain;
                         :func:`TimeKernelModel` makes the latter): problems given by their
                         kernel and bilateral response ``psiL`` only
=======================  ==========================================================================

A new kind of kernel subclasses :class:`Kernel` and implements ``evaluate(s)``; every CQ-based
method then accepts it through a :class:`KernelModel`.
"""

from .base import CallableKernel, Kernel
from .cq_weights import cq_weights
from .kernel_model import KernelModel, TimeKernelModel
from .laplace_inversion import invert_laplace
from .matrix import MatrixKernel
from .pole_residue import PoleResidueKernel
from .time_domain import TimeKernel, time_kernel_weights

__all__ = ["CallableKernel", "Kernel", "KernelModel", "MatrixKernel", "PoleResidueKernel", "TimeKernel",
           "TimeKernelModel", "cq_weights", "invert_laplace", "time_kernel_weights"]
