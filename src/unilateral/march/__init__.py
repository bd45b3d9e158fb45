"""Marches: step the convolutional LCP (Python or compiled) or the full model, one LCP per step.

================  ==============================================================================
module            content
================  ==============================================================================
``clcp``          :func:`~clcp.march_cq` (any history, any LCP solver) and
                  :func:`~clcp.march_cq_compiled` (naive or recursive history, compiled)
``compiled``      the numba loops: block principal pivoting, the CLCP marches, the linear sweep
``stepper``       :class:`~stepper.StructureStepper`: one step of the full model with a rule
``direct``        :func:`~direct.march_direct` (one condensed LCP per step) and
                  :func:`~direct.sweep_direct` (the linear sweep: ``psiL``, recovery of ``u``)
``active_set``    :func:`~active_set.march_direct_active_set`: the LCP in the full sparse space
``step_log``      :class:`~step_log.StepLog`: LCP statistics and the first failure of a march
================  ==============================================================================
"""
