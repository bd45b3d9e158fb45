"""Loads: earthquake ground-motion records, load time functions and unit conversions.

- :mod:`~unilateral.loads.records`: :class:`GroundMotion` and readers for PEER ``.AT2`` and
  plain-text records (accelerations in m/s^2).
- :mod:`~unilateral.loads.pulses`: load time functions ``f(t)`` (rectangular, triangular and
  half-sine pulses, constant, ramp, tabulated).
- :mod:`~unilateral.loads.combination`: :class:`LoadHistory`, a load ``q(t)`` made of patterns
  and time functions, sampled at all steps at once.
- :mod:`~unilateral.loads.synthetic`: synthetic accelerograms (Kanai-Tajimi filtered noise).
- :mod:`~unilateral.loads.units`: factors converting acceleration, length and force units to SI.
"""

from unilateral.loads.combination import LoadHistory
from unilateral.loads.pulses import Constant, HalfSine, Ramp, Rectangular, Tabulated, TimeFunction, Triangular
from unilateral.loads.records import (
    GroundMotion,
    RecordFormatError,
    Table,
    read_at2,
    read_record,
    read_table,
    read_text_record,
)
from unilateral.loads.synthetic import synthetic_accelerogram
from unilateral.loads.units import STANDARD_GRAVITY, acceleration_factor, force_factor, length_factor

__all__ = [
    "STANDARD_GRAVITY",
    "Constant",
    "GroundMotion",
    "HalfSine",
    "LoadHistory",
    "Ramp",
    "RecordFormatError",
    "Rectangular",
    "Table",
    "Tabulated",
    "TimeFunction",
    "Triangular",
    "acceleration_factor",
    "force_factor",
    "length_factor",
    "read_at2",
    "read_record",
    "read_table",
    "read_text_record",
    "synthetic_accelerogram",
]
