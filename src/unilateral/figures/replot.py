"""``unilateral plot``: redraw the figures of a ``results.nc`` into a folder as a set.

``unilateral plot --model`` draws the model figure of a model file the same way (:func:`replot_model`).

The figures are drawn into a hidden folder inside the target (``.plot.<random>.tmp``, which runs
ignore and replace) and moved into the target only when every one is drawn: a failure on the way
(a full disk) leaves the target as it was. In a run's folder the figures are then added to the
files its ``manifest.json`` lists, so the manifest stays true.

The examples ``halfspace`` and ``footings`` compare several runs in a figure of their own
(``halfspace.png``, ``footings.png``); each run is in a file of its own next to ``results.nc``,
which names them in its attribute ``run_files``. Their figure is redrawn from those files, read
from the folder of the ``results.nc`` the Dataset was read from. The figures of a run file itself
(``results_cones_pulse.nc``) get its attribute ``figure_prefix`` in front of their names
(``cones_pulse_fig2.png``), so they do not replace the figures of ``results.nc`` beside them.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
from importlib import import_module
from pathlib import Path

from ..io.folder import add_to_manifest
from . import FigureDataError
from .results import draw_figures

#: The examples whose ``results.nc`` names run files, and the module that draws their comparison
#: (its ``draw_comparison(datasets, path_without_suffix, formats)``).
EXAMPLE_FIGURES = {"halfspace": "unilateral.analysis.halfspace_example",
                   "footings": "unilateral.analysis.footings_example"}


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
    unilateral.figures.FigureDataError
        The attribute ``figure_prefix`` is not a plain file-name prefix; nothing is drawn.
    """
    out = Path(out_dir)
    prefix = figure_prefix(ds)
    out.mkdir(parents=True, exist_ok=True)
    stage = out / f".plot.{secrets.token_hex(4)}.tmp"
    stage.mkdir()
    skipped: list[str] = []
    try:
        drawn = draw_figures(ds, stage, formats, skipped=skipped)
        drawn += example_figure(ds, stage, formats, skipped)
        paths = []
        for path in drawn:
            os.replace(path, out / f"{prefix}{path.name}")
            paths.append(out / f"{prefix}{path.name}")
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    add_to_manifest(out, [p.name for p in paths])
    return paths, skipped


def replot_model(drawing, out_dir, formats=("png",)) -> list[Path]:
    """Draw the model figure of ``drawing`` into ``out_dir`` as :func:`replot` draws its figures:
    staged in a hidden folder, moved in once drawn, listed in a run's ``manifest.json``.

    Parameters
    ----------
    drawing : unilateral.figures.model.ModelDrawing
    out_dir : str or path-like
        Created if missing.
    formats : sequence of str
        As for :func:`~unilateral.figures.results.draw_figures`.

    Returns
    -------
    list of pathlib.Path
        The files written in ``out_dir`` (``model.png``, ...).
    """
    from .model import draw_model

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    stage = out / f".plot.{secrets.token_hex(4)}.tmp"
    stage.mkdir()
    try:
        paths = []
        for path in draw_model(drawing, stage, formats):
            os.replace(path, out / path.name)
            paths.append(out / path.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    add_to_manifest(out, [p.name for p in paths])
    return paths


def figure_prefix(ds) -> str:
    """The attribute ``figure_prefix`` of ``ds`` (``""`` without it), checked to be a plain name part."""
    prefix = str(ds.attrs.get("figure_prefix", ""))
    if prefix and (Path(prefix).name != prefix or prefix.startswith(".")):
        raise FigureDataError(f"the attribute figure_prefix = {prefix[:60]!r} is not a file-name prefix (no folders, "
                         "not hidden)")
    return prefix


def example_figure(ds, out_dir, formats, skipped: list) -> list[Path]:
    """The comparison figure of an example's ``results.nc`` (``halfspace.png``), from its run files.

    Parameters
    ----------
    ds : xarray.Dataset
        Read from a file (its ``encoding["source"]``), with the attributes ``example`` and
        ``run_files`` (a JSON list of file names in the same folder); other Datasets draw nothing.
    out_dir : path
        Where the figure is drawn.
    formats : sequence of str
    skipped : list
        Receives ``"<figure>: <why>"`` if the figure cannot be drawn (a run file missing or damaged).

    Returns
    -------
    list of pathlib.Path
        The files drawn.
    """
    from ..io.results import ResultsFileError, open_results

    example = str(ds.attrs.get("example", ""))
    if example not in EXAMPLE_FIGURES or "run_files" not in ds.attrs or not formats:
        return []
    try:
        folder = Path(ds.encoding["source"]).parent if ds.encoding.get("source") else None
        if folder is None:
            raise FigureDataError("the Dataset was not read from a file, so its run files cannot be found")
        runs = [open_results(folder / name) for name in run_files(ds)]
        draw = import_module(EXAMPLE_FIGURES[example]).draw_comparison
        return draw(runs, Path(out_dir) / example, formats)
    except (FigureDataError, ResultsFileError) as exc:
        skipped.append(f"{example}: {exc}")
        return []


def run_files(ds) -> list[str]:
    """The file names of the attribute ``run_files`` of an example's ``results.nc``.

    Raises
    ------
    unilateral.figures.FigureDataError
        The attribute is not a JSON list of plain file names.
    """
    text = str(ds.attrs["run_files"])
    try:
        names = json.loads(text)
    except (ValueError, RecursionError):         # RecursionError: nested thousands deep
        names = None
    if not isinstance(names, list) or not all(isinstance(n, str) and n and Path(n).name == n for n in names):
        raise FigureDataError(f"the attribute run_files = {text[:60]!r} is not a JSON list of file names")
    return names
