"""Soil as an unbounded medium: impedances and dynamic flexibilities in the Laplace domain.

Modules (one concept each):

* :mod:`.patches` - rectangular surface patches (``RectangularPatches``, ``strips``, ``grid``, ``disc``).
* :mod:`.statics` - closed-form Boussinesq flexibilities of points and rectangles (Love/Steinbrenner).
* :mod:`.lamb` - Lamb's problem in the Laplace domain: wavenumber kernel, deformed contour.
* :mod:`.halfspace` - ``HalfSpace``: rigorous surface flexibility ``Phi(s)`` of patches (vertical, or
  the horizontal and vertical Green's tensor), point Green's fn.
* :mod:`.layered` - ``Layered``: horizontal layers over a half-space or a rigid base, the same ``Phi(s)``.
* :mod:`.rigid` - ``rigid_impedance``: impedances of a rigid footing from its patches.
* :mod:`.structure_weights` - the structure's CQ weights of a foundation model by compiled stepping.
* :mod:`.pekeris` - Pekeris (1955) / Mooney / Kausel closed form of the step point-load response.
* :mod:`.chao` - Chao (1960) / Kausel closed form of the step response to a horizontal point load.
* :mod:`.impedances` - Veletsos & Verbic (1973) rational disc impedances.
* :mod:`.cones` - Wolf (1994) cone models and cone-type coupled flexibility of patches.
* :mod:`.fit` - AAA rational fits of tabulated data (``fit_rational``, ``read_table``).
* :mod:`.timedomain` - step responses of soil kernels by convolution quadrature (``step_response``).
* :mod:`.flexibility` - ``SoilFlexibility`` (``Phi(s)`` of the contact points from any of the above).
* :mod:`.foundation_model` - ``FoundationModel``: a structure on the soil through unilateral contacts,
  ``FoundationKernel`` (the dual kernel).
  Its solution route (``method="cq"`` and ``"modal"``) is :mod:`unilateral.methods.foundation_solve`.

Sign convention: vertical forces and displacements positive downward (into the soil); kernels are
Laplace transforms, evaluated for ``Re s >= 0``, real for real ``s``.
"""

from importlib import import_module

#: Public name -> the submodule that defines it. Imported on first use, so that importing
#: :mod:`unilateral.soil.foundation_model` (done by the solvers) does not import scipy.special or
#: scipy.interpolate.
_LAZY = {
    **dict.fromkeys(("Cone", "cone", "cone_flexibility"), "cones"),
    **dict.fromkeys(("FoundationKernel", "FoundationModel"), "foundation_model"),
    **dict.fromkeys(("SoilFlexibility", "SoilPoles"), "flexibility"),
    **dict.fromkeys(("RationalFit", "fit_rational", "read_table"), "fit"),
    "HalfSpace": "halfspace",
    "Layered": "layered",
    **dict.fromkeys(("VeletsosVerbic", "veletsos_verbic"), "impedances"),
    **dict.fromkeys(("RectangularPatches", "disc", "grid", "points", "strips"), "patches"),
    **dict.fromkeys(("rigid_impedance", "rigid_kinematics"), "rigid"),
    **dict.fromkeys(("arrival_times", "lamb_step_vertical", "pekeris_quarter"), "pekeris"),
    **dict.fromkeys(("cerruti_surface", "chao_quarter", "lamb_step_coupled", "lamb_step_horizontal"), "chao"),
    **dict.fromkeys(("boussinesq", "mean_inverse_distance", "rectangle_corner_displacement"), "statics"),
    "step_response": "timedomain",
}

__all__ = list(_LAZY)


def __getattr__(name):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'unilateral.soil' has no attribute {name!r}")
    value = getattr(import_module(f"{__name__}.{module}"), name)
    globals()[name] = value         # later lookups skip __getattr__
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
