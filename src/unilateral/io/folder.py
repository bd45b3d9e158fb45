"""An output folder replaced as a set: a run's files are all old or all new, never a mix.

A run writes every file into a staging folder next to the output folder (same file system), then
swaps the two: on Linux with one atomic ``renameat2(RENAME_EXCHANGE)``, elsewhere with two
renames (the old folder aside, the staging folder in). At every instant the output folder holds
the complete files of one run (with two renames there is an instant without it; a run killed in
that instant leaves the old set aside, and the next run puts it back). The staging folder holds
a manifest, ``manifest.json`` (run id, time, files), which marks the folder as written by
unilateral.

:meth:`OutputFolder.prepare` checks the folder before anything is solved: the path must be a
folder or not exist, every part above it must be a folder, the folder must hold nothing but the
outputs of an earlier run (its content is replaced as a whole), and a staging folder and a file
in it must be creatable. It also removes what runs killed earlier left behind: staging folders
and old sets whose process is gone and whose lock is free (a run in progress in another process
keeps its staging folder locked with ``flock``, so it is never touched).

Names next to ``DIR``: ``.DIR.staging-<pid>-<token>`` (a run writing) and ``.DIR.old-<pid>-<token>``
(an old set being removed).
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import errno
import json
import os
import re
import secrets
import shutil
import time
from pathlib import Path

from .. import __version__

MANIFEST = "manifest.json"
#: Suffixes of the files a run or ``unilateral plot`` writes (also accepted without a manifest).
OUTPUT_SUFFIXES = (".nc", ".csv", ".json", ".png", ".pdf", ".svg")
#: Files that mark a folder written by an earlier version (no manifest yet).
MARKERS = ("results.nc", "summary.json")
_TEMP = re.compile(r"^\..+\.[0-9a-f]{8}\.tmp(\.\w+)?$")          # unilateral.io.atomic's temporary files
_SIDE = re.compile(r"^\.(?P<name>.+)\.(?P<kind>staging|old)-(?P<pid>\d+)-[0-9a-f]+$")
_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


class OutputFolderError(ValueError):
    """An output folder that cannot be used, found before anything is solved.

    Attributes
    ----------
    path : str
        The output folder, as given.
    problem : str
        What is wrong, without the folder's name.
    """

    def __init__(self, path, problem: str):
        self.path = str(path)
        self.problem = problem
        super().__init__(f"cannot write the outputs to {self.path}: {problem}")


class OutputFolder:
    """The output folder ``path`` of one run, written through a staging folder.

    Parameters
    ----------
    path : str or path-like
        The output folder. It is created if missing; an existing one may hold only the outputs of
        an earlier run (their names are in its manifest, or end in :data:`OUTPUT_SUFFIXES`).

    Attributes
    ----------
    path : pathlib.Path
        The output folder, as given.
    staging : pathlib.Path or None
        The folder the run writes into (after :meth:`prepare`).
    run_id : str
        Recorded in the manifest.

    Examples
    --------
    >>> with OutputFolder("out") as folder:          # doctest: +SKIP
    ...     (folder.staging / "a.csv").write_text("1,2")
    ...     folder.commit()                           # "out" now holds a.csv and the manifest
    """

    def __init__(self, path: str | os.PathLike):
        self.path = Path(path)
        self.staging: Path | None = None
        self.run_id = f"{time.strftime('%Y%m%dT%H%M%S')}-{os.getpid()}-{secrets.token_hex(4)}"
        self._lock_fd: int | None = None
        self._committed = False

    # ------------------------------------------------------------------ public
    def prepare(self) -> Path:
        """Check the folder, remove leftovers of killed runs, create and lock the staging folder.

        Returns
        -------
        pathlib.Path
            The staging folder.

        Raises
        ------
        OutputFolderError
            The path is a file or goes through one, the folder holds other files than outputs, is
            the current folder, its name is too long for the names next to it (:func:`staging_name`),
            or no folder or file can be created next to it or in it.
        """
        if self.staging is not None:
            return self.staging
        real = self._real_path()
        _check_name_length(self.path, real)
        _make_parents(self.path, real.parent)
        cleanup_leftovers(real)
        if real.exists():
            _check_replaceable(self.path, real)
        self.staging = self._make_staging(real)
        return self.staging

    def commit(self) -> Path:
        """Write the manifest and swap the staging folder in; return the output folder."""
        if self.staging is None:
            raise RuntimeError("OutputFolder.commit() before prepare()")
        files = sorted(p.name for p in self.staging.iterdir() if p.name != MANIFEST)
        manifest = {"run": self.run_id, "unilateral": __version__,
                    "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "files": files}
        from .atomic import write_json_atomic

        write_json_atomic(self.staging / MANIFEST, manifest)
        _fsync_dir(self.staging)
        _swap_in(self.staging, self._real_path())
        self._committed = True
        self.close()
        return self.path

    def close(self) -> None:
        """Release the lock; remove the staging folder unless it was committed."""
        if self._lock_fd is not None:
            os.close(self._lock_fd)            # releases the flock
            self._lock_fd = None
        if self.staging is not None and not self._committed:
            shutil.rmtree(self.staging, ignore_errors=True)
        self.staging = None

    def __enter__(self) -> OutputFolder:
        self.prepare()
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # ------------------------------------------------------------------ pieces
    def _real_path(self) -> Path:
        real = Path(os.path.realpath(self.path))
        if real.parent == real:
            raise OutputFolderError(self.path, "it is the root folder; give a folder of its own")
        try:
            cwd = Path.cwd().resolve()
        except OSError:                         # the current folder was removed
            return real
        if real == cwd or real in cwd.parents:
            raise OutputFolderError(self.path, "it is the current folder or contains it; the outputs replace "
                                               "the folder as a whole, so give a folder of their own")
        return real

    def _make_staging(self, real: Path) -> Path:
        staging = real.with_name(staging_name(real.name, os.getpid()))
        try:
            staging.mkdir()
            self._lock_fd = _lock(staging)
            probe = staging / ".probe"
            with open(probe, "wb") as fh:
                fh.write(b"unilateral")
            probe.unlink()
        except OSError as exc:
            if self._lock_fd is not None:
                os.close(self._lock_fd)
                self._lock_fd = None
            shutil.rmtree(staging, ignore_errors=True)
            raise OutputFolderError(self.path, f"cannot create a folder or a file next to it in {real.parent} "
                                               f"({exc.strerror or exc})") from None
        return staging


def staging_name(name: str, pid: int) -> str:
    """The name of a staging folder of the output folder ``name``, written by process ``pid``."""
    return f".{name}.staging-{pid}-{secrets.token_hex(4)}"


#: The longest process id the staging names must hold (Linux allows up to 2**22).
_PID_DIGITS = 7


def _check_name_length(given: Path, real: Path) -> None:
    """Refuse a folder name that leaves no room for its staging folder's (the file system's limit)."""
    try:
        limit = os.pathconf(real.parent if real.parent.exists() else "/", "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):       # not POSIX
        limit = -1
    limit = limit if limit > 0 else 255                 # -1: no limit known
    name = len(os.fsencode(real.name))
    extra = len(os.fsencode(staging_name(real.name, 10**_PID_DIGITS - 1))) - name
    if name + extra > limit:
        raise OutputFolderError(given, f"its name has {name} bytes and the staging folder next to it adds {extra}, "
                                       f"more than the {limit} a file name may have here: give a name of at "
                                       f"most {limit - extra} bytes")


def cleanup_leftovers(target: str | os.PathLike) -> list[Path]:
    """Remove what killed runs left next to ``target``; put an old set back if ``target`` is missing.

    A staging or old folder is left when it is locked or its process (the pid in its name) is
    running: it belongs to a run in progress.

    Returns
    -------
    list of pathlib.Path
        The folders removed (or, for an old set put back, ``target``).
    """
    target = Path(target)
    try:
        entries = list(target.parent.iterdir())
    except OSError:
        return []
    done = []
    stale = []
    for entry in entries:
        match = _SIDE.match(entry.name)
        if match is None or match["name"] != target.name or not entry.is_dir() or entry.is_symlink():
            continue
        if _alive(int(match["pid"])) or _locked(entry):
            continue
        stale.append((match["kind"], entry))
    # a run killed between its two renames: the output folder is missing, its old set is aside
    olds = sorted((entry for kind, entry in stale if kind == "old"), key=lambda p: p.stat().st_mtime)
    if olds and not target.exists():
        with contextlib.suppress(OSError):
            os.rename(olds[-1], target)
            done.append(target)
            stale = [(kind, entry) for kind, entry in stale if entry != olds[-1]]
    for _, entry in stale:
        shutil.rmtree(entry, ignore_errors=True)
        if not entry.exists():
            done.append(entry)
    return done


def foreign_entries(folder: str | os.PathLike) -> list[str]:
    """Names in ``folder`` that are not outputs of a unilateral run (empty: it may be replaced)."""
    folder = Path(folder)
    names = sorted(p.name for p in folder.iterdir())
    listed = _manifest_files(folder / MANIFEST)
    if listed is None:
        if names and not any(name in names for name in MARKERS):
            return names                        # no manifest of ours, no results: not an output folder
        listed = set()
    return [name for name in names
            if name != MANIFEST and name not in listed and not _TEMP.match(name)
            and not ((folder / name).is_file() and Path(name).suffix.lower() in OUTPUT_SUFFIXES)]


# ---------------------------------------------------------------------- helpers
def _manifest_files(path: Path) -> set | None:
    """The files listed by a manifest written by :meth:`OutputFolder.commit`, else None."""
    data = _read_manifest(path)
    return None if data is None else set(data["files"])


def _read_manifest(path: Path) -> dict | None:
    """A manifest written by :meth:`OutputFolder.commit` (its ``files`` the names only), else None."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError):
        return None
    if not isinstance(data, dict) or "unilateral" not in data or "run" not in data:
        return None                             # another program's manifest.json
    files = data.get("files")
    if not isinstance(files, list):
        return None
    return {**data, "files": [name for name in files if isinstance(name, str)]}


def add_to_manifest(folder: str | os.PathLike, names) -> bool:
    """List ``names`` among the files of the manifest of ``folder`` (rewritten atomically).

    Returns
    -------
    bool
        False, and nothing written, when ``folder`` has no manifest written by unilateral.
    """
    path = Path(folder) / MANIFEST
    data = _read_manifest(path)
    if data is None:
        return False
    from .atomic import write_json_atomic

    data["files"] = sorted({*data["files"], *names})
    write_json_atomic(path, data)
    return True


def _make_parents(given: Path, parent: Path) -> None:
    try:
        parent.mkdir(parents=True, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        blocker = next((p for p in (parent, *parent.parents) if p.exists() and not p.is_dir()), parent)
        raise OutputFolderError(given, f"{blocker} is a file, not a folder") from None
    except OSError as exc:
        raise OutputFolderError(given, f"cannot create the folder {parent} ({exc.strerror or exc})") from None
    if not parent.is_dir():
        raise OutputFolderError(given, f"{parent} is not a folder")


def _check_replaceable(given: Path, real: Path) -> None:
    if not real.is_dir():
        raise OutputFolderError(given, "it is a file, not a folder; give a folder (new, empty or of an earlier run)")
    try:
        foreign = foreign_entries(real)
    except OSError as exc:
        raise OutputFolderError(given, f"cannot list it ({exc.strerror or exc})") from None
    if foreign:
        shown = ", ".join(foreign[:5]) + (f" and {len(foreign) - 5} more" if len(foreign) > 5 else "")
        raise OutputFolderError(given, f"it holds files that are not outputs of unilateral ({shown}); a run "
                                       "replaces the folder's content as a whole, so give a new or empty "
                                       "folder or the folder of an earlier run")
    try:
        _probe_writable(real)
    except OSError as exc:
        raise OutputFolderError(given, f"it is not writable ({exc.strerror or exc}), so its files cannot be "
                                       "replaced") from None


def _probe_writable(folder: Path) -> None:
    """Create a file in ``folder`` and remove it; raise OSError when that is refused.

    An unnamed file (``O_TMPFILE``) where the system has them: it never shows in the folder, even
    when the process is killed here. Elsewhere a named one that a later run ignores (``_TEMP``).
    """
    unnamed = getattr(os, "O_TMPFILE", 0)
    if unnamed:
        try:
            os.close(os.open(folder, unnamed | os.O_WRONLY, 0o600))
            return
        except OSError as exc:
            if exc.errno not in (errno.EOPNOTSUPP, errno.EISDIR, errno.EINVAL):
                raise
    probe = folder / f".probe.{secrets.token_hex(4)}.tmp"
    os.close(os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    os.unlink(probe)


def _swap_in(staging: Path, target: Path) -> None:
    """Put ``staging`` at ``target``; the previous ``target`` (if any) is removed afterwards."""
    for _ in range(10):                         # another run may swap at the same moment
        if not target.exists():
            try:
                os.rename(staging, target)      # also replaces an empty folder
                _fsync_dir(target.parent)
                return
            except OSError:
                if not target.exists():
                    raise
        if _exchange(staging, target):
            _fsync_dir(target.parent)
            shutil.rmtree(staging, ignore_errors=True)          # now the old set
            return
        old = target.with_name(f".{target.name}.old-{os.getpid()}-{secrets.token_hex(4)}")
        try:
            os.rename(target, old)
        except FileNotFoundError:
            continue
        try:
            os.rename(staging, target)
        except BaseException:                   # also Ctrl-C between the two renames
            with contextlib.suppress(OSError):
                os.rename(old, target)          # put the old set back
            raise
        _fsync_dir(target.parent)
        shutil.rmtree(old, ignore_errors=True)
        return
    raise OSError(f"could not move the outputs from {staging} to {target}: the folder kept changing")


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux ``renameat2``); False where that is not available."""
    renameat2 = _renameat2()
    if renameat2 is None:
        return False
    if renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    return False                                # EINVAL, ENOSYS (file system), ENOENT: fall back


_RENAMEAT2 = []


def _renameat2():
    if not _RENAMEAT2:
        function = None
        if os.name == "posix":
            with contextlib.suppress(OSError, AttributeError, TypeError):
                function = getattr(ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True), "renameat2")
                function.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
                function.restype = ctypes.c_int
        _RENAMEAT2.append(function)
    return _RENAMEAT2[0]


def _lock(folder: Path) -> int | None:
    """An open descriptor of ``folder`` holding an exclusive ``flock`` (None without flock)."""
    try:
        import fcntl
    except ImportError:                         # not POSIX: the pid in the name protects the folder
        return None
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        os.close(fd)
        raise
    return fd


def _locked(folder: Path) -> bool:
    """True if another process holds the ``flock`` of ``folder``."""
    try:
        import fcntl
    except ImportError:
        return False
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return True                             # cannot tell: leave it
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return False
    except OSError:
        return True
    finally:
        os.close(fd)


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return False                            # our own leftovers (an earlier, failed run here)
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True


def _fsync_dir(folder: Path) -> None:
    if os.name != "posix":
        return
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
