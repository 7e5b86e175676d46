//! A minimal FMI 2.0 Co-Simulation master over the packaged FMU's shared library, loaded at run
//! time (libloading) from the `.fmu` archive: what `cargo fmu` runs the default scene with.
//! (rust-fmi's importer does the same in the import test, `tests/import_with_rust_fmi.rs`, but it
//! needs libclang to build; `cargo fmu` must work with cargo alone.) The only `unsafe` code of
//! the packaging tool.
#![allow(unsafe_code)]

use std::ffi::CString;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::ptr::{null, null_mut};

use crate::fmu::platform_folder;
use libloading::Library;
use wheel_rail_contact_fmu::fmi2::*;
use wheel_rail_contact_fmu::model_description::{GUID, MODEL_IDENTIFIER};

type Instantiate = unsafe extern "C" fn(
    fmi2String,
    fmi2Type,
    fmi2String,
    fmi2String,
    *const fmi2CallbackFunctions,
    fmi2Boolean,
    fmi2Boolean,
) -> fmi2Component;
type Setup = unsafe extern "C" fn(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real) -> fmi2Status;
type Mode = unsafe extern "C" fn(fmi2Component) -> fmi2Status;
type SetReal = unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *const fmi2Real) -> fmi2Status;
type GetReal = unsafe extern "C" fn(fmi2Component, *const fmi2ValueReference, usize, *mut fmi2Real) -> fmi2Status;
type DoStep = unsafe extern "C" fn(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean) -> fmi2Status;
type Free = unsafe extern "C" fn(fmi2Component);

/// The FMU's library, extracted from the archive into a folder of its own.
pub struct LoadedFmu {
    library: Library,
    _folder: TempFolder,
}

/// A folder removed on drop.
struct TempFolder(PathBuf);

impl Drop for TempFolder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl LoadedFmu {
    /// Extracts `binaries/<platform>/<modelIdentifier>.<ext>` of `fmu_path` and loads it.
    pub fn open(fmu_path: &Path) -> Result<Self, String> {
        let entry = format!("binaries/{}/{MODEL_IDENTIFIER}.{}", platform_folder()?, std::env::consts::DLL_EXTENSION);
        let file = std::fs::File::open(fmu_path).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
        let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{}: {e}", fmu_path.display()))?;
        let mut bytes = Vec::new();
        archive
            .by_name(&entry)
            .map_err(|e| format!("{}: {entry}: {e}", fmu_path.display()))?
            .read_to_end(&mut bytes)
            .map_err(|e| format!("{entry}: {e}"))?;
        let folder = std::env::temp_dir().join(format!("wheel_rail_contact_fmu_{}", std::process::id()));
        std::fs::create_dir_all(&folder).map_err(|e| format!("{}: {e}", folder.display()))?;
        let folder = TempFolder(folder);
        let path = folder.0.join(entry.rsplit('/').next().unwrap_or("fmu"));
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        // SAFETY: the library is this project's FMU; loading runs no initialiser of its own.
        let library = unsafe { Library::new(&path) }.map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(Self { library, _folder: folder })
    }

    fn function<T: Copy>(&self, name: &str) -> Result<T, String> {
        // SAFETY: each name is looked up with its FMI 2.0 signature (the types above).
        unsafe { self.library.get::<T>(name.as_bytes()).map(|symbol| *symbol).map_err(|e| format!("{name}: {e}")) }
    }

    /// A co-simulation instance, initialised at its start values from time 0.
    pub fn instantiate(&self, name: &str) -> Result<Instance<'_>, String> {
        let callbacks = Box::new(fmi2CallbackFunctions {
            logger: None,
            allocateMemory: None,
            freeMemory: None,
            stepFinished: None,
            componentEnvironment: null_mut(),
        });
        let (name, guid) = (CString::new(name).map_err(|e| e.to_string())?, CString::new(GUID).unwrap());
        let instantiate: Instantiate = self.function("fmi2Instantiate")?;
        // SAFETY: valid NUL-terminated strings and callbacks that outlive the instance.
        let component = unsafe {
            instantiate(
                name.as_ptr(),
                fmi2Type_fmi2CoSimulation,
                guid.as_ptr(),
                null(),
                &*callbacks,
                fmi2False,
                fmi2False,
            )
        };
        if component.is_null() {
            return Err("fmi2Instantiate returned NULL".into());
        }
        let instance = Instance { fmu: self, component, _callbacks: callbacks };
        let setup: Setup = self.function("fmi2SetupExperiment")?;
        // SAFETY: a live instance.
        instance.check("fmi2SetupExperiment", unsafe { setup(component, fmi2False, 0.0, 0.0, fmi2False, 0.0) })?;
        for call in ["fmi2EnterInitializationMode", "fmi2ExitInitializationMode"] {
            let mode: Mode = self.function(call)?;
            // SAFETY: a live instance.
            instance.check(call, unsafe { mode(component) })?;
        }
        Ok(instance)
    }
}

/// One instance, terminated and freed on drop.
pub struct Instance<'a> {
    fmu: &'a LoadedFmu,
    component: fmi2Component,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Instance<'_> {
    fn check(&self, call: &str, status: fmi2Status) -> Result<(), String> {
        if status == fmi2Status_fmi2OK {
            Ok(())
        } else {
            Err(format!("{call} returned status {status}"))
        }
    }

    pub fn set_real(&self, references: &[u32], values: &[f64]) -> Result<(), String> {
        assert_eq!(references.len(), values.len());
        let set: SetReal = self.fmu.function("fmi2SetReal")?;
        // SAFETY: a live instance; arrays valid for their length.
        self.check("fmi2SetReal", unsafe {
            set(self.component, references.as_ptr(), references.len(), values.as_ptr())
        })
    }

    pub fn get_real(&self, references: &[u32]) -> Result<Vec<f64>, String> {
        let mut values = vec![0.0; references.len()];
        let get: GetReal = self.fmu.function("fmi2GetReal")?;
        // SAFETY: a live instance; arrays valid for their length.
        let status = unsafe { get(self.component, references.as_ptr(), references.len(), values.as_mut_ptr()) };
        self.check("fmi2GetReal", status).map(|()| values)
    }

    pub fn do_step(&self, time: f64, step: f64) -> Result<(), String> {
        let do_step: DoStep = self.fmu.function("fmi2DoStep")?;
        // SAFETY: a live instance.
        self.check("fmi2DoStep", unsafe { do_step(self.component, time, step, fmi2True) })
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        if let (Ok(terminate), Ok(free)) =
            (self.fmu.function::<Mode>("fmi2Terminate"), self.fmu.function::<Free>("fmi2FreeInstance"))
        {
            // SAFETY: a live instance, freed exactly once.
            unsafe {
                terminate(self.component);
                free(self.component);
            }
        }
    }
}
