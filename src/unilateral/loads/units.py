"""Conversion factors from engineering units to SI.

Each ``*_factor(unit)`` returns the number that multiplies a value in ``unit`` to give it in
the SI base unit (m/s^2, m, N or kg). Unit names are case-insensitive and spaces are ignored;
acceleration units also accept the spellings found in PEER and COSMOS headers: ``sec`` for
``s``, ``/s/s``, ``^2`` and ``**2`` (so ``"CM/S/S"``, ``"cm/sec/sec"`` and ``"cm/sec^2"`` all
mean cm/s^2). Because matching ignores case, ``"MN"`` and ``"mn"`` both mean meganewton.
"""

from __future__ import annotations

STANDARD_GRAVITY = 9.80665
"""Standard acceleration of gravity, m/s^2 (the "g" of strong-motion records)."""

_INCH = 0.0254
_FOOT = 0.3048
_POUND_FORCE = 4.4482216152605

_ACCELERATION = {
    "g": STANDARD_GRAVITY,
    "m/s2": 1.0,
    "cm/s2": 1e-2,
    "gal": 1e-2,
    "mm/s2": 1e-3,
    "in/s2": _INCH,
    "ft/s2": _FOOT,
}
_LENGTH = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": _INCH, "ft": _FOOT}
_FORCE = {"N": 1.0, "kN": 1e3, "MN": 1e6, "lbf": _POUND_FORCE, "kip": 1e3 * _POUND_FORCE}
_MASS = {"kg": 1.0, "t": 1e3, "Mg": 1e3}

# Spelling variants, applied in order to the lower-cased name without spaces.
_SPELLINGS = (("sec", "s"), ("**2", "2"), ("^2", "2"), ("/s/s", "/s2"))


def acceleration_factor(unit: str) -> float:
    """Factor converting an acceleration in ``unit`` to m/s^2.

    Parameters
    ----------
    unit : str
        One of ``g`` (standard gravity, 9.80665 m/s^2), ``m/s2``, ``cm/s2`` (= ``gal``),
        ``mm/s2``, ``in/s2``, ``ft/s2``, in any case and with the spelling variants of the
        module docstring.

    Returns
    -------
    float
        Multiplier to m/s^2.

    Raises
    ------
    ValueError
        If the unit is unknown; the message lists the valid units.
    """
    return _factor("acceleration", unit, _ACCELERATION)


def length_factor(unit: str) -> float:
    """Factor converting a length in ``unit`` (``m``, ``cm``, ``mm``, ``in``, ``ft``) to m.

    Raises ``ValueError`` listing the valid units if ``unit`` is unknown.
    """
    return _factor("length", unit, _LENGTH)


def force_factor(unit: str) -> float:
    """Factor converting a force in ``unit`` (``N``, ``kN``, ``MN``, ``lbf``, ``kip``) to N.

    Raises ``ValueError`` listing the valid units if ``unit`` is unknown.
    """
    return _factor("force", unit, _FORCE)


def mass_factor(unit: str) -> float:
    """Factor converting a mass in ``unit`` (``kg``, ``t`` = tonne, ``Mg`` = megagram = t) to kg.

    Unlike the other units, case matters (spaces are ignored): ``"mg"`` would be a milligram
    and is refused, as is any unknown unit, with a ``ValueError`` listing the valid units.
    """
    if not isinstance(unit, str):
        raise TypeError(f"mass unit must be a string, got {unit!r}")
    key = "".join(unit.split())
    if key in _MASS:
        return _MASS[key]
    raise ValueError(f"unknown mass unit {unit!r}; valid units: {', '.join(_MASS)} (case matters: t = Mg = 1000 kg)")


def _factor(kind: str, unit: str, table: dict[str, float]) -> float:
    if not isinstance(unit, str):
        raise TypeError(f"{kind} unit must be a string, got {unit!r}")
    key = "".join(unit.lower().split())
    for variant, canonical in _SPELLINGS:
        key = key.replace(variant, canonical)
    for name, factor in table.items():
        if name.lower() == key:
            return factor
    valid = ", ".join(table)
    raise ValueError(f"unknown {kind} unit {unit!r}; valid units: {valid} (any case)")
