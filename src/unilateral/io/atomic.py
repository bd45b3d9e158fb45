"""Atomic file writing: a file is either the old one or the complete new one, never a torso.

Every writer gets a temporary path in the target's directory (same file system, so the final
:func:`os.replace` is atomic). The temporary file is flushed to disk with ``fsync`` and renamed
over the target only when the writer returns; if it raises, the temporary file is removed and a
previous file at the target is left untouched. An ``OSError`` on the way (a full disk, a
read-only folder) is raised as :class:`WriteError`, whose message names the file, the folder and
the cause: ``could not write results.nc to out: No space left on device``.
"""

from __future__ import annotations

import json
import math
import os
import secrets
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from pathlib import Path

import numpy as np


class WriteError(OSError):
    """A file that could not be written: ``could not write NAME to FOLDER: cause``.

    ``errno`` is that of the underlying error (e.g. ``errno.ENOSPC``); the target is untouched and
    no temporary file is left.
    """

    def __init__(self, path, cause: BaseException):
        path = Path(path)
        reason = getattr(cause, "strerror", None) or str(cause) or type(cause).__name__
        super().__init__(getattr(cause, "errno", None), reason)
        self.path = path
        self.reason = reason

    def __str__(self) -> str:
        return f"could not write {self.path.name} to {self.path.parent}: {self.reason}"


@contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path that replaces ``path`` when the block succeeds.

    Parameters
    ----------
    path : str or path-like
        The target file. Its directory must exist.

    Yields
    ------
    pathlib.Path
        An empty file next to the target, named ``.<name>.<random>.tmp<suffix>`` (it keeps the
        target's suffix for writers that infer the format from it). Write it by name.

    Raises
    ------
    WriteError
        An ``OSError`` while the file was reserved, written, flushed or renamed.

    Examples
    --------
    >>> with atomic_path("results.nc") as tmp:      # doctest: +SKIP
    ...     dataset.to_netcdf(tmp)
    """
    target = Path(path)
    try:
        tmp = _reserve(target)
    except OSError as exc:
        raise WriteError(target, exc) from exc
    try:
        yield tmp
        _fsync(tmp, os.O_RDWR)
        os.replace(tmp, target)
    except BaseException as exc:
        with suppress(OSError):
            tmp.unlink(missing_ok=True)
        if isinstance(exc, OSError) and not isinstance(exc, WriteError):
            raise WriteError(target, exc) from exc
        raise
    if os.name == "posix":          # make the rename itself durable
        _fsync(target.parent, os.O_RDONLY)


def atomic_write(path: str | os.PathLike, writer: Callable[[Path], object]) -> Path:
    """Call ``writer(tmp_path)`` and move the result to ``path`` atomically.

    Parameters
    ----------
    path : str or path-like
        The target file.
    writer : callable
        ``writer(tmp_path)`` writes the complete file at ``tmp_path``; its return value is ignored.

    Returns
    -------
    pathlib.Path
        The target path.
    """
    with atomic_path(path) as tmp:
        writer(tmp)
    return Path(path)


def write_text_atomic(path: str | os.PathLike, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically, without newline translation.

    Returns
    -------
    pathlib.Path
        The target path.
    """
    return atomic_write(path, lambda tmp: tmp.write_text(text, encoding=encoding, newline=""))


#: The key of a JSON object written by :func:`write_json_atomic` that lists its non-finite values.
NON_FINITE_KEY = "non_finite"


def write_json_atomic(path: str | os.PathLike, obj, *, indent: int | None = 2) -> Path:
    """Write ``obj`` as strict JSON to ``path`` atomically; numpy scalars and arrays are converted.

    JSON has no ``NaN`` or ``Infinity`` (strict parsers reject Python's ``NaN`` literal): a
    non-finite number is written as ``null`` and, when ``obj`` is a dictionary, its key path
    (``"results.uplift.peak_base_shear"``, ``"periods[0]"``) is listed under ``"non_finite"``.

    Returns
    -------
    pathlib.Path
        The target path.
    """
    data, paths = strict_jsonable(obj)
    if paths and isinstance(data, dict):
        data[NON_FINITE_KEY] = list(data.get(NON_FINITE_KEY) or []) + paths
    return write_text_atomic(path, json.dumps(data, indent=indent, allow_nan=False) + "\n")


def strict_jsonable(obj) -> tuple[object, list[str]]:
    """:func:`to_jsonable` with every non-finite float replaced by None, and the key paths replaced.

    Returns
    -------
    data : JSON types only, every float finite
    paths : list of str, the key paths (``a.b[2]``) of the values that were NaN or infinite
    """
    paths: list[str] = []

    def clean(value, where):
        if isinstance(value, float) and not math.isfinite(value):
            paths.append(where or "<value>")
            return None
        if isinstance(value, dict):
            return {key: clean(item, f"{where}.{key}" if where else key) for key, item in value.items()}
        if isinstance(value, list):
            return [clean(item, f"{where}[{i}]") for i, item in enumerate(value)]
        return value

    return clean(to_jsonable(obj), ""), paths


def to_jsonable(obj):
    """Return ``obj`` with numpy scalars and arrays, tuples and paths turned into JSON types.

    Dictionary keys become strings. Raises ``TypeError`` for objects JSON cannot represent.
    """
    if isinstance(obj, (np.generic, np.ndarray)):       # before float: np.float64 is a float
        return obj.tolist()
    if obj is None or isinstance(obj, (bool, int, float, str)):
        return obj
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if isinstance(obj, dict):
        return {str(key): to_jsonable(value) for key, value in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(value) for value in obj]
    raise TypeError(f"cannot convert an object of type {type(obj).__name__} to JSON: {obj!r:.60}")


def _reserve(target: Path) -> Path:
    """Create an empty, uniquely named file next to ``target`` (mode 0o666 less the umask)."""
    while True:
        tmp = target.with_name(f".{target.name}.{secrets.token_hex(4)}.tmp{target.suffix}")
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
        except FileExistsError:
            continue
        return tmp


def _fsync(path: Path, flags: int) -> None:
    fd = os.open(path, flags)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
