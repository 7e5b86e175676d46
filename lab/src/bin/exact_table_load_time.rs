//! What reading the `exact_table` model's table costs the FMU (docs/exact_table.md, "Where the
//! table lives"): reading `data/exact_table.bin`, checking its frame (`Table::check_bytes`, at
//! fmi2Instantiate) and decoding it (`Table::from_bytes`, when an instance first selects the
//! model), each timed three times, and the decoded table's size.
//!
//! Run: `cargo run --release -p lab --bin exact_table_load_time`.

use std::time::Instant;

use wheel_rail_contact::models::exact_table::Table;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/exact_table.bin");
    for _ in 0..3 {
        let started = Instant::now();
        let bytes = std::fs::read(path)?;
        let read = started.elapsed();
        let started = Instant::now();
        Table::check_bytes(&bytes)?;
        let checked = started.elapsed();
        let started = Instant::now();
        let table = Table::from_bytes(&bytes)?;
        let decoded = started.elapsed();
        println!(
            "read {read:.1?}, frame checked {checked:.2?}, decoded {decoded:.1?}: {} nodes, ≈ {:.0} MB of f32 × 4",
            table.axes.len(),
            table.axes.len() as f64 * 16.0 / 1e6
        );
    }
    Ok(())
}
