//! The default scene through the packaged FMU: a creepage sweep, as a master would run it,
//! with the project's own minimal master ([`crate::master`]; no Python and no libclang needed).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::master::LoadedFmu;
use wheel_rail_contact_fmu::model_description::value_reference as vr;

use crate::plot::{line_plot, Series};

/// One communication point of the sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    pub creepage_longitudinal: f64,
    pub force_longitudinal: f64,
    pub force_lateral: f64,
    pub adhesion_utilisation: f64,
}

/// The sweep of the README: ξ = 0 … 1 % in steps of 0.05 %, everything else at the start values.
pub fn default_creepages() -> Vec<f64> {
    (0..=20).map(|i| i as f64 * 5e-4).collect()
}

/// Loads the FMU, initialises it at its start values, and for each creepage sets it, does one
/// step of 1 ms and reads the outputs.
pub fn sweep(fmu_path: &Path, creepages: &[f64]) -> Result<Vec<Row>, String> {
    let fmu = LoadedFmu::open(fmu_path)?;
    let instance = fmu.instantiate("default_scene")?;
    let step = 1e-3;
    let mut rows = Vec::with_capacity(creepages.len());
    for (index, &creepage) in creepages.iter().enumerate() {
        instance.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[creepage])?;
        instance.do_step(index as f64 * step, step)?;
        let outputs = instance.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION])?;
        let [force_longitudinal, force_lateral, adhesion_utilisation] = outputs[..] else { unreachable!() };
        rows.push(Row { creepage_longitudinal: creepage, force_longitudinal, force_lateral, adhesion_utilisation });
    }
    Ok(rows)
}

/// The table printed by `cargo fmu`.
pub fn table(rows: &[Row]) -> String {
    let mut text = String::from("  creepage ξ [%]   F_x [kN]   F_y [kN]   |F|/(μQ)\n");
    for row in rows {
        writeln!(
            text,
            "{:>16.3} {:>10.3} {:>10.3} {:>10.4}",
            row.creepage_longitudinal * 100.0,
            // `+ 0.0` prints a force of −0 (no creepage in that direction) as 0.
            row.force_longitudinal / 1e3 + 0.0,
            row.force_lateral / 1e3 + 0.0,
            row.adhesion_utilisation
        )
        .unwrap();
    }
    text
}

/// CSV in SI units, every digit kept.
pub fn csv(rows: &[Row]) -> String {
    let mut text = String::from("creepage_longitudinal,force_longitudinal,force_lateral,adhesion_utilisation\n");
    for row in rows {
        writeln!(
            text,
            "{:?},{:?},{:?},{:?}",
            row.creepage_longitudinal, row.force_longitudinal, row.force_lateral, row.adhesion_utilisation
        )
        .unwrap();
    }
    text
}

/// Runs the sweep and writes `default_scene.csv` and `default_scene.svg` into `out_dir`.
pub fn run(fmu_path: &Path, out_dir: &Path) -> Result<(Vec<Row>, [PathBuf; 2]), String> {
    let rows = sweep(fmu_path, &default_creepages())?;
    let series = Series {
        label: "F_x through the FMU (default scene)".into(),
        points: rows.iter().map(|r| (r.creepage_longitudinal * 100.0, r.force_longitudinal / 1e3)).collect(),
    };
    let svg = line_plot("wheel_rail_contact.fmu: creepage sweep", "creepage ξ [%]", "F_x [kN]", &[series]);
    let paths = [out_dir.join("default_scene.csv"), out_dir.join("default_scene.svg")];
    for (path, text) in paths.iter().zip([csv(&rows), svg]) {
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok((rows, paths))
}
