"""Figures drawn by a forked process while the caller writes the other outputs.

A run of the command line spends as long drawing its figures (importing matplotlib, then about
0.2 s per figure) as solving and writing everything else. :class:`BackgroundFigures` forks a
process at the start of the run, which imports the figure code while the caller solves, then
draws the figures of the Dataset it is sent (:func:`unilateral.figures.results.draw_figures`, the
same code and files as in process) while the caller writes ``results.nc``, the tables and the
summary. On a machine with two cores this takes the figures off the run's critical path.

Only on Linux (``fork``; the child is killed with its parent, ``PR_SET_PDEATHSIG``); elsewhere
:meth:`BackgroundFigures.available` is False and the caller draws in process. The child never
returns into the caller's code: it leaves by :func:`os._exit`, and a failure is sent back and
raised by :meth:`BackgroundFigures.result` (a :class:`~unilateral.io.atomic.WriteError` as such).
"""

from __future__ import annotations

import contextlib
import importlib
import os
import pickle
import signal
import sys
import traceback
from pathlib import Path

from ..io.atomic import WriteError


class FigureProcessError(RuntimeError):
    """The figure process failed; ``details`` holds its traceback."""

    def __init__(self, message: str, details: str = ""):
        super().__init__(message)
        self.details = details


class BackgroundFigures:
    """A forked process that draws the figures of one run.

    Use: ``figures = BackgroundFigures()`` (forks), later ``figures.submit(ds, out, formats)``,
    write the other outputs, then ``paths = figures.result()``; ``figures.close()`` in a
    ``finally`` (kills the process if it was never used or the run failed).

    Parameters
    ----------
    preload : names of modules the process imports while it waits, e.g. ``("xarray",)`` to
        unpickle a Dataset at once (the figure code itself is always imported)
    """

    def __init__(self, preload=()):
        if not self.available():
            raise RuntimeError("BackgroundFigures needs os.fork on Linux; draw in process instead")
        job_read, self._job = os.pipe()
        self._reply, reply_write = os.pipe()
        for stream in (sys.stdout, sys.stderr):
            stream.flush()
        parent = os.getpid()
        self.pid = os.fork()
        if self.pid == 0:                       # the child: never returns
            os.close(self._job)
            os.close(self._reply)
            _child(job_read, reply_write, parent, preload)
        os.close(job_read)
        os.close(reply_write)
        self._submitted = False
        self._shared = None

    @staticmethod
    def available() -> bool:
        """True where the figures can be drawn by a forked process (Linux)."""
        return sys.platform.startswith("linux") and hasattr(os, "fork")

    def submit(self, ds, out_dir, formats) -> None:
        """Send the Dataset to draw and where to (``out_dir``, ``formats`` of ``draw_figures``).

        ``ds``: an :class:`xarray.Dataset` or a :class:`unilateral.io.dataset.Dataset` (neither process
        then imports xarray)."""
        data = pickle.dumps((ds, str(out_dir), tuple(formats)), protocol=pickle.HIGHEST_PROTOCOL)
        self._shared = _shared_file(data)
        with os.fdopen(self._job, "wb") as pipe:
            pipe.write(b"F" + os.fsencode(self._shared) if self._shared else b"P" + data)
        self._job = None
        self._submitted = True

    def result(self) -> list[Path]:
        """Wait for the figures; return the files written, or raise what the process raised."""
        if not self._submitted:
            raise RuntimeError("BackgroundFigures.result() before submit()")
        with os.fdopen(self._reply, "rb") as pipe:
            data = pipe.read()
        self._reply = None
        _, status = os.waitpid(self.pid, 0)
        self.pid = None
        self._remove_shared()
        if not data:
            raise FigureProcessError(f"the figure process ended without a result ({_status_text(status)})")
        kind, value = pickle.loads(data)
        if kind == "ok":
            return [Path(p) for p in value]
        if kind == "write_error":
            path, errno_, reason = value
            raise WriteError(path, OSError(errno_, reason))
        message, details = value
        raise FigureProcessError(f"drawing the figures failed: {message}", details)

    def close(self) -> None:
        """Release the pipes; kill and reap the process if it is still running."""
        for fd in (self._job, self._reply):
            if fd is not None:
                os.close(fd)
        self._job = self._reply = None
        if self.pid is not None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            os.waitpid(self.pid, 0)
            self.pid = None
        self._remove_shared()

    def _remove_shared(self) -> None:
        """Remove the file the job was handed over in, if the process has not (it died first)."""
        if getattr(self, "_shared", None):
            with contextlib.suppress(OSError):
                os.unlink(self._shared)
        self._shared = None


#: Where a job is handed over: a file in memory (tmpfs), read by the process at the speed of memory,
#: where the pipe takes 0.2 s for the 80 MB of a 3000-step frame (its 64 KiB swapped 1200 times).
SHARED_FOLDER = "/dev/shm"


def _shared_file(data: bytes) -> str | None:
    """Write ``data`` to a new file in :data:`SHARED_FOLDER`: its path, or None (the pipe then carries
    it) where there is no such folder or it cannot hold the data."""
    import tempfile

    if not os.path.isdir(SHARED_FOLDER):
        return None
    path = None
    try:
        fd, path = tempfile.mkstemp(prefix="unilateral-figures-", suffix=".pickle", dir=SHARED_FOLDER)
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        return path
    except OSError:
        if path is not None:
            with contextlib.suppress(OSError):
                os.unlink(path)
        return None


def _received(message: bytes) -> bytes:
    """The job of a message of :meth:`BackgroundFigures.submit`: ``P`` and the job, or ``F`` and the
    path of the file that holds it (read, then removed)."""
    if message[:1] == b"P":
        return message[1:]
    path = os.fsdecode(message[1:])
    try:
        with open(path, "rb") as f:
            return f.read()
    finally:
        os.unlink(path)


def _status_text(status: int) -> str:
    if os.WIFSIGNALED(status):
        return f"killed by signal {os.WTERMSIG(status)}"
    return f"exit status {os.WEXITSTATUS(status)}"


def _child(job_read: int, reply_write: int, parent: int, preload) -> None:
    """Import the figure code, wait for the job, draw, send the result, exit: never returns."""
    code = 1
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)       # the parent decides; it kills us
        _die_with_parent()
        if os.getppid() != parent:                          # it died before we asked
            os._exit(1)
        from .results import draw_figures               # matplotlib: imported while the parent solves

        for module in preload:
            importlib.import_module(module)
        no_dask = contextlib.ExitStack()                # held until the process ends
        if "xarray" in sys.modules:                     # this process never holds Dask arrays
            from ..io.results import without_dask_arrays

            no_dask.enter_context(without_dask_arrays())

        with os.fdopen(job_read, "rb") as pipe:
            data = pipe.read()
        if not data:                                        # the parent closed without a job
            os._exit(0)
        ds, out_dir, formats = pickle.loads(_received(data))
        try:
            reply = _draw_in_two(ds, out_dir, formats)
        except Exception as exc:
            reply = _failure(exc)
        with os.fdopen(reply_write, "wb") as pipe:
            pipe.write(pickle.dumps(reply))
        code = 0
    except BaseException:                                   # noqa: BLE001 - nothing may escape a fork
        pass
    finally:
        os._exit(code)


def _failure(exc: Exception) -> tuple:
    if isinstance(exc, WriteError):
        return ("write_error", (str(exc.path), exc.errno, exc.reason))
    return ("error", (f"{type(exc).__name__}: {exc}", traceback.format_exc()))


def _draw_share(ds, out_dir, formats, names) -> tuple:
    """Draw the figures ``names`` in order: ``(index, reply)``, the reply of the first that fails (its
    index in :data:`~unilateral.figures.results.FIGURES`) or ``(None, ("ok", files))``."""
    from .results import FIGURES, draw_figures

    order = [name for name, _ in FIGURES]
    written = []
    for name in names:
        try:
            written += [str(p) for p in draw_figures(ds, out_dir, formats, only=(name,))]
        except Exception as exc:
            return order.index(name), _failure(exc)
    return None, ("ok", written)


def _draw_in_two(ds, out_dir, formats) -> tuple:
    """Draw the figures as :func:`~unilateral.figures.results.draw_figures` does, half of them in a
    process forked for it: on a machine with two cores the caller, done with its own outputs, waits
    for the figures alone (Agg draws on one core). The reply is the files in the order of
    ``draw_figures``, or the failure of the first figure (in that order) that failed."""
    from .results import FIGURES

    names = [name for name, _ in FIGURES]
    theirs = names[1::2] if len(names) > 1 else []
    helper = None
    if theirs:
        read_fd, write_fd = os.pipe()
        pid = os.fork()
        if pid == 0:                                        # the helper: never returns
            code = 1
            try:
                os.close(read_fd)
                _die_with_parent()
                with os.fdopen(write_fd, "wb") as pipe:
                    pipe.write(pickle.dumps(_draw_share(ds, out_dir, formats, theirs)))
                code = 0
            except BaseException:                           # noqa: BLE001 - nothing may escape a fork
                pass
            finally:
                os._exit(code)
        os.close(write_fd)
        helper = (pid, read_fd)
    results = [_draw_share(ds, out_dir, formats, [name for name in names if name not in theirs])]
    if helper is not None:
        pid, read_fd = helper
        with os.fdopen(read_fd, "rb") as pipe:
            data = pipe.read()
        _, status = os.waitpid(pid, 0)
        if not data:
            raise FigureProcessError(f"the figure helper process ended without a result ({_status_text(status)})")
        results.append(pickle.loads(data))
    failed = [(index, reply) for index, reply in results if index is not None]
    if failed:
        return min(failed, key=lambda item: item[0])[1]
    files = [path for _, (_, paths) in results for path in paths]
    return "ok", sorted(files, key=lambda path: names.index(Path(path).name.rpartition(".")[0]))


def _die_with_parent() -> None:
    """Ask Linux to kill this process when its parent dies (``prctl(PR_SET_PDEATHSIG, SIGKILL)``)."""
    import ctypes

    PR_SET_PDEATHSIG = 1
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
    except (OSError, AttributeError):
        pass
