"""``unilateral plot``: redraw the figures of a ``results.nc`` into a folder as a set.

The figures are drawn into a hidden folder inside the target (``.plot.<random>.tmp``, which runs
ignore and replace) and moved into the target only when every one is drawn: a failure on the way
(a full disk) leaves the target as it was. In a run's folder the figures are then added to the
files its ``manifest.json`` lists, so the manifest stays true.
"""

from __future__ import annotations

import os
import secrets
import shutil
from pathlib import Path

from ..io.folder import add_to_manifest
from .results import draw_figures


def replot(ds, out_dir, formats=("png",)) -> tuple[list[Path], list[str]]:
    """Draw the figures of ``ds`` into ``out_dir``, all or none; list them in its manifest.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`unilateral.analysis.outputs.figure_view` of a ``results.nc``.
    out_dir : str or path-like
        Created if missing. If it holds a run's ``manifest.json``, the figures join its files.
    formats : sequence of str
        As for :func:`~unilateral.figures.results.draw_figures`.

    Returns
    -------
    paths : list of pathlib.Path
        The files written in ``out_dir``.
    skipped : list of str
        ``"<figure>: <why>"`` for each figure the Dataset cannot give.

    Raises
    ------
    OSError
        (:class:`~unilateral.io.atomic.WriteError` for a figure) ``out_dir`` is then unchanged.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    stage = out / f".plot.{secrets.token_hex(4)}.tmp"
    stage.mkdir()
    skipped: list[str] = []
    try:
        drawn = draw_figures(ds, stage, formats, skipped=skipped)
        paths = []
        for path in drawn:
            os.replace(path, out / path.name)
            paths.append(out / path.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    add_to_manifest(out, [p.name for p in paths])
    return paths, skipped
