"""Reading input files safely: regular files only, and no more than a size limit.

A model file, a study file or a record that is a named pipe (FIFO) would block the reader
forever, a symbolic link to ``/dev/zero`` would fill the memory, and a folder gives a confusing
``IsADirectoryError``. :func:`read_input_bytes` opens the file without blocking, checks that it is
a regular file (after following symbolic links) no larger than the limit, and reads at most the
limit. :func:`file_problem` says, without opening it, why a path cannot be read as an input file.

This module imports nothing heavy: :mod:`unilateral.loads` and :mod:`unilateral.modelfile` use it.
"""

from __future__ import annotations

import os
import stat

MIB = 1 << 20
#: Largest TOML model or study file read [bytes].
TOML_LIMIT = 64 * MIB
#: Largest record or table file read [bytes].
TABLE_LIMIT = 1024 * MIB

_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a named pipe (FIFO)"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


class InputFileError(ValueError):
    """An input file that is not a regular file, or is larger than the limit.

    Attributes
    ----------
    path : str
        The file, as given.
    problem : str
        What is wrong, without the file name (e.g. ``"not a regular file but a named pipe (FIFO)"``).
    """

    def __init__(self, path, problem: str):
        self.path = str(path)
        self.problem = problem
        super().__init__(f"{self.path}: {problem}")


def file_kind(mode: int) -> str:
    """``"a folder"``, ``"a named pipe (FIFO)"``, ... for a ``st_mode``; ``"a regular file"``."""
    if stat.S_ISREG(mode):
        return "a regular file"
    return next((name for test, name in _KINDS if test(mode)), "not a file")


def file_problem(path: str | os.PathLike) -> str | None:
    """Why ``path`` cannot be read as an input file, or None if it is a regular file.

    Follows symbolic links; does not open the file (so a FIFO does not block).

    Returns
    -------
    str or None
        e.g. ``"file not found"``, ``"not a regular file but a folder"``, ``"not a regular file
        but a symbolic link to /dev/zero, a character device"``.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        if os.path.islink(path):
            return f"file not found (a symbolic link to {os.readlink(path)}, which does not exist)"
        return "file not found"
    except NotADirectoryError:
        return "file not found (a part of the path is a file, not a folder)"
    except OSError as exc:
        return f"cannot read it ({exc.strerror or exc})"
    if stat.S_ISREG(mode):
        return None
    return _not_regular(path, mode)


def read_input_bytes(path: str | os.PathLike, *, limit: int) -> bytes:
    """The content of the regular file ``path``, at most ``limit`` bytes.

    Parameters
    ----------
    path : str or path-like
        The file; a symbolic link is followed.
    limit : int
        Largest size read [bytes].

    Returns
    -------
    bytes

    Raises
    ------
    InputFileError
        Not a regular file (a folder, a FIFO, a device, a socket), or larger than ``limit``.
    OSError
        The file cannot be opened (``FileNotFoundError``, ``PermissionError``, ...).
    """
    # O_NONBLOCK: opening a FIFO without a writer returns at once instead of waiting for one
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise InputFileError(path, _not_regular(path, info.st_mode))
        if info.st_size > limit:
            raise InputFileError(path, _too_large(info.st_size, limit))
    except BaseException:
        os.close(fd)
        raise
    with os.fdopen(fd, "rb", buffering=0) as fh:
        chunks, size = [], 0
        while size <= limit:                    # the file may grow while it is read
            chunk = fh.read(min(limit + 1 - size, 16 * MIB))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
        if size > limit:
            raise InputFileError(path, _too_large(size, limit))
        return b"".join(chunks)


def read_input_text(path: str | os.PathLike, *, limit: int, errors: str = "strict") -> str:
    """The UTF-8 text (a byte order mark is dropped) of the regular file ``path``; see
    :func:`read_input_bytes`. Decoding errors raise ``UnicodeDecodeError`` unless ``errors``
    says otherwise (``"replace"``)."""
    return read_input_bytes(path, limit=limit).decode("utf-8-sig", errors=errors)


def size_text(size: int) -> str:
    """``73400320`` -> ``"70 MiB (73400320 bytes)"``."""
    for unit, factor in (("GiB", 1 << 30), ("MiB", MIB), ("KiB", 1 << 10)):
        if size >= factor:
            return f"{size / factor:.4g} {unit} ({size} bytes)"
    return f"{size} bytes"


def _too_large(size: int, limit: int) -> str:
    return (f"the file is too large: {size_text(size)}, more than the limit of {size_text(limit)} "
            "(is it the right file?)")


def _not_regular(path, mode: int) -> str:
    kind = file_kind(mode)
    if os.path.islink(path):
        kind = f"a symbolic link to {os.path.realpath(path)}, {kind}"
    return f"not a regular file but {kind}; give a regular file"
