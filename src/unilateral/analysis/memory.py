"""An analysis in memory: :func:`run` gives an :class:`Analysis` without writing anything.

>>> import unilateral
>>> a = unilateral.run("examples/pounding.toml", t_end=1.0)          # doctest: +SKIP
>>> a["results"]["unilateral"]["base_shear"]                           # the summary, as summary.json
>>> a.solutions["bilateral"].u, a.dataset["base_shear"]                # every result, as xarray
>>> a.figure("fig2"); a.save("pounding")                               # a figure; the usual files

:func:`results_dataset` is the ``results.nc`` Dataset of solutions of a structure, in memory.
"""

from __future__ import annotations

import html
from pathlib import Path

from .outputs import ComputedResults, compute_results, write_results
from .run import model_file_job, solve_cases


class Analysis(dict):
    """A solved analysis: the summary (this dict: what ``summary.json`` holds, with ``success_all``) and
    every result in memory.

    Attributes
    ----------
    solutions : dict of str to Solution
        ``"unilateral"`` and ``"bilateral"`` (the cases run).
    computed : ComputedResults
        The Dataset of every result, the spectra and the summary (:func:`~unilateral.analysis.outputs.compute_results`).
    recorders : unilateral.io.recorders.Recorders
        What :meth:`save` writes (the model file's ``[output]``, or ``output=``).
    """

    def __init__(self, computed: ComputedResults, *, recorders=None, formats=("png",)):
        super().__init__(computed.summary)
        self["success_all"] = all(sol.success for sol in computed.solutions.values())
        self.computed, self.solutions, self.recorders, self.formats = computed, computed.solutions, recorders, formats
        self._dataset = None

    @property
    def dataset(self):
        """Every result as an :class:`xarray.Dataset` (dimension ``case``), as ``histories = "full"`` writes it."""
        if self._dataset is None:
            self._dataset = self.computed.ds.to_xarray()
        return self._dataset

    @property
    def datasets(self) -> dict:
        """The :attr:`dataset` of each case (``{"unilateral": ds, "bilateral": ds}``)."""
        ds = self.dataset
        if "case" not in ds.dims:
            return {next(iter(self.solutions)): ds}
        return {str(case): ds.sel(case=case) for case in ds["case"].values}

    def written(self):
        """``(Dataset, info)``: what :meth:`save` writes to ``results.nc`` and what was chosen
        (:func:`unilateral.io.recorders.select`)."""
        from ..io.recorders import Recorders, select

        figure = self.computed.figure
        ds, info = select(self.computed.ds, Recorders.of(self.recorders), figure_node=figure and figure["node"])
        return ds.to_xarray(), info

    def figure(self, name: str):
        """The matplotlib figure ``name`` (``fig2``, ``constraints``, ``hysteresis``, ``base_forces``, ``energy``,
        ``spectra``, ... of :data:`unilateral.figures.results.FIGURES`), drawn from every result."""
        from ..figures.results import FIGURES
        from .outputs import figure_view

        draw = dict(FIGURES).get(name)
        if draw is None:
            raise ValueError(f"no figure {name!r}; valid: {', '.join(n for n, _ in FIGURES)}")
        return draw(figure_view(self.computed.ds))

    def animate(self, path, *, case: str = "unilateral", **kwargs) -> Path:
        """The motion of a 2-D frame as a GIF (or MP4) at ``path`` (:func:`unilateral.figures.motion.animate`)."""
        from ..figures.motion import animate

        return animate(self.dataset, Path(path), case=case, **kwargs)

    def save(self, out, *, formats=None) -> dict:
        """Write ``results.nc``, the CSV tables, ``summary.json`` and the figures (``formats``; default those of
        :func:`run`) to the folder ``out``, replacing its previous set atomically; return the summary written
        (with ``output`` and ``figures``)."""
        from ..io.atomic import WriteError
        from ..io.folder import OutputFolder

        folder = OutputFolder(Path(out))
        try:
            staging = folder.prepare()
            result = write_results(self.computed, staging, formats=self.formats if formats is None else formats,
                                   recorders=self.recorders)
            final = folder.commit()
        except WriteError as exc:
            raise WriteError(folder.path / exc.path.name, exc) from exc
        except OSError as exc:
            raise WriteError(folder.path, exc) from exc
        finally:
            folder.close()
        result["figures"] = [str(final / Path(p).name) for p in result["figures"]]
        self.update(output=result["output"], figures=result["figures"])
        return result

    def report(self) -> str:
        """The terminal summary (:func:`unilateral.analysis.report`)."""
        from .terminal import report

        return report(dict(self))

    def __repr__(self) -> str:
        cases = ", ".join(f"{name}: {'ok' if sol.success else 'failed'} ({len(sol.t) - 1} steps)"
                          for name, sol in self.solutions.items())
        return f"<Analysis {self.title!r}: {cases}>"

    @property
    def title(self) -> str:
        """The analysis's title (the model file's ``[analysis] title``, or its name)."""
        return str(self.computed.title or self.get("extra", {}).get("title", ""))

    def _repr_html_(self) -> str:
        return (f"<b>{html.escape(self.title or 'analysis')}</b>"
                f"<pre style='font-size: 90%'>{html.escape(self.report())}</pre>")


def run(model, out=None, *, bilateral=False, figures=("png",), progress=None, output=None, point=None,
        storeys=None, **overrides) -> Analysis:
    """Analyse a model file (a path, or a ``ModelSpec`` of :func:`unilateral.modelfile.load_model_file`) in memory.

    Parameters
    ----------
    model : str, path or ModelSpec
    out : path, optional
        Also write the usual files there (:meth:`Analysis.save`); None (default): nothing is written.
    bilateral, progress, point, storeys, **overrides
        As :func:`unilateral.analysis.run_model_file` (``dt``, ``t_end``, ``method``, ``rule``, ``lcp``, ``initial``).
    figures : figure formats of :meth:`Analysis.save`
    output : dict or Recorders, optional
        What :meth:`Analysis.save` writes (replaces keys of the file's ``[output]``).

    Returns
    -------
    Analysis
    """
    from ..modelfile import ModelSpec, load_model_file

    spec = model if isinstance(model, ModelSpec) else load_model_file(Path(model))
    if spec.analysis.get("type") == "pushover":
        raise ValueError(f"{spec.source}: a [pushover] file is analysed by unilateral.analysis.run_model_file (or "
                         "`unilateral run`), not in memory")
    if out is not None:                         # a folder that cannot be written fails before the solving
        from ..io.folder import OutputFolder

        check = OutputFolder(Path(out))
        check.prepare()
        check.close()
    job = model_file_job(spec, bilateral=bilateral, point=point, storeys=storeys, output=output, **overrides)
    settings, recorders = job.pop("settings"), job.pop("recorders")
    solved = solve_cases(job["model"], job["load"], settings, job.pop("cases"), progress=progress)
    computed = compute_results(solved, rule=settings["rule"], **job)
    analysis = Analysis(computed, recorders=recorders, formats=figures)
    if out is not None:
        analysis.save(out)
    return analysis


def results_dataset(solution, structure=None, *, model=None, load=None, units=None, labels=None):
    """The ``results.nc`` Dataset of ``solution`` (a Solution, or a dict of cases on one time axis), in memory.

    Parameters
    ----------
    solution : Solution or dict of str to Solution
    structure : Structure, optional
        A frame: its results (end forces, base shear, drifts, energies, modes, ...) are added; ``model``
        defaults to ``structure.to_model()``.
    load : the load solved (energy input, ground motions), optional
    units : dict ``{"length", "force", "time"}``, optional

    Returns
    -------
    xarray.Dataset
        With a dimension ``case`` for a dict of cases, without it for one Solution.
    """
    cases = solution if isinstance(solution, dict) else {"unilateral": solution}
    if model is None and structure is not None:
        model = structure.to_model()
    done = compute_results(cases, structure=structure, units=units, model=model, load=load, labels=labels)
    ds = done.ds.to_xarray()
    return ds if isinstance(solution, dict) or "case" not in ds.dims else ds.isel(case=0, drop=True)
