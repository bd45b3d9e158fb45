"""Matrix-level models: ``M, K, C, F, H`` (and ``F_v, H_v, g``) read from Matrix Market files.

A structure exported from another finite element code enters as its matrices; loads then act on
DOFs by name or index and a ground motion needs its influence vector ``r``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ..model import Model
from .errors import Problems, compact_ids, did_you_mean, value_problem
from .schema import Matrices

_MATRIX_KEYS = ("M", "K", "F", "H", "C", "F_v", "H_v")


def read_matrix_model(section: Matrices, folder: Path) -> Model:
    """The :class:`~unilateral.Model` of a ``[matrices]`` table; files relative to ``folder``.

    Raises
    ------
    Problems
        An unreadable file, a names file of the wrong length, or matrices the model rejects
        (shapes, symmetry, definiteness).
    """
    given = {key: getattr(section, key) for key in _MATRIX_KEYS if getattr(section, key) is not None}
    arrays = {key: _read(("matrices", key), name, folder) for key, name in given.items()}
    n = arrays["K"].shape[0]
    g = None if section.g is None else read_vector(("matrices", "g"), section.g, folder, arrays["F"].shape[1])
    names = None if section.dofs is None else _read_names(section.dofs, folder, n)
    try:
        return Model(arrays.pop("M"), arrays.pop("K"), arrays.pop("F"), arrays.pop("H"), arrays.pop("C", None),
                     g, **arrays, dof_names=names, constraint_names=section.constraints)
    except (ValueError, TypeError) as exc:
        raise Problems([f"matrices: {exc}"]) from None


def read_vector(parts, name: str, folder: Path, size: int) -> np.ndarray:
    """A vector of ``size`` entries from a Matrix Market file (a column or a row)."""
    array = _read(parts, name, folder)
    array = array.toarray() if sp.issparse(array) else np.asarray(array, dtype=float)
    if 1 not in array.shape or array.size != size:
        raise Problems([value_problem(parts, name, f"expected a vector of {size} entries, "
                                                   f"got a matrix of shape {array.shape}")])
    return array.ravel()


def dof_index(model: Model, parts, ref) -> int:
    """Index of the DOF ``ref``: a name of ``model.dof_names`` or a 0-based index."""
    n = model.n
    if isinstance(ref, int):
        if ref < n:
            return ref
        raise Problems([value_problem(parts, ref, f"no DOF {ref} (indices are {compact_ids(range(n))})")])
    if ref in model.dof_names:
        return model.dof_names.index(ref)
    shown = ", ".join(model.dof_names[:10]) + (", ..." if n > 10 else "")
    raise Problems([value_problem(parts, ref, f'no DOF "{ref}" (DOFs are {shown})')
                    + did_you_mean(ref, model.dof_names)])


MAX_DENSE_BYTES = 2 * 1024 ** 3
"""Largest dense (``array``) Matrix Market matrix read, in bytes of float64 entries."""
MAX_DIMENSION = 10_000_000
"""Most rows or columns of a sparse (``coordinate``) Matrix Market matrix."""


def _read(parts, name: str, folder: Path):
    import scipy.io                             # here: a model file without matrices does not import it

    try:
        _check_header(parts, name, scipy.io.mminfo(folder / name))
        array = scipy.io.mmread(folder / name)
    except (ValueError, OSError, IndexError) as exc:
        raise Problems([value_problem(parts, name, f"not a readable Matrix Market file ({exc})")]) from None
    return sp.csr_matrix(array, dtype=float) if sp.issparse(array) else np.asarray(array, dtype=float)


def _check_header(parts, name: str, info: tuple) -> None:
    """Refuse, from the header alone, a matrix that is not real or too large to read.

    ``info`` is ``(rows, cols, entries, format, field, symmetry)`` as from :func:`scipy.io.mminfo`.
    """
    rows, cols, _, layout, kind, _ = info
    if kind not in ("real", "integer"):
        raise Problems([value_problem(parts, name, f'a {layout} {kind} matrix: the matrices of a model are real '
                                      '(write the file with field "real" or "integer"'
                                      + (", with every value" if kind == "pattern" else "") + ")")])
    size = f"{rows} x {cols}"
    if layout == "array" and 8 * rows * cols > MAX_DENSE_BYTES:
        raise Problems([value_problem(parts, name, f"a dense {size} matrix ({8 * rows * cols / 1024 ** 3:.3g} GiB): "
                                      f"more than the {MAX_DENSE_BYTES / 1024 ** 3:g} GiB read (write a large "
                                      "matrix in coordinate format, with its nonzeros only)")])
    if max(rows, cols) > MAX_DIMENSION:
        raise Problems([value_problem(parts, name, f"a {size} matrix: more than the {MAX_DIMENSION:,} rows or "
                                      "columns read")])


def _read_names(name: str, folder: Path, n: int) -> list[str]:
    lines = (folder / name).read_text(encoding="utf-8-sig").splitlines()
    names = [line.strip() for line in lines if line.strip() and not line.lstrip().startswith("#")]
    if len(names) != n:
        raise Problems([value_problem(("matrices", "dofs"), name,
                                      f"{len(names)} DOF names for the {n} DOFs of K (one name per line)")])
    return names

