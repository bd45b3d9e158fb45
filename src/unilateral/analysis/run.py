"""Analyses from Python with the command line's outputs: :func:`run_model_file`, :func:`run_example`.

>>> import unilateral
>>> result = unilateral.run("examples/pounding.toml", out="pounding", t_end=1.0)   # doctest: +SKIP
>>> result["results"]["unilateral"]["base_shear"]                                # doctest: +SKIP

Both return the summary dict that ``summary.json`` holds (plus ``"figures"``, the files drawn),
and write ``results.nc``, the CSV tables, ``summary.json`` and the figures to ``out``.
"""

from __future__ import annotations

from pathlib import Path

EXAMPLES = ("liolios1990", "halfspace", "footings")
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}
SETTINGS = ("dt", "t_end", "method", "rule", "lcp", "initial")
#: The shortest period of a response spectrum [s]: far below any record's time step, where the
#: oscillator is rigid; much shorter periods make its exact step overflow (Sa NaN below ~1e-20 s).
MIN_SPECTRUM_PERIOD = 1e-6


def settings_of(defaults: dict, **given) -> dict:
    """``dt, t_end, method, rule, lcp, initial`` from defaults and the given (non-None) values."""
    unknown = set(given) - set(SETTINGS)
    if unknown:
        raise TypeError(f"unknown setting(s) {sorted(unknown)}; valid: {', '.join(SETTINGS)}")
    out = {key: defaults.get(key) for key in SETTINGS}
    out["initial"] = out["initial"] or "static"
    out.update({key: value for key, value in given.items() if value is not None})
    return out


def run_model_file(path, out=None, *, bilateral=False, figures=("png",), progress=None, point=None,
                   storeys=None, figure_process=None, output=None, **overrides) -> dict:
    """Analyse a model file and write every output, as ``unilateral run`` does.

    Parameters
    ----------
    path : the TOML model file (see ``docs/model-file.md``)
    out : output directory (default: the file's stem, in the current directory)
    bilateral : hold every constraint bilateral only (no uplift)
    figures : figure formats (``("png",)``, ``("png", "pdf")``, ``()``)
    progress : callable ``progress(done, total)`` in work units over the whole run, optional
    point, storeys : see :func:`unilateral.analysis.write_outputs`
    figure_process : :class:`unilateral.figures.background.BackgroundFigures`, optional
        A forked process that draws the figures while this one writes the other outputs (the
        command line starts one as it starts); by default the figures are drawn in process.
    output : dict or unilateral.io.recorders.Recorders, optional
        What is written (``histories``, ``variables``, ``nodes``, ``elements``, ``every``,
        ``precision``, ``csv``): these keys replace those of the file's ``[output]``.
    **overrides : ``dt``, ``t_end``, ``method``, ``rule``, ``lcp``, ``initial``

    Returns
    -------
    dict : the summary (``summary.json``) and ``figures``, the files drawn.
    """
    from ..modelfile import load_model_file

    path = Path(path)
    spec = load_model_file(path)
    if spec.analysis.get("type") == "pushover":     # [pushover]: unilateral.pushover.files
        from ..pushover.files import run_file

        return run_file(spec, Path(out) if out is not None else Path(path.stem), figures=figures,
                        bilateral=bilateral, **overrides)
    job = model_file_job(spec, bilateral=bilateral, point=point, storeys=storeys, output=output, **overrides)
    return analyse(**job, out=Path(out) if out is not None else Path(path.stem), formats=figures,
                   progress=progress, figure_process=figure_process)


def model_file_job(spec, *, bilateral=False, point=None, storeys=None, output=None, **overrides) -> dict:
    """The arguments of :func:`analyse` (but ``out``, ``formats``, ``progress``, ``figure_process``) for the
    model file read as ``spec`` (:func:`unilateral.modelfile.load_model_file`); see :func:`run_model_file`."""
    a = spec.analysis
    source = Path(spec.source)
    if point is None and spec.document.output.overturning_about is not None:
        point = tuple(spec.document.output.overturning_about)
    return dict(model=spec.model, load=spec.load, settings=settings_of(a, **overrides), structure=spec.structure,
                units=spec.units, figure=spec.figure, title=a.get("title") or source.stem,
                meta={"model_file": str(source)},
                cases=_cases(bool(a.get("bilateral_reference", True)) and not bilateral, not bilateral),
                labels=case_labels(_kinds(spec)), point=point, storeys=storeys, spectra=spectra_settings(spec),
                model_figure=spec.structure is not None, recorders=recorders_of(spec.document.output, output))


def recorders_of(table, output=None):
    """The :class:`~unilateral.io.recorders.Recorders` of a model file's ``[output]`` ``table`` with the keys of
    ``output`` (a dict, a ``Recorders`` or None) in place of the file's."""
    from ..io.recorders import FIELDS, Recorders

    if isinstance(output, Recorders):
        return output
    given = {key: getattr(table, key) for key in FIELDS if getattr(table, key, None) is not None}
    return Recorders.of(given | dict(output or {}))


def spectra_settings(spec):
    """The response spectra asked for by the ``[output]`` of a model file (None for matrices).

    The periods not given default to :data:`unilateral.analysis.spectra.DEFAULT_PERIODS` (in
    seconds, converted to the model's time unit).

    Parameters
    ----------
    spec : ModelSpec
        :func:`unilateral.modelfile.load_model_file` of the file.

    Returns
    -------
    unilateral.analysis.spectra.SpectraSettings or None

    Raises
    ------
    unilateral.modelfile.ModelFileError
        ``floor_spectra`` in a matrix-level model; the resolved shortest period is not below
        the longest (its nodes are checked with the model file, :mod:`unilateral.modelfile.checks`).
    """
    from ..modelfile.errors import ModelFileError
    from ..modelfile.schema import TIME_UNITS
    from .spectra import DEFAULT_PERIODS, SpectraSettings, period_grid

    output = spec.document.output
    if spec.structure is None:
        if output.floor_spectra:
            raise ModelFileError(spec.source, ["output.floor_spectra: needs a frame (a matrix-level model has no "
                                               "nodes)"])
        return None
    problems = []                           # the nodes of floor_spectra: modelfile.checks
    seconds = TIME_UNITS[spec.document.units.time]
    periods = output.spectra_periods
    shortest = periods.min if periods.min is not None else DEFAULT_PERIODS[0] / seconds
    longest = periods.max if periods.max is not None else DEFAULT_PERIODS[1] / seconds
    if periods.min is not None and not periods.min * seconds >= MIN_SPECTRUM_PERIOD:
        unit = spec.document.units.time
        problems.append(f"output.spectra_periods: min = {periods.min!r} is below {MIN_SPECTRUM_PERIOD / seconds:g} "
                        f"{unit} ({MIN_SPECTRUM_PERIOD:g} s): the oscillator's exact step "
                        "exp(F dt) cannot be represented (Sa would be NaN), and a shorter period is rigid (Sa = the "
                        f"peak ground acceleration); give min >= {MIN_SPECTRUM_PERIOD / seconds:g}")
    if not shortest < longest:
        problems.append(f"output.spectra_periods: min must be < max, got min={shortest:g} and max={longest:g} "
                        f"(the default {'max' if periods.max is None else 'min'} is "
                        f"{(longest if periods.max is None else shortest):g} {spec.document.units.time})")
    if problems:
        raise ModelFileError(spec.source, problems)
    return SpectraSettings(periods=period_grid(shortest, longest, periods.count), damping=output.spectra_damping,
                           nodes=tuple(output.floor_spectra))


def run_example(name="liolios1990", out=None, *, figures=("png",), progress=None, figure_process=None,
                **overrides) -> dict:
    """Run a built-in example with and without uplift; see :func:`run_model_file`.

    ``"liolios1990"``: the paper's example. ``"halfspace"``: the paper's tower on the Winkler-Kelvin
    soil, cones and the elastic half-space under the pulse and an earthquake
    (:func:`unilateral.analysis.halfspace_example.run_halfspace_example`). ``"footings"``: a
    two-bay frame on two footings on one layered soil
    (:func:`unilateral.analysis.footings_example.run_footings_example`).
    """
    if name not in EXAMPLES:
        raise ValueError(f"no example {name!r}; valid: {', '.join(EXAMPLES)}")
    if name in ("halfspace", "footings"):           # examples with several runs and a figure of their own
        from importlib import import_module

        unknown = set(overrides) - set(SETTINGS)
        if unknown:
            raise TypeError(f"unknown setting(s) {sorted(unknown)}; valid: {', '.join(SETTINGS)}")
        runner = getattr(import_module(f"{__package__}.{name}_example"), f"run_{name}_example")
        return runner(Path(out) if out is not None else Path(name), figures=figures, progress=progress,
                      figure_process=figure_process, **overrides)
    from ..structure.examples import liolios1990

    structure, load, info = liolios1990()
    settings = settings_of({"dt": 1e-3, "t_end": 0.5, "method": "cq", "rule": "bdf2", "lcp": "bpp"}, **overrides)
    return analyse(structure.to_model(), load, settings, Path(out) if out is not None else Path(name),
                   structure=structure, units=UNITS_KN, figure=info["figure2"],
                   title="Liolios (1990), Fig. 2: vertical displacement of node 3",
                   meta={"example": name, "model": "Liolios (1990) section 5, reconstruction in docs/theory.md"},
                   cases=("unilateral", "bilateral"), formats=figures, progress=progress,
                   labels=case_labels(structure_kinds(structure)), point=info["left_edge"],
                   figure_process=figure_process)


#: What each kind of unknown does in the label of the case that lets it act.
_ACTIONS = {"yield": "yield", "friction": "slip", "soil": "uplift", "foundation": "uplift", "gap": "pounding",
            "cable": "slack"}
_ORDER = ("yield", "slip", "uplift", "pounding", "slack", "contact")


def case_labels(kinds) -> dict | None:
    """Legend labels of the cases ``"unilateral"`` and ``"bilateral"`` of a model with unknowns of ``kinds``.

    Parameters
    ----------
    kinds : the kind of each unknown (``"soil"``, ``"gap"``, ``"cable"``, ``"contact"``, ``"yield"``,
        ``"friction"``)

    Returns
    -------
    dict or None
        None without unknowns. The first case is named by what acts (``"with uplift"``,
        ``"with yield, slip and uplift"``; a plain contact is an uplift). The second holds every
        unknown at its initial state: ``"without uplift"`` (contacts only, ``"without pounding"``
        ...), ``"elastic"`` (yield only), ``"no slip"`` (friction only) or
        ``"linear (constraints held)"``.
    """
    kinds = set(kinds)
    if not kinds:
        return None
    actions = sorted({_ACTIONS.get(kind, "uplift") for kind in kinds}, key=_ORDER.index)
    first = actions[0] if len(actions) == 1 else f"{', '.join(actions[:-1])} and {actions[-1]}"
    if not kinds & {"yield", "friction"}:
        return {"unilateral": f"with {first}", "bilateral": f"without {first}"}
    held = {frozenset({"yield"}): "elastic", frozenset({"friction"}): "no slip"}.get(frozenset(kinds),
                                                                                     "linear (constraints held)")
    return {"unilateral": f"with {first}", "bilateral": held}


def _kinds(spec) -> list[str]:
    """The kind of each unknown of a model file: the element's for a contact, else its family."""
    if spec.structure is not None:
        return structure_kinds(spec.structure)
    return list(getattr(getattr(spec.model, "law", None), "kinds", ()))


def structure_kinds(structure) -> list[str]:
    """The kind of each unknown of a frame: the element's for a contact, else its family; then the
    footings' contacts (``"foundation"``) and, for footings that slide, their shears and slips
    (``"friction"``)."""
    footings = structure.foundation
    soil = [] if footings is None else ["foundation"] * footings.m + ["friction"] * (3 * footings.m
                                                                                   if footings.sliding else 0)
    return [e.kind if u.kind == "contact" else u.kind for e, u in structure.constraints] + soil


def _cases(bilateral_reference: bool, unilateral: bool) -> tuple:
    cases = ("unilateral",) if unilateral else ()
    return cases + (("bilateral",) if bilateral_reference or not unilateral else ())


def analyse(model, load, settings, out, *, structure, units, figure, title, meta, cases, labels,
            formats=("png",), progress=None, point=None, storeys=None, figure_process=None, spectra=None,
            model_figure=False, recorders=None) -> dict:
    """Solve ``cases`` (``"unilateral"``, ``"bilateral"``) and write every output to ``out``.

    With ``model_figure`` a frame (``structure``) also gets the model figure ``model.png``, and with
    ``spectra`` (a :class:`~unilateral.analysis.spectra.SpectraSettings`) and a ground motion the
    response spectra (:func:`write_outputs`).

    ``progress(done, total)`` is called with work units over the whole run: ``N`` per case (step
    by step where the march reports) and ``N`` for writing the outputs and figures.

    The output folder is checked (and its staging folder created) before anything is solved, so a
    read-only folder or a path through a file fails at once
    (:class:`~unilateral.io.folder.OutputFolderError`). A case that fails (``success=False``) does
    not stop the run: every case is written as far as it got, and ``success_all`` is False.

    ``figure_process`` (a :class:`~unilateral.figures.background.BackgroundFigures`, optional)
    draws the figures while this process writes the other outputs (:func:`write_outputs`).
    """
    from ..io.folder import OutputFolder
    from ..solve import small_model_blas
    from .outputs import write_outputs

    _steps(settings)                            # dt and t_end checked before the folder
    folder = OutputFolder(out)
    folder.prepare()
    try:
        solved = solve_cases(model, load, settings, cases, progress=progress)
        with small_model_blas(model):           # the results of a small model: tiny products, one thread
            result = write_outputs(folder, solved, structure=structure, units=units, figure=figure, title=title,
                                   meta=meta, labels=labels, model=model, load=load, rule=settings["rule"],
                                   formats=formats, point=point, storeys=storeys, figure_process=figure_process,
                                   spectra=spectra, model_figure=model_figure, recorders=recorders)
    finally:
        folder.close()
    if progress is not None:
        total = _steps(settings) * (len(cases) + 1)
        progress(total, total)
    result["success_all"] = all(sol.success for sol in solved.values())
    return result


def _steps(settings) -> int:
    from .._validate import positive_float
    from ..discretization import step_count

    dt = positive_float("dt", settings["dt"])
    return max(step_count(positive_float("t_end", settings["t_end"]), dt), 1)


def solve_cases(model, load, settings, cases, *, progress=None) -> dict:
    """Solve ``cases`` (``"unilateral"``, ``"bilateral"``) of ``model`` under ``load`` with ``settings``
    (:func:`settings_of`); ``progress(done, total)`` in steps over the cases and the writing after them."""
    from ..solve import solve

    N = _steps(settings)
    total = N * (len(cases) + 1)
    kw = {key: settings[key] for key in SETTINGS}
    solved = {}
    for k, name in enumerate(cases):
        done = k * N
        callback = None if progress is None else (lambda step, _N, done=done: progress(done + step, total))
        solved[name] = solve(model, load, callback=callback, bilateral=(name == "bilateral"), **kw)
        if progress is not None:
            progress((k + 1) * N, total)
    return solved

