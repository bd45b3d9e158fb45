"""The checks of the builders' numbers: a finite real, a positive one, a strength, a hardening
ratio, the yield forces of a yield link and the parameters of Coulomb friction on a contact.

Each check names the element (``where``) and the argument in its message; :class:`Frame2D
<unilateral.structure.Frame2D>` and :class:`Frame3D <unilateral.structure.Frame3D>` share them.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

_isfinite = math.isfinite


def _real(where, arg, value, bound=None) -> float:
    """``float(value)``, finite, and ``> 0`` (bound ``">0"``) or ``>= 0`` (``">=0"``)."""
    kind = type(value)
    if kind is float or kind is int:            # the common case, checked without the ABCs
        x = float(value)
        if _isfinite(x) and (bound is None or (x > 0 if bound == ">0" else x >= 0 if bound == ">=0" else True)):
            return x
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{where}: {arg} must be a real number, got {value!r}")
    x = float(value)
    if not np.isfinite(x):
        raise ValueError(f"{where}: {arg}={value!r} must be finite")
    if bound == ">0" and x <= 0:
        raise ValueError(f"{where}: {arg}={value!r} must be > 0")
    if bound == ">=0" and x < 0:
        raise ValueError(f"{where}: {arg}={value!r} must be >= 0")
    return x


def _friction(where, mu, kt, ct):
    """``(mu, kt, ct)`` of a contact with Coulomb friction, or None without ``mu``."""
    if mu is None and kt is None and (ct is None or (type(ct) is float and ct == 0.0)):
        return None
    if mu is None:
        extra = [arg for arg, value in (("kt", kt), ("ct", ct)) if value is not None and value != 0.0]
        if extra:
            raise ValueError(f"{where}: {extra[0]} is a friction parameter; give the friction coefficient mu "
                             "too (or remove it)")
        return None
    mu = _real(where, "mu", mu, ">=0")
    if kt is None:
        raise ValueError(f"{where}: friction (mu={mu!r}) needs the stick stiffness kt (force/length, > 0)")
    return mu, _real(where, "kt", kt, ">0"), _real(where, "ct", ct, ">=0")


def _yield_forces(where, Fy, Fy_t, Fy_c) -> tuple[float, float]:
    """``(Fy_t, Fy_c)`` from ``Fy`` (both ways) or from both ``Fy_t`` and ``Fy_c``."""
    if Fy is not None:
        if Fy_t is not None or Fy_c is not None:
            raise ValueError(f"{where}: give either Fy (both ways) or Fy_t and Fy_c, not both")
        Fy = _strength(where, "Fy", Fy)
        return Fy, Fy
    if Fy_t is None or Fy_c is None:
        missing = "Fy" if Fy_t is None and Fy_c is None else ("Fy_t" if Fy_t is None else "Fy_c")
        raise ValueError(f"{where}: {missing} is missing; give the yield force Fy (both ways) or both Fy_t "
                         "(tension) and Fy_c (compression), > 0")
    return _strength(where, "Fy_t", Fy_t), _strength(where, "Fy_c", Fy_c)


#: The smallest yield force or moment: below it the summary's force ratios (force / Fy) and
#: ductilities (deformation / (Fy / k)) overflow or lose every digit.
MIN_STRENGTH = 1e-150


def _strength(where, arg, value) -> float:
    """A strength (``Fy``, ``My``, ...): finite, > 0 and >= :data:`MIN_STRENGTH`."""
    value = _real(where, arg, value, ">0")
    if value < MIN_STRENGTH:
        raise ValueError(f"{where}: {arg}={value!r} is below {MIN_STRENGTH:g}: the force ratios and ductilities "
                         f"(force / {arg}) cannot be represented in double precision; give {arg} >= "
                         f"{MIN_STRENGTH:g} (in the model's units), or leave the element out for no strength")
    return value


def _hardening(where, value) -> float:
    """The kinematic hardening ratio ``h >= 0``.

    Softening (``-1 < h < 0``) would make the model's ``A`` indefinite, which
    :meth:`Model.from_natural` refuses.
    """
    h = _real(where, "hardening", value)
    if h < 0:
        raise ValueError(f"{where}: hardening={value!r} must be >= 0 (the ratio of the kinematic hardening "
                         "modulus to the elastic stiffness; softening is not supported)")
    return h
