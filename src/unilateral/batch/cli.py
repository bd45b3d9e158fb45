"""The ``unilateral batch`` command: run a study file on Dask (see ``docs/study-file.md``).

:data:`batch` is a click command; ``python -m unilateral.batch STUDY.toml --out DIR`` runs it too.
"""

from __future__ import annotations

import sys
from pathlib import Path

import click


@click.command(context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("study", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--out", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Output directory (default: the study file's name without .toml, in the current directory).")
@click.option("--scheduler", default=None, metavar="ADDRESS",
              help="Address of a running Dask scheduler (e.g. tcp://host:8786) instead of a local cluster; "
                   "its workers need no access to the study's files (they are sent through Dask).")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Worker processes of the local cluster (default: one per core).")
@click.option("--synchronous", is_flag=True, help="Run the analyses one by one in this process, without Dask "
                                                   "(for debugging).")
@click.option("--retry-failed", is_flag=True, help="Run again the analyses that failed in an earlier run.")
@click.option("--no-figures", is_flag=True, help="Write the table only.")
@click.option("--fsync", is_flag=True, help="Flush every result to disk (survives a crash of the machine, "
                                            "about 8 ms per analysis).")
@click.option("--quiet", "-q", is_flag=True, help="No progress bar.")
def batch(study, out, scheduler, workers, synchronous, retry_failed, no_figures, fsync, quiet):
    """Run every analysis of the study file STUDY (records x intensities x parameters x models).

    The result of each analysis is written to OUT/results/ as soon as it is done (by this
    process: the workers need no access to the files); running the same command again skips what
    is done, so an interrupted study (Ctrl-C, a crash) continues where it stopped. The table of peak quantities goes to OUT/study.nc and OUT/study.csv, the IDA and
    fragility curves to OUT/ida.png and OUT/fragility.png. Exits with status 1 if an analysis
    failed, 130 if interrupted.
    """
    from ..modelfile import ModelFileError
    from .runner import ClusterError, StudyInterrupted, check_workers, run_study
    from .study import load_study

    out = out if out is not None else Path(study.stem)
    try:
        check_workers(workers)
        spec = load_study(study, announce=None if quiet else lambda size: click.echo(
            f"{study}: {size.describe()}", err=True))
    except ClusterError as exc:
        raise click.BadParameter(str(exc), param_hint="--workers") from None
    except ModelFileError as exc:
        raise click.ClickException(str(exc)) from None
    if not quiet:
        click.echo(f"{study}: {len(spec.analyses)} analyses ({len(spec.variants)} model variant(s) x "
                   f"{max(len(spec.records), 1)} record(s) x "
                   f"{len(spec.document.scaling.values) if spec.document.scaling else 1} level(s)) read; "
                   f"results in {out}/", err=True)
    try:
        result = run_study(spec, out, scheduler=scheduler, workers=workers, synchronous=synchronous,
                           progress=not quiet, retry_failed=retry_failed, figures=not no_figures,
                           fsync=fsync)
    except ClusterError as exc:
        raise click.BadParameter(str(exc), param_hint="--scheduler") from None
    except StudyInterrupted as exc:
        done = len(spec.analyses) - exc.result.counts.get("pending", 0)
        click.echo(f"interrupted: {done} of {len(spec.analyses)} analyses done and kept in {out}/results/; "
                   "run the same command again to continue", err=True)
        sys.exit(130)
    click.echo(result.summary(), err=quiet is False)
    for path in result.figures:
        click.echo(f"figure: {path}", err=True)
    collapsed = int((result.table["collapse"].values == 1).sum()) if "collapse" in result.table else 0
    if collapsed:                                       # a result, not a failure: the exit status stays 0
        click.echo(f"{collapsed} of {len(spec.analyses)} analyses: the structure collapsed (columns collapse and "
                   f"collapse_reason of {out / 'study.csv'})", err=True)
    failures = sum(result.counts.get(s, 0) for s in ("failed", "error", "timeout"))
    if failures:
        click.echo(f"{failures} of {len(spec.analyses)} analyses failed: see the status and message columns "
                   f"of {out / 'study.csv'}", err=True)
        sys.exit(1)
