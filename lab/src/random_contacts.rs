//! Random contacts shared by the lab's studies: a seeded stream and the contact of a creepage
//! direction and size in units of the characteristic creepage.
use wheel_rail_contact::{ContactInput, KalkerCoefficients};

/// Q \[N\], μ, G \[Pa\] of every random contact.
pub const NORMAL_FORCE: f64 = 80e3;
pub const FRICTION: f64 = 0.3;
pub const SHEAR_MODULUS: f64 = 82e9;
/// c = √(ab) of every random contact \[m\]; a/b varies around it.
pub const MEAN_SEMI_AXIS: f64 = 5e-3;

/// A seeded stream of uniform numbers in [0, 1): a 64-bit linear congruential generator
/// (Knuth's MMIX constants), its top 53 bits. Reproducible across platforms and without a
/// dependency; plenty for choosing test contacts.
pub struct Uniform(u64);

impl Uniform {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn sample(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The contact at a/b (c = [`MEAN_SEMI_AXIS`]) and ν whose creepages are `level` × the
/// characteristic creepage (Kalker's linear force = μQ) along the unit direction of
/// (ξ/ξ*, η/η*, φ/φ*) with spin component `z` and planar angle `angle` \[rad\] (φ* with C23).
pub fn contact_along(a_over_b: f64, poisson_ratio: f64, level: f64, z: f64, angle: f64) -> ContactInput {
    let planar = (1.0 - z * z).sqrt();
    let k = KalkerCoefficients::new(a_over_b, poisson_ratio);
    let c = MEAN_SEMI_AXIS;
    let unit = FRICTION * NORMAL_FORCE / SHEAR_MODULUS / (c * c);
    ContactInput {
        creepage_longitudinal: level * planar * angle.cos() * unit / k.c11,
        creepage_lateral: level * planar * angle.sin() * unit / k.c22,
        spin_creepage: level * z * unit / (c * k.c23),
        normal_force: NORMAL_FORCE,
        semi_axis_a: c * a_over_b.sqrt(),
        semi_axis_b: c / a_over_b.sqrt(),
        friction_coefficient: FRICTION,
        shear_modulus: SHEAR_MODULUS,
        poisson_ratio,
    }
}

/// A random contact of the studies: a/b log-uniform in [10^−`span`, 10^`span`], ν uniform in
/// [0, 0.5], the creepage direction uniform on the sphere of (ξ/ξ*, η/η*, φ/φ*), its size
/// log-uniform from 0.01 to 30 × the characteristic creepage.
pub fn random_contact(uniform: &mut Uniform, span: f64) -> ContactInput {
    random_contact_over(uniform, (-span, span))
}

/// A random contact as [`random_contact`]'s, with a/b log-uniform in [10^`low`, 10^`high`]
/// for `exponents` = (low, high).
pub fn random_contact_over(uniform: &mut Uniform, (low, high): (f64, f64)) -> ContactInput {
    let a_over_b = 10f64.powf(low + (high - low) * uniform.sample());
    let poisson_ratio = 0.5 * uniform.sample();
    let level = 10f64.powf(-2.0 + uniform.sample() * (30f64.log10() + 2.0));
    let (z, angle) = (2.0 * uniform.sample() - 1.0, 2.0 * std::f64::consts::PI * uniform.sample());
    contact_along(a_over_b, poisson_ratio, level, z, angle)
}
