//! The default scene through the packaged FMU: a creepage sweep, as a master would run it,
//! with the project's C-ABI master (`fmu_master`, libloading; no Python and no libclang needed).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fmu_master::binary::{file_uri, Functions, Instance, Status};
use wheel_rail_contact_fmu::model_description::{value_reference as vr, GUID, MODEL_IDENTIFIER};

use crate::fmu::Platform;
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
    let folder = tempfile_folder()?;
    let binary = extract(fmu_path, &folder.0)?;
    let functions = Functions::load(&binary)?;
    let instance = Instance::new(&functions, "default_scene", GUID, &file_uri(&folder.0.join("resources")))?;
    let check = |call: &str, status: Status| match status {
        Status::Ok => Ok(()),
        status => Err(format!("{call}: {status:?} {:?}", instance.take_messages())),
    };
    check("fmi2EnterInitializationMode", instance.enter_initialization(0.0))?;
    check("fmi2ExitInitializationMode", instance.exit_initialization())?;
    let step = 1e-3;
    let mut rows = Vec::with_capacity(creepages.len());
    for (index, &creepage) in creepages.iter().enumerate() {
        check("fmi2SetReal", instance.set_real(&[vr::CREEPAGE_LONGITUDINAL], &[creepage]))?;
        check("fmi2DoStep", instance.do_step(index as f64 * step, step))?;
        let (status, outputs) =
            instance.get_real(&[vr::FORCE_LONGITUDINAL, vr::FORCE_LATERAL, vr::ADHESION_UTILISATION]);
        check("fmi2GetReal", status)?;
        let [force_longitudinal, force_lateral, adhesion_utilisation] = outputs[..] else { unreachable!() };
        rows.push(Row { creepage_longitudinal: creepage, force_longitudinal, force_lateral, adhesion_utilisation });
    }
    Ok(rows)
}

/// A folder of this process's own, removed on drop.
struct TempFolder(PathBuf);

impl Drop for TempFolder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn tempfile_folder() -> Result<TempFolder, String> {
    let folder =
        std::path::absolute(std::env::temp_dir().join(format!("wheel_rail_contact_scene_{}", std::process::id())))
            .map_err(|e| format!("the temporary folder: {e}"))?;
    std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    Ok(TempFolder(folder))
}

/// Unzips the FMU into `folder` (an absolute path), as a master does, and returns the path of this
/// machine's binary (`binaries/<platform>/<modelIdentifier>.<ext>`).
fn extract(fmu_path: &Path, folder: &Path) -> Result<PathBuf, String> {
    let platform = Platform::this_machine()
        .ok_or_else(|| format!("no FMI 2.0 platform for {}/{}", std::env::consts::OS, std::env::consts::ARCH))?;
    let file = std::fs::File::open(fmu_path).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    archive.extract(folder).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    let binary =
        folder.join("binaries").join(platform.folder()).join(format!("{MODEL_IDENTIFIER}.{}", platform.extension()));
    if binary.is_file() {
        Ok(binary)
    } else {
        Err(format!("{} has no {}", fmu_path.display(), binary.strip_prefix(folder).unwrap_or(&binary).display()))
    }
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
