"""Layered soil (unilateral.soil.Layered): exact layer stiffness matrices on a wavenumber contour.

Figures printed by the tests (run with ``-s``) are quoted in docs/theory.md ("Layered soil").
"""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, Layered, disc, grid, strips


def _rel(a, b):
    return float(np.max(np.abs(a - b)) / np.max(np.abs(b)))


def _layer(h, G=1.0, nu=0.3, rho=1.0, **kw):
    return dict(thickness=h, G=G, nu=nu, rho=rho, **kw)


# --- identical materials: the layered code must reproduce the half-space ------------------------

@pytest.mark.parametrize("components", ["z", "xz", "xyz"])
@pytest.mark.parametrize("patches", [grid(2.0, 2.0, 2, 2), strips(2.0, 6.0, 3)], ids=["grid2x2", "strips3"])
def test_identical_layers_reproduce_halfspace(patches, components):
    """Three layers of the half-space's own material: a0 = omega a / cs = 0.5, 1, 2 (a = patch width)
    and one real s. The integrand is computed from the layer stiffness matrices, not from Lamb's
    kernel, so this checks the P-SV matrices, the condensation and the half-space termination."""
    hs = HalfSpace(G=2.0e7, nu=0.3, rho=2000.0)
    a = float(patches.sizes[:, 0].min())
    a0 = np.array([0.5, 1.0, 2.0])
    s = np.concatenate([1j * a0 * hs.cs / a, [1.0 * hs.cs / a]])
    L = Layered([_layer(0.4, G=2.0e7, rho=2000.0), _layer(1.1, G=2.0e7, rho=2000.0),
                 dict(thickness=2.5, Vs=hs.cs, nu=0.3, rho=2000.0)], hs)
    F = L.surface_flexibility(patches, s, components=components)
    ref = hs.surface_flexibility(patches, s, components=components)
    assert F.shape == ref.shape == (4, len(components) * patches.m, len(components) * patches.m)
    err = _rel(F, ref)
    print(f"identical layers vs HalfSpace ({components}): max rel error {err:.1e}")
    assert err < 1e-3            # measured 1e-16 (z) and 1.6e-9 (HalfSpace's quadrature noise at real s)


def test_identical_damped_materials_agree_with_damped_halfspace():
    for model in ("constant_q", "kelvin_voigt"):
        hs = HalfSpace(G=1.0, nu=0.25, rho=1.0, damping=0.05, damping_model=model, omega_ref=3.0)
        L = Layered([_layer(0.7, nu=0.25, damping=0.05)], hs)
        assert L.damping_model == model
        p = grid(2.0, 1.0, 2, 1)
        s = np.array([0.5j, 2j, 1.0 + 1j])
        assert _rel(L.surface_flexibility(p, s), hs.surface_flexibility(p, s)) < 1e-10


def test_kernels_equal_lamb_on_complex_wavenumbers():
    """The condensed layer stiffness matrices of a homogeneous stack give Lamb's kernels (the P-SV
    vertical, radial and coupling ones and the SH one of :mod:`unilateral.soil.lamb`), statics included."""
    from unilateral.soil import lamb
    nu = 0.3
    hs = HalfSpace(G=2.0, nu=nu, rho=1.5)
    L = Layered([_layer(0.7, G=2.0, rho=1.5), _layer(1.3, G=2.0, rho=1.5)], hs)
    k = np.array([0.01, 0.3, 1.0 + 0.3j, 5 + 0.2j, 40 + 0.1j])
    worst = 0.0
    for s in (0.0, 0.5, 2j, 0.1 + 3j):
        S = np.array([s * s * hs.rho / hs.G])
        krr, ktt, kc = lamb.tensor_kernels(k, S, lamb.eta_of(nu), nu)
        ref = {"zz": lamb.kernel(k, S, lamb.eta_of(nu), nu) + (1 - nu) / k, "rr": krr + (1 - nu) / k,
               "tt": ktt + 1 / k, "c": kc + (0.5 - nu) / k}
        got = L.kernels(k, s)
        for name, r in ref.items():
            worst = max(worst, _rel(got[name], r / hs.G))
    print(f"layer kernels vs Lamb: max rel error {worst:.1e}")
    assert worst < 1e-9


# --- limits of a layer on a rigid base ------------------------------------------------------------

def test_thin_layer_on_rigid_base_is_oedometric():
    """H << a: Phi ~ H/(E_oed A), E_oed = lambda + 2G = G/eta; the edge correction is linear in H/a,
    so the Richardson extrapolation of H = a/100, a/50 must give exactly 1."""
    nu = 0.3
    eta = (1 - 2 * nu) / (2 * (1 - nu))
    p = grid(1.0, 1.0, 1, 1)
    r = {}
    for H in (0.01, 0.02):
        F = Layered([_layer(H, nu=nu)]).surface_flexibility(p, 0.0)[0, 0, 0]
        assert abs(F.imag) < 1e-12 * abs(F)
        r[H] = F.real * (1.0 / eta) * 1.0 / H
    extrap = 2 * r[0.01] - r[0.02]
    print(f"oedometric ratio: H/a=0.01 {r[0.01]:.5f}, 0.02 {r[0.02]:.5f}, extrapolated {extrap:.6f}")
    assert 0.99 < r[0.01] < 1.0
    assert extrap == pytest.approx(1.0, abs=2e-4)


def test_thick_layer_on_rigid_base_tends_to_halfspace():
    hs = HalfSpace(G=1.0, nu=0.3, rho=1.0)
    p = grid(2.0, 2.0, 2, 2)
    # real s: the base is felt through exp(-2 s H / c_p) only
    R = Layered([_layer(20.0)])
    for s in (1.0, 2.0):
        assert _rel(R.surface_flexibility(p, s), hs.surface_flexibility(p, s)) < 1e-7   # HalfSpace ~1e-8
        assert _rel(R.surface_flexibility(p, s, components="xyz"),
                    hs.surface_flexibility(p, s, components="xyz")) < 1e-7
    # statics: the rigid base removes a nearly uniform displacement ~ 1/H
    F0 = hs.surface_flexibility(p, 0.0)[0].real
    d = {}
    for H in (10.0, 20.0, 40.0):
        d[H] = np.max(np.abs(Layered([_layer(H)]).surface_flexibility(p, 0.0)[0].real - F0))
    rate = np.log2(d[10.0] / d[20.0]), np.log2(d[20.0] / d[40.0])
    print(f"static |Phi_layer - Phi_hs| ~ H^-p, fitted p = {rate[0]:.3f}, {rate[1]:.3f}")
    assert 0.9 < rate[1] < 1.1


def test_rigid_disc_on_stratum_static_stiffness_against_kausel_formula():
    """K_v = 4 G R/(1 - nu) (1 + 1.28 R/H) for a rigid disc on a stratum over rigid rock (Kausel 1974,
    MIT thesis; quoted by Gazetas 1983, Soil Dyn. Earthq. Eng. 2(1), 2-42, and 1991). It is an
    approximate fit: we compare the *ratio* to the half-space stiffness computed with the same
    patches (so the square-cell discretisation of the disc cancels) and allow 5 %."""
    nu = 1 / 3
    p = disc(1.0, 8)
    R = np.sqrt(p.areas.sum() / np.pi)
    Kh = np.linalg.inv(HalfSpace(G=1.0, nu=nu, rho=1.0).surface_flexibility(p, 0.0)[0].real).sum()
    for H in (2.0, 3.0, 5.0):
        K = np.linalg.inv(Layered([_layer(H, nu=nu)]).surface_flexibility(p, 0.0)[0].real).sum()
        ratio = (K / Kh) / (1 + 1.28 * R / H)
        print(f"disc on stratum H/R = {H / R:.2f}: K/K_hs = {K / Kh:.4f}, formula {1 + 1.28 * R / H:.4f}")
        assert abs(ratio - 1) < 0.05


def test_no_radiation_below_the_first_cutoff_of_a_stratum():
    """Undamped stratum on rigid rock: no propagating mode below omega_1 = pi c_s / (2 H), so the
    flexibility is real (no radiation damping; Kausel 1974, Gazetas 1983); above the cutoffs it is
    not, and -Im Phi is positive semidefinite (energy is radiated, not created)."""
    H = 1.0
    p = strips(2.0, 4.0, 4)
    w1 = np.pi / (2 * H)
    wp = w1 * np.sqrt(2 * (1 - 0.3) / (1 - 0.6))
    L = Layered([_layer(H)])
    below = L.surface_flexibility(p, 1j * w1 * np.array([0.3, 0.6, 0.9]), components="xyz")
    above = L.surface_flexibility(p, 1j * wp * np.array([1.2, 2.0]), components="xyz")
    im_below = np.max(np.abs(below.imag)) / np.max(np.abs(below))
    im_above = np.max(np.abs(above.imag), axis=(1, 2)) / np.max(np.abs(above), axis=(1, 2))
    print(f"stratum: max |Im|/|Phi| below cutoff {im_below:.1e}, above {im_above}")
    assert im_below < 1e-6
    assert np.all(im_above > 1e-2)
    for F in above:
        assert np.linalg.eigvalsh(-F.imag).min() > -1e-9 * np.abs(F).max()


def test_rigid_disc_on_stratum_horizontal_static_stiffness():
    """K_h = 8 G R/(2 - nu) (1 + R/(2H)) (Kausel 1974; Gazetas 1983), ratio to the half-space with
    the same patches; horizontal tractions only (relaxed) and with vertical ones (welded, rigid-body
    translation with zero vertical displacement)."""
    nu = 0.3
    p = disc(1.0, 8)
    m = p.m
    R = np.sqrt(p.areas.sum() / np.pi)

    def stiffness(F):
        e = np.r_[np.ones(m), np.zeros(m)]
        return np.linalg.inv(F[:m, :m]).sum(), e @ np.linalg.inv(F) @ e

    kh = stiffness(HalfSpace(G=1.0, nu=nu, rho=1.0).surface_flexibility(p, 0.0, components="xz")[0].real)
    for H in (2.0, 3.0, 5.0):
        F = Layered([_layer(H, nu=nu)]).surface_flexibility(p, 0.0, components="xz")[0].real
        k = stiffness(F)
        ref = 1 + R / (2 * H)
        print(f"horizontal, H/R = {H / R:.2f}: K/K_hs relaxed {k[0] / kh[0]:.4f}, welded {k[1] / kh[1]:.4f}, "
              f"formula {ref:.4f}")
        assert abs(k[0] / kh[0] / ref - 1) < 0.02 and abs(k[1] / kh[1] / ref - 1) < 0.02


# --- layer on a half-space: the two limits ---------------------------------------------------------

def test_rigid_disc_on_layer_over_halfspace_against_published_formulas():
    """Static stiffnesses of a rigid disc on a layer (G1, thickness H) over a stiffer half-space
    (G2), as ratios to the half-space of the layer's material (the square-cell discretisation
    cancels), against the closed forms tabulated by Mylonakis, Nikolaou & Gazetas (2006, Soil Dyn.
    Earthq. Eng. 26, 824-853) for a circular footing on a layer over a half-space:
    ``(1 + c R/H) / (1 + c (R/H) G1/G2)`` with ``c`` = 1.28 (vertical), 1/2 (horizontal), 1/6
    (rocking); at ``G2 -> oo`` they are Kausel's stratum formulas above. They are fits of rigorous
    solutions: we allow 10 % (measured 0.967 to 1.078, the largest at H/R = 1)."""
    nu = 1 / 3
    p = disc(1.0, 8)
    m = p.m
    R = np.sqrt(p.areas.sum() / np.pi)
    x, e = p.centres[:, 0], np.ones(m)

    def stiffness(soil):
        Kz = np.linalg.inv(soil.surface_flexibility(p, 0.0)[0].real)
        Kx = np.linalg.inv(soil.surface_flexibility(p, 0.0, components="xz")[0].real[:m, :m])
        return np.array([e @ Kz @ e, e @ Kx @ e, x @ Kz @ x])      # vertical, horizontal (relaxed), rocking

    k_hs = stiffness(HalfSpace(G=1.0, nu=nu, rho=1.0))
    c = np.array([1.28, 0.5, 1 / 6])
    worst = []
    for G2 in (2.0, 4.0, 10.0):
        previous = np.ones(3)
        for H in (3.0, 2.0, 1.0):
            k = stiffness(Layered([_layer(H, nu=nu)], HalfSpace(G=G2, nu=nu, rho=1.0))) / k_hs
            ref = (1 + c * R / H) / (1 + c * R / H / G2)
            print(f"G2/G1 = {G2:4.0f}, H/R = {H / R:.2f}: K/K_hs vertical {k[0]:.3f} ({ref[0]:.3f}), "
                  f"horizontal {k[1]:.3f} ({ref[1]:.3f}), rocking {k[2]:.3f} ({ref[2]:.3f})")
            assert np.all(k > previous)             # a thinner soft layer: stiffer in every mode
            previous = k
            worst.append(np.abs(k / ref - 1).max())
    print(f"largest deviation from the formulas: {max(worst):.3f}")
    assert max(worst) < 0.10


def test_layer_on_stiff_halfspace_tends_to_rigid_base():
    p = grid(2.0, 2.0, 2, 2)
    s = np.array([0.0, 0.8j, 2.5j, 1.0])
    rigid = Layered([_layer(1.0)]).surface_flexibility(p, s)
    errs = []
    for ratio in (1e2, 1e4):
        L = Layered([_layer(1.0)], HalfSpace(G=ratio, nu=0.3, rho=1.0))
        errs.append(_rel(L.surface_flexibility(p, s), rigid))
    print(f"layer on half-space G2/G1 = 1e2, 1e4 vs rigid base: {errs[0]:.1e}, {errs[1]:.1e}")
    assert errs[1] < 1e-3 and errs[1] < errs[0] / 10


# --- quadrature / contour convergence ----------------------------------------------------------------

@pytest.mark.parametrize("name", ["stratum", "soft_on_stiff", "stiff_on_soft"])
def test_contour_and_truncation_converged(name):
    profiles = {
        "stratum": Layered([_layer(1.0)]),
        "soft_on_stiff": Layered([_layer(1.0, nu=0.35)], HalfSpace(G=9.0, nu=0.25, rho=1.2)),
        "stiff_on_soft": Layered([_layer(0.5, G=4.0, nu=0.2), _layer(2.0, nu=0.4)],
                                 HalfSpace(G=2.0, nu=0.3, rho=1.0)),
    }
    L = profiles[name]
    p = grid(2.0, 2.0, 2, 2)
    s = np.concatenate([1j * np.linspace(0.3, 6.0, 8), [0.0, 1.0, 0.5 + 2j]])
    A = L.surface_flexibility(p, s, components="xz")
    e_h = _rel(L.surface_flexibility(p, s, components="xz", height_factor=0.5), A)
    e_k = [_rel(L.surface_flexibility(p, s, components="xz", kmax_factor=f), A) for f in (0.25, 0.5)]
    print(f"{name}: contour height Y/2 changes {e_h:.1e}; k_max x 1/4, 1/2 change {e_k[0]:.1e}, {e_k[1]:.1e}")
    assert e_h < 1e-6 and e_k[1] < 1e-7
    assert e_k[1] < 1e-3 * e_k[0]             # exponential convergence in k_max (exp(-2 k h_1))


# --- symmetry ---------------------------------------------------------------------------------------

def test_reciprocity_conjugation_and_real_axis():
    L = Layered([_layer(0.6, G=1.0), _layer(1.5, G=3.0, nu=0.25, damping=0.02)],
                HalfSpace(G=6.0, nu=0.3, rho=1.1, damping=0.02))
    p = RectangularPatchesMixed()
    s = np.array([0.7, 2.0 + 1.5j, 2.0 - 1.5j, 3j])
    F = L.surface_flexibility(p, s, components="xyz")
    assert F.shape == (4, 3 * p.m, 3 * p.m)
    np.testing.assert_allclose(L.surface_flexibility(p, s)[1], F[1, 2 * p.m:, 2 * p.m:], rtol=1e-12)
    np.testing.assert_allclose(F, F.transpose(0, 2, 1), rtol=0, atol=1e-14 * np.abs(F).max())
    np.testing.assert_allclose(F[2], np.conj(F[1]), rtol=1e-13)
    assert np.all(F[0].imag == 0)                       # real for real s
    assert np.linalg.eigvalsh(F[0].real).min() > 0


def RectangularPatchesMixed():
    from unilateral.soil import RectangularPatches
    return RectangularPatches([[0.0, 0.0], [1.3, 0.2], [-0.4, 1.7]], [[1.0, 0.5], [0.6, 0.6], [0.8, 1.2]])


# --- validation -------------------------------------------------------------------------------------

@pytest.mark.parametrize("layer, match", [
    (dict(thickness=0.0, G=1.0, nu=0.3, rho=1.0), r"layers\[0\]\['thickness'\]"),
    (dict(thickness=-1.0, G=1.0, nu=0.3, rho=1.0), r"thickness"),
    (dict(thickness=1.0, G=1.0, nu=0.5, rho=1.0), r"layers\[0\]\['nu'\]"),
    (dict(thickness=1.0, G=1.0, nu=-0.1, rho=1.0), r"'nu'"),
    (dict(thickness=1.0, G=1.0, nu=0.4995, rho=1.0), r"nearly incompressible"),
    (dict(thickness=1.0, G=0.0, nu=0.3, rho=1.0), r"\['G'\]"),
    (dict(thickness=1.0, Vs=-2.0, nu=0.3, rho=1.0), r"\['Vs'\]"),
    (dict(thickness=1.0, G=1.0, nu=0.3, rho=-1.0), r"\['rho'\]"),
    (dict(thickness=1.0, G=1.0, Vs=1.0, nu=0.3, rho=1.0), r"exactly one of"),
    (dict(thickness=1.0, G=1.0, nu=0.3, rho=1.0, Damping=0.1), r"unknown key.*Damping"),
    (dict(thickness=1.0, G=1.0, nu=0.3, rho=1.0, damping=-0.1), r"\['damping'\]"),
    (dict(thickness=1.0, G=1.0, nu=0.3), r"missing the key 'rho'"),
])
def test_bad_layers(layer, match):
    with pytest.raises(ValueError, match=match):
        Layered([layer])


def test_bad_arguments():
    with pytest.raises(TypeError, match="halfspace"):
        Layered([_layer(1.0)], halfspace="rock")
    with pytest.raises(ValueError, match="at least one layer"):
        Layered([])
    with pytest.raises(ValueError, match="damping_model"):
        Layered([_layer(1.0)], HalfSpace(G=1.0, nu=0.3, rho=1.0), damping_model="kelvin_voigt")
    L = Layered([_layer(1.0, damping=0.05)])
    p = grid(1.0, 1.0, 1, 1)
    with pytest.raises(ValueError, match="constant_q"):
        L.surface_flexibility(p, 0.0)
    with pytest.raises(ValueError, match="Re s"):
        L.surface_flexibility(p, -1.0)
    with pytest.raises(ValueError, match="components"):
        L.surface_flexibility(p, 1.0, components="q")
    # a rigid base at s = 0 is fine statically (Kelvin-Voigt keeps G(0) = G)
    kv = Layered([_layer(1.0, damping=0.05)], damping_model="kelvin_voigt")
    F = kv.surface_flexibility(p, 0.0)
    assert np.isfinite(F).all() and F[0, 0, 0].real > 0


# --- in the time domain ------------------------------------------------------------------------------

@pytest.mark.slow
def test_layered_soil_in_convolution_quadrature():
    """A damped layer on a damped half-space as a ``SoilFlexibility``: its BDF2 CQ weights decay and
    sum to the static flexibility (the generating function at zeta = 1 is Phi(s = 0))."""
    from unilateral.soil import SoilFlexibility
    p = strips(2.0, 6.0, 2)
    hs = HalfSpace(G=8e7, nu=0.3, rho=2000.0, damping=0.05, damping_model="kelvin_voigt",
                   omega_ref=2 * np.pi * 5)
    L = Layered([dict(thickness=2.0, Vs=120.0, nu=0.35, rho=1800.0, damping=0.05)], hs)
    soil = SoilFlexibility(lambda s: L.surface_flexibility(p, s), p.m, description="layered")
    W = soil.cq_weights(300, 2e-3, "bdf2")
    F0 = L.surface_flexibility(p, 0.0)[0].real
    err = np.abs(W.sum(0) - F0).max() / np.abs(F0).max()
    tail = np.abs(W[-20:]).max() / np.abs(W).max()
    print(f"CQ weights: |sum W - Phi(0)| / |Phi(0)| = {err:.1e}, tail {tail:.1e}")
    assert tail < 1e-5 and err < 1e-4


# --- compiled kernels against the numpy formulation ---------------------------------------------------

def _random_profile(rng, base, damping_model):
    """1-3 random layers (0.3 to 30 thick) on a random half-space or on a rigid base."""
    xi = 0.0 if damping_model is None else 0.03
    layers = [dict(thickness=float(h), G=float(rng.uniform(0.3, 5.0)), nu=float(rng.uniform(0.0, 0.45)),
                   rho=float(rng.uniform(0.8, 2.2)), damping=float(rng.uniform(0.0, xi)))
              for h in rng.choice([0.3, 1.0, 2.5, 30.0], size=int(rng.integers(1, 4)))]
    kw = {} if damping_model is None else dict(damping_model=damping_model, omega_ref=2.0)
    if base == "rigid":
        return Layered(layers, None, **kw)
    return Layered(layers, HalfSpace(G=float(rng.uniform(0.5, 20.0)), nu=float(rng.uniform(0.1, 0.45)),
                                     rho=1.3, damping=xi, **kw))


@pytest.mark.parametrize("seed", range(6))
def test_compiled_kernels_equal_numpy_reference(seed):
    """The compiled per-(s, k) loop (2 x 2 symmetric/antisymmetric split of the layer matrices,
    closed-form inverses) against the original batched numpy formulation (4 x 4 LAPACK solves),
    entry by entry, for random profiles, complex s (statics where allowed) and k on both parts of
    the contour, from k h = 0.015 to exp(-k h) below the smallest double. (For k h << 1 both lose
    about log10(1/(k h)) digits to the condensation, differently: see the next test.)"""
    rng = np.random.default_rng(seed)
    base = ("rigid", "halfspace")[seed % 2]
    model = (None, "kelvin_voigt", "constant_q")[seed % 3]
    L = _random_profile(rng, base, model)
    x = np.geomspace(0.05, 60.0, 25)
    k = np.concatenate([x * (1 + 0.3j), x + 1j * rng.uniform(0.05, 0.5)])
    s = np.array([0.7, 3j, 0.4 + 2j, 15.0 + 40j, 1e-3 + 1e-3j] + ([] if model == "constant_q" else [0.0]))
    got = L.kernels(k, s)
    ref = L._kernels_reference(k, s)
    worst = 0.0
    for name, r in ref.items():
        assert got[name].shape == r.shape == (s.size, k.size)
        assert np.all(np.isfinite(got[name]))
        worst = max(worst, float(np.max(np.abs(got[name] - r) / np.abs(r))))
    print(f"seed {seed} ({L!r}, {model}): compiled vs numpy kernels, max rel error {worst:.1e}")
    assert worst < 1e-12


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_compiled_kernels_as_accurate_as_numpy_for_thin_layers(nu):
    """Thin layers, k h down to 5e-4 (statics included): the stiffness formulation loses digits to
    the condensation (K ~ 1/h, the condensed stack O(1)) whatever the algebra, so the compiled and
    the numpy kernels differ by more than 1e-12 there (by up to their own error); both are measured
    against Lamb's kernels (a homogeneous stack) and must stay within the same bound."""
    from unilateral.soil import lamb
    hs = HalfSpace(G=2.0, nu=nu, rho=1.5)
    L = Layered([_layer(0.05, G=2.0, nu=nu, rho=1.5)] * 3, hs)
    x = np.geomspace(1e-2, 60.0, 25)
    k = np.concatenate([x * (1 + 0.3j), x + 0.2j])
    err = {"compiled": 0.0, "numpy": 0.0}
    for s in (0.0, 1e-3 + 1e-3j, 0.7, 3j, 0.4 + 2j, 15.0 + 40j):
        S = np.array([s * s * hs.rho / hs.G])
        krr, ktt, _ = lamb.tensor_kernels(k, S, lamb.eta_of(nu), nu)
        ref = {"zz": lamb.kernel(k, S, lamb.eta_of(nu), nu) + (1 - nu) / k, "rr": krr + (1 - nu) / k,
               "tt": ktt + 1 / k}
        for path, got in (("compiled", L.kernels(k, s)), ("numpy", L._kernels_reference(k, s))):
            for name, r in ref.items():
                err[path] = max(err[path], float(np.max(np.abs(got[name] - r / hs.G) / np.abs(r / hs.G))))
    print(f"thin layers, nu = {nu}: max rel error vs Lamb, compiled {err['compiled']:.1e}, "
          f"numpy {err['numpy']:.1e}")
    assert err["compiled"] < 5e-11 and err["numpy"] < 5e-11       # measured <= 1.5e-11, 3.1e-12


@pytest.mark.parametrize("components", ["z", "xyz"])
def test_surface_flexibility_equals_numpy_reference_path(monkeypatch, components):
    """The whole flexibility with the compiled kernels evaluated in small blocks equals the one with
    the numpy kernels in one block per group of s (the former code path)."""
    from unilateral.soil import layered
    L = Layered([_layer(0.6, G=1.0), _layer(1.5, G=3.0, nu=0.25, damping=0.02)],
                HalfSpace(G=6.0, nu=0.3, rho=1.1, damping=0.02))
    p = RectangularPatchesMixed()
    s = np.array([0.7, 2.0 + 1.5j, 2.0 - 1.5j, 3j, 0.1j, 8.0 + 20j])
    monkeypatch.setattr(layered, "_BLOCK", 50)          # several blocks per group
    new = L.surface_flexibility(p, s, components=components)
    monkeypatch.setattr(layered, "_BLOCK", 10 ** 12)
    monkeypatch.setattr(Layered, "_kernels_compiled",
                        lambda self, k, sq, sh: self._kernels_reference(k, sq, sh=sh))
    old = L.surface_flexibility(p, s, components=components)
    err = _rel(new, old)
    print(f"surface_flexibility ({components}): compiled blocks vs numpy path {err:.1e}")
    assert err < 1e-12
