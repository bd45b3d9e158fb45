"""The ``unilateral`` command line.

Imports are lazy: this module imports click only, so ``unilateral --help`` and option errors
answer at once; numpy, scipy, numba, xarray and matplotlib are imported when a command needs them.
The names of methods, rules and LCP solvers are listed here (``tests/test_figures_cli.py`` checks
them against the registries) so that a wrong ``--lcp`` fails before anything heavy is loaded.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import click

from . import _LCP_NAMES, _MATRIX_METHOD_NAMES, _RULE_NAMES, __version__

EXAMPLES = ("liolios1990", "halfspace", "footings")                          # unilateral.analysis.run.EXAMPLES
METHOD_NAMES = _MATRIX_METHOD_NAMES                              # unilateral.methods.MATRIX_METHOD_NAMES
RULE_NAMES = tuple(sorted(_RULE_NAMES))                          # unilateral.rules.RULES
LCP_NAMES = _LCP_NAMES                                           # unilateral.lcp.LCP_SOLVERS
FIGURE_FORMATS = ("png", "pdf", "svg")


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="unilateral")
def main():
    """Dynamics of structures with unilateral constraints (Liolios 1990).

    Foundations that lift off tensionless soil, gaps that close and open, cables that go slack:
    the problem is reduced to the unilateral unknowns and solved as a convolutional linear
    complementarity problem, one small LCP per time step.
    """


def _figure_formats(ctx, param, value):
    if value is None:
        return ("png",)
    parts = [p.strip().lower() for p in value.split(",") if p.strip()]
    if parts == ["none"]:
        return ()
    bad = [p for p in parts if p not in FIGURE_FORMATS]
    if bad or not parts:
        raise click.BadParameter(f"{value!r}: give a comma-separated list of {', '.join(FIGURE_FORMATS)}, "
                                 "or none", ctx=ctx, param=param)
    return tuple(dict.fromkeys(parts))


def _method(ctx, param, value):
    """A method name: the common ones without importing anything; others from the registry."""
    if value is None or value in METHOD_NAMES:
        return value
    from .methods import MATRIX_METHOD_NAMES

    if value not in MATRIX_METHOD_NAMES:
        raise click.BadParameter(f"{value!r} is not one of {', '.join(map(repr, MATRIX_METHOD_NAMES))}",
                                 ctx=ctx, param=param)
    return value


class PositiveFinite(click.ParamType):
    """A click parameter: a finite number > 0 (a time step, an end time)."""

    name = "positive number"

    def __init__(self, example: str):
        self.example = example

    def convert(self, value, param, ctx):
        try:
            x = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number; give a positive finite number, e.g. {self.example}", param, ctx)
        if not math.isfinite(x) or x <= 0.0:
            self.fail(f"{value} is not a positive finite number; give a number > 0, e.g. {self.example}", param, ctx)
        return x


def _analysis_options(function):
    options = [
        click.option("--method", default=None, callback=_method, metavar="[" + "|".join(METHOD_NAMES) + "]",
                     help="auto: the fastest correct method; cq: the paper's convolutional LCP; "
                          "modal: the same with a recursive history; direct: full-model time stepping; "
                          "event: exact integration between contact changes (small models, exact loads). "
                          "Default: cq for examples, the model file's [analysis] method for run."),
        click.option("--rule", type=click.Choice(RULE_NAMES), default=None,
                     help="Time discretisation (default bdf2; newmark is Newmark(1/2, 1/4), the trapezoidal rule, "
                          "and runs as trapezoidal with a note; hht needs --method direct)."),
        click.option("--dt", type=PositiveFinite("0.001"), default=None, help="Time step [time unit of the model]."),
        click.option("--t-end", "t_end", type=PositiveFinite("1.0"), default=None, help="End time."),
        click.option("--lcp", type=click.Choice(LCP_NAMES), default=None, help="LCP solver (default bpp)."),
        click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
                     help="Output directory."),
        click.option("--figures", "formats", default=None, callback=_figure_formats, metavar="FORMATS",
                     help="Figure formats: png (default), pdf, svg, comma-separated, or none."),
    ]
    for option in reversed(options):
        function = option(function)
    return function


@main.command()
@click.argument("name", type=click.Choice(EXAMPLES))
@_analysis_options
def example(name, method, rule, dt, t_end, lcp, out, formats):
    """Run a built-in example, with and without uplift, and write results and figures.

    liolios1990: the paper's example (a mass on a column on a rigid foundation resting on
    three tensionless spring-dashpot soil elements, gravity and a horizontal pulse). Writes
    results.nc, CSV tables, summary.json and the paper's Fig. 2 to OUT (default ./liolios1990).

    halfspace: the same tower on a rigid footing on the paper's soil, on cones and on the elastic
    half-space, under the pulse and a synthetic earthquake; adds halfspace.png (uplift, rocking and
    contact pressure side by side) to OUT (default ./halfspace). Its results.nc holds the
    half-space under the earthquake, and results_<soil>_<load>.nc every run: `unilateral plot`
    redraws halfspace.png from them.

    footings: a two-bay frame on two footings on one soil (a soft layer over stiffer ground), with
    yielding beam hinges, under a synthetic earthquake; adds footings.png (uplift, footing forces
    and roof drift with the footings interacting through the ground and without) to OUT.
    """
    overrides = dict(method=method, rule=rule, dt=dt, t_end=t_end, lcp=lcp)
    _run(lambda progress, figure_process: _analysis().run_example(
        name, out or Path(name), figures=formats, progress=progress, figure_process=figure_process, **overrides),
        out or Path(name), overrides, figures=bool(formats))


@main.command()
@click.argument("model_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@_analysis_options
@click.option("--bilateral", is_flag=True, help="Hold every constraint bilateral (no uplift) only.")
@click.option("--histories", type=click.Choice(("auto", "key", "full")), default=None,
              help="What is written: every history (full), the key ones (key), or by the run's size (auto, the "
                   "default); replaces [output] histories.")
def run(model_file, method, rule, dt, t_end, lcp, out, formats, bilateral, histories):
    """Analyse the structure described by MODEL_FILE (TOML; see docs/model-file.md)."""
    overrides = dict(method=method, rule=rule, dt=dt, t_end=t_end, lcp=lcp)
    if histories is not None:
        overrides["output"] = {"histories": histories}
    target = out or Path(model_file.stem)
    try:
        check_model_file(model_file)
    except ValueError as exc:
        raise click.ClickException(str(exc)) from None
    _run(lambda progress, figure_process: _analysis().run_model_file(
        model_file, target, bilateral=bilateral, figures=formats, progress=progress, figure_process=figure_process,
        **overrides), target, overrides, figures=bool(formats))


def check_model_file(path: Path) -> None:
    """Check the model file ``path`` at once: everything that can be found without building it.

    A file that cannot be read, a TOML syntax error (with its line and column), a wrong key or value
    (``unilateral[0].kk: unknown key``, ``k = -2e5: must be > 0``) and the cross checks (a node, a beam
    or a file that does not exist, a duplicate name, keys that go together) raise the
    :class:`~unilateral.modelfile.ModelFileError` that :func:`~unilateral.modelfile.load_model_file`
    raises for them (it runs the same checks, :mod:`unilateral.modelfile.checks`), before numpy, scipy,
    numba, xarray or matplotlib are imported (pydantic only). What needs the structure or the data of
    the files (a mechanism, a record that cannot be read) is left to ``load_model_file``.
    """
    from .modelfile.checks import check_file

    check_file(path)


@main.command()
@click.argument("results", required=False, type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--model", "model_file", type=click.Path(exists=True, dir_okay=False, path_type=Path), default=None,
              metavar="MODEL.toml", help="Draw the model figure (model.png) of a model file instead of RESULTS.")
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Output directory (default: the folder of RESULTS; with --model the current directory).")
@click.option("--figures", "formats", default=None, callback=_figure_formats, metavar="FORMATS",
              help="Figure formats: png (default), pdf, svg, comma-separated, or none.")
@click.option("--animate", is_flag=True, default=False,
              help="Also the motion of a 2-D frame: deformed_shape.png (at the peak drift) and motion.gif.")
@click.option("--case", default="unilateral", show_default=True, help="The case the motion shows (with --animate).")
def plot(results, model_file, out, formats, animate, case):
    """Draw the figures of a results.nc written by `run` or `example` (the same files they drew).

    The figures are drawn into a hidden folder in OUT and moved in only when all are drawn, so a
    failure (a full disk) leaves OUT as it was; in a run's folder they join the files its
    manifest.json lists. A figure the file cannot give (a variable missing, an attribute that
    names nothing) is skipped with the reason and the others are drawn; the exit code is then 1.

    With --model MODEL.toml (and no RESULTS): the model figure model.png of the file, without
    solving anything: the nodes, elements, unilateral elements and footings with their names, and
    the first mode shapes of the bilateral structure.
    """
    if (results is None) == (model_file is None):
        raise click.UsageError("give either RESULTS (a results.nc) or --model MODEL.toml")
    if model_file is not None:
        _plot_model(model_file, out or Path("."), formats)
        return
    from .figures import FigureDataError
    from .io.atomic import WriteError
    from .io.results import ResultsFileError

    target = out or results.parent
    try:
        paths, skipped, note = _plot(results, target, formats)
    except ResultsFileError as exc:
        raise _UsageFailure(str(exc)) from None
    except FigureDataError as exc:
        raise click.ClickException(f"cannot draw the figures of {results}: {exc}") from None
    except (WriteError, OSError) as exc:
        raise click.ClickException(f"cannot write the figures to {target}: {exc}; {target} is unchanged") from None
    if animate:
        paths = paths + _plot_motion(results, target, case)
    for path in paths:
        click.echo(path)
    for line in ([note] if note else []) + [f"skipped {text}" for text in skipped]:
        click.echo(line, err=True)
    if skipped:
        sys.exit(1)


def _plot_motion(results: Path, target: Path, case: str) -> list[Path]:
    """``unilateral plot --animate``: deformed_shape.png and motion.gif of ``case`` into ``target``."""
    import xarray as xr

    from .figures import FigureDataError
    from .figures.motion import animate, deformed_shape_figure
    from .io.atomic import atomic_write

    try:
        with xr.open_dataset(results) as ds:
            ds.load()
        shape = target / "deformed_shape.png"
        fig = deformed_shape_figure(ds, case)
        atomic_write(shape, lambda tmp: fig.savefig(tmp))
        return [shape, animate(ds, target / "motion.gif", case=case)]
    except FigureDataError as exc:
        raise click.ClickException(f"cannot draw the motion of {results}: {exc}") from None


def _plot_model(model_file: Path, target: Path, formats) -> None:
    """``unilateral plot --model``: check and read the model file, draw model.png into ``target``."""
    try:
        check_model_file(model_file)                # before the imports: a wrong file fails at once
    except ValueError as exc:                   # ModelFileError: the file's problems, one per line
        raise click.ClickException(str(exc)) from None
    from .io.atomic import WriteError

    try:
        from .figures.model import model_file_drawing
        from .figures.replot import replot_model

        paths = replot_model(model_file_drawing(model_file), target, formats)
    except (WriteError, OSError) as exc:
        raise click.ClickException(f"cannot write the model figure to {target}: {exc}; {target} is unchanged") from None
    except ValueError as exc:                   # ModelFileError: the file's problems, one per line
        raise click.ClickException(str(exc)) from None
    for path in paths:
        click.echo(path)


def _plot(results, target, formats):
    """Read ``results`` and draw its figures into ``target``: the files, the figures skipped and a note
    (None, or where the drawing stops because ``u`` or ``v`` are not finite after it)."""
    from .analysis.outputs import figure_view
    from .figures.replot import replot
    from .io.results import open_results, without_dask_arrays

    with without_dask_arrays():
        ds = open_results(results)
        view = figure_view(ds)
        paths, skipped = replot(view, target, formats)
    note = None
    if view.sizes["time"] < ds.sizes["time"]:
        note = (f"drawn up to t = {float(view['time'].values[-1]):g}: after it u or v are not finite "
                "(a case that stopped early, or inf in the file)")
    return paths, skipped, note


@main.command()
@click.argument("script", type=click.Path(exists=True, dir_okay=False, path_type=Path))
def opensees(script):
    """Run an OpenSees script with this library's OpenSees commands (unilateral.opensees).

    SCRIPT is a Tcl script (model.tcl, run by Python's Tcl interpreter) or an OpenSeesPy script
    (model.py, its openseespy.opensees being unilateral.opensees). Files are read and written
    relative to the current directory, as OpenSees does. A command outside the subset stops the
    script with a message naming it, why and the nearest alternative (docs/opensees.md).
    """
    from .opensees import OpenSeesRefused
    from .opensees.tcl import run_script

    try:
        run_script(script)
    except (OpenSeesRefused, RuntimeError) as exc:
        raise click.ClickException(str(exc)) from None


@main.command()
@click.argument("script", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--out", type=click.Path(dir_okay=False, path_type=Path), default=None, metavar="OUT.toml",
              help="The model file to write (default: SCRIPT with the suffix .toml); its records and tables are "
                   "written beside it (OUT.ground<tag>.txt, OUT.pattern<tag>.txt).")
@click.option("--force", is_flag=True, help="Replace OUT and its records and tables if they exist.")
def convert(script, out, force):
    """Write the model of an OpenSees script (structure, loads, analysis) as a model file.

    SCRIPT (model.py, OpenSeesPy; model.tcl, Tcl) runs on unilateral.opensees as `unilateral
    opensees` runs it; its main analysis (the first transient one, after any static gravity
    analysis, or a DisplacementControl pushover) becomes the model file's [analysis]. The file is
    read back and its model checked against the script's before anything is written. A command
    the model file cannot express is refused, naming it (docs/opensees.md, Conversion).
    """
    out = out or script.with_suffix(".toml")
    if script.suffix.lower() not in (".py", ".tcl"):
        raise click.BadParameter(f"{script}: an OpenSees script is a .py (OpenSeesPy) or a .tcl file",
                                 param_hint="'SCRIPT'")
    if out.suffix.lower() != ".toml":
        raise click.BadParameter(f"{out}: a model file ends in .toml", param_hint="'-o' / '--out'")
    if out.exists() and not force:
        raise click.ClickException(f"{out} exists: give --force to replace it")
    from .opensees import OpenSeesRefused
    from .opensees.convert import convert_script

    try:
        result = convert_script(script, out, force=force)
    except (OpenSeesRefused, RuntimeError, ValueError, OSError) as exc:
        raise click.ClickException(str(exc)) from None
    for path in [result["path"], *result["files"]]:
        click.echo(path)
    click.echo(f"{result['kind']} analysis of {result['steps']} steps: unilateral run {result['path']}", err=True)


@main.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True,
                                "help_option_names": []})
@click.pass_context
def bench(ctx):
    """Run the benchmark suite (options: see `unilateral bench --help`; `--quick` for a smoke run).

    Times every method on the paper's example, a tower under an earthquake record and beams on a
    tensionless Winkler foundation; prints a table and writes JSON and a scaling figure.
    """
    from .bench.__main__ import main as bench_main

    sys.exit(bench_main(ctx.args))


def _register_batch():
    """``unilateral batch``: imported here, the batch package imports Dask only when it runs."""
    from .batch.cli import batch

    main.add_command(batch, name="batch")


_register_batch()


# ---------------------------------------------------------------------- helpers
def _analysis():
    from . import analysis

    return analysis


def _run(call, out, overrides, *, figures):
    """Run an analysis with a progress bar, print the report; exit 1 if a case failed.

    ``call(progress, figure_process)`` runs it. With ``figures``, a process forked first (before
    the heavy imports) imports the figure code and later draws the figures while this one writes
    the other outputs (:class:`~unilateral.figures.background.BackgroundFigures`).
    """
    started = time.perf_counter()
    figure_process = _figure_process() if figures else None
    bar = _ProgressBar() if sys.stderr.isatty() else None
    from .figures.background import FigureProcessError
    from .io.atomic import WriteError
    from .io.folder import OutputFolderError
    from .march.policy import COMMAND_LINE, size_policy

    try:
        with size_policy(COMMAND_LINE):     # short runs in Python: a CLI process would spend 1-1.5 s loading numba
            result = call(bar, figure_process)          # results.nc is written without xarray (nor pandas, dask)
    except OutputFolderError as exc:
        raise click.BadParameter(str(exc), param_hint="'--out'") from None
    except WriteError as exc:
        raise click.ClickException(f"{exc}; the previous outputs in {out} are unchanged") from None
    except (ValueError, TypeError, FigureProcessError) as exc:
        raise click.ClickException(str(exc)) from None
    except MemoryError as exc:                  # solve() refuses runs that would not fit, with the figures
        raise click.ClickException(str(exc) or "out of memory: increase --dt or shorten --t-end") from None
    finally:
        if figure_process is not None:
            figure_process.close()
        if bar is not None:
            bar.close()
    report = result["report"] if "report" in result else _analysis().report(result)   # a pushover's own
    click.echo(report)
    click.echo(f"results in {out}/ ({time.perf_counter() - started:.2f} s)")
    if not result.get("success_all", True):
        sys.exit(1)


def _figure_process():
    """A :class:`~unilateral.figures.background.BackgroundFigures`, or None where it cannot fork."""
    from .figures.background import BackgroundFigures

    return BackgroundFigures() if BackgroundFigures.available() else None


class _UsageFailure(click.ClickException):
    """An error in what the user gave (a wrong file): exit code 2, like click's usage errors."""

    exit_code = 2


class _ProgressBar:
    """A one-line progress bar on stderr with the ETA of the whole run (cases and writing).

    It appears only for runs longer than a second, and redraws at most ten times a second. The ETA
    comes from the rate since the first report (the set-up before it, imports and factorisations,
    says nothing about the steps) and is shown once 1 % of the steps have been timed ("ETA ?"
    before). ``clock``: a function giving seconds (tests pass their own).
    """

    def __init__(self, width=30, clock=time.perf_counter):
        self.clock = clock
        self.start = clock()
        self.width = width
        self.last = 0.0
        self.first = None                   # (time, done) of the first report
        self.shown = False

    def __call__(self, done, total):
        now = self.clock()
        elapsed = now - self.start
        if self.first is None:
            self.first = (now, done)
        if elapsed < 1.0 or (now - self.last < 0.1 and done < total) or total <= 0:
            return
        self.last = now
        frac = min(done / total, 1.0)
        filled = int(self.width * frac)
        sys.stderr.write(f"\r[{'#' * filled}{'.' * (self.width - filled)}] {100 * frac:5.1f}%  "
                         f"elapsed {elapsed:5.1f} s  ETA {self.eta(now, done, total)} ")
        sys.stderr.flush()
        self.shown = True

    def eta(self, now, done, total) -> str:
        """The time left at the rate since the first report, or "?" before 1 % of the steps."""
        t0, done0 = self.first
        timed = done - done0
        if timed < 0.01 * total or now <= t0:
            return "    ?"
        return f"{(now - t0) / timed * (total - done):5.1f} s"

    def close(self):
        if self.shown:
            sys.stderr.write("\n")
            sys.stderr.flush()
