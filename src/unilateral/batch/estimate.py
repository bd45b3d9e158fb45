"""What a study costs, from its file alone: the counts, and the memory and time of reading it.

:func:`study_size` counts the model variants (per model, the product of the lengths of the swept
groups), the records (the record files of the folder, the files, the seeds, the pairs times their
angles), the intensity levels and the analyses of a validated study file. Nothing is built, read
or generated: the product of the sweeps is never formed, so a sweep of 1000 x 1000 x 1000 values
is counted (1e9 variants) in microseconds. :func:`size_problems` refuses, before anything is
allocated, a study whose reading would not fit in memory (the variants are built when the study is
read, and every analysis is listed), naming the key, the count and the limit;
:meth:`StudySize.describe` is the line ``unilateral batch`` prints before it reads the study.

The costs per variant and per analysis are rough figures measured on the paper's tower
(``examples/ida.toml``): a larger model costs more per variant, so the figures for variants are
lower bounds. :func:`combinations` lists the combinations of the swept values (groups zipped,
groups crossed) once the count is known to fit.
"""

from __future__ import annotations

import itertools
import math
import os
from dataclasses import dataclass
from pathlib import Path

VARIANT_BYTES = 64 * 1024
"""Memory of one model variant held while a study is read and run (its built model, structure and
load: about 40 KiB for the paper's tower, measured with tracemalloc; more for larger models)."""
VARIANT_SECONDS = 0.02
"""Time to build and check one model variant of the paper's tower (20-50 ms measured, loaded machine)."""
ANALYSIS_BYTES = 8 * 1024
"""Memory per analysis of a study in the process that runs it: its entry when the study is read
(0.6 KiB measured with tracemalloc), its row of the table (2.4 KiB held, 3.3 KiB more while it is
built) and of the manifest (3.4 KiB while written); Dask's own state of its task is not counted."""
RESULT_FILE_BYTES = 4096
"""Disk taken by the result file of one analysis (``results/<key>.json``, about 1 KiB: a block)."""
ANALYSIS_SECONDS = 1e-4
"""Time to list one analysis when the study is read (its scale factor and key)."""
MEMORY_FRACTION = 0.5
"""Most of the machine's memory a study may take when it is read (as ``unilateral.solve``'s runs)."""
RECORD_SUFFIXES = (".at2", ".txt", ".dat", ".csv")
"""Files of a records folder that are read as records (any case); .AT2 files carry their units."""


def machine_memory() -> int | None:
    """The machine's physical memory in bytes (None where it cannot be read)."""
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):        # not a POSIX system
        return None


def parameter_groups(doc) -> list[list]:
    """The swept groups of ``doc`` (a validated :class:`~unilateral.batch.schema.StudyFile`): per
    group (``group`` or the parameter alone) the list of its parameters."""
    groups: dict = {}
    for k, parameter in enumerate(doc.parameters):
        groups.setdefault(parameter.group or f"#{k}", []).append(parameter)
    return list(groups.values())


def combinations(doc) -> list[dict]:
    """Every combination ``{key path: value}`` of the swept parameters: groups zipped, groups crossed
    (``[{}]`` without parameters). Call it after :func:`size_problems`: it forms the product."""
    axes = [[{p.key: p.values[i] for p in members} for i in range(len(members[0].values))]
            for members in parameter_groups(doc)]
    combos = []
    for choice in itertools.product(*axes):
        combo = {}
        for part in choice:
            combo.update(part)
        combos.append(combo)
    return combos or [{}]


def record_count(doc, folder: Path) -> int:
    """The records of ``[records]`` (1 without records): the record files of the folder (by their
    suffix, not read), the files, the seeds, and the pairs times their angles."""
    rec = doc.records
    if rec is None:
        return 1
    count = len(rec.files)
    if rec.folder is not None and (folder / rec.folder).is_dir():
        count += sum(1 for p in (folder / rec.folder).iterdir()
                     if p.suffix.lower() in RECORD_SUFFIXES and not p.name.startswith("."))
    if rec.synthetic is not None:
        count += len(rec.synthetic.seeds)
    angles = len(rec.angle) if isinstance(rec.angle, list) else 1
    return count + len(rec.pairs) * angles


@dataclass
class StudySize:
    """The counts of a study and the rough cost of reading it.

    Attributes
    ----------
    models, records, levels : int
        ``[[models]]``, records (1 without records), intensity levels (1 without ``[scaling]``).
    group_sizes : list of int
        The number of values of each swept group (crossed: their product is the combinations).
    steps : int or None
        Time steps of each analysis (``t_end / dt`` of ``[analysis]``; None when a model file or the
        records give them).
    """

    models: int
    records: int
    levels: int
    group_sizes: list
    steps: int | None = None

    @property
    def combinations(self) -> int:
        return math.prod(self.group_sizes)

    @property
    def variants(self) -> int:
        return self.models * self.combinations

    @property
    def analyses(self) -> int:
        return self.variants * self.records * self.levels

    @property
    def variant_bytes(self) -> int:
        return self.variants * VARIANT_BYTES

    @property
    def analysis_bytes(self) -> int:
        return self.analyses * ANALYSIS_BYTES

    @property
    def memory(self) -> int:
        """Bytes the study takes in the process that reads and runs it (at least)."""
        return self.variant_bytes + self.analysis_bytes

    @property
    def read_seconds(self) -> float:
        """Seconds to read the study: build every variant, list every analysis (rough)."""
        return self.variants * VARIANT_SECONDS + self.analyses * ANALYSIS_SECONDS

    def describe(self) -> str:
        """``2,000,000 analyses (1 model variant x 10 records x 200,000 levels) of 1,000 steps ...``."""
        steps = f" of {self.steps:,} steps ({self.analyses * self.steps:.3g} steps in all)" if self.steps else ""
        return (f"{self.analyses:,} analyses ({self.variants:,} model variant{'s' * (self.variants != 1)} x "
                f"{self.records:,} record{'s' * (self.records != 1)} x {self.levels:,} "
                f"level{'s' * (self.levels != 1)}){steps}; reading the study: about {_seconds(self.read_seconds)} "
                f"and {_bytes(self.memory)}; the results: {_bytes(self.analyses * RESULT_FILE_BYTES)} of files")


def study_size(doc, folder: Path) -> StudySize:
    """The :class:`StudySize` of the validated study file ``doc`` whose folder is ``folder``."""
    analysis = doc.analysis
    steps = None
    if analysis.dt is not None and isinstance(analysis.t_end, float):
        steps = max(1, round(analysis.t_end / analysis.dt))
    return StudySize(models=len(doc.models), records=record_count(doc, Path(folder)),
                     levels=len(doc.scaling.values) if doc.scaling is not None else 1,
                     group_sizes=[len(members[0].values) for members in parameter_groups(doc)], steps=steps)


def size_problems(size: StudySize, total: int | None = None) -> list[str]:
    """Why a study of ``size`` cannot be read in memory (``[]`` if it can): one line naming the key,
    the count and the limit (``total``: the machine's memory, default :func:`machine_memory`)."""
    total = machine_memory() if total is None else total
    if total is None or size.memory <= MEMORY_FRACTION * total:
        return []
    limit = f"more than {MEMORY_FRACTION:.0%} of this machine's {_bytes(total)}"
    if size.variant_bytes > MEMORY_FRACTION * total / 2:
        crossed = " x ".join(f"{n:,}" for n in size.group_sizes)
        return [f"parameters: {crossed} values crossed = {size.combinations:,} combinations, x {size.models} "
                f"model{'s' * (size.models != 1)} = {size.variants:,} model variants, each built and checked when "
                f"the study is read (at least {_bytes(VARIANT_BYTES)} and {VARIANT_SECONDS:g} s each: "
                f"{_bytes(size.variant_bytes)}, {_seconds(size.variants * VARIANT_SECONDS)}): {limit}; "
                "give the parameters that vary together one group (group = \"...\": zipped, not crossed), "
                "sweep fewer values, or split the study"]
    key = "scaling.values" if size.levels >= size.records else "records"
    return [f"{key}: {size.levels:,} levels x {size.records:,} records x {size.variants:,} model variants = "
            f"{size.analyses:,} analyses (about {_bytes(ANALYSIS_BYTES)} each in the process that runs them: "
            f"{_bytes(size.memory)}): {limit}; use fewer levels or records, or split the study"]


def _bytes(n: float) -> str:
    for unit, scale in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= scale:
            return f"{n / scale:.3g} {unit}"
    return f"{n:.0f} B"


def _seconds(s: float) -> str:
    if s >= 86400:
        return f"{s / 86400:.3g} days"
    if s >= 3600:
        return f"{s / 3600:.3g} h"
    return f"{s:.2g} s" if s < 60 else f"{s / 60:.3g} min"
