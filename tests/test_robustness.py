"""What fuzzing the command line and the model files found: a clear error or a documented behaviour.

Each case was reproduced before it was fixed (a hang, MemoryError, RecursionError, a traceback, a
segmentation fault, an empty or mixed output folder); each test asserts the message's words.
"""

from __future__ import annotations

import errno
import importlib
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import unilateral
from unilateral.cli import main
from unilateral.io import OutputFolder, OutputFolderError, WriteError, open_results
from unilateral.io.files import InputFileError, read_input_bytes
from unilateral.io.folder import MANIFEST
from unilateral.loads.records import read_table
from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.modelfile.build import read_toml
from unilateral.modelfile.errors import Problems

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "liolios1990.toml"
POSIX = pytest.mark.skipif(os.name != "posix", reason="FIFOs, /dev/zero and signals are POSIX")


@contextmanager
def deadline(seconds=20):
    """Fail instead of hanging (a FIFO read blocks forever)."""
    def expired(signum, frame):
        raise TimeoutError(f"still running after {seconds} s: the reader blocked")

    previous = signal.signal(signal.SIGALRM, expired)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def invoke(*args):
    with deadline(120):
        return CliRunner().invoke(main, [str(a) for a in args])


def listing(folder: Path) -> dict:
    """name -> bytes of every file in ``folder``."""
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def leftovers(folder: Path) -> list[str]:
    """Staging folders, old sets and temporary files next to ``folder`` or in it."""
    beside = [p.name for p in folder.parent.iterdir() if p.name.startswith(f".{folder.name}.")]
    inside = [p.name for p in folder.iterdir() if p.name.startswith(".")] if folder.is_dir() else []
    return beside + inside


@pytest.fixture(scope="module")
def previous_run(tmp_path_factory):
    """A complete run of the paper's example: the 'previous results' later runs must not damage."""
    out = tmp_path_factory.mktemp("previous") / "run"
    result = invoke("run", EXAMPLE, "--out", out, "--t-end", "0.05")
    assert result.exit_code == 0, result.output
    return out


# ---------------------------------------------------------------------- 1. input files
@POSIX
def test_a_model_file_that_is_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "model.toml"
    os.mkfifo(fifo)
    result = invoke("run", fifo, "--out", tmp_path / "out")
    assert result.exit_code == 1
    assert f"{fifo}: not a regular file but a named pipe (FIFO); give a regular file" in result.output
    assert not (tmp_path / "out").exists()


@POSIX
@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_a_symlink_to_an_endless_device_is_refused(tmp_path):
    link = tmp_path / "model.toml"
    link.symlink_to("/dev/zero")
    result = invoke("run", link)
    assert result.exit_code == 1
    assert "not a regular file but a symbolic link to /dev/zero, a character device" in result.output
    with deadline(), pytest.raises(Problems, match="symbolic link to /dev/zero"):
        read_toml(link)                          # the reader of study files too


def test_a_model_file_over_the_size_limit_is_refused(tmp_path):
    big = tmp_path / "model.toml"
    with open(big, "wb") as fh:
        fh.truncate(65 << 20)                    # sparse: 65 MiB on paper, nothing on disk
    with pytest.raises(ModelFileError, match=r"model.toml: the file is too large: 65 MiB \(68157440 bytes\), "
                                             r"more than the limit of 64 MiB \(67108864 bytes\)"):
        load_model_file(big)
    with pytest.raises(InputFileError, match=r"more than the limit of 1000 bytes"):
        read_input_bytes(big, limit=1000)


def test_deeply_nested_toml_is_an_error_not_a_recursion_error(tmp_path):
    deep = tmp_path / "model.toml"
    deep.write_text("a = " + "[" * 100_000 + "\n")
    result = invoke("run", deep)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert "model.toml: invalid TOML: arrays or tables nested too deeply to be read" in result.output


@POSIX
def test_records_and_tables_read_only_regular_files(tmp_path):
    fifo = tmp_path / "record.txt"
    os.mkfifo(fifo)
    with deadline(), pytest.raises(InputFileError, match="record.txt: not a regular file but a named pipe"):
        read_table(fifo)
    with pytest.raises(InputFileError, match="not a regular file but a folder"):
        read_table(tmp_path)
    with pytest.raises(FileNotFoundError):       # as before: a missing file is FileNotFoundError
        read_table(tmp_path / "missing.txt")


@POSIX
@pytest.mark.parametrize("kind", ["folder", "fifo"])
def test_a_file_named_in_a_model_file_must_be_a_regular_file(tmp_path, kind):
    text = EXAMPLE.read_text().replace('time_function = { type = "rectangular", t_end = 0.1 }',
                                       'time_function = { type = "table", file = "factors.csv" }')
    assert "factors.csv" in text
    model = tmp_path / "model.toml"
    model.write_text(text)
    (tmp_path / "factors.csv").mkdir() if kind == "folder" else os.mkfifo(tmp_path / "factors.csv")
    what = "a folder" if kind == "folder" else "a named pipe (FIFO)"
    with deadline(), pytest.raises(ModelFileError) as info:
        load_model_file(model)
    assert (f'loads.nodal[0].time_function.file = "factors.csv": not a regular file but {what}; give a '
            f"regular file (looked for {tmp_path / 'factors.csv'})") in str(info.value)


# ---------------------------------------------------------------------- 2. options
@pytest.mark.parametrize("option, value", [("--dt", "0"), ("--dt", "nan"), ("--dt", "-1"), ("--dt", "inf"),
                                           ("--t-end", "inf"), ("--t-end", "0"), ("--t-end", "-0.5")])
def test_time_options_must_be_positive_and_finite(tmp_path, option, value):
    result = invoke("run", EXAMPLE, option, value, "--out", tmp_path / "out")
    assert result.exit_code == 2
    assert f"Invalid value for '{option}': {value} is not a positive finite number; give a number > 0" in result.output
    assert not (tmp_path / "out").exists()
    result = invoke("example", "liolios1990", option, "x", "--out", tmp_path / "out")
    assert result.exit_code == 2 and f"Invalid value for '{option}': 'x' is not a number" in result.output


def test_a_run_too_large_for_the_memory_is_refused_without_a_traceback(tmp_path):
    result = invoke("run", EXAMPLE, "--dt", "1e-9", "--out", tmp_path / "out")     # 1e9 steps: the most allowed
    assert result.exit_code == 1 and not isinstance(result.exception, MemoryError)
    assert "Error: t_end/dt = 1000000000 steps with method='cq' would need about" in result.output
    assert "increase dt, shorten t_end or use method='modal' or 'direct'" in result.output
    assert list(tmp_path.iterdir()) == []        # the staging folder is gone


@pytest.mark.parametrize("key, value", [("dt", 0.0), ("t_end", float("inf")), ("dt", float("nan"))])
def test_python_run_checks_dt_and_t_end_before_dividing(tmp_path, key, value):
    with pytest.raises(ValueError, match=f"{key} must be a positive finite number, got {value!r}"):
        unilateral.run(EXAMPLE, out=tmp_path / "out", figures=(), **{key: value})
    assert not (tmp_path / "out").exists() and not list(tmp_path.iterdir())


# ---------------------------------------------------------------------- 3. a failed case
@pytest.fixture()
def pgs_one_sweep(monkeypatch):
    """PGS limited to one sweep: the rocking example's LCP then fails at a step with contact changes."""
    from unilateral.lcp.pgs import ProjectedGaussSeidel

    monkeypatch.setattr(ProjectedGaussSeidel, "default_max_iter", lambda self, m: 1)


def test_a_failed_unilateral_case_is_reported_and_written(tmp_path, pgs_one_sweep):
    out = tmp_path / "out"
    result = invoke("run", EXAMPLE, "--out", out, "--lcp", "pgs", "--t-end", "0.1")
    assert result.exit_code == 1, result.output
    assert "common time axis" not in result.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["success"] is False
    cases = summary["extra"]["cases"]
    failed, bilateral = cases["unilateral"], cases["bilateral"]
    assert failed["success"] is False and "PGS did not converge in 1 sweeps" in failed["message"]
    assert bilateral["success"] is True and bilateral["steps_computed"] == 100
    assert bilateral["t_reached"] == pytest.approx(0.1)
    k = failed["steps_computed"]
    assert 0 < k < 100
    assert f"unilateral (with uplift) case FAILED at t = {k * 1e-3:.4g} (step {k}): {failed['message']}" in result.output
    assert "what to try: a smaller time step (--dt), another LCP solver (--lcp bpp or lemke)" in result.output
    # the failed case up to where it stopped, the bilateral case whole
    ds = open_results(out / "results.nc")
    v = ds["v"].sel(case="unilateral").values
    assert np.isfinite(v[: k + 1]).all() and np.isnan(v[k + 1:]).all()
    assert ds["steps_computed"].values.tolist() == [k, 100] and ds["success"].values.tolist() == [0, 1]
    assert np.isfinite(ds["u"].sel(case="bilateral").values).all()
    assert len((out / "displacements.csv").read_text().splitlines()) == 1 + (k + 1)
    assert len((out / "bilateral_displacements.csv").read_text().splitlines()) == 1 + 101
    assert np.isfinite(summary["results"]["unilateral"]["base_shear"]["max"])
    assert (out / "fig2.png").stat().st_size > 0
    # and `plot` redraws it
    result = invoke("plot", out / "results.nc", "--out", tmp_path / "figures")
    assert result.exit_code == 0, result.output
    assert (tmp_path / "figures" / "constraints.png").stat().st_size > 0


# ---------------------------------------------------------------------- 4. the output folder
@pytest.fixture()
def no_solving(monkeypatch):
    """Make solving fail loudly: checks of the output folder must come first."""
    def solve(*args, **kwargs):
        raise AssertionError("solved before the output folder was checked")

    monkeypatch.setattr(importlib.import_module("unilateral.solve"), "solve", solve)


def test_an_output_path_through_a_file_fails_before_solving(tmp_path, no_solving):
    (tmp_path / "afile").write_text("x")
    result = invoke("run", EXAMPLE, "--out", tmp_path / "afile" / "sub")
    assert result.exit_code == 2
    assert (f"Invalid value for '--out': cannot write the outputs to {tmp_path / 'afile' / 'sub'}: "
            f"{tmp_path / 'afile'} is a file, not a folder") in result.output
    result = invoke("run", EXAMPLE, "--out", tmp_path / "afile")
    assert result.exit_code == 2 and "Invalid value for '--out'" in result.output and "is a file" in result.output
    with pytest.raises(OutputFolderError, match="is a file, not a folder"):
        unilateral.run(EXAMPLE, out=tmp_path / "afile", figures=())
    assert (tmp_path / "afile").read_text() == "x"


def read_only(monkeypatch, folder: Path):
    """Make ``folder`` read-only; as root (who may write anyway) creating entries in it is refused."""
    folder.chmod(0o555)
    if os.geteuid() != 0:
        return
    itself = str(folder.resolve())
    inside = itself + os.sep

    def guard(real):
        def call(path, *args, **kwargs):
            if os.fspath(path) == itself or os.fspath(path).startswith(inside):
                raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), os.fspath(path))
            return real(path, *args, **kwargs)
        return call

    monkeypatch.setattr(os, "open", guard(os.open))
    monkeypatch.setattr(os, "mkdir", guard(os.mkdir))


def test_a_read_only_output_folder_fails_before_solving(tmp_path, monkeypatch, no_solving):
    out = tmp_path / "out"
    out.mkdir()
    read_only(monkeypatch, out)
    result = invoke("run", EXAMPLE, "--out", out)
    assert result.exit_code == 2
    assert (f"Invalid value for '--out': cannot write the outputs to {out}: it is not writable (Permission "
            "denied)") in result.output
    read_only(monkeypatch, tmp_path)             # a new folder in a read-only one
    result = invoke("run", EXAMPLE, "--out", tmp_path / "new")
    assert result.exit_code == 2
    assert f"cannot write the outputs to {tmp_path / 'new'}: cannot create a folder or a file next to it" \
        in result.output
    monkeypatch.undo()
    tmp_path.chmod(0o755)
    out.chmod(0o755)


def test_a_folder_with_other_files_is_refused_and_left_alone(tmp_path, monkeypatch, no_solving):
    (tmp_path / "model.toml").write_text(EXAMPLE.read_text())
    (tmp_path / "notes.txt").write_text("mine")
    before = listing(tmp_path)
    result = invoke("run", tmp_path / "model.toml", "--out", tmp_path)
    assert result.exit_code == 2
    assert (f"cannot write the outputs to {tmp_path}: it holds files that are not outputs of unilateral "
            "(model.toml, notes.txt); a run replaces the folder's content as a whole") in result.output
    assert listing(tmp_path) == before
    monkeypatch.chdir(tmp_path)
    result = invoke("run", "model.toml", "--out", ".")
    assert result.exit_code == 2 and "it is the current folder or contains it" in result.output


# ---------------------------------------------------------------------- 5. a full disk
def test_a_full_disk_is_a_clear_error_and_keeps_the_previous_results(previous_run, monkeypatch):
    before = listing(previous_run)

    def half_then_enospc(path, data):
        with open(path, "wb") as fh:
            fh.write(bytes(data)[: len(data) // 2])
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr("unilateral.io.results._write_bytes", half_then_enospc)
    result = invoke("run", EXAMPLE, "--out", previous_run, "--t-end", "0.03", "--figures", "none")
    assert result.exit_code == 1
    assert (f"Error: could not write results.nc to {previous_run}: No space left on device; the previous "
            f"outputs in {previous_run} are unchanged") in result.output
    assert listing(previous_run) == before and leftovers(previous_run) == []


def test_save_netcdf_names_the_file_and_the_cause(tmp_path, monkeypatch):
    ds = xr.Dataset({"x": ("t", np.arange(3.0))})

    def full(path, data):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr("unilateral.io.results._write_bytes", full)
    with pytest.raises(WriteError, match=f"could not write a.nc to {tmp_path}: No space left on device") as info:
        unilateral.io.save_netcdf(ds, tmp_path / "a.nc")
    assert info.value.errno == errno.ENOSPC and list(tmp_path.iterdir()) == []
    # a Dataset too large for memory is written by HDF5 after a check of the free space
    monkeypatch.setattr("unilateral.io.results.IN_MEMORY_LIMIT", 0)
    monkeypatch.setattr("shutil.disk_usage", lambda path: type("usage", (), {"free": 1000})())
    with pytest.raises(WriteError, match=r"could not write a.nc to .*: No space left on device \(16 MiB .* needed, "
                                         r"1000 bytes free\)"):
        unilateral.io.save_netcdf(ds, tmp_path / "a.nc")
    monkeypatch.undo()
    monkeypatch.setattr("unilateral.io.results.IN_MEMORY_LIMIT", 0)
    unilateral.io.save_netcdf(ds, tmp_path / "a.nc")
    assert unilateral.io.load_netcdf(tmp_path / "a.nc")["x"].values.tolist() == [0.0, 1.0, 2.0]


@POSIX
def test_a_real_write_failure_in_a_subprocess_does_not_crash(tmp_path):
    """A file size limit (RLIMIT_FSIZE) makes the write of results.nc fail for real, as a full disk
    does: HDF5 writing the file itself crashed with a segmentation fault (rc 139)."""
    resource = pytest.importorskip("resource")
    out = tmp_path / "out"

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

    done = subprocess.run([sys.executable, "-m", "unilateral", "run", str(EXAMPLE), "--out", str(out),
                           "--t-end", "0.2", "--figures", "none", "--method", "direct"],
                          capture_output=True, text=True, timeout=300, preexec_fn=limit)
    assert done.returncode == 1, (done.returncode, done.stderr[-2000:])
    assert f"Error: could not write results.nc to {out}: File too large" in done.stderr
    assert "Traceback" not in done.stderr
    assert list(tmp_path.iterdir()) == []        # neither the folder nor a staging folder


# ---------------------------------------------------------------------- 6. outputs replaced as a set
@pytest.fixture(scope="module")
def two_runs():
    """Two solutions of the example of different lengths (their files differ)."""
    from unilateral.structure.examples import liolios1990

    structure, load, info = liolios1990()
    model = structure.to_model()
    runs = {t_end: {name: unilateral.solve(model, load, dt=1e-3, t_end=t_end, bilateral=(name == "bilateral"))
                    for name in ("unilateral", "bilateral")} for t_end in (0.02, 0.03)}
    return structure, model, load, info, runs


def write(folder, two_runs, t_end, formats=("png",), full=True):
    """The outputs of the run to ``t_end``; ``full=False``: without the structure's results (faster)."""
    from unilateral.analysis import write_outputs

    structure, model, load, info, runs = two_runs
    return write_outputs(folder, runs[t_end], structure=structure, model=model if full else None, load=load,
                         figure=info["figure2"],
                         units={"length": "m", "force": "kN", "time": "s"}, meta={"marker": f"run {t_end}"},
                         formats=formats)


def one_set(folder: Path) -> str:
    """The marker of the run whose complete files ``folder`` holds (fails on a mix)."""
    manifest = json.loads((folder / MANIFEST).read_text())
    assert sorted(p.name for p in folder.iterdir()) == sorted([*manifest["files"], MANIFEST])
    marker = json.loads((folder / "summary.json").read_text())["extra"]["marker"]
    assert open_results(folder / "results.nc").attrs["marker"] == marker
    steps = round(float(marker.split()[1]) / 1e-3)
    for name in ("displacements.csv", "bilateral_constraints.csv", "base.csv"):
        if name in manifest["files"] or name != "base.csv":
            assert len((folder / name).read_text().splitlines()) == 1 + steps + 1, name
    return marker


def interrupt(monkeypatch, when):
    """Raise KeyboardInterrupt (as Ctrl-C does) before a file is written when ``when(names so far)``."""
    import unilateral.io.atomic as atomic

    reserve = atomic._reserve
    calls = []

    def interrupted(target):
        calls.append(target.name)
        if when(calls):
            raise KeyboardInterrupt(f"killed while writing {target.name}")
        return reserve(target)

    monkeypatch.setattr(atomic, "_reserve", interrupted)
    return calls


def test_a_run_interrupted_at_any_file_leaves_the_previous_set(tmp_path, two_runs, monkeypatch):
    out = tmp_path / "out"
    write(out, two_runs, 0.02, formats=(), full=False)
    before = listing(out)
    assert one_set(out) == "run 0.02"
    for k in range(len(before)):                # at every file of the run, the manifest last
        calls = interrupt(monkeypatch, lambda calls, k=k: len(calls) > k)
        with pytest.raises(KeyboardInterrupt):
            write(out, two_runs, 0.03, formats=(), full=False)
        monkeypatch.undo()
        assert listing(out) == before and leftovers(out) == [], calls
    assert calls[-1] == MANIFEST and len(calls) == len(before)
    write(out, two_runs, 0.03, formats=(), full=False)
    assert one_set(out) == "run 0.03" and leftovers(out) == []


def test_a_run_interrupted_at_a_figure_or_the_swap_leaves_the_previous_set(tmp_path, two_runs, monkeypatch):
    out = tmp_path / "out"
    write(out, two_runs, 0.02)
    before = listing(out)
    assert one_set(out) == "run 0.02" and any(name.endswith(".png") for name in before)
    calls = interrupt(monkeypatch, lambda calls: sum(name.endswith(".png") for name in calls) == 2)
    with pytest.raises(KeyboardInterrupt):
        write(out, two_runs, 0.03)
    monkeypatch.undo()
    assert listing(out) == before and leftovers(out) == [], calls
    # the swap itself, with two renames (no renameat2): interrupted between them
    import unilateral.io.folder as folder

    monkeypatch.setattr(folder, "_exchange", lambda a, b: False)
    rename = os.rename

    def second_rename_interrupted(src, dst):
        if Path(src).name.startswith(".out.staging-"):
            raise KeyboardInterrupt("killed between the renames")
        return rename(src, dst)

    monkeypatch.setattr(os, "rename", second_rename_interrupted)
    with pytest.raises(KeyboardInterrupt):
        write(out, two_runs, 0.03, formats=(), full=False)
    monkeypatch.undo()
    assert listing(out) == before and leftovers(out) == []
    # and with no interruption, the new set replaces the old one (both swaps)
    result = write(out, two_runs, 0.03)
    assert one_set(out) == "run 0.03" and leftovers(out) == []
    assert sorted(result["figures"]) == [str(out / name) for name in json.loads((out / MANIFEST).read_text())["files"]
                                         if name.endswith(".png")]
    monkeypatch.setattr(folder, "_exchange", lambda a, b: False)
    write(out, two_runs, 0.02, formats=(), full=False)
    assert one_set(out) == "run 0.02" and leftovers(out) == [] and not list(out.glob("*.png"))


def test_leftovers_of_killed_runs_are_removed_but_not_a_running_one(tmp_path):
    out = tmp_path / "out"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    dead_pid = int(dead.stdout)
    stale = tmp_path / f".out.staging-{dead_pid}-0badc0de"
    stale.mkdir()
    (stale / "results.nc").write_bytes(b"half")
    old = tmp_path / f".out.old-{dead_pid}-0badc0df"       # killed between two renames: out is missing
    old.mkdir()
    (old / "summary.json").write_text("{}")
    running = OutputFolder(out)
    running.prepare()                           # a run in progress (locked)
    assert not stale.exists()
    assert (out / "summary.json").read_text() == "{}" and not old.exists()     # the old set is back
    other = OutputFolder(out)
    other.prepare()
    assert running.staging.is_dir()             # not removed: it is locked
    other.close()
    running.close()
    assert leftovers(out) == []


@POSIX
def test_outputs_killed_by_sigkill_are_one_complete_set(tmp_path):
    """A process replacing a folder's files in a loop, killed by SIGKILL at random times."""
    out = tmp_path / "out"
    child = textwrap.dedent(f"""
        import sys
        from unilateral.io import OutputFolder
        k = 0
        while True:
            k += 1
            with OutputFolder({str(out)!r}) as folder:
                for j in range(20):
                    (folder.staging / f"part{{j}}.csv").write_text(f"{{k}}\\n" * 2000)
                folder.commit()
            if k == 1:
                print("first", flush=True)
        """)
    rng = np.random.default_rng(1990)
    seen = set()
    for _ in range(6):
        proc = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, text=True)
        assert proc.stdout.readline().strip() == "first"
        time.sleep(rng.uniform(0.0, 0.3))
        proc.kill()
        proc.wait()
        proc.stdout.close()
        marks = {(out / f"part{j}.csv").read_text() for j in range(20)}
        assert len(marks) == 1, "a mix of two runs"
        manifest = json.loads((out / MANIFEST).read_text())
        assert sorted(p.name for p in out.iterdir()) == sorted([*manifest["files"], MANIFEST])
        seen.add(marks.pop())
        with OutputFolder(out):                 # removes what the killed run left
            pass
        assert leftovers(out) == []
    assert seen


# ---------------------------------------------------------------------- 7. plot
def foreign_netcdf(path):
    xr.Dataset({"x": ("time", np.arange(3.0))}, coords={"time": np.arange(3.0)}).to_netcdf(path, engine="h5netcdf")


@pytest.mark.parametrize("make, why", [
    (lambda p, run: p.write_bytes((run / "results.nc").read_bytes()[:5000]),
     "it cannot be read, is it truncated or damaged? (OSError: "),
    (lambda p, run: p.write_bytes(b""), "the file is empty"),
    (lambda p, run: foreign_netcdf(p),
     "it is a netCDF file another program wrote (no source attribute; unilateral writes source = 'unilateral "),
    (lambda p, run: xr.Dataset({"x": ("t", [1.0])}).to_netcdf(p, engine="scipy"),
     "it is a netCDF-3 file; unilateral writes netCDF-4 (HDF5)"),
    (lambda p, run: p.write_bytes((run / "summary.json").read_bytes()),
     "it looks like JSON; give the results.nc that `unilateral run` wrote"),
], ids=["truncated", "empty", "foreign", "netcdf3", "summary.json"])
def test_plot_refuses_what_is_not_a_results_nc(tmp_path, previous_run, make, why):
    path = tmp_path / "results.nc"
    make(path, previous_run)
    result = invoke("plot", path, "--out", tmp_path / "figures")
    assert result.exit_code == 2 and "Traceback" not in result.output
    assert f"Error: {path} is not a results.nc written by unilateral: {why}" in result.output
    assert not (tmp_path / "figures").exists()


@POSIX
def test_plot_refuses_a_fifo_without_blocking(tmp_path):
    fifo = tmp_path / "results.nc"
    os.mkfifo(fifo)
    result = invoke("plot", fifo)
    assert result.exit_code == 2
    assert f"{fifo} is not a results.nc written by unilateral: not a regular file but a named pipe" in result.output
