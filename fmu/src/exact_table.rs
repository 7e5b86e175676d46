//! The `exact_table` model's table: one copy in the FMU's `resources/`, not one in each
//! platform's binary (the core is built without its `embedded-table` feature; why:
//! docs/exact_table.md, "Where the table lives").
//!
//! - At fmi2Instantiate, [`check`] reads the file and checks its frame (magic bytes, CRC-32,
//!   format version) without decoding it: a missing or corrupted table fails the instantiation
//!   with a message naming the file, so a broken FMU is refused before it computes anything.
//! - When an instance first selects `creep_force_model = exact_table`, [`table`] decodes it.
//!
//! Both are done once per process and resources directory (instances of one FMU share the
//! table, and a scene that never selects the model never decodes it: ≈ 48 MB of memory and
//! ≈ 0.11 s it does not pay). A decoded table lives until the process ends, as the compiled-in
//! one did.

use crate::files::read_regular_file;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use wheel_rail_contact::models::exact_table::Table;

/// The table's file name in the FMU's `resources/` (`cargo fmu` packs `data/exact_table.bin` there).
pub const FILE_NAME: &str = "exact_table.bin";

/// The largest table file read \[bytes\]: the shipped one has 22.9 MB; a file beyond 64 MiB in
/// its place is not a table.
const MAX_TABLE_SIZE: u64 = 64 << 20;

/// What is known of each resources directory's table: checked, or decoded.
#[derive(Clone, Copy)]
enum Known {
    Checked,
    Decoded(&'static Table),
}

/// Every resources directory's table file and what is known of it. Held while a table is read,
/// so that instances instantiated on several threads at once read and decode it once.
static KNOWN: Mutex<Vec<(PathBuf, Known)>> = Mutex::new(Vec::new());

/// Runs `body` with what is known of `file` (`None`: nothing yet) and records what it returns.
/// (The lock is only poisoned by a panic inside `body`, a bug caught at the export; the list
/// holds only finished entries then, so it is used as is.)
fn with_known<T>(file: &Path, body: impl FnOnce(Option<Known>) -> Result<(Known, T), String>) -> Result<T, String> {
    let mut known = KNOWN.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let index = known.iter().position(|(path, _)| path == file);
    let (state, value) = body(index.map(|i| known[i].1))?;
    match index {
        Some(i) => known[i].1 = state,
        None => known.push((file.to_owned(), state)),
    }
    Ok(value)
}

fn read(file: &Path) -> Result<Vec<u8>, String> {
    read_regular_file(file, MAX_TABLE_SIZE)
        .map_err(|e| format!("cannot read the exact_table model's table {}: {e}", file.display()))
}

/// fmi2Instantiate's check of the table in `resources`: `Ok` when it is there and its frame is
/// sound, or when there is no resources directory to look in (a master that passes no usable
/// resource location, or one that names no existing directory: then selecting `exact_table` is
/// the error, see [`table`]).
pub fn check(resources: Option<&Path>) -> Result<(), String> {
    let Some(resources) = resources.filter(|directory| directory.is_dir()) else { return Ok(()) };
    let file = resources.join(FILE_NAME);
    with_known(&file, |known| match known {
        Some(known) => Ok((known, ())),
        None => {
            Table::check_bytes(&read(&file)?).map_err(|e| format!("{}: {e}", file.display()))?;
            Ok((Known::Checked, ()))
        }
    })
}

/// The table in `resources`, decoded on the first call for that directory.
pub fn table(resources: Option<&Path>) -> Result<&'static Table, String> {
    let resources = resources.ok_or_else(|| {
        format!(
            "the model reads its table from the FMU's resources/{FILE_NAME}, but the master passed no usable \
             resource location to fmi2Instantiate"
        )
    })?;
    let file = resources.join(FILE_NAME);
    with_known(&file, |known| match known {
        Some(Known::Decoded(table)) => Ok((Known::Decoded(table), table)),
        _ => {
            let table = Table::from_bytes(&read(&file)?).map_err(|e| format!("{}: {e}", file.display()))?;
            let table: &'static Table = Box::leak(Box::new(table));
            Ok((Known::Decoded(table), table))
        }
    })
}
