"""The end time of a model file's analysis: ``t_end = "record"`` and ``t_after``.

``[analysis] t_end = "record"`` runs to the end of the longest ground motion record plus
``t_after`` (free vibration after the record, the ground at rest), as a study's
``t_end = "record"`` does; ``t_after`` with a number ``t_end`` is refused (extend ``t_end``).
"""

from __future__ import annotations

from .errors import Problems


def resolved_analysis(document, load) -> dict:
    """``document.analysis`` as a dict with ``t_end`` a number: the longest record's end plus
    ``t_after`` for ``t_end = "record"`` (the ground motions' time functions: the last terms of
    ``load``, in the model's time unit).

    Raises
    ------
    Problems
        ``t_end = "record"`` without ``[[loads.ground_motion]]``, or ``t_after`` with a number ``t_end``.
    """
    analysis = document.analysis.model_dump()
    t_end, t_after = analysis["t_end"], analysis["t_after"]
    if t_end != "record":
        if t_after > 0 and t_end is not None:
            raise Problems([f"analysis.t_after = {t_after!r}: applies with t_end = \"record\" only (here t_end = "
                            f"{t_end!r}; run to t_end = {t_end + t_after!r} instead, or set t_end = \"record\")"])
        return analysis
    count = len(document.loads.ground_motion)
    if count == 0:
        raise Problems(['analysis.t_end = "record": the model has no [[loads.ground_motion]] (a number t_end is '
                        "valid without one)"])
    ends = [float(f.t[-1]) for _, f in load.terms[-count:]]
    analysis["t_end"] = max(ends) + t_after
    return analysis

