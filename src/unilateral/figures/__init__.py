"""Figures of analyses: histories, openings and contact forces, force-deformation paths.

Built on :class:`matplotlib.figure.Figure` with an Agg canvas (no pyplot); ``run`` and ``plot``
on the command line draw them with the same functions. Import this package only when drawing:
matplotlib takes a while to import.
"""

from .plots import PAGE_WIDTH, plot_constraints, plot_displacement, plot_force_deformation, save_figure

__all__ = ["PAGE_WIDTH", "plot_constraints", "plot_displacement", "plot_force_deformation", "save_figure"]
