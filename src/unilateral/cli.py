"""The ``unilateral`` command line."""

from __future__ import annotations

import sys
from contextlib import contextmanager
from pathlib import Path

import click

from . import __version__
from .rules import RULES
from .methods import MATRIX_METHOD_NAMES

EXAMPLES = ("liolios1990",)
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="unilateral")
def main():
    """Dynamics of structures with unilateral constraints (Liolios 1990).

    Foundations that lift off tensionless soil, gaps that close and open, cables that go slack:
    the problem is reduced to the unilateral unknowns and solved as a convolutional linear
    complementarity problem, one small LCP per time step.
    """


def _analysis_options(function):
    options = [
        click.option("--method", type=click.Choice(MATRIX_METHOD_NAMES), default=None,
                     help="auto: the fastest correct method; cq: the paper's convolutional LCP; "
                          "modal: the same with a recursive history; direct: full-model time stepping. "
                          "Default: cq for examples, the model file's [analysis] method for run."),
        click.option("--rule", type=click.Choice(sorted(RULES)), default=None,
                     help="Time discretisation (default bdf2; newmark and hht need --method direct)."),
        click.option("--dt", type=float, default=None, help="Time step [time unit of the model]."),
        click.option("--t-end", "t_end", type=float, default=None, help="End time."),
        click.option("--lcp", default=None, help="LCP solver: bpp (default), lemke, pgs, newton, enumerate."),
        click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
                     help="Output directory."),
    ]
    for option in reversed(options):
        function = option(function)
    return function


@main.command()
@click.argument("name", type=click.Choice(EXAMPLES))
@_analysis_options
def example(name, method, rule, dt, t_end, lcp, out):
    """Run a built-in example, with and without uplift, and write results and figures.

    liolios1990: the paper's example (a mass on a column on a rigid foundation resting on
    three tensionless spring-dashpot soil elements, gravity and a horizontal pulse). Writes
    results.nc, CSV tables, summary.json and the paper's Fig. 2 to OUT (default ./liolios1990).
    """
    from .structure.examples import liolios1990

    structure, load, info = liolios1990()
    settings = _settings({"dt": 1e-3, "t_end": 0.5, "method": "cq", "rule": "bdf2", "lcp": "bpp"},
                         method=method, rule=rule, dt=dt, t_end=t_end, lcp=lcp)
    fig = info["figure2"]
    _run(structure.to_model(), load, settings, out or Path(name), structure=structure,
         units=UNITS_KN, figure=fig, title="Liolios (1990), Fig. 2: vertical displacement of node 3",
         meta={"example": name, "model": "Liolios (1990) section 5, reconstruction in docs/theory.md"},
         bilateral_reference=True, unilateral=True,
         labels={"unilateral": "with uplift", "bilateral": "without uplift"})


@main.command()
@click.argument("model_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@_analysis_options
@click.option("--bilateral", is_flag=True, help="Hold every constraint bilateral (no uplift) only.")
def run(model_file, method, rule, dt, t_end, lcp, out, bilateral):
    """Analyse the structure described by MODEL_FILE (TOML; see docs/model-file.md)."""
    from .modelfile import ModelFileError, load_model_file

    try:
        spec = load_model_file(model_file)
    except ModelFileError as exc:
        raise click.ClickException(str(exc)) from None
    a = spec.analysis
    settings = _settings(a, method=method, rule=rule, dt=dt, t_end=t_end, lcp=lcp)
    _run(spec.model, spec.load, settings, out or Path(model_file.stem), structure=spec.structure,
         units=spec.units, figure=spec.figure, title=a.get("title") or model_file.stem,
         meta={"model_file": str(model_file)},
         bilateral_reference=bool(a.get("bilateral_reference", True)) and not bilateral,
         unilateral=not bilateral, labels=None)


@main.command()
@click.argument("results", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Output directory (default: the folder of RESULTS).")
def plot(results, out):
    """Draw the figures of a results.nc written by `run` or `example`."""
    from .io import from_dataset, load_netcdf
    from .figures import plot_constraints, plot_displacement, save_figure

    ds = load_netcdf(results)
    out = out or results.parent
    out.mkdir(parents=True, exist_ok=True)
    cases = ({str(c): from_dataset(ds.sel(case=c)) for c in ds["case"].values} if "case" in ds.dims
             else {"unilateral": from_dataset(ds)})
    units = {key: ds.attrs[f"units_{key}"] for key in ("length", "force", "time") if f"units_{key}" in ds.attrs}
    written = []
    for name, sol in cases.items():
        if sol.v.shape[1]:
            written += save_figure(plot_constraints(sol, units=units or None), out / f"constraints_{name}")
    node, dof = ds.attrs.get("figure_node"), ds.attrs.get("figure_dof")
    if node is not None and "node_displacement" in ds:
        nd = ds["node_displacement"].sel(node=str(node), component=dof)
        curves = ({str(c): (ds["time"].values, nd.sel(case=c).values) for c in ds["case"].values}
                  if "case" in nd.dims else {"": (ds["time"].values, nd.values)})
        fig = plot_displacement(curves, ylabel=f"{dof} of node {node}", title=ds.attrs.get("title"))
        written += save_figure(fig, out / "fig2")
    for path in written:
        click.echo(path)


@main.command(context_settings={"ignore_unknown_options": True, "allow_extra_args": True,
                                "help_option_names": []})
@click.pass_context
def bench(ctx):
    """Run the benchmark suite (options: see `unilateral bench --help`; `--quick` for CI).

    Times every method on the paper's example, a tower under an earthquake record and beams on a
    tensionless Winkler foundation; prints a table and writes JSON and a scaling figure.
    """
    from .bench.__main__ import main as bench_main

    sys.exit(bench_main(ctx.args))


# ---------------------------------------------------------------------- helpers
def _settings(defaults: dict, **given) -> dict:
    out = {key: defaults.get(key) for key in ("dt", "t_end", "method", "rule", "lcp", "initial")}
    out["initial"] = out["initial"] or "static"
    out.update({key: value for key, value in given.items() if value is not None})
    return out


def _run(model, load, settings, out, *, structure, units, figure, title, meta,
         bilateral_reference, unilateral, labels):
    from .analysis import report, run_cases, write_outputs

    N = int(round(settings["t_end"] / settings["dt"]))
    click.echo(f"unilateral {__version__}: n = {model.n} DOFs, m = {model.m} unilateral constraints, "
               f"{N} steps of {settings['dt']:g}, method {settings['method']}, rule {settings['rule']}")
    try:
        with _progress(N, "unilateral" if unilateral else "bilateral") as progress:
            cases = run_cases(model, load, bilateral_reference=bilateral_reference,
                              unilateral=unilateral, progress=progress, **settings)
        meta = dict(meta, title=title)
        if figure is not None:
            meta.update(figure_node=str(figure["node"]), figure_dof=figure["dof"])
        result = write_outputs(out, cases, structure=structure, units=units, figure=figure,
                               title=title, meta=meta, labels=labels)
    except (ValueError, TypeError) as exc:
        raise click.ClickException(str(exc)) from None
    click.echo(report(result))
    click.echo(f"results in {out}/")
    if not all(sol.success for sol in cases.values()):
        sys.exit(1)


@contextmanager
def _progress(N, label):
    """A progress bar on a terminal for runs of more than a few seconds; silent otherwise."""
    if N < 2000 or not sys.stderr.isatty():
        yield None
        return
    with click.progressbar(length=N, label=label, file=sys.stderr) as bar:
        yield lambda k, total: bar.update(1)
