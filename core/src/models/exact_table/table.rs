//! The table: its axes, its nodes and its file format, checked when it is read.
//!
//! Format (little-endian): the 16-byte magic `WRC-EXACT-TABLE\0`, the format version (u32),
//! the provenance text (u32 length + UTF-8: generator version, solver grid, command), the node
//! counts along a/b, ν, β, α, τ (5 × u32), the a/b and ν ranges (4 × f64), the scale factors k
//! at every (a/b, ν) node (3 × f64 each), the collapse t_c of every ray (a/b, ν, β, α) (f32,
//! see `coordinates.rs`), the units of the stored values at every τ node (the force's and the
//! moment's, 2 × f64 each), the values (3 × i16 per node, in the units of its τ node: F_x/(μQ),
//! F_y/(μQ), M_z/(μQc); differenced along τ and ν and split into byte planes, see
//! `encode_counts`), and a CRC-32 of all the bytes before it.
//!
//! The values are 16-bit, which keeps the table at 22.9 MB (docs/exact_table.md, "What is
//! tabulated": the 29 a/b nodes up to a/b = 10 take 18.4 MB, the 7 on to 10^1.5 for a flange's
//! long patches 4.5 MB).
//! Each τ node has its own units, its largest |F| and |M_z| over the table divided by 32767:
//! near t = 0 the forces are O(s), and one unit for all nodes (1/32767 μQ) made the first τ
//! node's spin-driven F_y (≈ 2e-5 μQ at a/b = 0.1) wrong by up to 80 %, and the linear limit by
//! 1.4 % (core/tests/library/exact_table.rs). Above the knee the force unit is 1/32767 μQ (3e-5 μQ, against
//! the 0.003 μQ median the table is held to). M_z is rounded to the nearest count; a force is
//! stored as the counts nearest to it whose length is its length rounded to the nearest count
//! (`quantize_force`), inside the Coulomb disc.
//!
//! Layout: node (i_ab, i_ν, i_β, i_α, i_τ) at ((((i_ab·n_ν + i_ν)·n_β + i_β)·n_α + i_α)·n_τ + i_τ),
//! so the two τ nodes of every corner of an interpolation cell are adjacent in memory; ray
//! (i_ab, i_ν, i_β, i_α) is that index over n_τ. In memory each node also holds |F|/(μQ),
//! derived when the table is made (see `interpolate.rs`), and the values are f32 (in μQ and μQc),
//! converted once: the evaluation's blend then needs no integer conversions (16-bit values in
//! memory measured 1.2× slower per evaluation).
//!
//! A table of the smallest shape — two nodes along a/b, ν, β and α, five along τ — made, written,
//! checked and read back (the generator's last steps; the shipped table has the same frame):
//!
//! ```
//! use wheel_rail_contact::models::exact_table::{Table, TableAxes, A_OVER_B_RANGE, FORMAT_VERSION};
//!
//! let axes = TableAxes { counts: [2, 2, 2, 2, 5], a_over_b: A_OVER_B_RANGE, poisson_ratio: (0.0, 0.5) };
//! assert_eq!((axes.len(), axes.is_empty()), (80, false));
//! assert!(axes.a_over_b_node(0) == 0.1 && axes.a_over_b_node(1) == A_OVER_B_RANGE.1);
//! assert_eq!(axes.poisson_node(1), 0.5);
//! // The shipped table's axes: ν every 0.1, a/b = 10 at its 29th node.
//! let shipped = TableAxes { counts: [36, 6, 17, 17, 49], ..axes.clone() };
//! assert!((shipped.poisson_node(3) - 0.3).abs() < 1e-15 && (shipped.a_over_b_node(28) - 10.0).abs() < 1e-12);
//! assert_eq!(axes.direction_node(0, 1, 4), (-1.0, 1.0, 1.0)); // β, α, τ
//! // F_x/(μQ) = 0.6, F_y/(μQ) = −0.8 (on the Coulomb circle), M_z/(μQc) = 0.1 at every node.
//! let values = [0.6f32, -0.8, 0.1].repeat(axes.len());
//! let table = Table::new("example".into(), axes.clone(), vec![[1.0; 3]; 4], vec![0.5; 16], values).unwrap();
//! let bytes = table.to_bytes();
//! assert_eq!(&bytes[..16], b"WRC-EXACT-TABLE\0");
//! assert_eq!(bytes[16..20], FORMAT_VERSION.to_le_bytes());
//! assert!(Table::check_bytes(&bytes).is_ok());
//! assert_eq!(Table::from_bytes(&bytes).unwrap(), table);
//! // Outside the Coulomb disc, or a collapse outside its range: refused when made.
//! let outside = [0.9f32, -0.8, 0.0].repeat(axes.len());
//! let error = Table::new("".into(), axes.clone(), vec![[1.0; 3]; 4], vec![0.5; 16], outside).unwrap_err();
//! assert!(error.to_string().contains("|F| > μQ"), "{error}");
//! let values = [0.0f32; 3].repeat(axes.len());
//! assert!(Table::new("".into(), axes, vec![[1.0; 3]; 4], vec![0.2; 16], values).is_err());
//! ```

use std::fmt;

use super::coordinates::{COLLAPSE_RANGE, IDENTITY_END};

const MAGIC: &[u8; 16] = b"WRC-EXACT-TABLE\0";
/// Version of this file format (not of the values: the provenance text says how they were made).
pub const FORMAT_VERSION: u32 = 3;
/// The a/b range of the shipped table: 10^±1 as the first table had, then on to 10^1.5 (at the
/// same node spacing), for the long Hertz patches of a wheel's flange (a/b = 16–22 on the
/// Manchester benchmark's case A-2.2). Exactly 10^1.5 in f64 (`10f64.powf(1.5)`).
pub const A_OVER_B_RANGE: (f64, f64) = (0.1, 31.622776601683793);
/// The a/b range every table must cover (the first table's): the model's domain.
pub const A_OVER_B_LEAST: (f64, f64) = (0.1, 10.0);
/// Relative rounding of a/b accepted at the ends of a table's range.
const RANGE_ROUNDING: f64 = 1e-12;
/// Values this far outside the Coulomb disc are refused (float rounding of the solver's values).
const BOUND_TOLERANCE: f32 = 1e-5;
/// The largest stored count: a unit is the largest |value| of its τ node over FULL_SCALE.
const FULL_SCALE: f64 = 32767.0;

/// Node counts and ranges of the table's five axes: ln(a/b) and ν uniform over their ranges,
/// β uniform over [−1, 1], α and the kink-fitted size τ uniform over [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct TableAxes {
    /// Nodes along a/b (uniform in ln(a/b)), ν, β, α and τ.
    pub counts: [usize; 5],
    /// Smallest and largest a/b.
    pub a_over_b: (f64, f64),
    /// Smallest and largest ν.
    pub poisson_ratio: (f64, f64),
}

impl TableAxes {
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.counts.iter().product()
    }

    /// False: a table has at least two nodes along every axis.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// a/b of node `i` along the first axis.
    pub fn a_over_b_node(&self, i: usize) -> f64 {
        let (low, high) = (self.a_over_b.0.ln(), self.a_over_b.1.ln());
        // The ends exactly (exp(ln 0.1) is 0.10000000000000002).
        if i == 0 {
            return self.a_over_b.0;
        }
        if i + 1 == self.counts[0] {
            return self.a_over_b.1;
        }
        (low + (high - low) * i as f64 / (self.counts[0] - 1) as f64).exp()
    }

    /// ν of node `i`.
    pub fn poisson_node(&self, i: usize) -> f64 {
        let (low, high) = self.poisson_ratio;
        low + (high - low) * i as f64 / (self.counts[1] - 1) as f64
    }

    /// β, α and τ of nodes `(k, l, m)`.
    pub fn direction_node(&self, k: usize, l: usize, m: usize) -> (f64, f64, f64) {
        let unit = |i: usize, n: usize| i as f64 / (n - 1) as f64;
        (2.0 * unit(k, self.counts[2]) - 1.0, unit(l, self.counts[3]), unit(m, self.counts[4]))
    }

    /// Distance in rays between neighbouring rays along a/b, ν, β and α.
    pub(crate) fn ray_strides(&self) -> [usize; 4] {
        let [_, n_nu, n_beta, n_alpha, _] = self.counts;
        [n_alpha * n_beta * n_nu, n_alpha * n_beta, n_alpha, 1]
    }
}

/// Where a coordinate falls along one axis of uniformly spaced nodes: node i sits at
/// `origin + i / inverse_step`. Derived from the axes when a table is made (the evaluation
/// would otherwise pay two logarithms and five divisions for it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AxisMap {
    pub origin: f64,
    pub inverse_step: f64,
    pub nodes: usize,
}

impl AxisMap {
    fn new(low: f64, high: f64, nodes: usize) -> Self {
        Self { origin: low, inverse_step: (nodes - 1) as f64 / (high - low), nodes }
    }
}

/// A table of the exact theory's forces, read and checked.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// How the values were made: generator version, solver grid, command.
    pub provenance: String,
    /// The axes.
    pub axes: TableAxes,
    /// Scale factors k (see `coordinates.rs`) at each (a/b, ν) node, index i_ab·n_ν + i_ν.
    pub(crate) scales: Vec<[f64; 3]>,
    /// The collapse t_c of each ray (a/b, ν, β, α), index: the node index over n_τ.
    pub(crate) collapse: Vec<f32>,
    /// F_x/(μQ), F_y/(μQ), M_z/(μQc) and |F|/(μQ) at each node.
    pub(crate) nodes: Vec<[f32; 4]>,
    /// The value of one count of the stored forces F_x, F_y and of M_z, at each τ node.
    pub(crate) units: Vec<[f64; 2]>,
    /// The axes as [`AxisMap`]s: ln(a/b), ν, β, α, τ.
    pub(crate) maps: [AxisMap; 5],
    /// Distances between neighbouring rays along a/b, ν, β and α ([`TableAxes::ray_strides`]),
    /// kept so that the evaluation pays no integer division.
    pub(crate) ray_strides: [usize; 4],
    /// The 16 corner rays of an interpolation cell (a/b, ν, β, α) relative to its first ray, as
    /// 8 pairs: for each (a/b, ν, β) corner (a/b slowest, β fastest) the first of its two rays,
    /// which are adjacent (α is the fastest ray index, stride 1), so that the pair's two t_c are
    /// read with one range check. Kept, like `ray_strides`, so that the evaluation derives no
    /// corner index of its own.
    pub(crate) alpha_pairs: [usize; 8],
}

/// Why a table was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TableError(pub String);

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "the exact_table data is unusable: {}", self.0)
    }
}

impl std::error::Error for TableError {}

impl Table {
    /// Assembles a table from its parts (the generator's last step): `values` are the nodes'
    /// F_x/(μQ), F_y/(μQ), M_z/(μQc), stored in 16 bits in the units of their τ node.
    pub fn new(
        provenance: String,
        axes: TableAxes,
        scales: Vec<[f64; 3]>,
        collapse: Vec<f32>,
        values: Vec<f32>,
    ) -> Result<Self, TableError> {
        if values.len() != 3 * axes.len() {
            return Err(TableError(format!("{} values for {} nodes", values.len(), axes.len())));
        }
        for (node, v) in values.chunks_exact(3).enumerate() {
            if !(v.iter().all(|x| x.is_finite()) && v[0].hypot(v[1]) <= 1.0 + BOUND_TOLERANCE) {
                return Err(TableError(format!("node {node} holds {v:?}: not finite or |F| > μQ")));
            }
        }
        // Onto the disc first (the solver's rounding), then the largest |F| and |M_z| per τ node.
        let n_t = axes.counts[4];
        let values: Vec<[f64; 3]> = values
            .chunks_exact(3)
            .map(|v| {
                let [x, y, m] = [v[0], v[1], v[2]].map(f64::from);
                let shrink = 1.0 / x.hypot(y).max(1.0);
                [x * shrink, y * shrink, m]
            })
            .collect();
        let mut ranges = vec![[0.0f64; 2]; n_t];
        for (node, [x, y, m]) in values.iter().enumerate() {
            let range = &mut ranges[node % n_t];
            *range = [range[0].max(x.hypot(*y)), range[1].max(m.abs())];
        }
        // (|F| ≤ 1 up to the last bit of the shrink above.)
        let unit = |range: f64| if range > 0.0 { range / FULL_SCALE } else { 1.0 / FULL_SCALE };
        let units: Vec<[f64; 2]> = ranges.iter().map(|&[force, moment]| [unit(force.min(1.0)), unit(moment)]).collect();
        let quantize = |x: f64, unit: f64| (x / unit).round().clamp(-FULL_SCALE, FULL_SCALE) as i16;
        let stored = values
            .iter()
            .enumerate()
            .flat_map(|(node, &[x, y, m])| {
                let [force_unit, moment_unit] = units[node % n_t];
                let [qx, qy] = quantize_force(x / force_unit, y / force_unit);
                [qx, qy, quantize(m, moment_unit)]
            })
            .collect();
        Self::from_parts(provenance, axes, scales, collapse, units, stored)
    }

    fn from_parts(
        provenance: String,
        axes: TableAxes,
        scales: Vec<[f64; 3]>,
        collapse: Vec<f32>,
        units: Vec<[f64; 2]>,
        stored: Vec<i16>,
    ) -> Result<Self, TableError> {
        let [n_ab, n_nu, n_beta, n_alpha, n_t] = axes.counts;
        let maps = [
            AxisMap::new(axes.a_over_b.0.ln(), axes.a_over_b.1.ln(), n_ab),
            AxisMap::new(axes.poisson_ratio.0, axes.poisson_ratio.1, n_nu),
            AxisMap::new(-1.0, 1.0, n_beta),
            AxisMap::new(0.0, 1.0, n_alpha),
            AxisMap::new(0.0, 1.0, n_t),
        ];
        let ray_strides = axes.ray_strides();
        let [stride_ab, stride_nu, stride_beta, _] = ray_strides;
        let alpha_pairs =
            std::array::from_fn(|pair| (pair / 4) * stride_ab + (pair / 2 % 2) * stride_nu + (pair % 2) * stride_beta);
        if stored.len() != 3 * axes.len() || collapse.len() != axes.len() / n_t {
            return Err(TableError(format!(
                "{} values and {} rays for {} nodes",
                stored.len(),
                collapse.len(),
                axes.len()
            )));
        }
        if units.len() != n_t {
            return Err(TableError(format!("{} value units for {n_t} τ nodes", units.len())));
        }
        // A force unit above 1/FULL_SCALE would let FULL_SCALE counts exceed μQ.
        if let Some((m, unit)) = units.iter().enumerate().find(|(_, [force, moment])| {
            !(force.is_finite() && *force > 0.0 && *force <= 1.0 / FULL_SCALE && moment.is_finite() && *moment > 0.0)
        }) {
            return Err(TableError(format!("τ node {m}: value units {unit:?}")));
        }
        if let Some((node, v)) =
            stored.chunks_exact(3).enumerate().find(|(_, v)| f64::from(v[0]).hypot(f64::from(v[1])) > FULL_SCALE)
        {
            let forces = [v[0], v[1]].map(|x| f64::from(x) * units[node % n_t][0]);
            return Err(TableError(format!("node {node} holds F/(μQ) = {forces:?}: |F| > μQ")));
        }
        let nodes = stored
            .chunks_exact(3)
            .enumerate()
            .map(|(node, v)| {
                let [force_unit, moment_unit] = units[node % n_t];
                let [x, y, m] = [(v[0], force_unit), (v[1], force_unit), (v[2], moment_unit)]
                    .map(|(count, unit)| f64::from(count) * unit);
                let length = (stored_length(v[0], v[1]) * force_unit).min(1.0);
                [x, y, m, length].map(|value| value as f32)
            })
            .collect();
        let table = Self { provenance, axes, scales, collapse, nodes, units, maps, ray_strides, alpha_pairs };
        table.check()?;
        Ok(table)
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut bytes = Vec::with_capacity(6 * self.nodes.len() + 4 * self.collapse.len() + 1024);
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        bytes.extend_from_slice(&(self.provenance.len() as u32).to_le_bytes());
        bytes.extend_from_slice(self.provenance.as_bytes());
        for count in self.axes.counts {
            bytes.extend_from_slice(&(count as u32).to_le_bytes());
        }
        let (ab, nu) = (self.axes.a_over_b, self.axes.poisson_ratio);
        for x in [ab.0, ab.1, nu.0, nu.1].into_iter().chain(self.scales.iter().flatten().copied()) {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
        for t_c in &self.collapse {
            bytes.extend_from_slice(&t_c.to_le_bytes());
        }
        for unit in self.units.iter().flatten() {
            bytes.extend_from_slice(&unit.to_le_bytes());
        }
        let n_t = self.axes.counts[4];
        let counts: Vec<i16> = self
            .nodes
            .iter()
            .enumerate()
            .flat_map(|(i, node)| {
                let [force_unit, moment_unit] = self.units[i % n_t];
                // Exactly the stored count: the f32 is within 2e-3 counts of it.
                [(node[0], force_unit), (node[1], force_unit), (node[2], moment_unit)]
                    .map(|(value, unit)| (f64::from(value) / unit).round() as i16)
            })
            .collect();
        bytes.extend_from_slice(&encode_counts(&self.axes, &counts));
        let checksum = crc32fast::hash(&bytes);
        bytes.extend_from_slice(&checksum.to_le_bytes());
        bytes
    }

    /// Checks a table file's frame without decoding its values: its magic bytes, checksum
    /// (CRC-32 over everything before it) and format version. Cheap enough for an FMU to run at
    /// fmi2Instantiate on a table it may never decode; [`Table::from_bytes`] runs it first.
    pub fn check_bytes(bytes: &[u8]) -> Result<(), TableError> {
        checked_contents(bytes).map(|_| ())
    }

    /// Reads and checks a table file: magic, version, sizes, checksum, finite values inside the
    /// Coulomb disc. The error says what is wrong.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, TableError> {
        let mut reader = Reader { bytes: checked_contents(bytes)? };
        let text_length = reader.u32()? as usize;
        let provenance = String::from_utf8(reader.take(text_length)?.to_vec())
            .map_err(|_| TableError("provenance text is not UTF-8".into()))?;
        let mut counts = [0; 5];
        for count in &mut counts {
            *count = reader.u32()? as usize;
        }
        if counts.iter().any(|&n| !(2..=4096).contains(&n)) {
            return Err(TableError(format!("node counts {counts:?} outside [2, 4096]")));
        }
        let mut f64s = |n: usize| (0..n).map(|_| reader.f64()).collect::<Result<Vec<f64>, _>>();
        let ranges = f64s(4)?;
        let scales: Vec<[f64; 3]> =
            f64s(3 * counts[0] * counts[1])?.chunks_exact(3).map(|k| [k[0], k[1], k[2]]).collect();
        let axes = TableAxes { counts, a_over_b: (ranges[0], ranges[1]), poisson_ratio: (ranges[2], ranges[3]) };
        let collapse: Vec<f32> = reader
            .take(4 * (axes.len() / counts[4]))?
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        let units: Vec<[f64; 2]> =
            (0..counts[4]).map(|_| Ok([reader.f64()?, reader.f64()?])).collect::<Result<_, _>>()?;
        let stored = decode_counts(&axes, reader.take(2 * 3 * axes.len())?);
        if !reader.bytes.is_empty() {
            return Err(TableError(format!("{} bytes after the values", reader.bytes.len())));
        }
        Self::from_parts(provenance, axes, scales, collapse, units, stored)
    }

    /// This table with `earlier`'s force counts at `earlier`'s nodes (this table's first ones,
    /// as in a table extended along a/b, [`super::generation::extend`]) for every τ node whose
    /// force unit is the same in both. Quantizing a table's own values again can move a force by
    /// a count (a stored length is its length rounded up, a quantized one is rounded to the
    /// nearest), which on the full-sliding plateau broke the resultant's monotone rise along a
    /// ray (core/tests/library/ladder_invariants.rs); where a τ node's unit grew, its counts are the new one's.
    pub(crate) fn keeping_force_counts_of(self, earlier: &Table) -> Result<Self, TableError> {
        if earlier.axes.counts[1..] != self.axes.counts[1..] || earlier.nodes.len() > self.nodes.len() {
            return Err(TableError(format!(
                "nodes {:?} are not the first of {:?}",
                earlier.axes.counts, self.axes.counts
            )));
        }
        let n_t = self.axes.counts[4];
        let count = |value: f32, unit: f64| (f64::from(value) / unit).round() as i16;
        let mut stored: Vec<i16> = self
            .nodes
            .iter()
            .enumerate()
            .flat_map(|(i, node)| {
                let [force_unit, moment_unit] = self.units[i % n_t];
                [count(node[0], force_unit), count(node[1], force_unit), count(node[2], moment_unit)]
            })
            .collect();
        for (i, node) in earlier.nodes.iter().enumerate() {
            let force_unit = earlier.units[i % n_t][0];
            if force_unit == self.units[i % n_t][0] {
                stored[3 * i] = count(node[0], force_unit);
                stored[3 * i + 1] = count(node[1], force_unit);
            }
        }
        Self::from_parts(self.provenance, self.axes, self.scales, self.collapse, self.units, stored)
    }

    /// Whether the table covers this a/b (its ends up to the rounding of a/b: a = c√10,
    /// b = c/√10 gives 10.000000000000002), as the model's evaluation checks:
    ///
    /// ```
    /// use wheel_rail_contact::ExactTable;
    ///
    /// let table = ExactTable::new().unwrap().table();
    /// assert!(table.covers_a_over_b(0.1) && table.covers_a_over_b(22.0)); // a flange's long patch
    /// assert!(table.covers_a_over_b(10f64.powf(1.5) * (1.0 + 1e-15)));
    /// assert!(!table.covers_a_over_b(0.0999) && !table.covers_a_over_b(32.0) && !table.covers_a_over_b(f64::NAN));
    /// ```
    pub fn covers_a_over_b(&self, a_over_b: f64) -> bool {
        let (low, high) = self.axes.a_over_b;
        (low * (1.0 - RANGE_ROUNDING)..=high * (1.0 + RANGE_ROUNDING)).contains(&a_over_b)
    }

    /// The invariants the interpolation relies on.
    fn check(&self) -> Result<(), TableError> {
        let axes = &self.axes;
        let (ab, nu) = (axes.a_over_b, axes.poisson_ratio);
        // Every table covers the model's domain in a/b (the model's error names the table's own
        // range), and every valid ν must be inside the table (outside, the interpolation would
        // clamp silently).
        let covers_least = ab.0 > 0.0 && ab.0 <= A_OVER_B_LEAST.0 && ab.1 >= A_OVER_B_LEAST.1 && ab.1.is_finite();
        if !covers_least || nu != (0.0, 0.5) {
            return Err(TableError(format!(
                "a/b range {ab:?} and ν range {nu:?}: this build reads tables over a/b covering {A_OVER_B_LEAST:?}, ν (0, 0.5)"
            )));
        }
        if self.scales.len() != axes.counts[0] * axes.counts[1]
            || self.scales.iter().flatten().any(|k| !(k.is_finite() && *k > 0.0))
        {
            return Err(TableError("scale factors missing, not finite or not positive".into()));
        }
        // The first τ cell must lie in the identity piece of the size map (see `interpolate.rs`).
        if (axes.counts[4] - 1) as f64 * IDENTITY_END < 1.0 {
            return Err(TableError(format!("{} τ nodes: at least 5 are needed", axes.counts[4])));
        }
        // In f32, as stored (the range's ends are t_c values too).
        let range = COLLAPSE_RANGE.0 as f32..=COLLAPSE_RANGE.1 as f32;
        if let Some((ray, t_c)) = self.collapse.iter().enumerate().find(|(_, t_c)| !range.contains(t_c)) {
            return Err(TableError(format!("ray {ray}: collapse at t = {t_c}, outside {COLLAPSE_RANGE:?}")));
        }
        Ok(())
    }
}

/// The force (F_x, F_y) in counts as two counts inside the disc of FULL_SCALE counts whose
/// [`stored_length`] is |F| rounded to the nearest count; among those, the nearest to (x, y).
///
/// The evaluation interpolates the stored lengths (`interpolate.rs`, the chord correction), and
/// rounding a length is monotone where rounding two components is not: along a ray without spin
/// the exact theory's |F| rises monotonically to μQ, and components rounded one by one made the
/// lengths of neighbouring nodes on the full-sliding plateau go down and up by a count
/// (core/tests/library/ladder_invariants.rs). The chosen counts are within 2 counts of (x, y): half a count
/// for the rounded length, one for the lattice of counts in a ring one count wide, half a count
/// across.
fn quantize_force(x: f64, y: f64) -> [i16; 2] {
    let length = x.hypot(y);
    let target = length.round().min(FULL_SCALE);
    // The point of length `target` in the direction of (x, y), and the counts around it.
    let scale = if length > 0.0 { target / length } else { 0.0 };
    let (px, py) = (x * scale, y * scale);
    let mut best: Option<([i16; 2], f64)> = None;
    for qx in (px.floor() as i32 - 2)..=(px.ceil() as i32 + 2) {
        for qy in (py.floor() as i32 - 2)..=(py.ceil() as i32 + 2) {
            let (Ok(qx), Ok(qy)) = (i16::try_from(qx), i16::try_from(qy)) else { continue };
            let distance = (f64::from(qx) - x).hypot(f64::from(qy) - y);
            if stored_length(qx, qy) == target && best.is_none_or(|(_, d)| distance < d) {
                best = Some(([qx, qy], distance));
            }
        }
    }
    // Always found (two floors or ceilings of (px, py) already give a length within a count
    // below `target`); the components rounded one by one, inside the disc, otherwise.
    best.map_or_else(
        || {
            let [mut qx, mut qy] = [x, y].map(|c| c.round().clamp(-FULL_SCALE, FULL_SCALE) as i16);
            while f64::from(qx).hypot(f64::from(qy)) > FULL_SCALE {
                let larger = if qx.abs() >= qy.abs() { &mut qx } else { &mut qy };
                *larger -= larger.signum();
            }
            [qx, qy]
        },
        |(counts, _)| counts,
    )
}

/// The length of a stored force in counts, as the evaluation uses it: |(qx, qy)| rounded up, so
/// that it is never shorter than the components (the bound |F| ≤ μQ holds for both).
fn stored_length(qx: i16, qy: i16) -> f64 {
    f64::from(qx).hypot(f64::from(qy)).ceil()
}

/// Sequential little-endian reads with a clear error at the end of the data.
/// The value counts as stored in the file: for each of F_x, F_y, M_z (component-major), the
/// differences along τ and then along ν (wrapping i16 arithmetic, so exactly invertible), their
/// low bytes and then their high bytes. Neighbouring nodes differ by a few counts, so the
/// differences are small and the high-byte plane nearly constant: the zip's deflate then takes
/// the table from 15.7 MB to 7.5 MB with the same counts (docs/exact_table.md, "How the table is
/// stored"). `counts` is node-major (3 per node), as in memory.
fn encode_counts(axes: &TableAxes, counts: &[i16]) -> Vec<u8> {
    let n = axes.len();
    let [_, n_nu, _, _, n_t] = axes.counts;
    let nu_stride = axes.len() / (axes.counts[0] * n_nu);
    let mut bytes = vec![0u8; 2 * counts.len()];
    for component in 0..3 {
        let count = |i: usize| counts[3 * i + component];
        let along_tau = |i: usize| if i % n_t > 0 { count(i).wrapping_sub(count(i - 1)) } else { count(i) };
        for i in 0..n {
            let difference = if (i / nu_stride) % n_nu > 0 {
                along_tau(i).wrapping_sub(along_tau(i - nu_stride))
            } else {
                along_tau(i)
            };
            let [low, high] = difference.to_le_bytes();
            bytes[2 * component * n + i] = low;
            bytes[(2 * component + 1) * n + i] = high;
        }
    }
    bytes
}

/// The inverse of `encode_counts`: sums along ν, then along τ.
fn decode_counts(axes: &TableAxes, bytes: &[u8]) -> Vec<i16> {
    let n = axes.len();
    let [_, n_nu, _, _, n_t] = axes.counts;
    let nu_stride = axes.len() / (axes.counts[0] * n_nu);
    let mut counts = vec![0i16; 3 * n];
    for component in 0..3 {
        let mut values: Vec<i16> = (0..n)
            .map(|i| i16::from_le_bytes([bytes[2 * component * n + i], bytes[(2 * component + 1) * n + i]]))
            .collect();
        for i in 0..n {
            if (i / nu_stride) % n_nu > 0 {
                values[i] = values[i].wrapping_add(values[i - nu_stride]);
            }
        }
        for i in 0..n {
            if i % n_t > 0 {
                values[i] = values[i].wrapping_add(values[i - 1]);
            }
            counts[3 * i + component] = values[i];
        }
    }
    counts
}

/// The contents of a table file after its magic bytes and format version, once these and the
/// checksum are right.
fn checked_contents(bytes: &[u8]) -> Result<&[u8], TableError> {
    let (body, stored) = bytes
        .split_last_chunk::<4>()
        .ok_or_else(|| TableError(format!("{} bytes is too short for a table", bytes.len())))?;
    if body.len() < MAGIC.len() || &body[..MAGIC.len()] != MAGIC {
        return Err(TableError("not a table file (wrong magic bytes)".into()));
    }
    let (computed, stored) = (crc32fast::hash(body), u32::from_le_bytes(*stored));
    if computed != stored {
        return Err(TableError(format!(
            "checksum mismatch (stored {stored:08x}, computed {computed:08x}): the file is corrupted"
        )));
    }
    let mut reader = Reader { bytes: &body[MAGIC.len()..] };
    let version = reader.u32()?;
    if version != FORMAT_VERSION {
        return Err(TableError(format!("format version {version}, this build reads {FORMAT_VERSION}")));
    }
    Ok(reader.bytes)
}

struct Reader<'a> {
    bytes: &'a [u8],
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], TableError> {
        if n > self.bytes.len() {
            return Err(TableError(format!("truncated: {n} bytes wanted, {} left", self.bytes.len())));
        }
        let (head, tail) = self.bytes.split_at(n);
        self.bytes = tail;
        Ok(head)
    }

    fn u32(&mut self) -> Result<u32, TableError> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }

    fn f64(&mut self) -> Result<f64, TableError> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 16-bit storage: within one unit of the value, the unit of each τ node its largest
    /// value / 32767 (small near t = 0), never outside the Coulomb disc, full sliding along an
    /// axis exactly μQ, and the derived |F| the stored length.
    #[test]
    fn values_are_stored_to_the_nearest_count_of_their_tau_node_inside_the_disc() {
        let axes = TableAxes { counts: [2, 2, 3, 2, 5], a_over_b: A_OVER_B_RANGE, poisson_ratio: (0.0, 0.5) };
        let mut values = vec![0.0f32; 3 * 120];
        // Nodes 1, 2 and 4 of the first ray (τ = 0.25, 0.5, 1), node 1 of the second ray.
        let nodes: [(usize, [f32; 3]); 4] = [
            (1, [1.0e-4, -2.0e-5, 3.0e-6]),
            (6, [-4.0e-4, 0.000_123_456, -7.0e-6]),
            (2, [0.6, 0.8, 2.5]),
            (4, [1.000_005, 0.0, 0.0]),
        ];
        for (i, node) in nodes {
            values[3 * i..3 * i + 3].copy_from_slice(&node);
        }
        let table = Table::new("test".into(), axes, vec![[1.0; 3]; 4], [0.35, 0.9].repeat(12), values).unwrap();
        let expected_units = [
            [1.0 / FULL_SCALE; 2],
            [f64::from(-4.0e-4f32).hypot(f64::from(0.000_123_456f32)) / FULL_SCALE, f64::from(7.0e-6f32) / FULL_SCALE],
            [1.0 / FULL_SCALE, 2.5 / FULL_SCALE],
            [1.0 / FULL_SCALE; 2],
            [1.0 / FULL_SCALE; 2],
        ];
        for (m, (unit, expected)) in table.units.iter().zip(expected_units).enumerate() {
            for k in 0..2 {
                assert!((unit[k] - expected[k]).abs() <= 1e-9 * expected[k], "τ node {m}: {unit:?} vs {expected:?}");
            }
        }
        for (i, node) in nodes {
            let stored = table.nodes[i].map(f64::from);
            let [force_unit, moment_unit] = table.units[i % 5];
            for (k, unit) in [force_unit, force_unit, moment_unit].into_iter().enumerate() {
                let value = f64::from(node[k]).clamp(-1.0, 2.5);
                let count = stored[k] / unit;
                assert!((count - count.round()).abs() < 3e-3, "node {i}, value {k}: {count} counts");
                // Forces within 2 counts (`quantize_force`), moments within half a count.
                let counts = if k < 2 { 2.0 } else { 0.5 };
                assert!(
                    (stored[k] - value).abs() <= counts * unit + 1e-7 * unit * FULL_SCALE,
                    "node {i}, value {k}: {stored:?}"
                );
            }
            // The derived length: |F| rounded to the nearest count, never shorter than the stored
            // components.
            let (length, unit) = (stored[0].hypot(stored[1]), force_unit);
            let exact = f64::from(node[0]).hypot(f64::from(node[1])).min(1.0);
            assert!(length <= 1.0 + 1e-7 && stored[3] <= 1.0, "node {i}: {stored:?}");
            assert!(stored[3] >= length - 1e-7 && stored[3] - length < unit + 1e-7, "node {i}: {stored:?}");
            assert!((stored[3] - (exact / unit).round() * unit).abs() <= 1e-7, "node {i}: {stored:?}");
        }
        assert_eq!(table.nodes[4], [1.0, 0.0, 0.0, 1.0], "full sliding along ξ is μQ exactly");
        assert_eq!(Table::from_bytes(&table.to_bytes()), Ok(table));
    }

    /// The stored length is |F| rounded to the nearest count, so it keeps the order of the
    /// forces' lengths along a ray (monotone saturation), also on the full-sliding plateau where
    /// neighbouring nodes differ by less than a count; the counts stay within 2 counts of the
    /// force and inside the disc.
    #[test]
    fn stored_lengths_keep_the_order_of_the_forces() {
        let lengths =
            [0.0, 0.3, 0.7, 1.0, 1.49, 2.6, 17.3, 1000.5, 20000.2, 32765.9, 32766.2, 32766.5, 32766.8, 32767.0];
        for direction in 0..2000 {
            let angle = direction as f64 * 0.003_141_6;
            let mut previous = 0.0;
            for length in lengths {
                let (x, y) = (length * angle.cos(), length * angle.sin());
                let [qx, qy] = quantize_force(x, y);
                let stored = stored_length(qx, qy);
                assert_eq!(stored, x.hypot(y).round(), "angle {angle}, length {length}: counts ({qx}, {qy})");
                assert!(stored >= previous && f64::from(qx).hypot(f64::from(qy)) <= FULL_SCALE);
                assert!((f64::from(qx) - x).hypot(f64::from(qy) - y) <= 2.0, "angle {angle}, length {length}");
                previous = stored;
            }
        }
    }
}
