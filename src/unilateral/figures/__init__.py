"""Figures of analyses: histories, openings and contact forces, force-deformation paths, and more.

:func:`draw_figures` (``results``) draws every figure of a ``results.nc`` dataset; ``run`` and
``plot`` on the command line both call it, so they write the same files. ``plots`` holds the house
style, the Agg figure factory (no pyplot) and atomic saving; ``background`` draws the figures in a
forked process while the caller writes the other outputs. The names below are imported on first
use: matplotlib takes a while to import, and the figure process imports it while the run solves.
"""

from importlib import import_module

_EXPORTS = {"PAGE_WIDTH": "plots", "save_figure": "plots", "draw_figures": "results"}

__all__ = sorted([*_EXPORTS, "FigureDataError"])


class FigureDataError(ValueError):
    """What a ``results.nc`` holds that a figure cannot show: the variable or attribute, its value
    and what would be valid (``unilateral plot`` says it and skips that figure)."""


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'unilateral.figures' has no attribute {name!r}")
    value = getattr(import_module(f"unilateral.figures.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
