"""The keys of a study's analyses, computed fast: the parts common to a model variant encoded once.

An analysis is named by ``sha256_json(ident)[:24]`` of its ident ``{"ground_motion", "model",
"overrides", "quantities", "record", "scale", "settings", "version"}``
(:func:`unilateral.batch.study.sha256_json`: sorted keys, compact separators). Encoding the whole
ident per analysis took most of the time of reading a study of many levels (0.2 ms per analysis,
most of it in ``json.dumps`` of the overrides and quantities shared by every analysis of a
variant). :class:`AnalysisKeys` builds the same text from fragments: the common ones encoded once
per variant, the settings once per end time; the key is the same, character for character
(``tests/test_study_size.py`` checks it).
"""

from __future__ import annotations

import hashlib
import json
import math


def _encode(value) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), default=str, allow_nan=True)


class AnalysisKeys:
    """The keys of the analyses of one model variant.

    Parameters
    ----------
    model : str
        The variant's digest.
    overrides : list
        Its changed values ``[(key path, value), ...]``.
    ground_motion : dict
        How the records enter it.
    quantities : list of dict
        The study's quantities (``model_dump()`` of each).
    version : str
        The package version.
    """

    def __init__(self, model, overrides, ground_motion, quantities, version):
        self.head = (f'{{"ground_motion":{_encode(ground_motion)},"model":{_encode(model)},'
                     f'"overrides":{_encode(overrides)},"quantities":{_encode(quantities)}')
        self.tail = f',"version":{_encode(version)}}}'
        self._settings: dict = {}
        self._records: dict = {}

    def settings(self, base: dict, t_end) -> tuple[dict, str]:
        """``(settings, text)``: ``base`` (the variant's settings with the study's ``lcp_options`` and
        ``timeout``) with ``t_end``, one dict per end time shared by the analyses that have it (nothing
        changes them), and its encoding without ``timeout`` (as in the ident)."""
        hit = self._settings.get(t_end)
        if hit is None:
            settings = dict(base, t_end=t_end)
            hit = self._settings[t_end] = (settings, _encode({k: v for k, v in settings.items() if k != "timeout"}))
        return hit

    def key(self, record, scale: float, settings_text: str) -> str:
        """``sha256_json(ident)[:24]`` of the analysis of ``record`` (its digest or None) at ``scale``
        with the settings encoded as ``settings_text`` (:meth:`settings`)."""
        text = self._records.get(record)
        if text is None:
            text = self._records[record] = _encode(record)
        # json.dumps of a finite float is its repr
        number = repr(scale) if type(scale) is float and math.isfinite(scale) else _encode(scale)
        full = f'{self.head},"record":{text},"scale":{number},"settings":{settings_text}{self.tail}'
        return hashlib.sha256(full.encode()).hexdigest()[:24]
