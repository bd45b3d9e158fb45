"""Soil as an unbounded medium: impedances and dynamic flexibilities in the Laplace domain.

Modules (one concept each):

* :mod:`.patches` - rectangular surface patches (``RectangularPatches``, ``strips``, ``grid``, ``disc``).
* :mod:`.statics` - closed-form Boussinesq flexibilities of points and rectangles (Love/Steinbrenner).
* :mod:`.lamb` - Lamb's problem in the Laplace domain: wavenumber kernel, deformed contour.
* :mod:`.halfspace` - ``HalfSpace``: rigorous surface flexibility ``Phi(s)`` of patches, point Green's fn.
* :mod:`.pekeris` - Pekeris (1955) / Mooney / Kausel closed form of the step point-load response.
* :mod:`.impedances` - Veletsos & Verbic (1973) rational disc impedances.
* :mod:`.cones` - Wolf (1994) cone models and cone-type coupled flexibility of patches.
* :mod:`.fit` - AAA rational fits of tabulated data (``fit_rational``, ``read_table``).
* :mod:`.timedomain` - step responses of soil kernels by convolution quadrature (``step_response``).

Sign convention: vertical forces and displacements positive downward (into the soil); kernels are
Laplace transforms, evaluated for ``Re s >= 0``, real for real ``s``.
"""

from .cones import Cone, cone, cone_flexibility
from .fit import RationalFit, fit_rational, read_table
from .halfspace import HalfSpace
from .impedances import VeletsosVerbic, veletsos_verbic
from .patches import RectangularPatches, disc, grid, points, strips
from .pekeris import arrival_times, lamb_step_vertical, pekeris_quarter
from .statics import boussinesq, mean_inverse_distance, rectangle_corner_displacement
from .timedomain import step_response

__all__ = [
    "Cone", "cone", "cone_flexibility",
    "RationalFit", "fit_rational", "read_table",
    "HalfSpace",
    "VeletsosVerbic", "veletsos_verbic",
    "RectangularPatches", "disc", "grid", "points", "strips",
    "arrival_times", "lamb_step_vertical", "pekeris_quarter",
    "boussinesq", "mean_inverse_distance", "rectangle_corner_displacement",
    "step_response",
]
