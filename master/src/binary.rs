//! The FMU's binary loaded with libloading, its FMI 2.0 functions called through their C types
//! (declared here from `fmi2FunctionTypes.h`: the master must not share a line of Rust with the
//! adapter it tests), and one instance as a safe handle.

use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::path::Path;
use std::ptr::null_mut;
use std::sync::Mutex;

pub type Component = *mut c_void;
pub type FmuState = *mut c_void;

/// `fmi2Status`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Ok,
    Warning,
    Discard,
    Error,
    Fatal,
    Pending,
    Unknown(c_int),
}

impl From<c_int> for Status {
    fn from(status: c_int) -> Status {
        [Status::Ok, Status::Warning, Status::Discard, Status::Error, Status::Fatal, Status::Pending]
            .get(status as usize)
            .copied()
            .unwrap_or(Status::Unknown(status))
    }
}

/// The logger as the FMU calls it: C-variadic `(env, instance, status, category, format, ...)`
/// with format `"%s"` and one string. Declared with that string as a sixth named parameter,
/// since stable Rust cannot define a variadic function: x86-64 System V and Windows x64 pass the
/// arguments of a variadic call exactly as those of a non-variadic one (pointers only here).
type Logger = unsafe extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char, *const c_char);

/// `fmi2CallbackFunctions`.
#[repr(C)]
pub struct Callbacks {
    logger: Option<Logger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, c_int)>,
    component_environment: *mut c_void,
}

// The C runtime's allocator, which a master hands to the FMU (FMI 2.0.4, section 2.1.5).
extern "C" {
    fn calloc(count: usize, size: usize) -> *mut c_void;
    fn free(pointer: *mut c_void);
}

/// One logged message: (status, category, text).
pub type Message = (Status, String, String);

unsafe extern "C" fn log_message(
    environment: *mut c_void,
    _instance_name: *const c_char,
    status: c_int,
    category: *const c_char,
    format: *const c_char,
    text: *const c_char,
) {
    // SAFETY: the environment is the instance's `Mutex<Vec<Message>>`, alive as long as the
    // instance; the FMU passes NUL-terminated strings and, for format "%s", one more.
    let (messages, category, format) =
        unsafe { (&*environment.cast::<Mutex<Vec<Message>>>(), CStr::from_ptr(category), CStr::from_ptr(format)) };
    let text = if format == c"%s" {
        unsafe { CStr::from_ptr(text) }.to_string_lossy().into_owned()
    } else {
        format!("(format {format:?})")
    };
    messages.lock().unwrap().push((Status::from(status), category.to_string_lossy().into_owned(), text));
}

macro_rules! functions {
    ($($name:ident: fn($($argument:ty),*) $(-> $result:ty)?;)*) => {
        /// The FMI 2.0 functions this master calls, resolved from the binary.
        #[allow(non_snake_case)]
        pub struct Functions {
            $(pub $name: unsafe extern "C" fn($($argument),*) $(-> $result)?,)*
            _library: libloading::Library,
        }

        impl Functions {
            pub fn load(path: &Path) -> Result<Functions, String> {
                // SAFETY: loading the FMU runs no initialiser with requirements on the caller.
                let library = unsafe { libloading::Library::new(path) }.map_err(|e| format!("{}: {e}", path.display()))?;
                // SAFETY: each symbol is the FMI 2.0 function of that name and C type.
                unsafe {
                    Ok(Functions {
                        $($name: *library
                            .get(concat!(stringify!($name), "\0").as_bytes())
                            .map_err(|e| format!("{}: {e}", stringify!($name)))?,)*
                        _library: library,
                    })
                }
            }
        }
    };
}

functions! {
    fmi2GetVersion: fn() -> *const c_char;
    fmi2GetTypesPlatform: fn() -> *const c_char;
    fmi2Instantiate: fn(*const c_char, c_int, *const c_char, *const c_char, *const Callbacks, c_int, c_int) -> Component;
    fmi2FreeInstance: fn(Component);
    fmi2SetupExperiment: fn(Component, c_int, f64, f64, c_int, f64) -> c_int;
    fmi2EnterInitializationMode: fn(Component) -> c_int;
    fmi2ExitInitializationMode: fn(Component) -> c_int;
    fmi2Terminate: fn(Component) -> c_int;
    fmi2SetReal: fn(Component, *const c_uint, usize, *const f64) -> c_int;
    fmi2GetReal: fn(Component, *const c_uint, usize, *mut f64) -> c_int;
    fmi2SetInteger: fn(Component, *const c_uint, usize, *const c_int) -> c_int;
    fmi2DoStep: fn(Component, f64, f64, c_int) -> c_int;
    fmi2GetFMUstate: fn(Component, *mut FmuState) -> c_int;
    fmi2SetFMUstate: fn(Component, FmuState) -> c_int;
    fmi2FreeFMUstate: fn(Component, *mut FmuState) -> c_int;
    fmi2SerializedFMUstateSize: fn(Component, FmuState, *mut usize) -> c_int;
    fmi2SerializeFMUstate: fn(Component, FmuState, *mut u8, usize) -> c_int;
    fmi2DeSerializeFMUstate: fn(Component, *const u8, usize, *mut FmuState) -> c_int;
    fmi2GetDirectionalDerivative: fn(Component, *const c_uint, usize, *const c_uint, usize, *const f64, *mut f64) -> c_int;
}

impl Functions {
    /// `fmi2GetVersion` and `fmi2GetTypesPlatform`.
    pub fn version_and_types_platform(&self) -> (String, String) {
        // SAFETY: both return static NUL-terminated strings.
        unsafe {
            (
                CStr::from_ptr((self.fmi2GetVersion)()).to_string_lossy().into_owned(),
                CStr::from_ptr((self.fmi2GetTypesPlatform)()).to_string_lossy().into_owned(),
            )
        }
    }
}

/// One co-simulation instance (`fmi2CoSimulation`, not visible, debug logging off: errors are
/// still logged), freed on drop.
pub struct Instance<'a> {
    functions: &'a Functions,
    component: Component,
    _callbacks: Box<Callbacks>,
    messages: Box<Mutex<Vec<Message>>>,
}

impl<'a> Instance<'a> {
    /// fmi2Instantiate with `resource_location`, the URI of the FMU's `resources/`.
    pub fn new(
        functions: &'a Functions,
        name: &str,
        guid: &str,
        resource_location: &str,
    ) -> Result<Instance<'a>, String> {
        let messages = Box::new(Mutex::new(Vec::new()));
        let callbacks = Box::new(Callbacks {
            logger: Some(log_message),
            allocate_memory: Some(calloc),
            free_memory: Some(free),
            step_finished: None,
            component_environment: (&*messages as *const Mutex<Vec<Message>>).cast_mut().cast(),
        });
        let [name, guid, location] = [name, guid, resource_location].map(|text| CString::new(text).unwrap());
        const CO_SIMULATION: c_int = 1;
        // SAFETY: valid strings; the callbacks and the logger's environment outlive the instance.
        let component = unsafe {
            (functions.fmi2Instantiate)(
                name.as_ptr(),
                CO_SIMULATION,
                guid.as_ptr(),
                location.as_ptr(),
                &*callbacks,
                0,
                0,
            )
        };
        if component.is_null() {
            return Err(format!("fmi2Instantiate returned NULL: {:?}", messages.lock().unwrap()));
        }
        Ok(Instance { functions, component, _callbacks: callbacks, messages })
    }

    /// The messages logged since the last call, oldest first.
    pub fn take_messages(&self) -> Vec<Message> {
        std::mem::take(&mut *self.messages.lock().unwrap())
    }

    /// fmi2SetupExperiment (no tolerance, no stop time), fmi2EnterInitializationMode.
    pub fn enter_initialization(&self, start_time: f64) -> Status {
        // SAFETY: live instance.
        match Status::from(unsafe { (self.functions.fmi2SetupExperiment)(self.component, 0, 0.0, start_time, 0, 0.0) })
        {
            Status::Ok => Status::from(unsafe { (self.functions.fmi2EnterInitializationMode)(self.component) }),
            status => status,
        }
    }

    pub fn exit_initialization(&self) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions.fmi2ExitInitializationMode)(self.component) })
    }

    pub fn set_real(&self, references: &[u32], values: &[f64]) -> Status {
        assert_eq!(references.len(), values.len());
        // SAFETY: live instance, arrays of the given length.
        Status::from(unsafe {
            (self.functions.fmi2SetReal)(self.component, references.as_ptr(), references.len(), values.as_ptr())
        })
    }

    pub fn get_real(&self, references: &[u32]) -> (Status, Vec<f64>) {
        let mut values = vec![f64::NAN; references.len()];
        // SAFETY: live instance, arrays of the given length.
        let status = unsafe {
            (self.functions.fmi2GetReal)(self.component, references.as_ptr(), references.len(), values.as_mut_ptr())
        };
        (Status::from(status), values)
    }

    /// fmi2GetDirectionalDerivative: J·`seed` for the `unknowns` with respect to the `knowns`.
    pub fn directional_derivative(&self, unknowns: &[u32], knowns: &[u32], seed: &[f64]) -> (Status, Vec<f64>) {
        assert_eq!(knowns.len(), seed.len());
        let mut rates = vec![f64::NAN; unknowns.len()];
        // SAFETY: live instance, arrays of the given lengths.
        let status = unsafe {
            (self.functions.fmi2GetDirectionalDerivative)(
                self.component,
                unknowns.as_ptr(),
                unknowns.len(),
                knowns.as_ptr(),
                knowns.len(),
                seed.as_ptr(),
                rates.as_mut_ptr(),
            )
        };
        (Status::from(status), rates)
    }

    pub fn set_integer(&self, references: &[u32], values: &[i32]) -> Status {
        assert_eq!(references.len(), values.len());
        // SAFETY: live instance, arrays of the given length.
        Status::from(unsafe {
            (self.functions.fmi2SetInteger)(self.component, references.as_ptr(), references.len(), values.as_ptr())
        })
    }

    pub fn do_step(&self, time: f64, step: f64) -> Status {
        // SAFETY: live instance.
        Status::from(unsafe { (self.functions.fmi2DoStep)(self.component, time, step, 1) })
    }

    /// fmi2GetFMUstate, then fmi2SerializedFMUstateSize and fmi2SerializeFMUstate; the state is freed.
    pub fn serialized_state(&self) -> Result<Vec<u8>, String> {
        let mut state: FmuState = null_mut();
        let mut size = 0;
        // SAFETY: live instance; `state` is the FMU's until fmi2FreeFMUstate; `bytes` has `size` bytes.
        unsafe {
            check("fmi2GetFMUstate", (self.functions.fmi2GetFMUstate)(self.component, &mut state))?;
            check(
                "fmi2SerializedFMUstateSize",
                (self.functions.fmi2SerializedFMUstateSize)(self.component, state, &mut size),
            )?;
            let mut bytes = vec![0; size];
            check(
                "fmi2SerializeFMUstate",
                (self.functions.fmi2SerializeFMUstate)(self.component, state, bytes.as_mut_ptr(), size),
            )?;
            check("fmi2FreeFMUstate", (self.functions.fmi2FreeFMUstate)(self.component, &mut state))?;
            Ok(bytes)
        }
    }

    /// fmi2DeSerializeFMUstate, fmi2SetFMUstate, fmi2FreeFMUstate.
    pub fn restore_state(&self, bytes: &[u8]) -> Result<(), String> {
        let mut state: FmuState = null_mut();
        // SAFETY: live instance; `bytes` is a readable slice; the state is freed here.
        unsafe {
            check(
                "fmi2DeSerializeFMUstate",
                (self.functions.fmi2DeSerializeFMUstate)(self.component, bytes.as_ptr(), bytes.len(), &mut state),
            )?;
            check("fmi2SetFMUstate", (self.functions.fmi2SetFMUstate)(self.component, state))?;
            check("fmi2FreeFMUstate", (self.functions.fmi2FreeFMUstate)(self.component, &mut state))
        }
    }

    /// fmi2GetFMUstate.
    pub fn state(&self) -> Result<State<'_, 'a>, String> {
        let mut pointer: FmuState = null_mut();
        // SAFETY: live instance; the state is the FMU's until `State` drops it.
        check("fmi2GetFMUstate", unsafe { (self.functions.fmi2GetFMUstate)(self.component, &mut pointer) })?;
        Ok(State { instance: self, pointer })
    }
}

/// An FMU state of one instance (fmi2GetFMUstate), restorable any number of times and freed
/// (fmi2FreeFMUstate) when dropped: what a master needs to retry or probe a step.
pub struct State<'s, 'a> {
    instance: &'s Instance<'a>,
    pointer: FmuState,
}

impl State<'_, '_> {
    /// fmi2SetFMUstate: the instance as it was when the state was taken.
    pub fn restore(&self) -> Result<(), String> {
        let instance = self.instance;
        // SAFETY: live instance and a state it gave.
        check("fmi2SetFMUstate", unsafe { (instance.functions.fmi2SetFMUstate)(instance.component, self.pointer) })
    }
}

impl Drop for State<'_, '_> {
    fn drop(&mut self) {
        let instance = self.instance;
        // SAFETY: live instance (the borrow outlives the state), a state it gave, freed once.
        unsafe { (instance.functions.fmi2FreeFMUstate)(instance.component, &mut self.pointer) };
    }
}

fn check(call: &str, status: c_int) -> Result<(), String> {
    match Status::from(status) {
        Status::Ok => Ok(()),
        status => Err(format!("{call} returned {status:?}")),
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: live instance, freed once.
        unsafe {
            (self.functions.fmi2Terminate)(self.component);
            (self.functions.fmi2FreeInstance)(self.component);
        }
    }
}

/// An absolute path as a file URI (RFC 8089): `/` separators, a Windows drive after `file:///`,
/// every byte but the unreserved ones, `/` and the drive's `:` percent-encoded.
pub fn file_uri(path: &Path) -> String {
    let path = path.to_str().expect("a UTF-8 path").replace('\\', "/");
    let mut uri = String::from(if path.starts_with('/') { "file://" } else { "file:///" });
    for (index, byte) in path.bytes().enumerate() {
        match byte {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'/' => uri.push(byte as char),
            b':' if index == 1 => uri.push(':'),
            _ => uri.push_str(&format!("%{byte:02X}")),
        }
    }
    uri
}
