"""The figure process of the command line: the same files as drawn in process, errors raised in the
caller, nothing left running."""

import os
import signal
import subprocess
import sys
import time

import pytest

from unilateral.analysis import write_outputs
from unilateral.figures.background import BackgroundFigures, FigureProcessError
from unilateral.io import WriteError
from unilateral.solve import solve
from unilateral.structure.examples import liolios1990

pytestmark = pytest.mark.skipif(not BackgroundFigures.available(), reason="needs os.fork on Linux")
UNITS = {"length": "m", "force": "kN", "time": "s"}


@pytest.fixture(scope="module")
def cases():
    structure, load, info = liolios1990()
    model = structure.to_model()
    kw = dict(dt=2e-3, t_end=0.1, method="cq")
    solved = {"unilateral": solve(model, load, **kw), "bilateral": solve(model, load, bilateral=True, **kw)}
    return solved, dict(structure=structure, model=model, load=load, units=UNITS, figure=info["figure2"])


def gone(pid) -> bool:
    try:
        os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        return True
    return False


def test_the_figure_process_draws_the_same_files(cases, tmp_path):
    solved, kw = cases
    here = write_outputs(tmp_path / "here", solved, **kw)
    process = BackgroundFigures(preload=("xarray",))
    try:
        there = write_outputs(tmp_path / "there", solved, figure_process=process, **kw)
    finally:
        process.close()
    names = sorted(os.path.basename(p) for p in here["figures"])
    assert names == sorted(os.path.basename(p) for p in there["figures"]) and "fig2.png" in names
    for name in names:
        assert (tmp_path / "here" / name).read_bytes() == (tmp_path / "there" / name).read_bytes(), name
    assert process.pid is None


@pytest.mark.parametrize("shared", ["memory", "pipe"])
def test_the_job_is_handed_over_in_memory_or_by_the_pipe_and_nothing_is_left(cases, tmp_path, monkeypatch,
                                                                             shared):
    import unilateral.figures.background as background

    folder = tmp_path / "shm"
    folder.mkdir()
    if shared == "pipe":                                # no such folder: the pipe carries the job
        folder = tmp_path / "missing"
    monkeypatch.setattr(background, "SHARED_FOLDER", str(folder))
    files, write = [], background._shared_file
    monkeypatch.setattr(background, "_shared_file", lambda data: files.append(write(data)) or files[-1])
    solved, kw = cases
    process = BackgroundFigures()
    try:
        there = write_outputs(tmp_path / "there", solved, figure_process=process, **kw)
    finally:
        process.close()
    assert any(os.path.basename(p) == "fig2.png" for p in there["figures"])
    assert (files[0] is not None) == (shared == "memory")
    assert not folder.exists() or not list(folder.iterdir())         # the file read and removed


def test_a_write_error_in_the_figure_process_is_raised_as_such(cases, tmp_path):
    solved, kw = cases
    out = tmp_path / "out"
    write_outputs(out, solved, formats=(), **kw)
    process = BackgroundFigures()
    try:
        import xarray as xr

        ds = xr.load_dataset(out / "results.nc", engine="h5netcdf")
        blocked = tmp_path / "blocked"
        (blocked / "fig2.png").mkdir(parents=True)         # the figure's name is taken by a folder
        process.submit(ds, blocked, ("png",))
        with pytest.raises(WriteError, match="could not write fig2.png to .*blocked"):
            process.result()
    finally:
        process.close()


def test_a_failure_in_the_figure_process_is_raised_with_its_traceback(tmp_path):
    process = BackgroundFigures()
    try:
        process.submit("not a dataset", tmp_path, ("png",))
        with pytest.raises(FigureProcessError, match="drawing the figures failed: .*Error") as info:
            process.result()
        assert "Traceback" in info.value.details
    finally:
        process.close()


def test_an_unused_figure_process_is_killed_and_reaped():
    process = BackgroundFigures()
    pid = process.pid
    process.close()
    assert process.pid is None and gone(pid)
    process.close()                                         # twice: nothing to do
    with pytest.raises(RuntimeError, match="before submit"):
        process.result()


def test_the_figure_process_dies_with_its_parent():
    code = ("import os, sys; from unilateral.figures.background import BackgroundFigures; "
            "p = BackgroundFigures(); print(p.pid, flush=True); os.kill(os.getpid(), 9)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == -signal.SIGKILL
    pid = int(out.stdout.split()[0])
    deadline = time.monotonic() + 600.0                    # PR_SET_PDEATHSIG: killed at once; a hang guard only
    while _alive(pid):
        if time.monotonic() > deadline:
            pytest.fail(f"the figure process {pid} outlived its parent (600 s)")
        time.sleep(0.05)


def _alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, killed and not yet reaped, does not)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_a_failed_write_stops_the_figure_process_before_the_staging_folder_goes(cases, tmp_path, monkeypatch):
    solved, kw = cases

    def full_disk(ds, path):
        time.sleep(0.3)                                     # the figure process is drawing by now
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("unilateral.analysis.outputs.save_netcdf", full_disk)
    process = BackgroundFigures(preload=("xarray",))
    try:
        with pytest.raises(WriteError, match="No space left"):
            write_outputs(tmp_path / "out", solved, figure_process=process, **kw)
        assert process.pid is None
    finally:
        process.close()
    time.sleep(0.5)                                         # nothing recreates the staging folder
    assert os.listdir(tmp_path) == []
