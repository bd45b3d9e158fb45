"""Figures of analyses: histories, openings and contact forces, force-deformation paths, and more.

:func:`draw_figures` (``results``) draws every figure of a ``results.nc`` dataset; ``run`` and
``plot`` on the command line both call it, so they write the same files. ``plots`` holds the house
style, the Agg figure factory (no pyplot) and atomic saving. Import this package only when drawing:
matplotlib takes a while to import.
"""

from .plots import PAGE_WIDTH, save_figure
from .results import draw_figures

__all__ = ["PAGE_WIDTH", "draw_figures", "save_figure"]
