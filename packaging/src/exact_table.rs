//! `cargo fmu exact-table`: generates `data/exact_table.bin`, the `exact_table` model's table,
//! from the exact solver. Slices of the table (one a/b, one ν) are solved in parallel (rayon,
//! every core) and saved as they finish under `target/exact-table/<settings>/`, so an
//! interrupted run resumes where it stopped; the table is assembled when all are present.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use wheel_rail_contact::models::exact_table::generation::{
    assemble, extend, extrapolate, refresh_full_slip, slice_values, Slice, SliceStatistics,
};
use wheel_rail_contact::models::exact_table::{Table, TableAxes, A_OVER_B_RANGE};
use wheel_rail_contact::ExactTheory;

/// Version of the generator (bump when the values it makes change for the same settings).
pub const GENERATOR_VERSION: u32 = 3;
/// Version of the saved slices' solves (bump when a slice solved on the same grid at the same
/// nodes would change), part of the slices' directory names: slices of an earlier generator
/// whose solves are still the same are reused.
const SLICE_VERSION: u32 = 2;

/// Below this a/b a contact is "wide" and its nodes are solved on `Settings::wide_grid`.
pub const WIDE_BELOW: f64 = 1.0 / 3.0;

/// What a generation makes.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The table's axes.
    pub axes: TableAxes,
    /// The exact solver's grid (longitudinal × lateral elements over 2.2 a × 2.2 b) for a/b ≥
    /// [`WIDE_BELOW`].
    pub grid: (usize, usize),
    /// The grid for a/b < [`WIDE_BELOW`], where the lateral elements are the coarse ones.
    pub wide_grid: (usize, usize),
    /// Whether every node is extrapolated along x from its grid and one with half the
    /// longitudinal elements ([`extrapolate`]).
    pub extrapolate: bool,
    /// An earlier table whose nodes are reused: the same axes but fewer a/b nodes at the same
    /// spacing from the same smallest a/b (the shipped table was extended so, from a/b ≤ 10 to
    /// 10^1.5; docs/exact_table.md, "How it was made").
    pub extend_from: Option<PathBuf>,
}

impl Settings {
    /// The shipped table: a/b ∈ [0.1, 10^1.5] (36 nodes, uniform in ln a/b), ν ∈ [0, 0.5] (4),
    /// β (41), α (13), τ (49); nodes solved on 80 × 20 elements (40 × 40 for a/b < 1/3) and on
    /// half as many along x, and extrapolated (docs/exact_table.md, "How it was made": the node
    /// study behind the choice); 16-bit values (its size: docs/exact_table.md, "What is
    /// tabulated").
    pub fn shipped() -> Self {
        Self {
            axes: TableAxes { counts: [36, 4, 41, 13, 49], a_over_b: A_OVER_B_RANGE, poisson_ratio: (0.0, 0.5) },
            grid: (80, 20),
            wide_grid: (40, 40),
            extrapolate: true,
            extend_from: None,
        }
    }

    /// Parses `--counts A,N,B,AL,T`, `--grid NXxNY`, `--wide-grid NXxNY`, `--extrapolate yes|no`
    /// and `--extend-from PATH` over the shipped settings.
    pub fn from_args(args: &[String]) -> Result<Self, String> {
        let mut settings = Self::shipped();
        let mut args = args.iter();
        while let Some(flag) = args.next() {
            let value = args.next().ok_or_else(|| format!("{flag} needs a value"))?;
            let numbers = |separator: char| -> Result<Vec<usize>, String> {
                value.split(separator).map(|n| n.parse().map_err(|_| format!("{flag} {value}: not a count"))).collect()
            };
            let grid = || match numbers('x')?.as_slice() {
                &[nx, ny] if nx >= 2 && ny >= 2 => Ok((nx, ny)),
                _ => Err(format!("{flag} {value}: NXxNY, at least 2 elements each way")),
            };
            match flag.as_str() {
                "--counts" => {
                    settings.axes.counts = numbers(',')?
                        .try_into()
                        .map_err(|_| format!("--counts {value}: five counts (a/b, ν, β, α, t)"))?
                }
                "--grid" => settings.grid = grid()?,
                "--wide-grid" => settings.wide_grid = grid()?,
                "--extrapolate" => {
                    settings.extrapolate = match value.as_str() {
                        "yes" => true,
                        "no" => false,
                        _ => return Err(format!("--extrapolate {value}: yes or no")),
                    }
                }
                "--extend-from" => settings.extend_from = Some(PathBuf::from(value)),
                _ => return Err(format!("unknown option {flag}")),
            }
        }
        if settings.extrapolate && [settings.grid, settings.wide_grid].iter().any(|g| !g.0.is_multiple_of(2)) {
            return Err(format!(
                "--grid {}x{} --wide-grid {}x{}: even counts along x, to extrapolate from half as many",
                settings.grid.0, settings.grid.1, settings.wide_grid.0, settings.wide_grid.1
            ));
        }
        let counts = settings.axes.counts;
        if counts.iter().any(|&n| n < 2) || counts[2].is_multiple_of(2) {
            return Err(format!("--counts {counts:?}: at least 2 nodes per axis, an odd count along β (β = 0 a node)"));
        }
        Ok(settings)
    }

    /// The grid the nodes at this a/b are solved on.
    fn grid_at(&self, a_over_b: f64) -> (usize, usize) {
        if a_over_b < WIDE_BELOW {
            self.wide_grid
        } else {
            self.grid
        }
    }

    /// The directory of the slices solved on `grid` (at the nodes found on `nodes_of`, when
    /// that is another grid).
    fn slice_directory(&self, grid: (usize, usize), nodes_of: (usize, usize)) -> String {
        let c = self.axes.counts;
        let at = if grid == nodes_of { String::new() } else { format!("-at-{}x{}", nodes_of.0, nodes_of.1) };
        format!("v{SLICE_VERSION}-{}x{}{at}-{}-{}-{}-{}-{}", grid.0, grid.1, c[0], c[1], c[2], c[3], c[4])
    }
}

/// The table at `path`, checked to have the first a/b nodes of `axes` (the same nodes along
/// every other axis).
fn earlier_table(path: &Path, axes: &TableAxes) -> Result<Table, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("--extend-from {}: {e}", path.display()))?;
    let table = Table::from_bytes(&bytes).map_err(|e| format!("--extend-from {}: {e}", path.display()))?;
    let earlier = &table.axes;
    let same_nodes = earlier.counts[1..] == axes.counts[1..]
        && earlier.poisson_ratio == axes.poisson_ratio
        && earlier.counts[0] <= axes.counts[0]
        && (0..earlier.counts[0]).all(|i| (earlier.a_over_b_node(i) / axes.a_over_b_node(i) - 1.0).abs() < 1e-12);
    if !same_nodes {
        return Err(format!(
            "--extend-from {}: its nodes {:?} over a/b {:?} are not the first of {:?} over a/b {:?}",
            path.display(),
            earlier.counts,
            earlier.a_over_b,
            axes.counts,
            axes.a_over_b
        ));
    }
    Ok(table)
}

/// Generates (or resumes) the table and writes it to `out`.
pub fn generate(settings: &Settings, work_dir: &Path, out: &Path) -> Result<(), String> {
    let [n_ab, n_nu, ..] = settings.axes.counts;
    let started = Instant::now();
    let mut totals = SliceStatistics::default();
    let earlier = match &settings.extend_from {
        Some(path) => Some(earlier_table(path, &settings.axes)?),
        None => None,
    };
    let reused = earlier.as_ref().map_or(0, |table| table.axes.counts[0]);
    let mut slices = Vec::new();
    for i_ab in reused..n_ab {
        for i_nu in 0..n_nu {
            let grid = settings.grid_at(settings.axes.a_over_b_node(i_ab));
            let mut obtain = |solved_on: (usize, usize), nodes_of: Option<&Slice>| {
                let directory = work_dir.join(settings.slice_directory(solved_on, grid));
                let path = directory.join(format!("slice-{i_ab:03}-{i_nu:03}.f32"));
                if let Some(saved) = read_slice(&path, &settings.axes) {
                    return Ok(refresh_full_slip(&settings.axes, i_ab, i_nu, &saved));
                }
                let slice_started = Instant::now();
                let solver = ExactTheory::new(solved_on.0, solved_on.1);
                let (slice, stats) = slice_values(&settings.axes, i_ab, i_nu, &solver, nodes_of)
                    .map_err(|e| format!("slice a/b node {i_ab}, ν node {i_nu}: {e}"))?;
                std::fs::create_dir_all(&directory).map_err(|e| format!("{}: {e}", directory.display()))?;
                write_slice(&path, &slice)?;
                totals += stats;
                println!(
                    "slice {:>3}/{} on {}x{}: a/b = {:.4}, ν = {:.3}: {} solves ({} unconverged), {:.1} Newton steps and {:.0} products per solve, {:.1} s",
                    i_ab * n_nu + i_nu + 1,
                    n_ab * n_nu,
                    solved_on.0,
                    solved_on.1,
                    settings.axes.a_over_b_node(i_ab),
                    settings.axes.poisson_node(i_nu),
                    stats.solves,
                    stats.unconverged,
                    stats.iterations as f64 / stats.solves.max(1) as f64,
                    stats.operator_products as f64 / stats.solves.max(1) as f64,
                    slice_started.elapsed().as_secs_f64()
                );
                Ok::<_, String>(slice)
            };
            let fine = obtain(grid, None)?;
            let slice = if settings.extrapolate {
                let coarse = obtain((grid.0 / 2, grid.1), Some(&fine))?;
                extrapolate(&fine, &coarse)
            } else {
                fine
            };
            slices.push(slice);
        }
    }
    let provenance = format!(
        "wheel-rail-contact {} exact_table generator v{GENERATOR_VERSION}: `cargo fmu exact-table{}`; \
         ExactTheory (FFT Newton-GMRES) on {} x {} elements over 2.2a x 2.2b ({} x {} for a/b < 1/3){}; \
         nodes a/b {} (ln-uniform over {:?}), nu {} over {:?}, beta {}, alpha {}, tau {} (kink-fitted size: \
         each ray's adhesion collapse at tau 0.5625, found by bisection); tau = 1 by full-sliding \
         quadrature; values 16-bit{}",
        env!("CARGO_PKG_VERSION"),
        args_text(settings),
        settings.grid.0,
        settings.grid.1,
        settings.wide_grid.0,
        settings.wide_grid.1,
        if settings.extrapolate { ", extrapolated along x from half as many elements" } else { "" },
        settings.axes.counts[0],
        settings.axes.a_over_b,
        settings.axes.counts[1],
        settings.axes.poisson_ratio,
        settings.axes.counts[2],
        settings.axes.counts[3],
        settings.axes.counts[4],
        if reused > 0 {
            format!(
                "; a/b nodes 0 to {} taken from an earlier table: {}",
                reused - 1,
                earlier.as_ref().map_or("", |table| table.provenance.as_str())
            )
        } else {
            String::new()
        },
    );
    let table = match &earlier {
        Some(earlier) => extend(earlier, provenance, settings.axes.clone(), slices),
        None => assemble(provenance, settings.axes.clone(), slices),
    }
    .map_err(|e| e.to_string())?;
    let bytes = table.to_bytes();
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(out, &bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    println!(
        "wrote {} ({} nodes, {:.1} MB) in {:.0} s; this run solved {} cases ({} unconverged)",
        out.display(),
        settings.axes.len(),
        bytes.len() as f64 / 1e6,
        started.elapsed().as_secs_f64(),
        totals.solves,
        totals.unconverged
    );
    Ok(())
}

fn args_text(settings: &Settings) -> String {
    if *settings == Settings::shipped() {
        return String::new();
    }
    let c = settings.axes.counts;
    let (g, w) = (settings.grid, settings.wide_grid);
    format!(
        " --counts {},{},{},{},{} --grid {}x{} --wide-grid {}x{} --extrapolate {}{}",
        c[0],
        c[1],
        c[2],
        c[3],
        c[4],
        g.0,
        g.1,
        w.0,
        w.1,
        if settings.extrapolate { "yes" } else { "no" },
        settings.extend_from.as_ref().map(|path| format!(" --extend-from {}", path.display())).unwrap_or_default()
    )
}

/// A saved slice (its values, then its rays' collapse, f32), or `None` when it is missing or
/// unreadable (then it is solved again).
fn read_slice(path: &Path, axes: &TableAxes) -> Option<Slice> {
    let rays = axes.counts[2] * axes.counts[3];
    let length = 3 * rays * axes.counts[4];
    let bytes = std::fs::read(path).ok()?;
    if bytes.len() != 4 * (length + rays) {
        return None;
    }
    let mut floats: Vec<f32> = bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
    let collapse = floats.split_off(length);
    Some(Slice { values: floats, collapse })
}

/// Writes a slice atomically (a temporary file renamed), so an interrupted write is not a slice.
fn write_slice(path: &Path, slice: &Slice) -> Result<(), String> {
    let temporary: PathBuf = path.with_extension("partial");
    let mut file = std::fs::File::create(&temporary).map_err(|e| format!("{}: {e}", temporary.display()))?;
    let bytes: Vec<u8> = slice.values.iter().chain(&slice.collapse).flat_map(|v| v.to_le_bytes()).collect();
    file.write_all(&bytes).and_then(|()| file.sync_all()).map_err(|e| format!("{}: {e}", temporary.display()))?;
    std::fs::rename(&temporary, path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use wheel_rail_contact::models::exact_table::generation::slices_of;

    fn parse(args: &str) -> Result<Settings, String> {
        Settings::from_args(&args.split_whitespace().map(String::from).collect::<Vec<_>>())
    }

    #[test]
    fn options_override_the_shipped_settings_and_the_provenance_repeats_them() {
        assert_eq!(parse(""), Ok(Settings::shipped()));
        let settings = parse("--counts 3,2,5,3,17 --grid 60x30 --wide-grid 30x60 --extrapolate no").unwrap();
        assert_eq!(settings.axes.counts, [3, 2, 5, 3, 17]);
        assert_eq!((settings.grid, settings.wide_grid, settings.extrapolate), ((60, 30), (30, 60), false));
        assert_eq!(parse(&args_text(&settings)), Ok(settings.clone()));
        assert_eq!(settings.grid_at(WIDE_BELOW * 0.99), (30, 60));
        assert_eq!(settings.grid_at(WIDE_BELOW), (60, 30));
    }

    /// `--extend-from` takes a table's slices when its a/b nodes are the first of the new axis
    /// (the same spacing from the same smallest a/b) and every other axis is the same.
    #[test]
    fn an_earlier_table_is_extended_only_from_the_same_first_nodes() {
        let settings = parse("--counts 3,2,3,2,5 --extend-from earlier.bin").unwrap();
        assert_eq!(settings.extend_from, Some(PathBuf::from("earlier.bin")));
        assert!(args_text(&settings).ends_with(" --extend-from earlier.bin"));
        assert_eq!(parse(&args_text(&settings)), Ok(settings));
        let directory = tempfile::tempdir().unwrap();
        let path = directory.path().join("earlier.bin");
        let axes = |a_over_b: (f64, f64), counts: [usize; 5]| TableAxes { counts, a_over_b, poisson_ratio: (0.0, 0.5) };
        let mut values = vec![0.0f32; 3 * 120];
        values[3 * 119] = 0.5; // the last node of the last slice
        let earlier =
            Table::new("earlier".into(), axes((0.1, 10.0), [2, 2, 3, 2, 5]), vec![[1.0; 3]; 4], vec![0.6; 24], values)
                .unwrap();
        std::fs::write(&path, earlier.to_bytes()).unwrap();
        // Nodes 0.1, 10 and 1000: the earlier table's two, then one more, whose slices extend it.
        let longer = axes((0.1, 1000.0), [3, 2, 3, 2, 5]);
        let read = earlier_table(&path, &longer).unwrap();
        assert_eq!(read.provenance, "earlier");
        let new_slice = || Slice { values: vec![0.25; 90], collapse: vec![0.6; 6] };
        let extended = extend(&read, "extended".into(), longer, vec![new_slice(), new_slice()]).unwrap();
        assert_eq!(extended.axes.counts[0], 3);
        // The earlier table's bytes are the extended table's first ones, up to the axes.
        assert_eq!(slices_of(&extended)[3], slices_of(&earlier)[3]);
        assert!((slices_of(&extended)[4].values[0] - 0.25).abs() < 1e-4); // within a count
        for (other, what) in [
            (axes((0.1, 100.0), [3, 2, 3, 2, 5]), "its nodes [2, 2, 3, 2, 5] over a/b (0.1, 10.0) are not the first"),
            (axes((0.1, 1000.0), [3, 2, 5, 2, 5]), "are not the first of [3, 2, 5, 2, 5]"),
            (axes((0.1, 10.0), [1, 2, 3, 2, 5]), "are not the first of [1, 2, 3, 2, 5]"),
        ] {
            let error = earlier_table(&path, &other).unwrap_err();
            assert!(error.contains(what) && error.starts_with("--extend-from "), "{error}");
        }
        let missing = earlier_table(&directory.path().join("none.bin"), &axes((0.1, 1000.0), [3, 2, 3, 2, 5]));
        assert!(missing.unwrap_err().contains("none.bin"));
    }

    #[test]
    fn bad_options_are_refused_with_the_option_named() {
        for (args, expected) in [
            ("--grid 81x20", "--grid 81x20 --wide-grid 40x40: even counts along x"),
            ("--grid 80", "--grid 80: NXxNY"),
            ("--wide-grid 1x40", "--wide-grid 1x40: NXxNY, at least 2"),
            ("--extrapolate maybe", "--extrapolate maybe: yes or no"),
            ("--counts 3,2,4,3,17", "an odd count along β"),
            ("--grid", "--grid needs a value"),
            ("--grids 80x20", "unknown option --grids"),
        ] {
            let error = parse(args).unwrap_err();
            assert!(error.contains(expected), "{args}: {error}");
        }
        assert!(parse("--grid 81x20 --wide-grid 41x40 --extrapolate no").is_ok());
    }
}
