"""Tests of the linear stability reference (linear_stability.py) and of its data against values
that do not come from it: the benchmark vehicle's masses, CONTACT's conicity, the contact unit's
own forces, the asymptotes of the free wheelset and a Routh–Hurwitz closed form."""

import csv
import math
import pathlib

import numpy as np
import pytest

import linear_stability as ls

ROOT = pathlib.Path(__file__).resolve().parents[3]
G = 9.81


@pytest.fixture(scope="module")
def parameters():
    return ls.load_parameters()


@pytest.fixture(scope="module")
def data():
    return ls.load_contact_data()


@pytest.fixture(scope="module")
def model(data):
    return ls.ContactModel(data)


def test_every_parameter_has_a_value_a_unit_and_a_source():
    import tomllib
    with open(ls.PARAMETERS, "rb") as file:
        document = tomllib.load(file)
    for table, entries in document.items():
        for name, entry in entries.items():
            assert set(entry) == {"value", "unit", "source"}, f"{table}.{name}"
            assert entry["source"], f"{table}.{name} has no source"


def test_derived_parameters_follow_from_the_benchmark(parameters):
    """Axle load: the Manchester vehicle's body 32 000 kg, two bogie frames of 2615 kg and four
    wheelsets of 1813 kg (Iwnicki 1998) on four axles; s: flange backs 1360 mm apart, running
    circles 70 mm outside them (S1002 on the Manchester track)."""
    w = parameters["wheelset"]
    assert w["axle_load"] == pytest.approx((32000 + 2 * 2615 + 4 * 1813) * G / 4, abs=0.1)
    assert w["half_contact_distance"] == pytest.approx((1.360 + 2 * 0.070) / 2, abs=1e-12)


def test_contact_data_was_made_from_these_parameters(parameters, data):
    """contact_data.json is regenerated when the parameter file changes."""
    assert data["wheel_load"] == pytest.approx(parameters["wheelset"]["axle_load"] / 2, rel=1e-8)
    assert data["shear_modulus"] == parameters["contact"]["shear_modulus"]
    assert data["poisson_ratio"] == parameters["contact"]["poisson_ratio"]
    assert data["nominal_radius"] == parameters["wheelset"]["nominal_rolling_radius"]
    assert (data["wheel_profile"], data["rail_profile"]) == (
        parameters["contact"]["wheel_profile"], parameters["contact"]["rail_profile"])


def test_equivalent_conicity_matches_contact(model):
    """tan γ_e in the data against CONTACT rev. 2707's Δr put through an independent Runge–Kutta
    integration of the kinematic motion (core/tests/data/conicity_contact_tan_gamma.csv,
    docs/conicity.md): within 1 % at every amplitude both have (0.5–6 mm)."""
    with open(ROOT / "core" / "tests" / "data" / "conicity_contact_tan_gamma.csv") as file:
        rows = [row for row in csv.reader(line for line in file if not line.startswith("#"))][1:]
    compared = 0
    for row in rows:
        amplitude = float(row[0]) * 1e-3
        if amplitude <= 6e-3 and abs(amplitude / 0.25e-3 - round(amplitude / 0.25e-3)) < 1e-9:
            assert model.equivalent_conicity(amplitude) == pytest.approx(float(row[1]), rel=0.01), row
            compared += 1
    assert compared >= 10


def _harmonic(lateral, force, amplitude, nodes=4000):
    """−K of F ≈ −K y by the first Fourier coefficient over y = A sin θ (computed here anew)."""
    theta = (np.arange(nodes) + 0.5) * math.pi / nodes
    return -2 / (math.pi * amplitude) * np.sum(np.interp(amplitude * np.sin(theta), lateral, force)
                                               * np.sin(theta)) * math.pi / nodes


@pytest.mark.parametrize("amplitude", [2e-3, 3e-3, 4.5e-3])
def test_force_model_reproduces_the_contact_unit_at_rest(data, model, amplitude):
    """The reference's lateral stiffness k_c (normal forces minus the lateral spin creep force,
    from each patch's N, δ, f23) and its creep yaw stiffness k_ψy (each patch's f11 and rolling
    radius, wheel spin imposed) against the same quantities linearised from the forces that the
    contact unit itself computes (`WheelRailContact`, `kalker_linear`, at rest in y and ψ).
    They check the signs and the presence of every term: without the spin creep force k_c would
    be 5–6 times larger (k_grav). Tolerances: the reference drops the creep forces' share of
    the vertical balance and cos δ in the lateral creep force (≈ 1–2 % of k_c, measured)."""
    lateral = model.lateral
    force = np.array([s["right_at_rest"]["force_lateral"] + s["left_at_rest"]["force_lateral"]
                      for s in data["samples"]])
    moment = np.array([s["right_at_rest"]["moment_yaw"] + s["left_at_rest"]["moment_yaw"]
                       for s in data["samples"]])
    c = model.linearised(amplitude, free_spin=False)
    assert c["contact_stiffness"] == pytest.approx(_harmonic(lateral, force, amplitude), rel=0.03)
    assert c["gravitational_stiffness"] > 4 * c["contact_stiffness"] > 0
    assert c["creep_yaw_stiffness"] + c["spin_yaw_stiffness"] == pytest.approx(
        _harmonic(lateral, moment, amplitude), rel=0.015)


@pytest.mark.parametrize("amplitude", [3e-3, 4.5e-3])
def test_free_wheelset_oscillates_at_klingels_frequency(parameters, model, amplitude):
    """The free wheelset (no suspension) at low speed: its kinematic mode's frequency tends to
    Klingel's ω = V √(tan γ_e / (r0 s)) (Klingel 1883; Wickens 2003 ch. 2), with γ_e the library's
    at that amplitude. Within 1 % with the wheel spin free (each wheel rolls without creepage);
    with the spin imposed (Ω = V/r_c) the stiffer wheel's f11 dominates and the frequency is
    3–5 % low (docs/wheelset.md)."""
    klingel = ls.variant(parameters, "klingel_check")
    free, imposed = model.linearised(amplitude), model.linearised(amplitude, free_spin=False)
    for speed in (0.5, 1.0, 2.0):
        expected = ls.klingel_frequency(free, speed)
        assert ls.kinematic_mode(klingel, free, speed).imag == pytest.approx(expected, rel=0.01)
        assert ls.kinematic_mode(klingel, imposed, speed).imag < 0.98 * expected


def test_free_wheelset_creep_modes_at_low_speed(parameters, model):
    """At low speed the free wheelset's two other modes are the creep forces' first-order lags,
    λ → −2 f22/(m V) and −d_ψ/(I V) (the creep forces act as dampers 2 f22/V, d_ψ/V; their
    coupling through conicity is of order V⁰, negligible against 1/V as V → 0)."""
    klingel = ls.variant(parameters, "klingel_check")
    c = model.linearised(3e-3)
    w = parameters["wheelset"]
    speed = 0.2
    fast = sorted(ls.eigenvalues(klingel, c, speed).real)[:2]
    expected = sorted([-2 * c["f22"] / (w["mass"] * speed), -c["yaw_creep_damping"] / (w["yaw_inertia"] * speed)])
    assert fast == pytest.approx(expected, rel=0.01)


def _yaw_stiffness_only(parameters, model, yaw_stiffness, yaw_inertia=None):
    """The wheelset on a yaw spring k_ψ alone: no lateral spring, no dampers, no spin creep or
    contact stiffness (the simplified model of the closed form)."""
    b1 = parameters["primary_suspension"]["lateral_semi_spacing"]
    suspension = dict(parameters["primary_suspension"], longitudinal_stiffness=yaw_stiffness / (2 * b1 * b1),
                      lateral_stiffness=0.0, longitudinal_damping=0.0, lateral_damping=0.0)
    wheelset = dict(parameters["wheelset"])
    if yaw_inertia is not None:
        wheelset["yaw_inertia"] = yaw_inertia
    contact = dict(model.linearised(4.5e-3), f23=0.0, f33=0.0, spin_yaw_stiffness=0.0, contact_stiffness=0.0)
    return dict(parameters, primary_suspension=suspension, wheelset=wheelset), contact


def _routh_hurwitz_critical_speed(parameters, contact, yaw_stiffness):
    """Hand-derived: det [[m λ² + a λ, −2 f22], [K, I λ² + b λ + k_ψ]] = 0 with a = 2 f22/V,
    b = d_ψ/V, K = k_ψy is a4 λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0 with a4 = m I, a3 = P/V
    (P = m d_ψ + 2 f22 I), a2 = m k_ψ + 2 f22 d_ψ/V², a1 = 2 f22 k_ψ/V, a0 = 2 f22 K. Hurwitz's
    boundary a3 a2 a1 = a4 a1² + a3² a0 gives
    1/V² = (2 m I f22 k_ψ² + P² K − P m k_ψ²) / (2 P f22 d_ψ k_ψ)."""
    m, inertia = parameters["wheelset"]["mass"], parameters["wheelset"]["yaw_inertia"]
    f22, d, k = contact["f22"], contact["yaw_creep_damping"], contact["creep_yaw_stiffness"]
    p = m * d + 2 * f22 * inertia
    u2 = (2 * m * inertia * f22 * yaw_stiffness ** 2 + p * p * k - p * m * yaw_stiffness ** 2) / (
        2 * p * f22 * d * yaw_stiffness)
    return 1 / math.sqrt(u2)


@pytest.mark.parametrize("yaw_stiffness", [0.5e6, 2e6, 8e6])
def test_critical_speed_of_the_wheelset_on_a_yaw_spring(parameters, model, yaw_stiffness):
    """The eigenvalues' zero crossing against the Routh–Hurwitz closed form (k_ψ in N m/rad)."""
    p, c = _yaw_stiffness_only(parameters, model, yaw_stiffness)
    assert ls.critical_speed(p, c, high=2000.0) == pytest.approx(
        _routh_hurwitz_critical_speed(p, c, yaw_stiffness), rel=1e-5)


def test_critical_speed_of_the_yaw_spring_model_without_yaw_inertia(parameters, model):
    """Its textbook limit: without yaw inertia (here 10⁻² kg m²) and with k_ψ² ≪ d_ψ K (d_ψ = 2 f11 s²,
    K = 2 f11 s γ / r0), V_c² = f22 k_ψ r0 / (m f11 s γ) (the classical form of the yaw-spring
    wheelset's critical speed, e.g. Wickens 2003; derived here from the closed form above), in
    the same variables: V_c² = 2 f22 d_ψ k_ψ / (m d_ψ K). Within 1 % for k_ψ² = 10⁻⁴ d_ψ K."""
    c0 = model.linearised(4.5e-3)
    yaw_stiffness = 1e-2 * math.sqrt(c0["yaw_creep_damping"] * c0["creep_yaw_stiffness"])
    p, c = _yaw_stiffness_only(parameters, model, yaw_stiffness, yaw_inertia=1e-2)
    expected = math.sqrt(2 * c["f22"] * yaw_stiffness / (p["wheelset"]["mass"] * c["creep_yaw_stiffness"]))
    assert ls.critical_speed(p, c, low=0.1, high=2000.0) == pytest.approx(expected, rel=0.01)
