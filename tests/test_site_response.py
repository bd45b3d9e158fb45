"""Free field by linear 1D site response (unilateral.loads.site_response) and [site] in model files.

Closed forms used (Kramer 1996, ch. 7): a uniform layer of thickness H and speed V over a rigid
base amplifies the base motion by 1/cos(omega H / V); over an elastic half-space of impedance
ratio a = Z_layer / Z_rock the outcrop motion is amplified by 1/(cos(omega H/V) + i a sin(omega H/V)),
whose peak 1/a is at f = V/(4H), and whose impulse response is the series of arrivals
2/(1 + a) * (-r)^n at (2n + 1) H/V, r = (1 - a)/(1 + a).
"""

import json
import re

import numpy as np
import pytest

from unilateral.loads import read_text_record
from unilateral.loads.site_response import free_field, transfer_function
from unilateral.modelfile import ModelFileError, load_model_file

H, VS, RHO = 20.0, 200.0, 1.9              # m, m/s, t/m^3: f1 = Vs/(4H) = 2.5 Hz, H/Vs = 0.1 s
NU = 0.3
VP = VS * np.sqrt(2 * (1 - NU) / (1 - 2 * NU))
F1 = VS / (4 * H)


def layer(**changes):
    return {"thickness": H, "Vs": VS, "nu": NU, "rho": RHO, "damping": 0.0} | changes


def rock(**changes):
    return {"Vs": 1000.0, "nu": 0.25, "rho": 2.4, "damping": 0.0} | changes


def gaussian(t, t0, sigma):
    return np.exp(-0.5 * ((t - t0) / sigma) ** 2)


# ---------------------------------------------------------------------- closed forms
def test_undamped_layer_on_rigid_base_amplifies_by_one_over_cos():
    f = np.array([0.0, 0.3, 0.9, 1.7, 3.1, 4.4]) * F1           # away from the poles (2n+1) f1
    H_f = transfer_function(f, [layer()], None, at="within", depth=H)
    expected = 1.0 / np.cos(2 * np.pi * f * H / VS)
    print("rigid base |H|:", np.round(np.abs(H_f), 6), "1/cos:", np.round(expected, 6))
    np.testing.assert_allclose(H_f, expected, rtol=1e-12, atol=1e-12)
    # two layers of the same material are one layer
    halves = [layer(thickness=H / 3), layer(thickness=2 * H / 3)]
    np.testing.assert_allclose(transfer_function(f, halves, None, at="within", depth=H), expected, rtol=1e-12)


def test_steady_sine_on_a_rigid_base_is_amplified_by_one_over_cos():
    xi, dt, f = 0.02, 0.005, 0.6 * F1
    t = np.arange(8000) * dt                                      # 40 s
    base = np.sin(2 * np.pi * f * t) * np.minimum(t / 2.0, 1.0)   # ramped on over 2 s
    surface = free_field(base, dt, [layer(damping=xi)], None, at="within", depth=H)
    window = (t > 28.0) & (t < 38.0)                              # the transient (1/(xi w1) = 3.2 s) is gone
    basis = np.column_stack([np.sin(2 * np.pi * f * t[window]), np.cos(2 * np.pi * f * t[window])])
    (s, c), *_ = np.linalg.lstsq(basis, surface[window], rcond=None)
    amplitude, phase = np.hypot(s, c), np.arctan2(c, s)
    damped = transfer_function([f], [layer(damping=xi)], None, at="within", depth=H)[0]
    undamped = 1.0 / np.cos(2 * np.pi * f * H / VS)
    print(f"steady sine at {f:g} Hz: amplitude {amplitude:.6f}, |H| damped {abs(damped):.6f}, "
          f"1/cos {undamped:.6f}")
    assert amplitude == pytest.approx(abs(damped), rel=1e-6)
    assert phase == pytest.approx(np.angle(damped), abs=1e-6)
    assert amplitude == pytest.approx(undamped, rel=3 * xi)        # small damping: near the undamped value
    residual = surface[window] - basis @ [s, c]
    assert np.max(np.abs(residual)) < 1e-4 * amplitude           # what is left of the transient


def test_no_impedance_contrast_passes_the_outcrop_motion_unchanged():
    # rock of the layer's material: the wave passes the interface without reflection; the surface
    # motion is twice the incident wave, i.e. the outcrop motion, H/Vs later (the outcrop motion is
    # referred to the top of the rock)
    f = np.linspace(0.0, 20.0, 201)
    H_f = transfer_function(f, [layer()], rock(Vs=VS, rho=RHO), at="outcrop")
    np.testing.assert_allclose(np.abs(H_f), 1.0, rtol=1e-13)
    np.testing.assert_allclose(H_f, np.exp(-2j * np.pi * f * H / VS), rtol=1e-12, atol=1e-12)
    dt = 0.002                                                    # H/Vs = 50 steps
    rng = np.random.default_rng(1)
    acc = np.convolve(rng.standard_normal(2000), np.hanning(15), mode="same")
    surface = free_field(acc, dt, [layer()], rock(Vs=VS, rho=RHO), at="outcrop")
    delay = round(H / VS / dt)
    error = np.max(np.abs(surface[delay:] - acc[:-delay])) / np.max(np.abs(acc))
    print(f"same material: max |surface(t) - outcrop(t - H/Vs)| / max|outcrop| = {error:.2e}")
    assert error < 1e-12
    assert np.max(np.abs(surface[:delay])) < 1e-12 * np.max(np.abs(acc))


def test_within_at_depth_zero_is_the_surface_motion():
    acc = np.sin(np.linspace(0.0, 30.0, 777)) ** 3
    for base in (rock(), None):
        np.testing.assert_array_equal(free_field(acc, 0.01, [layer(damping=0.05)], base, at="surface"), acc)
        within = free_field(acc, 0.01, [layer(damping=0.05)], base, at="within", depth=0.0)
        np.testing.assert_allclose(within, acc, rtol=0, atol=1e-13)
    np.testing.assert_allclose(transfer_function([0.5, 3.0], [layer()], rock(), at="within", depth=0), 1.0)


@pytest.mark.parametrize("wave, speed", [("S", VS), ("P", VP)])
def test_resonance_of_a_soft_layer_on_stiff_rock_is_at_v_over_4H(wave, speed):
    f = np.linspace(0.01, 1.5 * speed / (4 * H), 150001)
    contrast = rock()["rho"] * (1000.0 * (1.0 if wave == "S" else np.sqrt(2 * 0.75 / 0.5))) / (RHO * speed)
    undamped = np.abs(transfer_function(f, [layer()], rock(), wave=wave))
    peak = f[np.argmax(undamped)]
    print(f"{wave}: peak at {peak:.5f} Hz, V/(4H) = {speed / (4 * H):.5f} Hz, peak {undamped.max():.6f}, "
          f"Z_rock/Z_soil = {contrast:.6f}")
    assert abs(peak - speed / (4 * H)) <= f[1] - f[0]
    at_f1 = abs(transfer_function([speed / (4 * H)], [layer()], rock(), wave=wave)[0])
    assert at_f1 == pytest.approx(contrast, rel=1e-12)
    damped = np.abs(transfer_function(f, [layer(damping=0.05)], rock(damping=0.01), wave=wave))
    assert f[np.argmax(damped)] == pytest.approx(speed / (4 * H), rel=0.01)
    assert damped.max() < undamped.max()


@pytest.mark.parametrize("wave, speed", [("S", VS), ("P", VP)])
def test_outcrop_impulse_arrives_after_the_travel_time(wave, speed):
    # a narrow Gaussian pulse at the outcrop; the surface motion is the series of arrivals
    # 2/(1 + a) (-r)^n at (2n + 1) tau, tau = H/V (causal: nothing before tau)
    dt, sigma, t0 = 0.0005, 0.004, 0.05
    tau = H / speed
    rock_speed = 1000.0 if wave == "S" else 1000.0 * np.sqrt(2 * 0.75 / 0.5)
    a = RHO * speed / (rock()["rho"] * rock_speed)
    r = (1 - a) / (1 + a)
    t = np.arange(4000) * dt                                          # 2 s
    outcrop = gaussian(t, t0, sigma)
    surface = free_field(outcrop, dt, [layer()], rock(), at="outcrop", wave=wave)
    exact = sum(2 / (1 + a) * (-r) ** n * gaussian(t, t0 + (2 * n + 1) * tau, sigma) for n in range(200))
    before = t < t0 + tau - 8 * sigma
    print(f"{wave}: tau = {tau:.5f} s, first arrival {surface.max():.6f} (2/(1+a) = {2 / (1 + a):.6f}), "
          f"max before tau {np.max(np.abs(surface[before])):.1e}, max error {np.max(np.abs(surface - exact)):.1e}")
    assert np.max(np.abs(surface[before])) < 1e-10
    np.testing.assert_allclose(surface, exact, rtol=0, atol=1e-9)
    # incident energy flux (Z_rock integral v_inc^2) equals the flux reflected into the rock: the
    # surface motion is that of a lossless column, checked through the undamped |H| <= 1/a
    assert np.max(np.abs(surface)) <= 2 / (1 + a) + 1e-9


def test_hysteretic_damping_has_a_small_acausal_precursor():
    # G (1 + 2 i xi) at every frequency is not causal (Kramers-Kronig): with damping a little of a
    # sharp pulse shows before the travel time; the precursor grows with xi and stays below xi
    dt, sigma, t0 = 0.0005, 0.004, 0.3
    t = np.arange(6000) * dt
    outcrop = gaussian(t, t0, sigma)
    before = t < t0 + H / VS - 8 * sigma
    ratios = []
    for xi in (0.0, 0.01, 0.02, 0.05):
        surface = free_field(outcrop, dt, [layer(damping=xi)], rock(), at="outcrop")
        ratios.append(np.max(np.abs(surface[before])) / np.max(np.abs(surface)))
    print("precursor / peak for xi = 0, 0.01, 0.02, 0.05:", np.array(ratios).round(5))
    assert ratios[0] < 1e-12
    assert all(a < b for a, b in zip(ratios, ratios[1:]))
    assert all(r < xi for r, xi in zip(ratios[1:], (0.01, 0.02, 0.05)))


def test_padding_keeps_the_ringing_of_the_records_end_off_its_start():
    dt, sigma = 0.001, 0.004
    t = np.arange(3000) * dt
    outcrop = gaussian(t, t[-1] - 0.05, sigma)                        # a pulse near the end of the record
    soft = [layer(damping=0.02)]
    padded = free_field(outcrop, dt, soft, rock(), at="outcrop")
    wrapped = free_field(outcrop, dt, soft, rock(), at="outcrop", pad=0.0)
    start = t < 1.0                                                   # long before the pulse
    print(f"max |surface| over the first second: padded {np.max(np.abs(padded[start])):.1e}, "
          f"unpadded {np.max(np.abs(wrapped[start])):.1e}")
    assert np.max(np.abs(padded[start])) < 1e-5
    assert np.max(np.abs(wrapped[start])) > 1e-2


def test_a_thick_damped_profile_does_not_overflow():
    # |exp(i k h)| = exp(omega xi h / V) is far beyond the floating-point range at high frequencies
    thick = [layer(thickness=2000.0, Vs=100.0, damping=0.3)]
    H_f = transfer_function([0.0, 1.0, 100.0, 1000.0], thick, rock(), at="outcrop")
    assert np.all(np.isfinite(H_f)) and H_f[0] == 1.0 and abs(H_f[2]) < 1e-100
    surface = free_field(np.random.default_rng(0).standard_normal(2000), 0.001, thick, None, at="within",
                         depth=1500.0)
    assert np.all(np.isfinite(surface))


def test_undamped_column_on_a_rigid_base_warns_that_it_rings_on():
    with pytest.warns(RuntimeWarning, match="does not decay"):
        free_field(np.ones(100), 0.01, [layer()], None, at="within", depth=H)


# ---------------------------------------------------------------------- argument checks
BAD = [
    (dict(layers=[layer(thickness=0.0)]), ValueError, "layers[0]: thickness = 0.0 must be > 0"),
    (dict(layers=[layer(nu=0.5)]), ValueError, "layers[0]: nu = 0.5 must be >= 0 and < 0.5"),
    (dict(layers=[layer(nu=-0.1)]), ValueError, "layers[0]: nu = -0.1 must be >= 0 and < 0.5"),
    (dict(layers=[layer(G=76e3)]), ValueError, "layers[0]: give either G (shear modulus [F/L^2]) or Vs "
                                               "(shear-wave speed [L/T]), not both"),
    (dict(layers=[{"thickness": H, "rho": RHO}]), ValueError, "layers[0]: give either G"),
    (dict(base={"Vs": 1000.0}), ValueError, "base: missing 'rho'"),
    (dict(layers=[layer(Vs=200.0, thick=1.0)]), ValueError, "layers[0]: unknown key 'thick'"),
    (dict(layers=[layer(nu=None)], wave="P"), ValueError, "layers[0]: missing 'nu' (P waves need"),
    (dict(at="borehole"), ValueError, "at must be one of 'surface', 'outcrop', 'within'"),
    (dict(wave="SH"), ValueError, "wave must be 'S'"),
    (dict(at="within"), ValueError, "depth is required with at='within'"),
    (dict(at="within", depth=H + 0.5), ValueError, "depth=20.5 is below the profile: give 0 <= depth <= 20"),
    (dict(at="within", depth=-1.0), ValueError, "depth must be a finite number >= 0"),
    (dict(at="outcrop", depth=3.0), ValueError, "depth is only for at='within'"),
    (dict(base=None), ValueError, "at='outcrop' needs an elastic half-space: a rigid base (base=None) has no "
                                  "outcrop motion"),
    (dict(dt=0.0), ValueError, "dt must be a positive finite number"),
]


@pytest.mark.parametrize("change, error, message", BAD, ids=[m[:30] for _, _, m in BAD])
def test_bad_arguments_are_named(change, error, message):
    arguments = dict(acc=np.ones(10), dt=0.01, layers=[layer()], base=rock(), at="outcrop") | change
    with pytest.raises(error, match=re.escape(message)):
        free_field(**arguments)


def test_a_rigid_base_takes_the_base_motion_within():
    f = np.array([0.7, 1.3])
    np.testing.assert_allclose(transfer_function(f, [layer(damping=0.05)], None, at="within", depth=H),
                               transfer_function(f, [layer(damping=0.05)], rock(), at="within", depth=H))


# ---------------------------------------------------------------------- model files
def toml_text(document: dict) -> str:
    def inline(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(inline(x) for x in v) + "]"
        if isinstance(v, dict):
            return "{" + ", ".join(f"{k} = {inline(x)}" for k, x in v.items()) + "}"
        return repr(v)
    return "".join(f"{key} = {inline(value)}\n" for key, value in document.items())


SITE = {"layers": [{"thickness": 12.0, "Vs": 180.0, "nu": 0.35, "rho": 1.8, "damping": 0.04},
                   {"thickness": 18.0, "Vs": 320.0, "nu": 0.3, "rho": 2.0, "damping": 0.03}],
        "base": {"Vs": 900.0, "nu": 0.25, "rho": 2.3, "damping": 0.01}}
RECORD_DT = 0.005


def column(tmp_path, motion: dict, site=SITE, units=None) -> dict:
    """A cantilever column with a mass on top, shaken by a 4 s text record (m/s2) written in tmp_path."""
    t = np.arange(800) * RECORD_DT
    values = np.sin(2 * np.pi * 1.7 * t) * gaussian(t, 1.5, 0.4) + 0.3 * gaussian(t, 0.8, 0.02)
    np.savetxt(tmp_path / "record.txt", values)
    document = {"units": units or {"length": "m", "force": "kN", "time": "s"},
                "nodes": [{"id": 1, "x": 0.0, "y": 0.0}, {"id": 2, "x": 0.0, "y": 3.0}],
                "supports": [{"node": 1, "rz": True}],
                "elements": [{"type": "beam", "name": "column", "node_i": 1, "node_j": 2, "E": 30e6, "A": 0.16,
                              "I": 2e-3}],
                "masses": [{"node": 2, "m": 40.0}],
                "loads": {"ground_motion": [{"file": "record.txt", "units": "m/s2", "dt": RECORD_DT, "scale": 1.5}
                                            | motion]},
                "analysis": {"dt": RECORD_DT, "t_end": 0.1}}
    if site is not None:
        document["site"] = site
    return document


def write(tmp_path, document):
    path = tmp_path / "model.toml"
    path.write_text(toml_text(document))
    return path


def ground_load(spec, direction):
    """(N,) the ground acceleration of the load -M r a_g at the record's samples."""
    r = np.array([name.endswith("." + direction) for name in spec.model.dof_names], dtype=float)
    Mr = spec.model.M @ r
    k = int(np.argmax(np.abs(Mr)))
    t = np.arange(800) * RECORD_DT
    return np.array([(spec.load(tk) - spec.load.constant)[k] for tk in t]) / -Mr[k]


@pytest.mark.parametrize("direction, wave", [("ux", "S"), ("uy", "P")])
def test_model_file_outcrop_record_gives_the_free_field(tmp_path, direction, wave):
    spec = load_model_file(write(tmp_path, column(tmp_path, {"direction": direction, "at": "outcrop"})))
    record = read_text_record(tmp_path / "record.txt", units="m/s2", dt=RECORD_DT)
    expected = 1.5 * free_field(record.acceleration, RECORD_DT, SITE["layers"], SITE["base"], at="outcrop",
                                wave=wave)
    got = ground_load(spec, direction)
    print(f"{direction}: peak outcrop {1.5 * record.pga:.4f}, peak free field {np.max(np.abs(got)):.4f} m/s2")
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)
    assert not np.allclose(got, 1.5 * record.acceleration, atol=1e-3)       # the site changed the motion
    surface = load_model_file(write(tmp_path, column(tmp_path, {"direction": direction})))
    np.testing.assert_allclose(ground_load(surface, direction), 1.5 * record.acceleration, rtol=1e-12, atol=1e-14)


def test_model_file_within_and_rigid_base(tmp_path):
    site = {"layers": SITE["layers"], "base": "rigid"}
    spec = load_model_file(write(tmp_path, column(tmp_path, {"direction": "ux", "at": "within", "depth": 30.0},
                                                  site=site)))
    record = read_text_record(tmp_path / "record.txt", units="m/s2", dt=RECORD_DT)
    expected = 1.5 * free_field(record.acceleration, RECORD_DT, SITE["layers"], None, at="within", depth=30.0)
    np.testing.assert_allclose(ground_load(spec, "ux"), expected, rtol=1e-12, atol=1e-12)


def test_model_file_site_density_follows_the_mass_unit(tmp_path):
    # rho in kg/m^3 with units.mass = "kg" is the same site as rho in t/m^3 (= kN s^2/m^4)
    in_kg = {"layers": [dict(x, rho=x["rho"] * 1000.0) for x in SITE["layers"]],
             "base": dict(SITE["base"], rho=SITE["base"]["rho"] * 1000.0)}
    document = column(tmp_path, {"direction": "ux", "at": "outcrop"}, site=in_kg,
                      units={"length": "m", "force": "kN", "time": "s", "mass": "kg"})
    document["masses"] = [{"node": 2, "m": 40e3}]
    spec = load_model_file(write(tmp_path, document))
    reference = load_model_file(write(tmp_path, column(tmp_path, {"direction": "ux", "at": "outcrop"})))
    np.testing.assert_allclose(ground_load(spec, "ux"), ground_load(reference, "ux"), rtol=1e-10, atol=1e-12)


SITE_ERRORS = {
    "no site": ({"direction": "ux", "at": "outcrop"}, None,
                'loads.ground_motion[0].at = "outcrop": needs the [site] table with the soil profile under the record '
                '(layers = [{thickness, Vs or G, nu, rho, damping}, ...] and base = {Vs or G, nu, rho, damping} or '
                '"rigid")'),
    "unknown at": ({"direction": "ux", "at": "outcorp"}, SITE,
                   'loads.ground_motion[0].at = "outcorp": unknown record location (valid: surface, outcrop, '
                   'within); did you mean "outcrop"?'),
    "within without depth": ({"direction": "ux", "at": "within"}, SITE,
                             'loads.ground_motion[0].depth: missing key (at = "within" needs the depth [L]'),
    "depth below": ({"direction": "ux", "at": "within", "depth": 31.0}, SITE,
                    "loads.ground_motion[0].depth = 31.0: below the [site] profile: give 0 <= depth <= 30"),
    "depth without within": ({"direction": "ux", "depth": 3.0}, SITE,
                             'loads.ground_motion[0].depth = 3.0: only for at = "within"'),
    "negative depth": ({"direction": "ux", "at": "within", "depth": -3.0}, SITE,
                       "loads.ground_motion[0].depth = -3.0: must be >= 0"),
    "outcrop of a rigid base": ({"direction": "ux", "at": "outcrop"}, {"layers": SITE["layers"], "base": "rigid"},
                                'loads.ground_motion[0].at = "outcrop": a rigid base (site.base = "rigid") has no '
                                'outcrop motion: give the motion of the base with at = "within", depth = 30'),
    "bad base": ({"direction": "ux", "at": "outcrop"}, {"layers": SITE["layers"], "base": "rock"},
                 'site: base = "rock": expected "rigid" or a table'),
    "G and Vs": ({"direction": "ux", "at": "outcrop"},
                 {"layers": [SITE["layers"][0] | {"G": 6e4}], "base": SITE["base"]},
                 "site.layers[0].Vs = 180.0: give either G or Vs, not both"),
    "no G or Vs": ({"direction": "ux", "at": "outcrop"},
                   {"layers": SITE["layers"], "base": {"nu": 0.25, "rho": 2.3}},
                   "site.base.G: missing key (give G [F/L^2] or Vs [L/T])"),
    "nu for P waves": ({"direction": "uy", "at": "outcrop"},
                       {"layers": SITE["layers"], "base": {"Vs": 900.0, "rho": 2.3}},
                       "site.base.nu: missing key (loads.ground_motion[0] is vertical: P waves, which need "
                       "Poisson's ratio"),
    "nu range": ({"direction": "ux", "at": "outcrop"},
                 {"layers": [SITE["layers"][0] | {"nu": 0.5}], "base": SITE["base"]},
                 "site.layers[0].nu = 0.5: must be < 0.5"),
    "thickness": ({"direction": "ux", "at": "outcrop"},
                  {"layers": [SITE["layers"][0] | {"thickness": 0.0}], "base": SITE["base"]},
                  "site.layers[0].thickness = 0.0: must be > 0"),
    "no layers": ({"direction": "ux", "at": "outcrop"}, {"layers": [], "base": SITE["base"]},
                  "site.layers = []: give at least one layer"),
    "wave in a frame": ({"direction": "ux", "at": "outcrop", "wave": "S"}, SITE,
                        'loads.ground_motion[0].wave = "S": only for matrix-level models'),
    "unknown site key": ({"direction": "ux"}, SITE | {"bedrock": 3.0},
                         "site.bedrock: unknown key (valid keys: layers, base)"),
}


@pytest.mark.parametrize("motion, site, message", SITE_ERRORS.values(), ids=SITE_ERRORS)
def test_model_file_site_errors_are_named(tmp_path, motion, site, message):
    with pytest.raises(ModelFileError, match=re.escape("model.toml: " + message)):
        load_model_file(write(tmp_path, column(tmp_path, motion, site=site)))


def test_model_file_site_problems_are_listed_together(tmp_path):
    site = {"layers": [SITE["layers"][0] | {"G": 6e4}], "base": "rigid"}
    document = column(tmp_path, {"direction": "ux", "at": "outcrop", "depth": 3.0}, site=site)
    with pytest.raises(ModelFileError) as info:
        load_model_file(write(tmp_path, document))
    print(info.value)
    assert len(info.value.problems) == 3


def test_matrix_level_model_needs_the_wave_type(tmp_path):
    import scipy.io

    from unilateral.structure import liolios1990

    model = liolios1990()[0].to_model()
    for key in ("K", "M", "C", "F", "H", "F_v", "H_v"):
        scipy.io.mmwrite(tmp_path / f"{key}.mtx", getattr(model, key))
    r = np.array([1.0, 0.0, 0.0, 0.0, 0.0])
    scipy.io.mmwrite(tmp_path / "r.mtx", r[:, None])
    document = column(tmp_path, {"influence": "r.mtx", "at": "outcrop"})
    document = {"units": document["units"], "site": SITE, "loads": document["loads"],
                "matrices": {key: f"{key}.mtx" for key in ("K", "M", "C", "F", "H", "F_v", "H_v")},
                "analysis": document["analysis"]}
    with pytest.raises(ModelFileError, match=re.escape(
            'model.toml: loads.ground_motion[0].wave: missing key (a matrix-level model with at = "outcrop" needs '
            'wave = "S" (horizontal motion) or "P" (vertical))')):
        load_model_file(write(tmp_path, document))
    document["loads"]["ground_motion"][0]["wave"] = "S"
    spec = load_model_file(write(tmp_path, document))
    record = read_text_record(tmp_path / "record.txt", units="m/s2", dt=RECORD_DT)
    expected = 1.5 * free_field(record.acceleration, RECORD_DT, SITE["layers"], SITE["base"], at="outcrop")
    t = np.arange(800) * RECORD_DT
    got = np.array([(spec.load(tk) - spec.load.constant)[0] for tk in t]) / -(model.M @ r)[0]
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)
