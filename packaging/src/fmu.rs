//! Builds the shared library for every FMI platform whose toolchain is present, checks each
//! binary, and writes the `.fmu` archive.
//!
//! | folder     | Rust target              | toolchain                                             |
//! |------------|--------------------------|-------------------------------------------------------|
//! | `linux64`  | `x86_64-unknown-linux-gnu` | cargo-zigbuild (+ zig) for glibc ≥ [`GLIBC_BASELINE`]; else plain cargo, this machine's glibc |
//! | `win64`    | `x86_64-pc-windows-gnu`  | `rustup target add x86_64-pc-windows-gnu` + mingw-w64's `x86_64-w64-mingw32-gcc` |
//!
//! Every binary is read back before it is zipped ([`check_library`]): it must export the 34
//! FMI 2.0 functions, a linux64 one built for the baseline must need no newer glibc symbol, and
//! a win64 one may import only DLLs that Windows ships (the C runtime and libgcc linked
//! statically), so nothing but the FMU itself has to be copied to a user's machine.

use std::collections::BTreeSet;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::documentation::BinaryNote;
use object::read::elf::{ElfFile64, FileHeader as _};
use object::Object as _;
use wheel_rail_contact_fmu::model_description::{MODEL_DESCRIPTION_XML, MODEL_IDENTIFIER};
use zip::write::SimpleFileOptions;

/// The cargo package whose cdylib is the FMU's binary: the FMI adapter.
pub const LIBRARY_PACKAGE: &str = "wheel-rail-contact-fmu";
/// The file stem cargo gives that cdylib (its `[lib] name`): `lib<stem>.so`, `<stem>.dll`; the
/// FMU carries it renamed to the model identifier.
pub const LIBRARY_STEM: &str = "wheel_rail_contact_fmu";
/// The oldest glibc the linux64 binary loads on: 2.28 is Debian 10, RHEL/Rocky 8, Ubuntu 18.10.
pub const GLIBC_BASELINE: (u32, u32) = (2, 28);

/// The FMI 2.0 Co-Simulation functions (`fmi2Functions.h`: 19 common, 6 Co-Simulation, plus the
/// FMU-state, derivative and status functions), all of which the binary must export.
pub const FMI2_FUNCTIONS: [&str; 34] = [
    "fmi2GetTypesPlatform",
    "fmi2GetVersion",
    "fmi2SetDebugLogging",
    "fmi2Instantiate",
    "fmi2FreeInstance",
    "fmi2SetupExperiment",
    "fmi2EnterInitializationMode",
    "fmi2ExitInitializationMode",
    "fmi2Terminate",
    "fmi2Reset",
    "fmi2GetReal",
    "fmi2GetInteger",
    "fmi2GetBoolean",
    "fmi2GetString",
    "fmi2SetReal",
    "fmi2SetInteger",
    "fmi2SetBoolean",
    "fmi2SetString",
    "fmi2GetFMUstate",
    "fmi2SetFMUstate",
    "fmi2FreeFMUstate",
    "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate",
    "fmi2DeSerializeFMUstate",
    "fmi2GetDirectionalDerivative",
    "fmi2SetRealInputDerivatives",
    "fmi2GetRealOutputDerivatives",
    "fmi2DoStep",
    "fmi2CancelStep",
    "fmi2GetStatus",
    "fmi2GetRealStatus",
    "fmi2GetIntegerStatus",
    "fmi2GetBooleanStatus",
    "fmi2GetStringStatus",
];

/// DLLs every 64-bit Windows (10 and later) ships, matched case-insensitively; `api-ms-win-*`
/// API sets are resolved by the loader itself.
const WINDOWS_SYSTEM_DLLS: [&str; 10] = [
    "kernel32.dll",
    "ntdll.dll",
    "advapi32.dll",
    "bcrypt.dll",
    "bcryptprimitives.dll",
    "userenv.dll",
    "ws2_32.dll",
    "msvcrt.dll",
    "ucrtbase.dll",
    "shell32.dll",
];

/// The cargo profile the shared library is built with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Profile {
    /// What users get.
    Release,
    /// Cheaper to build: for tests that only need a loadable FMU.
    Dev,
}

/// An FMI 2.0 platform the FMU can carry a binary for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Platform {
    Linux64,
    Win64,
}

impl Platform {
    /// Every platform, in the order `cargo fmu` builds them.
    pub const ALL: [Platform; 2] = [Platform::Linux64, Platform::Win64];

    /// The folder under `binaries/` (FMI 2.0.4, section 2.3).
    pub fn folder(self) -> &'static str {
        match self {
            Platform::Linux64 => "linux64",
            Platform::Win64 => "win64",
        }
    }

    /// The Rust target the binary is compiled for.
    pub fn rust_target(self) -> &'static str {
        match self {
            Platform::Linux64 => "x86_64-unknown-linux-gnu",
            Platform::Win64 => "x86_64-pc-windows-gnu",
        }
    }

    /// The shared library's file extension on this platform.
    pub fn extension(self) -> &'static str {
        match self {
            Platform::Linux64 => "so",
            Platform::Win64 => "dll",
        }
    }

    /// The platform of the machine running this program, if it is one of them.
    pub fn this_machine() -> Option<Platform> {
        match (std::env::consts::OS, std::env::consts::ARCH) {
            ("linux", "x86_64") => Some(Platform::Linux64),
            ("windows", "x86_64") => Some(Platform::Win64),
            _ => None,
        }
    }
}

/// How one platform's binary was produced.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Linkage {
    /// cargo-zigbuild against glibc [`GLIBC_BASELINE`].
    GlibcBaseline,
    /// Plain `cargo build` for this machine: the binary needs this machine's glibc or newer.
    ThisMachinesGlibc,
    /// Cross-built with mingw-w64, its runtime linked statically.
    Mingw,
}

/// A binary built for the FMU and what its check found.
#[derive(Debug, Clone)]
pub struct PlatformBinary {
    pub platform: Platform,
    pub library: PathBuf,
    pub linkage: Linkage,
    /// What the check read off the binary (one line).
    pub summary: String,
}

/// A platform left out, and why (with how to add it).
#[derive(Debug, Clone)]
pub struct Skipped {
    pub platform: Platform,
    pub reason: String,
}

/// Which platforms [`package`] builds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reach {
    /// Only this machine's platform, with plain cargo (tests that need a loadable FMU).
    ThisMachine,
    /// Every platform whose toolchain is present (`cargo fmu`).
    EveryToolchainPresent,
}

/// What [`package`] wrote.
#[derive(Debug, Clone)]
pub struct Packaged {
    pub fmu: PathBuf,
    pub binaries: Vec<PlatformBinary>,
    pub skipped: Vec<Skipped>,
}

/// The workspace root (the core crate's directory).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("packaging/ lives in the workspace").to_path_buf()
}

/// `cargo-zigbuild`: on `PATH`, or in the workspace's `.venv` where the test command installs it
/// from PyPI (with the `ziglang` package it runs zig from).
fn cargo_zigbuild() -> Option<PathBuf> {
    let on_path = std::env::var_os("PATH")
        .map(|path| std::env::split_paths(&path).map(|folder| folder.join("cargo-zigbuild")).collect::<Vec<_>>())
        .unwrap_or_default();
    on_path.into_iter().chain([workspace_root().join(".venv/bin/cargo-zigbuild")]).find(|file| file.is_file())
}

/// Installs cargo-zigbuild and zig into the workspace's `.venv` (`scripts/install-zigbuild`,
/// pinned versions from PyPI), saying so, and returns it; `None`, after saying why, when that is
/// not possible here (no Python venv, no network): the linux64 binary then needs this machine's
/// glibc, which the check and the FMU's documentation state.
fn install_zigbuild() -> Option<PathBuf> {
    let script = workspace_root().join("scripts/install-zigbuild");
    eprintln!(
        "cargo fmu: cargo-zigbuild is missing; installing it and zig from PyPI into .venv (once, \
         scripts/install-zigbuild) so that the linux64 binary loads on glibc ≥ {}.{}",
        GLIBC_BASELINE.0, GLIBC_BASELINE.1
    );
    match Command::new(&script).status() {
        Ok(status) if status.success() => cargo_zigbuild(),
        outcome => {
            let reason = match outcome {
                Ok(status) => format!("{} ended with {status}", script.display()),
                Err(error) => format!("{}: {error}", script.display()),
            };
            eprintln!("cargo fmu: {reason}; building linux64 with plain cargo for this machine's glibc instead");
            None
        }
    }
}

/// Whether `program` runs (`--version`).
fn runs(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Whether rustup has the standard library for `target` (the sysroot holds `lib/rustlib/<target>/lib`).
fn rust_target_installed(target: &str) -> bool {
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    let Ok(output) = Command::new(rustc).args(["--print", "sysroot"]).output() else { return false };
    let sysroot = PathBuf::from(String::from_utf8_lossy(&output.stdout).trim());
    sysroot.join("lib/rustlib").join(target).join("lib").is_dir()
}

/// Runs `command` (a cargo build with `--message-format=json-render-diagnostics`) and returns the
/// path of the cdylib it reports.
fn cargo_artifact(mut command: Command, platform: Platform) -> Result<PathBuf, String> {
    if command.get_current_dir().is_none() {
        command.current_dir(workspace_root());
    }
    let output = command.stderr(Stdio::inherit()).output().map_err(|e| format!("cannot run {command:?}: {e}"))?;
    if !output.status.success() {
        return Err(format!("{}: the build of the FMU's library failed ({})", platform.folder(), output.status));
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let shared_library = stdout
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|message| message["reason"] == "compiler-artifact" && message["target"]["name"] == LIBRARY_STEM)
        .flat_map(|message| message["filenames"].as_array().cloned().unwrap_or_default())
        .filter_map(|file| file.as_str().map(PathBuf::from))
        .find(|file| file.extension().is_some_and(|e| e == platform.extension()));
    shared_library.ok_or_else(|| format!("cargo reported no {} library for {LIBRARY_STEM}", platform.extension()))
}

fn cargo_build_arguments(command: &mut Command, profile: Profile) {
    command.args(["--lib", "-p", LIBRARY_PACKAGE, "--message-format=json-render-diagnostics"]);
    if profile == Profile::Release {
        command.arg("--release");
    }
}

/// Builds the cdylib for this machine with plain `cargo build` and returns its path.
pub fn build_shared_library(profile: Profile) -> Result<PathBuf, String> {
    let platform = Platform::this_machine()
        .ok_or_else(|| format!("no FMI 2.0 platform folder for {}/{}", std::env::consts::OS, std::env::consts::ARCH))?;
    let mut command = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    command.arg("build");
    cargo_build_arguments(&mut command, profile);
    cargo_artifact(command, platform)
}

/// Builds `platform`'s binary if its toolchain is here: `Ok(Err(skipped))` when it is not.
fn build_platform(platform: Platform, profile: Profile) -> Result<Result<(PathBuf, Linkage), Skipped>, String> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = platform.rust_target();
    let skipped = |how_to_add: String| {
        Ok(Err(Skipped { platform, reason: format!("its toolchain is missing; to add it: {how_to_add}") }))
    };
    match platform {
        Platform::Linux64 => {
            let native = Platform::this_machine() == Some(Platform::Linux64);
            let zigbuild = match cargo_zigbuild() {
                None if native => install_zigbuild(),
                found => found,
            };
            match zigbuild {
                Some(zigbuild) if native || rust_target_installed(target) => {
                    let mut command = Command::new(&zigbuild);
                    let manifest = workspace_root().join("Cargo.toml");
                    command.args([
                        "zigbuild",
                        "--target",
                        &format!("{target}.{}.{}", GLIBC_BASELINE.0, GLIBC_BASELINE.1),
                    ]);
                    command.arg("--manifest-path").arg(manifest);
                    // Run from the file system's root: zig names its folders relative to the
                    // working directory when it lives below it (the workspace's .venv), and
                    // cargo-zigbuild hands these include folders to build scripts (bindgen), which
                    // run elsewhere; below the root, every path is absolute.
                    let root = workspace_root().ancestors().last().map(Path::to_path_buf).unwrap_or_default();
                    command.current_dir(root);
                    if let Some(venv_bin) = zigbuild.parent().filter(|folder| folder.join("python3").is_file()) {
                        // The `ziglang` package lives beside cargo-zigbuild, in the same venv.
                        command.env("CARGO_ZIGBUILD_PYTHON_PATH", venv_bin.join("python3"));
                    }
                    cargo_build_arguments(&mut command, profile);
                    Ok(Ok((cargo_artifact(command, platform)?, Linkage::GlibcBaseline)))
                }
                _ if native => Ok(Ok((build_shared_library(profile)?, Linkage::ThisMachinesGlibc))),
                _ => skipped(format!("`pip install cargo-zigbuild` (brings zig) and `rustup target add {target}`")),
            }
        }
        Platform::Win64 => {
            let mut missing = Vec::new();
            if !rust_target_installed(target) {
                missing.push(format!("`rustup target add {target}`"));
            }
            if !runs("x86_64-w64-mingw32-gcc") {
                missing.push("mingw-w64 (`apt-get install gcc-mingw-w64-x86-64`)".to_owned());
            }
            if !missing.is_empty() {
                return skipped(missing.join(" and "));
            }
            let mut command = Command::new(cargo);
            command.args(["build", "--target", target]);
            cargo_build_arguments(&mut command, profile);
            Ok(Ok((cargo_artifact(command, platform)?, Linkage::Mingw)))
        }
    }
}

/// A glibc symbol version `GLIBC_x.y[.z]` as (x, y), ignoring GLIBC_PRIVATE.
fn glibc_version(name: &str) -> Option<(u32, u32)> {
    let mut numbers = name.strip_prefix("GLIBC_")?.split('.').map(|n| n.parse::<u32>().ok());
    Some((numbers.next()??, numbers.next().flatten().unwrap_or(0)))
}

/// The glibc versions an ELF shared library needs (its `.gnu.version_r` entries), newest last.
pub fn glibc_versions_needed(library: &[u8]) -> Result<BTreeSet<(u32, u32)>, String> {
    let file = ElfFile64::<object::Endianness>::parse(library).map_err(|e| format!("not an ELF64 file: {e}"))?;
    let (endian, data) = (file.endian(), file.data());
    let sections = file.elf_header().sections(endian, data).map_err(|e| e.to_string())?;
    let mut versions = BTreeSet::new();
    if let Some((mut needs, link)) = sections.gnu_verneed(endian, data).map_err(|e| e.to_string())? {
        let strings = sections.strings(endian, data, link).map_err(|e| e.to_string())?;
        while let Some((_need, mut auxiliaries)) = needs.next().map_err(|e| e.to_string())? {
            while let Some(auxiliary) = auxiliaries.next().map_err(|e| e.to_string())? {
                let name = auxiliary.name(endian, strings).map_err(|e| e.to_string())?;
                versions.extend(glibc_version(&String::from_utf8_lossy(name)));
            }
        }
    }
    Ok(versions)
}

/// The names of the functions a shared library exports (ELF dynamic symbols, PE export table).
pub fn exported_functions(library: &[u8]) -> Result<BTreeSet<String>, String> {
    let file = object::File::parse(library).map_err(|e| format!("not an object file: {e}"))?;
    file.exports()
        .map_err(|e| e.to_string())?
        .map(|export| match export.map_err(|e| e.to_string())?.name() {
            object::NameOrOrdinal::Name(name) => Ok(String::from_utf8_lossy(name).into_owned()),
            object::NameOrOrdinal::Ordinal(ordinal) => Ok(format!("#{ordinal}")),
        })
        .collect()
}

/// The DLLs a PE library imports, lower-cased.
pub fn imported_dlls(library: &[u8]) -> Result<BTreeSet<String>, String> {
    let file = object::File::parse(library).map_err(|e| format!("not an object file: {e}"))?;
    file.imports()
        .map_err(|e| e.to_string())?
        .map(|import| {
            import
                .map(|import| String::from_utf8_lossy(import.library()).to_ascii_lowercase())
                .map_err(|e| e.to_string())
        })
        .collect()
}

/// Checks a binary before it goes into the FMU (see the module docs); returns a one-line
/// summary of what was read off it.
pub fn check_library(platform: Platform, linkage: &Linkage, library: &[u8]) -> Result<String, String> {
    let exports = exported_functions(library)?;
    let missing: Vec<&str> = FMI2_FUNCTIONS.iter().copied().filter(|name| !exports.contains(*name)).collect();
    if !missing.is_empty() {
        return Err(format!("does not export {}", missing.join(", ")));
    }
    let extra: Vec<&String> = exports.iter().filter(|name| !FMI2_FUNCTIONS.contains(&name.as_str())).collect();
    if !extra.is_empty() {
        return Err(format!("exports more than the FMI functions: {extra:?}"));
    }
    let exports_line = format!("exports the {} fmi2 functions", FMI2_FUNCTIONS.len());
    match platform {
        Platform::Linux64 => {
            let newest = glibc_versions_needed(library)?.last().copied();
            let (major, minor) = newest.unwrap_or((0, 0));
            match linkage {
                Linkage::GlibcBaseline if newest > Some(GLIBC_BASELINE) => Err(format!(
                    "needs GLIBC_{major}.{minor}, newer than the baseline {}.{}",
                    GLIBC_BASELINE.0, GLIBC_BASELINE.1
                )),
                Linkage::GlibcBaseline => Ok(format!("{exports_line}, needs glibc ≥ {major}.{minor}")),
                _ => Ok(format!(
                    "{exports_line}, needs glibc ≥ {major}.{minor} (this machine's: the {}.{} baseline was not applied, \
                     `pip install cargo-zigbuild`, on PATH or in ./.venv, applies it)",
                    GLIBC_BASELINE.0, GLIBC_BASELINE.1
                )),
            }
        }
        Platform::Win64 => {
            let dlls = imported_dlls(library)?;
            let foreign: Vec<&String> = dlls
                .iter()
                .filter(|dll| !dll.starts_with("api-ms-win-") && !WINDOWS_SYSTEM_DLLS.contains(&dll.as_str()))
                .collect();
            if foreign.is_empty() {
                Ok(format!(
                    "{exports_line}, imports only Windows' own DLLs ({})",
                    dlls.into_iter().collect::<Vec<_>>().join(", ")
                ))
            } else {
                Err(format!("imports DLLs that Windows does not ship: {foreign:?}"))
            }
        }
    }
}

/// Writes the `.fmu` (deflate, `/` separators): the model description, each binary named after
/// the model identifier in its platform folder, and the generated documentation, which states
/// what these binaries need (the glibc read off the linux64 one).
pub fn write_fmu(binaries: &[PlatformBinary], fmu_path: &Path) -> Result<(), String> {
    let mut entries: Vec<(String, Vec<u8>)> =
        vec![("modelDescription.xml".to_owned(), MODEL_DESCRIPTION_XML.as_bytes().to_vec())];
    let mut notes = Vec::new();
    for binary in binaries {
        let (platform, library) = (binary.platform, &binary.library);
        let bytes = std::fs::read(library).map_err(|e| format!("{}: {e}", library.display()))?;
        notes.push(match platform {
            Platform::Linux64 => BinaryNote::Linux64 {
                glibc: glibc_versions_needed(&bytes)?.last().copied().unwrap_or((0, 0)),
                baseline_applied: binary.linkage == Linkage::GlibcBaseline,
            },
            Platform::Win64 => BinaryNote::Win64,
        });
        entries.push((format!("binaries/{}/{MODEL_IDENTIFIER}.{}", platform.folder(), platform.extension()), bytes));
    }
    entries.push(("documentation/index.html".to_owned(), crate::documentation::index_html(&notes).into_bytes()));
    if let Some(folder) = fmu_path.parent() {
        std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    }
    let file = std::fs::File::create(fmu_path).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    let mut archive = zip::ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, bytes) in &entries {
        archive
            .start_file(name.as_str(), options)
            .and_then(|()| Ok(archive.write_all(bytes)?))
            .map_err(|e| format!("{name}: {e}"))?;
    }
    archive.finish().map_err(|e| format!("{}: {e}", fmu_path.display()))?;
    Ok(())
}

/// Builds and checks the libraries `reach` asks for and writes `<out_dir>/<modelIdentifier>.fmu`.
pub fn package(profile: Profile, reach: Reach, out_dir: &Path) -> Result<Packaged, String> {
    let (mut binaries, mut skipped) = (Vec::new(), Vec::new());
    for platform in Platform::ALL {
        let built = match reach {
            Reach::ThisMachine if Platform::this_machine() == Some(platform) => {
                Ok((build_shared_library(profile)?, Linkage::ThisMachinesGlibc))
            }
            Reach::ThisMachine => continue,
            // A cross build that fails leaves its platform out, loudly, rather than the FMU
            // (scripts/test-platforms fails if one is missing); this machine's must build.
            Reach::EveryToolchainPresent => match build_platform(platform, profile) {
                Err(problem) if Platform::this_machine() != Some(platform) => {
                    Err(Skipped { platform, reason: format!("{problem} (cargo's messages above)") })
                }
                built => built?,
            },
        };
        match built {
            Ok((library, linkage)) => {
                let bytes = std::fs::read(&library).map_err(|e| format!("{}: {e}", library.display()))?;
                let summary = check_library(platform, &linkage, &bytes)
                    .map_err(|problem| format!("{} ({}): {problem}", platform.folder(), library.display()))?;
                binaries.push(PlatformBinary { platform, library, linkage, summary });
            }
            Err(skip) => skipped.push(skip),
        }
    }
    if binaries.is_empty() {
        return Err("no platform could be built".to_owned());
    }
    let fmu = out_dir.join(format!("{MODEL_IDENTIFIER}.fmu"));
    write_fmu(&binaries, &fmu)?;
    Ok(Packaged { fmu, binaries, skipped })
}
