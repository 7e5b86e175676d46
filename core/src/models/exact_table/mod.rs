//! Kalker's exact theory, tabulated: the rung at about Polach's cost (the trade report,
//! docs/trade/README.md, measures the ratio) and as accurate as the exact theory ([`ExactTable`]).
//!
//! Kalker tabulated his own exact theory for the same purpose (USETAB, 1996: 25 a/b × 16 ξ ×
//! 16 η × 32 φ cases on 12 × 12 grids). This table is made by our exact solver
//! ([`crate::ExactTheory`]; how, and how close its nodes are to the converged theory:
//! docs/exact_table.md) and differs in
//! its coordinates (`coordinates.rs`): Kalker's similarity law removes Q, μ, G and the size of
//! the ellipse, the problem's symmetries fold the creepages onto one octant, and the creepages
//! become a direction (α, β) and a size t ∈ [0, 1] whose end t = 1 is full sliding, tabulated by
//! quadrature (`full_slip.rs`), so every creepage up to ±∞ is inside the table.
//!
//! Interpolation is multilinear in (ln a/b, ν, β, α, τ) (`interpolate.rs`), where τ is the
//! size t on a kink-fitted scale: each ray's nodes are placed so that its adhesion collapse (a
//! kink of the exact theory's forces, `coordinates.rs`) sits on one fixed node, and a query's τ
//! uses the collapse interpolated from its cell's rays. Multilinear interpolation is the
//! natural choice here because it keeps what the physics requires by construction: every
//! interpolated force is a convex combination of tabulated forces inside the Coulomb disc, so
//! |F| ≤ μQ holds exactly; values are continuous everywhere (τ is continuous in t and in the
//! interpolated collapse); the symmetries hold exactly (they are applied by folding, and the
//! table's fold edges are tabulated symmetric); and the derivative is exact for the
//! interpolant, on its cell edges and on the fold planes of its coordinates (a creepage = 0,
//! pure spin) the one-sided derivative along the direction (`coordinates::fold`), at the a/b
//! edges of the table the one from inside.
//!
//! Domain: a/b within the table's range (the shipped table's [0.1, 10^1.5 = 31.6], which holds a
//! flange's long Hertz patch); outside it the model returns an error naming the semi-axes (no
//! silent extrapolation). ν ∈ [0, 0.5], any creepage.
//!
//! With the `embedded-table` feature (the default) the table is compiled into the library
//! (`data/exact_table.bin`, read and checked once at first use by [`ExactTable::new`]): Rust users
//! get it with the crate and need no file. Without the feature the caller reads the file and
//! hands the table to [`ExactTable::with_table`]: the FMU does, from the one copy in its
//! `resources/`, so that the table is not carried once per platform's binary
//! (docs/exact_table.md, "Where the table lives"). A missing or corrupted table is refused with
//! [`TableError`] before any force is computed.

mod coordinates;
mod full_slip;
pub mod generation;
mod interpolate;
mod table;

use std::sync::OnceLock;

use crate::creep_force_model::{dual_derivative, NoForceBoundary};
use crate::models::rung::Rung;
use crate::numerics::Scalar;
use crate::{ContactInput, CreepForceModel, CreepForces, InvalidInput, ModelChoice};
pub use table::{Table, TableAxes, TableError, A_OVER_B_LEAST, A_OVER_B_RANGE, FORMAT_VERSION};

/// The table compiled into this library: empty without the `embedded-table` feature, or when
/// `data/exact_table.bin` was missing when it was built.
const COMPILED_IN: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/exact_table.bin"));

/// Kalker's exact theory interpolated from a precomputed table.
///
/// Below creepages of 1e-3 of saturation it blends into Kalker's linear theory (Table E.3:
/// C11 = 5.10 at a/b = 2, ν = 0.25, F_x = −G ab C11 ξ); above, it is the exact theory within
/// 0.01 μQ (docs/exact_table.md); at full sliding |F| = μQ:
///
/// ```
/// use wheel_rail_contact::{ContactInput, CreepForceModel, ExactTable};
///
/// let contact = |xi: f64| ContactInput {
///     creepage_longitudinal: xi,
///     creepage_lateral: 0.0,
///     spin_creepage: 0.0,
///     normal_force: 82e3,
///     semi_axis_a: 8e-3,
///     semi_axis_b: 4e-3,
///     friction_coefficient: 0.3,
///     shear_modulus: 82e9,
///     poisson_ratio: 0.25,
/// };
/// let table = ExactTable::new().unwrap();
/// let linear = |xi: f64| -82e9 * 32e-6 * 5.10 * xi;
/// let ratio = table.creep_forces(&contact(1e-7)).unwrap().force_longitudinal / linear(1e-7);
/// assert!((ratio - 1.0).abs() < 2e-3, "{ratio}");
/// // Near the linear range the error is small against μQ, not against the force: at ξ = 1e-5
/// // (5e-3 of saturation) the table is 4 % above the linear (and exact) force, 0.02 % of μQ.
/// let near = table.creep_forces(&contact(1e-5)).unwrap().force_longitudinal;
/// assert!((near - linear(1e-5)).abs() < 0.01 * 0.3 * 82e3);
/// let sliding = table.creep_forces(&contact(0.1)).unwrap();
/// assert!((sliding.force_longitudinal + 0.3 * 82e3).abs() < 0.01 * 0.3 * 82e3);
/// // The same model from the same table.
/// assert_eq!(ExactTable::with_table(table.table()).creep_forces(&contact(1e-3)), table.creep_forces(&contact(1e-3)));
/// ```
#[derive(Clone, Copy)]
pub struct ExactTable {
    table: &'static Table,
}

/// The exact theory's table's rung of the ladder.
pub const RUNG: Rung = Rung {
    name: "exact_table",
    fmu_value: 6,
    type_name: "ExactTable",
    fmu_parameters: &[],
    spin_moment: true,
    friction_limited: true,
    offline: false,
    summary: "Kalker's exact theory tabulated by our solver over a/b ∈ [0.1, 31.6], ν ∈ [0, 0.5] and every creepage (similarity-scaled, folded by the symmetries, full sliding analytic), multilinear: F, M_z at about Polach's cost; `cargo fmu exact-table` regenerates `data/exact_table.bin`",
    source: "Kalker 1990; Kalker's USETAB (1996) idea; [docs/exact_table.md](docs/exact_table.md)",
    documentation: "Kalker's exact theory interpolated from a table stored once in this FMU,
<code>resources/exact_table.bin</code> (made by the exact solver above; the idea of Kalker's USETAB, 1996; its
frame and checksum are checked at fmi2Instantiate, which fails if it is missing or corrupted, and it is read
when an instance first selects this model). By Kalker's similarity law the forces in units of μQ (and
M<sub>z</sub> in μQc) depend only on a/b, ν and the creepages scaled by μp<sub>0</sub>/G with Kalker's coefficients;
the table spans a/b ∈ [0.1, 31.6] (a flange's long patch included; outside: an error naming both semi-axes), ν ∈ [0, 0.5] and every creepage up
to full sliding, which it reaches continuously (computed analytically). Multilinear interpolation: |F| ≤ μQ,
continuous, the problem's symmetries exact, Kalker's linear theory at small creepage. Gives M<sub>z</sub>. Its
time per evaluation and its error against the exact theory on random held-out contacts are measured in
docs/trade/README.md in the source repository (<code>cargo run --release -p lab --bin trade_report</code>).",
    default_model: || Ok(ModelChoice::ExactTable(ExactTable::new()?)),
};

impl ExactTable {
    /// The model with the table compiled into this library, read and checked on the first call;
    /// an error without the `embedded-table` feature (then see [`Self::with_table`]).
    pub fn new() -> Result<Self, TableError> {
        static TABLE: OnceLock<Result<Table, TableError>> = OnceLock::new();
        match TABLE.get_or_init(compiled_in_table) {
            Ok(table) => Ok(Self { table }),
            Err(error) => Err(error.clone()),
        }
    }

    /// The model with another table: one read from a file (what a build without the
    /// `embedded-table` feature does), one just generated, or a test's. The table is borrowed for
    /// the program's life, so that the model stays `Copy` like every rung:
    ///
    /// ```
    /// use wheel_rail_contact::models::exact_table::Table;
    /// use wheel_rail_contact::ExactTable;
    ///
    /// let bytes = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin")).unwrap();
    /// let table: &'static Table = Box::leak(Box::new(Table::from_bytes(&bytes).unwrap()));
    /// let model = ExactTable::with_table(table);
    /// assert_eq!(model.table().axes.a_over_b, (0.1, 10f64.powf(1.5)));
    /// // A damaged file is refused, never read as a table.
    /// let mut damaged = bytes.clone();
    /// damaged[bytes.len() / 2] ^= 1;
    /// assert!(Table::from_bytes(&damaged).unwrap_err().to_string().contains("checksum mismatch"));
    /// assert!(Table::check_bytes(&damaged).is_err() && Table::check_bytes(&bytes).is_ok());
    /// ```
    pub fn with_table(table: &'static Table) -> Self {
        Self { table }
    }

    /// The table this model interpolates.
    pub fn table(&self) -> &'static Table {
        self.table
    }
}

/// The table compiled into this library, or why there is none.
fn compiled_in_table() -> Result<Table, TableError> {
    table_as_built(COMPILED_IN, cfg!(feature = "embedded-table"))
}

/// The table of `bytes` embedded by `build.rs` (with the `embedded-table` feature when
/// `embedded`): empty bytes are explained by how the library was built.
fn table_as_built(bytes: &[u8], embedded: bool) -> Result<Table, TableError> {
    if !bytes.is_empty() {
        Table::from_bytes(bytes)
    } else if embedded {
        Err(TableError(
            "no table was compiled in (data/exact_table.bin was missing at build time; \
             `cargo fmu exact-table` generates it)"
                .into(),
        ))
    } else {
        Err(TableError(
            "no table was compiled in (this build leaves it out: the library's `embedded-table` feature is off); \
             read data/exact_table.bin with Table::from_bytes and use ExactTable::with_table"
                .into(),
        ))
    }
}

impl PartialEq for ExactTable {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.table, other.table)
    }
}

impl std::fmt::Debug for ExactTable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExactTable({:?}, {})", self.table.axes.counts, self.table.provenance)
    }
}

impl CreepForceModel for ExactTable {
    fn creep_forces(&self, input: &ContactInput) -> Result<CreepForces, InvalidInput> {
        input.validate()?;
        interpolate::forces(self.table, input)
    }

    /// Exact for the interpolant (dual numbers through the interpolation weights); on cell
    /// edges and fold planes the one-sided derivative along `direction`, lim (F(x + h·d) −
    /// F(x))/h for h → 0⁺ (the side is chosen by the direction's rate where the value lies on
    /// the edge or plane). The force is μQ times a bounded function of u ∝ 1/(μQ), so it vanishes
    /// continuously at μ → 0 and Q → 0: the one-sided derivative is given there.
    fn directional_derivative(
        &self,
        input: &ContactInput,
        direction: &ContactInput,
    ) -> Result<CreepForces, InvalidInput> {
        self.creep_forces(input)?;
        dual_derivative(input, direction, NoForceBoundary::Continuous, |seeded| {
            interpolate::forces(self.table, seeded).unwrap_or_else(|_| zero_forces())
        })
    }
}

/// Zero forces with a zero moment (unreachable after the value's own evaluation succeeded).
fn zero_forces<D: Scalar>() -> CreepForces<D> {
    let zero = D::from(0.0);
    CreepForces { force_longitudinal: zero, force_lateral: zero, spin_moment: Some(zero), adhesion_utilisation: zero }
}

/// Nothing carried from one evaluation to the next: a read of the table.
impl crate::models::sequence::SequenceModel for ExactTable {
    type Memory = ();
    type Cache = ();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An empty embedded table says why it is empty and what to do; a present one is read.
    #[test]
    fn an_empty_build_table_is_explained_by_the_build() {
        let missing = table_as_built(&[], true).unwrap_err().to_string();
        assert!(
            missing.contains("data/exact_table.bin was missing at build time")
                && missing.contains("cargo fmu exact-table"),
            "{missing}"
        );
        let left_out = table_as_built(&[], false).unwrap_err().to_string();
        assert!(
            left_out.contains("`embedded-table` feature is off") && left_out.contains("ExactTable::with_table"),
            "{left_out}"
        );
        let bytes = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin")).unwrap();
        assert_eq!(table_as_built(&bytes, false).unwrap().axes.a_over_b, A_OVER_B_RANGE);
        // This build (the tests' default features) has its table.
        assert_eq!(compiled_in_table().is_ok(), cfg!(feature = "embedded-table"));
    }
}
