//! The table: its axes, its nodes and its file format, checked when it is read.
//!
//! Format (little-endian): the 16-byte magic `WRC-EXACT-TABLE\0`, the format version (u32),
//! the provenance text (u32 length + UTF-8: generator version, solver grid, command), the node
//! counts along a/b, ν, β, α, t (5 × u32), the a/b and ν ranges (4 × f64), the scale factors k
//! at every (a/b, ν) node (3 × f64 each), the values (3 × f32 per node: F_x/(μQ), F_y/(μQ),
//! M_z/(μQc)), and a CRC-32 of all the bytes before it.
//!
//! Layout: node (i_ab, i_ν, i_β, i_α, i_t) at ((((i_ab·n_ν + i_ν)·n_β + i_β)·n_α + i_α)·n_t + i_t),
//! so the two t nodes of every corner of an interpolation cell are adjacent in memory. In memory
//! each node also holds |F|/(μQ), derived when the table is made (see `interpolate.rs`).

use std::fmt;

const MAGIC: &[u8; 16] = b"WRC-EXACT-TABLE\0";
/// Version of this file format (not of the values: the provenance text says how they were made).
pub const FORMAT_VERSION: u32 = 1;
/// The a/b range of every table (the error for contacts outside it names this range).
pub const A_OVER_B_RANGE: (f64, f64) = (0.1, 10.0);
/// Values this far outside the Coulomb disc are refused (float rounding of stored values).
const BOUND_TOLERANCE: f32 = 1e-5;

/// Node counts and ranges of the table's five axes: ln(a/b) and ν uniform over their ranges,
/// β uniform over [−1, 1], α and t uniform over [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct TableAxes {
    /// Nodes along a/b (uniform in ln(a/b)), ν, β, α and t.
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

    /// β, α and t of nodes `(k, l, m)`.
    pub fn direction_node(&self, k: usize, l: usize, m: usize) -> (f64, f64, f64) {
        let unit = |i: usize, n: usize| i as f64 / (n - 1) as f64;
        (2.0 * unit(k, self.counts[2]) - 1.0, unit(l, self.counts[3]), unit(m, self.counts[4]))
    }

    /// Distance in nodes between neighbours along a/b, ν, β and α.
    pub(crate) fn strides(&self) -> [usize; 4] {
        let [_, n_nu, n_beta, n_alpha, n_t] = self.counts;
        [n_t * n_alpha * n_beta * n_nu, n_t * n_alpha * n_beta, n_t * n_alpha, n_t]
    }

    /// Index of node (i_ab, i_ν, i_β, i_α, i_t).
    pub(crate) fn index(&self, [i_ab, i_nu, k, l, m]: [usize; 5]) -> usize {
        let [_, n_nu, n_beta, n_alpha, n_t] = self.counts;
        (((i_ab * n_nu + i_nu) * n_beta + k) * n_alpha + l) * n_t + m
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
    /// F_x/(μQ), F_y/(μQ), M_z/(μQc) and |F|/(μQ) at each node.
    pub(crate) nodes: Vec<[f32; 4]>,
    /// The axes as [`AxisMap`]s: ln(a/b), ν, β, α, t.
    pub(crate) maps: [AxisMap; 5],
    /// Neighbour distances in `values` along a/b, ν, β and α ([`TableAxes::strides`]).
    pub(crate) strides: [usize; 4],
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
    /// Assembles a table from its parts (the generator's last step).
    pub fn new(
        provenance: String,
        axes: TableAxes,
        scales: Vec<[f64; 3]>,
        values: Vec<f32>,
    ) -> Result<Self, TableError> {
        let [n_ab, n_nu, n_beta, n_alpha, n_t] = axes.counts;
        let maps = [
            AxisMap::new(axes.a_over_b.0.ln(), axes.a_over_b.1.ln(), n_ab),
            AxisMap::new(axes.poisson_ratio.0, axes.poisson_ratio.1, n_nu),
            AxisMap::new(-1.0, 1.0, n_beta),
            AxisMap::new(0.0, 1.0, n_alpha),
            AxisMap::new(0.0, 1.0, n_t),
        ];
        let strides = axes.strides();
        if values.len() != 3 * axes.len() {
            return Err(TableError(format!("{} values for {} nodes", values.len(), axes.len())));
        }
        let nodes = values.chunks_exact(3).map(|v| [v[0], v[1], v[2], v[0].hypot(v[1])]).collect();
        let table = Self { provenance, axes, scales, nodes, maps, strides };
        table.check()?;
        Ok(table)
    }

    /// The file's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut bytes = Vec::with_capacity(12 * self.nodes.len() + 1024);
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
        for v in self.nodes.iter().flat_map(|node| &node[..3]) {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let checksum = crc32fast::hash(&bytes);
        bytes.extend_from_slice(&checksum.to_le_bytes());
        bytes
    }

    /// Reads and checks a table file: magic, version, sizes, checksum, finite values inside the
    /// Coulomb disc. The error says what is wrong.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, TableError> {
        if bytes.is_empty() {
            return Err(TableError(
                "no table was compiled in (data/exact_table.bin was missing at build time; \
                 `cargo fmu exact-table` generates it)"
                    .into(),
            ));
        }
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
        let value_count = 3 * axes.len();
        let values: Vec<f32> = reader
            .take(4 * value_count)?
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        if !reader.bytes.is_empty() {
            return Err(TableError(format!("{} bytes after the values", reader.bytes.len())));
        }
        Self::new(provenance, axes, scales, values)
    }

    /// The invariants the interpolation relies on.
    fn check(&self) -> Result<(), TableError> {
        let axes = &self.axes;
        let (ab, nu) = (axes.a_over_b, axes.poisson_ratio);
        // The model's messages name this a/b range, and every valid ν must be inside the table
        // (outside, the interpolation would clamp silently).
        if ab != A_OVER_B_RANGE || nu != (0.0, 0.5) {
            return Err(TableError(format!(
                "a/b range {ab:?} and ν range {nu:?}: this build reads tables over a/b {A_OVER_B_RANGE:?}, ν (0, 0.5)"
            )));
        }
        if self.scales.len() != axes.counts[0] * axes.counts[1]
            || self.scales.iter().flatten().any(|k| !(k.is_finite() && *k > 0.0))
        {
            return Err(TableError("scale factors missing, not finite or not positive".into()));
        }
        for (node, v) in self.nodes.iter().enumerate() {
            let inside = v.iter().all(|x| x.is_finite()) && v[3] <= 1.0 + BOUND_TOLERANCE;
            if !inside {
                return Err(TableError(format!("node {node} holds {:?}: not finite or |F| > μQ", &v[..3])));
            }
        }
        Ok(())
    }
}

/// Sequential little-endian reads with a clear error at the end of the data.
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
