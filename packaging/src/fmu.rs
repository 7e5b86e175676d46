//! Builds the shared library and writes the `.fmu` archive.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use wheel_rail_contact_fmu::model_description::{MODEL_DESCRIPTION_XML, MODEL_IDENTIFIER};
use zip::write::SimpleFileOptions;

/// The workspace package that builds the FMU's shared library (the FMI adapter's cdylib) …
pub const ADAPTER_PACKAGE: &str = "wheel-rail-contact-fmu";
/// … and its library target, whose file the FMU carries renamed to the model identifier.
pub const ADAPTER_LIBRARY: &str = "wheel_rail_contact_fmu";

/// The cargo profile the shared library is built with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// What users get.
    Release,
    /// Cheaper to build: for tests that only need a loadable FMU.
    Dev,
}

/// The workspace root (the core crate's directory).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("packaging/ lives in the workspace").to_path_buf()
}

/// Builds the adapter's cdylib with `cargo build` and returns the path of the `.so`.
pub fn build_shared_library(profile: Profile) -> Result<PathBuf, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut command = Command::new(cargo);
    command.args(["build", "--lib", "-p", ADAPTER_PACKAGE, "--message-format=json-render-diagnostics"]);
    if profile == Profile::Release {
        command.arg("--release");
    }
    let output = command
        .current_dir(workspace_root())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err(format!("cargo build of the FMU's library failed ({})", output.status));
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let shared_library = stdout
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|message| message["reason"] == "compiler-artifact" && message["target"]["name"] == ADAPTER_LIBRARY)
        .flat_map(|message| message["filenames"].as_array().cloned().unwrap_or_default())
        .filter_map(|file| file.as_str().map(PathBuf::from))
        .find(|file| file.extension().is_some_and(|e| e == std::env::consts::DLL_EXTENSION));
    shared_library.ok_or_else(|| format!("cargo reported no shared library for {ADAPTER_LIBRARY}"))
}

/// The FMI platform folder of this machine (the FMU is built for the machine it is built on).
pub fn platform_folder() -> Result<&'static str, String> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64" | "aarch64") => Ok("linux64"),
        (os, arch) => Err(format!("no FMI 2.0 platform folder for {os}/{arch}")),
    }
}

/// Writes the `.fmu` (deflate, `/` separators): the model description, the shared library named
/// after the model identifier, and the generated documentation.
pub fn write_fmu(shared_library: &Path, fmu_path: &Path) -> Result<(), String> {
    let library = std::fs::read(shared_library).map_err(|e| format!("{}: {e}", shared_library.display()))?;
    let library_entry =
        format!("binaries/{}/{MODEL_IDENTIFIER}.{}", platform_folder()?, std::env::consts::DLL_EXTENSION);
    let documentation = crate::documentation::index_html();
    let entries: [(&str, &[u8]); 3] = [
        ("modelDescription.xml", MODEL_DESCRIPTION_XML.as_bytes()),
        (&library_entry, &library),
        ("documentation/index.html", documentation.as_bytes()),
    ];
    if let Some(folder) = fmu_path.parent() {
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    }
    let file = std::fs::File::create(fmu_path).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    let mut archive = zip::ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in entries {
        archive
            .start_file(name, options)
            .and_then(|()| Ok(archive.write_all(bytes)?))
            .map_err(|e| format!("{name}: {e}"))?;
    }
    archive.finish().map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    Ok(())
}

/// Builds the library and writes `<out_dir>/<modelIdentifier>.fmu`; returns its path.
pub fn package(profile: Profile, out_dir: &Path) -> Result<PathBuf, String> {
    let shared_library = build_shared_library(profile)?;
    let fmu_path = out_dir.join(format!("{MODEL_IDENTIFIER}.fmu"));
    write_fmu(&shared_library, &fmu_path)?;
    Ok(fmu_path)
}
