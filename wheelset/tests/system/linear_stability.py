"""The linear stability reference of the suspended wheelset (issue 28; docs/wheelset.md).

A rigid wheelset, lateral displacement y and yaw ψ, on its primary suspension (per axlebox
longitudinal k_x, c_x and lateral k_y, c_y at ±b1) to a frame that moves straight at V, with the
two contacts' forces linearised: Kalker's linear creep coefficients, the equivalent conicity
γ_e, and the lateral forces of the normal forces (gravitational stiffness) and of spin that
follow from the contact angles. Everything per amplitude A of the oscillation (describing
functions, below), from the library's own geometry of S1002 on UIC60 1:40
(data/wheelset/contact_data.json, made by `cargo run --release -p lab --bin
wheelset_contact_data`), with the parameters of data/wheelset/passenger_coach.toml.

Conventions are the contact unit's (CONTACT's module 1, src/geometry/wheel_forces.rs): x along
the track, y to the right, z down, yaw ψ about z (ψ > 0 turns the heading towards +y). The wheel
turns at Ω = V/r_c, r_c the rolling radius of the centred wheelset, so that the centred wheelset
has no longitudinal creepage. A patch at contact angle δ (track coordinates) has creepages

    ξ = −(r − r_c)/r_c − ψ̇ Y/V,   η = ẏ/V − ψ,   φ = sin δ / r_c + ψ̇/V      (Y its track y)

and, by Kalker's linear theory (Kalker 1967; the crate's KalkerLinear), forces on the wheel
F_x = −f11 ξ, F_s = −f22 η − f23 φ, M_z = f23 η − f33 φ; its normal force carries the wheel load
Q vertically, so its lateral part is N sin δ = Q tan δ. The equations of motion are the classical
linear wheelset's (Wickens 2003, Fundamentals of Rail Vehicle Dynamics; Garg & Dukkipati 1984,
Dynamics of Railway Vehicle Systems, with the spin and gravitational terms; Iwnicki (ed.) 2006,
Handbook of Railway Vehicle Dynamics), written here term by term from the contact unit's
conventions above (the books were not at hand to compare their printed forms),
linearised:

    m ÿ + (2 f22/V + 2 c_y) ẏ + (2 f23/V) ψ̇ + (2 k_y + k_c) y − 2 f22 ψ = 0
    I ψ̈ + (d_ψ/V + 2 f33/V + 2 c_x b1²) ψ̇ − (2 f23/V) ẏ + (k_ψy + k_s) y + (2 k_x b1² + 2 f23) ψ = 0

with, from the contact data at amplitude A (ContactModel.linearised):
- f11, f22, f23, f33: Kalker's G ab C11, G ab C22, G (ab)^{3/2} C23, G (ab)² C33 per wheel
  (summed over its patches), averaged over the two wheels and over the cycle y = A sin θ;
- d_ψ = Σ f11 Y² (2 f11 s² for two equal wheels at ±s), less (Σ f11 Y)²/Σ f11 with the spin free;
- k_ψy: the yaw moment of the longitudinal creep forces at rest, −Σ Y f11 ξ, harmonically
  linearised (each wheel with its own f11 and rolling radius; the textbook 2 f11 s tan γ_e / r_c
  for two equal wheels), plus ε Σ f11 Y with the spin free (ε below);
- k_c: the lateral force of the contacts at rest, F_c(y) = Σ (N sin δ − f23 sin δ / r_c) (the
  normal forces' part is the gravitational stiffness k_grav, the other the spin creep force),
  and k_s: the spin moments' −Σ f33 sin δ / r_c, both harmonically linearised;
- tan γ_e(A), the library's equivalent conicity, for Klingel's ω = V √(tan γ_e/(r_c s)), s the
  contacts' mean half distance.
The wheel spin: imposed (Ω = V/r_c), or free (a spin degree of freedom taken as quasi-static:
Ω such that Σ F_x = 0, i.e. a common creepage ε = Σ f11 ((r − r_c)/r_c + ψ̇ Y/V) / Σ f11 added
to every patch's). With the spin free the kinematic motion is Klingel's, both wheels rolling
without creepage; with it imposed the wheel with the stiffer patch dominates the yaw moment.

Describing functions: γ_e(A) is the library's equivalent conicity (EN 15302's principle,
src/geometry/conicity.rs); a force F(y) is replaced by K y with K = (2/(πA)) ∫_0^π F(A sin θ)
sin θ dθ (its first Fourier coefficient, as the library's harmonic conicity).
"""

import json
import math
import pathlib
import tomllib

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[3]
PARAMETERS = ROOT / "data" / "wheelset" / "passenger_coach.toml"
CONTACT_DATA = ROOT / "data" / "wheelset" / "contact_data.json"

# Nodes of the describing functions' quadrature over θ (midpoint rule on [0, π]).
QUADRATURE_NODES = 2000


def load_parameters(path=PARAMETERS):
    """The parameter file as {table: {name: value}} (SI units, file header)."""
    with open(path, "rb") as file:
        document = tomllib.load(file)
    return {table: {name: entry["value"] for name, entry in entries.items()} for table, entries in document.items()}


def load_contact_data(path=CONTACT_DATA):
    with open(path) as file:
        return json.load(file)


# The columns of ContactModel.terms: one wheel's sums over its patches.
F11, F22, F23, F33 = 0, 1, 2, 3          # Kalker's linear stiffnesses [N, N, N m, N m²]
LATERAL = 4       # lateral force at rest Σ (N sin δ − f23 sin δ / r_c) [N]
SPIN_MOMENT = 5   # yaw moment of the spin moments at rest −Σ f33 sin δ / r_c [N m]
NORMAL = 6        # the normal forces' lateral part Σ N sin δ [N]
F11_Y = 7         # Σ f11 Y [N m] (Y the patch's track y)
F11_YY = 8        # Σ f11 Y² [N m²]
F11_DR = 9        # Σ f11 (r − r_c)/r_c [N] (r the patch's rolling radius)
F11_Y_DR = 10     # Σ f11 Y (r − r_c)/r_c [N m]


def _patch_terms(patches, shear_modulus, centred_radius):
    """One wheel's sums over its patches (the columns above)."""
    terms = np.zeros(11)
    for p in patches:
        area = p["semi_axis_a"] * p["semi_axis_b"]
        k11 = shear_modulus * area * p["c11"]
        k23 = shear_modulus * area ** 1.5 * p["c23"]
        k33 = shear_modulus * area ** 2 * p["c33"]
        sin = math.sin(p["contact_angle"])
        y, radius = p["track_lateral"], (p["rolling_radius"] - centred_radius) / centred_radius
        terms += [k11, shear_modulus * area * p["c22"], k23, k33,
                  p["normal_force"] * sin - k23 * sin / centred_radius, -k33 * sin / centred_radius,
                  p["normal_force"] * sin, k11 * y, k11 * y * y, k11 * radius, k11 * y * radius]
    return terms


class ContactModel:
    """The contact data of data/wheelset/contact_data.json, linearised at an amplitude."""

    def __init__(self, data):
        self.shear_modulus = data["shear_modulus"]
        samples = data["samples"]
        self.lateral = np.array([s["lateral"] for s in samples])
        self.centred_radius = data["centred_radius"]
        self.terms = {
            side: np.array([_patch_terms(s[side], self.shear_modulus, self.centred_radius) for s in samples])
            for side in ("right", "left")
        }
        table = np.array(data["conicity"])
        self.conicity_amplitudes, self.conicity_values = table[:, 0], table[:, 1]

    def equivalent_conicity(self, amplitude):
        """tan γ_e(A) of the library, at one of its tabulated amplitudes (0.25 mm steps)."""
        index = int(np.argmin(np.abs(self.conicity_amplitudes - amplitude)))
        if abs(self.conicity_amplitudes[index] - amplitude) > 1e-9:
            raise ValueError(f"amplitude {amplitude} m is not tabulated (every 0.25 mm, 0.25-6 mm)")
        return float(self.conicity_values[index])

    def _wheelset(self, y):
        """Both wheels' columns summed at displacements y, shape (len(y), columns)."""
        return sum(np.stack([np.interp(y, self.lateral, t[:, k]) for k in range(t.shape[1])], axis=1)
                   for t in self.terms.values())

    def linearised(self, amplitude, free_spin=True):
        """The coefficients at amplitude A [m] (module doc): f11, f22, f23, f33 per wheel (means
        over both wheels and the cycle) [N, N, N m, N m²]; the yaw creep damping d_ψ = Σ f11 Y²
        (less its part taken up by the spin, below) [N m²]; the half distance between the two
        wheels' contacts s (f11-weighted track y, mean over the cycle) [m]; tan γ_e; k_c,
        k_grav [N/m]; the creep yaw stiffness k_ψy and the spin moments' k_s [N]; r_c [m].

        `free_spin`: the wheelset's spin Ω follows the longitudinal creep forces (a spin degree
        of freedom, quasi-static: Ω such that Σ F_x = 0, a common creepage ε = Σ f11 ((r − r_c)/
        r_c + ψ̇ Y/V) / Σ f11 added to every patch's); otherwise Ω = V/r_c is imposed. With the
        spin free the kinematic motion is Klingel's (both wheels roll without creepage); with Ω
        imposed the wheel whose patch is stiffer in f11 dominates the yaw moment."""
        if not 0.0 < amplitude <= self.lateral[-1]:
            raise ValueError(f"amplitude {amplitude} m must be within (0, {self.lateral[-1]}] m")
        theta = (np.arange(QUADRATURE_NODES) + 0.5) * math.pi / QUADRATURE_NODES
        # Over a whole cycle y = A sin θ, θ ∈ [0, 2π): y and −y equally often.
        half = self._wheelset(amplitude * np.sin(theta))
        cycle = np.concatenate([half, self._wheelset(-amplitude * np.sin(theta))])
        moment = -half[:, F11_Y_DR]
        damping = cycle[:, F11_YY]
        if free_spin:
            moment += half[:, F11_DR] * half[:, F11_Y] / half[:, F11]
            damping = damping - cycle[:, F11_Y] ** 2 / cycle[:, F11]

        def harmonic(force):
            """−K of F ≈ −K y: the first Fourier coefficient over the cycle, over A."""
            return -2.0 / (math.pi * amplitude) * float(np.sum(force * np.sin(theta))) * math.pi / QUADRATURE_NODES

        f11 = 0.5 * float(np.mean(cycle[:, F11]))
        yaw_damping = float(np.mean(damping))
        y = np.concatenate([amplitude * np.sin(theta), -amplitude * np.sin(theta)])
        right, left = (self.terms[side] for side in ("right", "left"))
        half_distance = 0.5 * float(np.mean(np.interp(y, self.lateral, right[:, F11_Y] / right[:, F11])
                                            - np.interp(y, self.lateral, left[:, F11_Y] / left[:, F11])))
        return {
            "f11": f11, "f22": 0.5 * float(np.mean(cycle[:, F22])),
            "f23": 0.5 * float(np.mean(cycle[:, F23])), "f33": 0.5 * float(np.mean(cycle[:, F33])),
            "yaw_creep_damping": yaw_damping, "half_distance": half_distance,
            "tan_gamma": self.equivalent_conicity(amplitude),
            "contact_stiffness": harmonic(half[:, LATERAL]),
            "gravitational_stiffness": harmonic(half[:, NORMAL]),
            "creep_yaw_stiffness": harmonic(moment),
            "spin_yaw_stiffness": harmonic(half[:, SPIN_MOMENT]),
            "centred_radius": self.centred_radius,
        }


def variant(parameters, name):
    """The parameters with the primary suspension's entries that table `name` of the parameter
    file names replaced (`hunting_check`, `klingel_check`)."""
    suspension = dict(parameters["primary_suspension"], **parameters[name])
    return dict(parameters, primary_suspension=suspension)


def matrices(parameters, contact, speed, spin_creep=True, contact_stiffness=True, creep_weighted=True):
    """M, C, K of the linear model (module doc) at forward speed V [m/s]. Options, to measure
    the terms' shares: `spin_creep` False drops f23, f33 and k_s (k_c keeps the normal forces' part),
    `contact_stiffness` False drops k_c; `creep_weighted` False replaces the creep yaw stiffness
    k_ψy (each wheel's f11 and rolling radius) by its textbook form 2 f11 s tan γ_e / r_c with the
    mean f11 and the library's tan γ_e."""
    w, p = parameters["wheelset"], parameters["primary_suspension"]
    f11, f22, s, r = contact["f11"], contact["f22"], contact["half_distance"], contact["centred_radius"]
    f23, f33, k_s = (contact["f23"], contact["f33"], contact["spin_yaw_stiffness"]) if spin_creep else (0, 0, 0)
    k_c = contact["contact_stiffness"] if contact_stiffness else 0.0
    if not spin_creep and contact_stiffness:
        k_c = contact["gravitational_stiffness"]
    creep = contact["creep_yaw_stiffness"] if creep_weighted else 2 * f11 * s * contact["tan_gamma"] / r
    b1 = p["lateral_semi_spacing"]
    mass = np.diag([w["mass"], w["yaw_inertia"]])
    damping = np.array([
        [2 * f22 / speed + 2 * p["lateral_damping"], 2 * f23 / speed],
        [-2 * f23 / speed, contact["yaw_creep_damping"] / speed + 2 * f33 / speed + 2 * p["longitudinal_damping"] * b1 * b1],
    ])
    stiffness = np.array([
        [2 * p["lateral_stiffness"] + k_c, -2 * f22],
        [creep + k_s, 2 * p["longitudinal_stiffness"] * b1 * b1 + 2 * f23],
    ])
    return mass, damping, stiffness


def eigenvalues(parameters, contact, speed, **options):
    """The four eigenvalues [1/s] of the first-order form of M q̈ + C q̇ + K q = 0."""
    mass, damping, stiffness = matrices(parameters, contact, speed, **options)
    inverse = np.linalg.inv(mass)
    state = np.block([[np.zeros((2, 2)), np.eye(2)], [-inverse @ stiffness, -inverse @ damping]])
    return np.linalg.eigvals(state)


def growth_rate(parameters, contact, speed, **options):
    """The largest real part of the eigenvalues [1/s]."""
    return float(np.max(eigenvalues(parameters, contact, speed, **options).real))


def critical_speed(parameters, contact, low=1.0, high=400.0, tolerance=1e-6, **options):
    """The lowest speed in [low, high] m/s where the largest real part crosses zero (scan every
    1 m/s, then bisection to `tolerance` m/s); None if it stays of one sign."""
    speeds = np.arange(low, high + 0.5, 1.0)
    rates = [growth_rate(parameters, contact, v, **options) for v in speeds]
    for k in range(1, len(speeds)):
        if (rates[k - 1] < 0.0) != (rates[k] < 0.0):
            a, b = speeds[k - 1], speeds[k]
            sign_a = rates[k - 1] < 0.0
            while b - a > tolerance:
                middle = 0.5 * (a + b)
                if (growth_rate(parameters, contact, middle, **options) < 0.0) == sign_a:
                    a = middle
                else:
                    b = middle
            return 0.5 * (a + b)
    return None


def kinematic_mode(parameters, contact, speed):
    """The eigenvalue of the kinematic (Klingel) mode at V: the slowest one, with Im > 0."""
    e = eigenvalues(parameters, contact, speed)
    oscillating = e[e.imag > 0]
    return oscillating[np.argmin(np.abs(oscillating.real))]


def klingel_frequency(contact, speed):
    """Klingel's ω = V √(tan γ_e / (r0 s)) [rad/s] (r0 = r_c)."""
    return speed * math.sqrt(contact["tan_gamma"] / (contact["centred_radius"] * contact["half_distance"]))


def klingel_wavelength(contact):
    """Klingel's kinematic wavelength λ = 2π √(r0 s / tan γ_e) [m] (r0 = r_c)."""
    return 2 * math.pi * math.sqrt(contact["centred_radius"] * contact["half_distance"] / contact["tan_gamma"])


def creep_time_constants(parameters, contact, speed):
    """The creep forces' time constants at V [s]: lateral m V / (2 f22), yaw I V / d_ψ
    (d_ψ = 2 f11 s² with the spin imposed)."""
    w = parameters["wheelset"]
    lateral = w["mass"] * speed / (2 * contact["f22"])
    yaw = w["yaw_inertia"] * speed / contact["yaw_creep_damping"]
    return lateral, yaw


def report(amplitudes=(2e-3, 3e-3, 4e-3, 4.5e-3, 5e-3)):
    """The numbers of docs/wheelset.md: `.venv/bin/python wheelset/tests/system/linear_stability.py`."""
    parameters = load_parameters()
    model = ContactModel(load_contact_data())
    hunting, klingel = variant(parameters, "hunting_check"), variant(parameters, "klingel_check")
    print(f"r_c = {model.centred_radius:.6f} m (the centred wheelset's rolling radius)")
    print("A[mm] tanγe   f11[MN] f22[MN] f23[kNm] f33[Nm²] s[m]   k_grav[MN/m] k_c[MN/m] k_s[kN] "
          "k_ψy[MN] 2f11·s·tanγe/r_c[MN]  λ[m]")
    for amplitude in amplitudes:
        c = model.linearised(amplitude)
        textbook = 2 * c["f11"] * c["half_distance"] * c["tan_gamma"] / c["centred_radius"]
        print(f"{amplitude * 1e3:4.1f}  {c['tan_gamma']:.4f}  {c['f11'] / 1e6:6.3f}  {c['f22'] / 1e6:6.3f}  "
              f"{c['f23'] / 1e3:7.2f}  {c['f33']:7.1f}  {c['half_distance']:.4f}  "
              f"{c['gravitational_stiffness'] / 1e6:8.3f}    {c['contact_stiffness'] / 1e6:7.3f}  "
              f"{c['spin_yaw_stiffness'] / 1e3:7.2f}  {c['creep_yaw_stiffness'] / 1e6:7.3f}  {textbook / 1e6:7.3f}"
              f"              {klingel_wavelength(c):6.3f}")
    print("critical speed [m/s]: cited suspension | hunting_check: reference; without spin creep (f23, f33, "
          "k_s); without spin creep and k_c; textbook yaw coupling 2 f11 s tan γe / r_c; wheel spin imposed")
    variants = ({}, {"spin_creep": False}, {"spin_creep": False, "contact_stiffness": False},
                {"creep_weighted": False})
    for amplitude in amplitudes:
        c = model.linearised(amplitude)
        cited = critical_speed(parameters, c)
        speeds = [critical_speed(hunting, c, **options) for options in variants]
        speeds.append(critical_speed(hunting, model.linearised(amplitude, free_spin=False)))
        print(f"{amplitude * 1e3:4.1f}  {'none ≤ 400' if cited is None else f'{cited:.2f}'} | "
              + "  ".join(f"{v:.2f}" for v in speeds))
    for amplitude in (3e-3, 4.5e-3):
        print(f"klingel_check at A = {amplitude * 1e3} mm: V [m/s], the kinematic mode's eigenvalue [1/s] with the "
              "wheel spin free | imposed, Klingel's ω = V √(tan γe/(r_c s)) [rad/s]")
        free, imposed = model.linearised(amplitude), model.linearised(amplitude, free_spin=False)
        for speed in (1.0, 2.0, 5.0, 10.0):
            modes = [kinematic_mode(klingel, c, speed) for c in (free, imposed)]
            print(f"  {speed:4.1f}  " + " | ".join(f"{m.real:+.5f} {abs(m.imag):.5f}j" for m in modes)
                  + f"  {klingel_frequency(free, speed):.5f}")
    c = model.linearised(4.5e-3)
    print("creep time constants at A = 4.5 mm: V [m/s], lateral m V/(2 f22) [ms], yaw I V/d_ψ [ms]")
    for speed in (1, 5, 10, 20, 30, 40, 60, 80):
        lateral, yaw = creep_time_constants(parameters, c, speed)
        print(f"  {speed:3d}  {lateral * 1e3:7.4f}  {yaw * 1e3:7.4f}")


if __name__ == "__main__":
    report()
