//! An FMU binary's FMI 2.0 functions (all 44), looked up in the library that
//! [`crate::Library`] opened, as a C importer would, or linked into the test.
//! Statuses are kept as C ints so that a corrupt return value is reported, not
//! undefined behaviour in the importer.

use std::ffi::{c_char, c_int, c_uint, c_void};

pub type Component = *mut c_void;
pub type FmuState = *mut c_void;
pub type Status = c_int;
pub type Vr = c_uint;

pub const OK: Status = 0;
pub const WARNING: Status = 1;
pub const DISCARD: Status = 2;
pub const ERROR: Status = 3;
pub const FATAL: Status = 4;

/// Name of a status without the standard's prefix (the values are the same in
/// FMI 2.0 and FMI 3.0; 5 is fmi2Pending).
pub fn status_name(status: Status) -> String {
    match status {
        OK => "OK".into(),
        WARNING => "Warning".into(),
        DISCARD => "Discard".into(),
        ERROR => "Error".into(),
        FATAL => "Fatal".into(),
        5 => "Pending".into(),
        other => format!("status {other}"),
    }
}

/// fmi2CallbackFunctions with nullable members.
#[repr(C)]
pub struct CallbackFunctions {
    pub logger: *const c_void,
    pub allocate_memory: *const c_void,
    pub free_memory: *const c_void,
    pub step_finished: *const c_void,
    pub component_environment: *mut c_void,
}

/// fmi2EventInfo.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct EventInfo {
    pub new_discrete_states_needed: c_int,
    pub terminate_simulation: c_int,
    pub nominals_changed: c_int,
    pub states_changed: c_int,
    pub next_event_time_defined: c_int,
    pub next_event_time: f64,
}

type Str = *const c_char;

/// Declares `$name`: a binary with one function pointer per symbol, each looked up
/// with dlsym (a missing symbol refuses the whole binary) or filled with a function
/// linked into the test (`library` None: `crates/test/fmi-testing`). Shared by the
/// FMI 2.0 and FMI 3.0 binaries.
macro_rules! functions {
    ($(#[$doc:meta])* $name:ident { $($field:ident = $symbol:literal : fn($($arg:ty),*) $(-> $ret:ty)?;)* }) => {
        $(#[$doc])*
        #[allow(clippy::type_complexity)]
        pub struct $name {
            /// The library the functions were looked up in; None for functions
            /// linked into this process.
            pub library: Option<$crate::Library>,
            $(pub $field: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl $name {
            /// dlopen (RTLD_NOW | RTLD_LOCAL) and dlsym of every function.
            pub fn open(path: &std::path::Path) -> Result<$name, String> {
                let library = $crate::Library::open(path)
                    .map_err(|e| format!("dlopen {}: {e}", path.display()))?;
                let symbol = |name: &'static str| {
                    let name = std::ffi::CStr::from_bytes_with_nul(name.as_bytes())
                        .expect("a NUL-terminated name");
                    library.symbol(name)
                };
                Ok($name {
                    $($field: {
                        let p = symbol(concat!($symbol, "\0"));
                        if p.is_null() {
                            return Err(format!("symbol {} is missing", $symbol));
                        }
                        // SAFETY: the symbol has this C signature in the standard.
                        unsafe { std::mem::transmute::<*mut std::ffi::c_void, unsafe extern "C" fn($($arg),*) $(-> $ret)?>(p) }
                    },)*
                    // After every lookup: the library moves into the binary.
                    library: Some(library),
                })
            }
        }

        // The function pointers are plain code addresses; the standards let instances
        // of one binary be used from different threads (one thread per instance at a
        // time).
        unsafe impl Send for $name {}
        unsafe impl Sync for $name {}
    };
}
pub(crate) use functions;

functions! {
    /// The FMI 2.0 functions of one loaded binary (44).
    Binary {
    get_types_platform = "fmi2GetTypesPlatform": fn() -> Str;
    get_version = "fmi2GetVersion": fn() -> Str;
    set_debug_logging = "fmi2SetDebugLogging": fn(Component, c_int, usize, *const Str) -> Status;
    instantiate = "fmi2Instantiate": fn(Str, c_int, Str, Str, *const CallbackFunctions, c_int, c_int) -> Component;
    free_instance = "fmi2FreeInstance": fn(Component);
    setup_experiment = "fmi2SetupExperiment": fn(Component, c_int, f64, f64, c_int, f64) -> Status;
    enter_initialization_mode = "fmi2EnterInitializationMode": fn(Component) -> Status;
    exit_initialization_mode = "fmi2ExitInitializationMode": fn(Component) -> Status;
    terminate = "fmi2Terminate": fn(Component) -> Status;
    reset = "fmi2Reset": fn(Component) -> Status;
    get_real = "fmi2GetReal": fn(Component, *const Vr, usize, *mut f64) -> Status;
    get_integer = "fmi2GetInteger": fn(Component, *const Vr, usize, *mut c_int) -> Status;
    get_boolean = "fmi2GetBoolean": fn(Component, *const Vr, usize, *mut c_int) -> Status;
    get_string = "fmi2GetString": fn(Component, *const Vr, usize, *mut Str) -> Status;
    set_real = "fmi2SetReal": fn(Component, *const Vr, usize, *const f64) -> Status;
    set_integer = "fmi2SetInteger": fn(Component, *const Vr, usize, *const c_int) -> Status;
    set_boolean = "fmi2SetBoolean": fn(Component, *const Vr, usize, *const c_int) -> Status;
    set_string = "fmi2SetString": fn(Component, *const Vr, usize, *const Str) -> Status;
    get_fmu_state = "fmi2GetFMUstate": fn(Component, *mut FmuState) -> Status;
    set_fmu_state = "fmi2SetFMUstate": fn(Component, FmuState) -> Status;
    free_fmu_state = "fmi2FreeFMUstate": fn(Component, *mut FmuState) -> Status;
    serialized_size = "fmi2SerializedFMUstateSize": fn(Component, FmuState, *mut usize) -> Status;
    serialize = "fmi2SerializeFMUstate": fn(Component, FmuState, *mut c_char, usize) -> Status;
    deserialize = "fmi2DeSerializeFMUstate": fn(Component, *const c_char, usize, *mut FmuState) -> Status;
    get_directional_derivative = "fmi2GetDirectionalDerivative": fn(Component, *const Vr, usize, *const Vr, usize, *const f64, *mut f64) -> Status;
    enter_event_mode = "fmi2EnterEventMode": fn(Component) -> Status;
    new_discrete_states = "fmi2NewDiscreteStates": fn(Component, *mut EventInfo) -> Status;
    enter_continuous_time_mode = "fmi2EnterContinuousTimeMode": fn(Component) -> Status;
    completed_integrator_step = "fmi2CompletedIntegratorStep": fn(Component, c_int, *mut c_int, *mut c_int) -> Status;
    set_time = "fmi2SetTime": fn(Component, f64) -> Status;
    set_continuous_states = "fmi2SetContinuousStates": fn(Component, *const f64, usize) -> Status;
    get_derivatives = "fmi2GetDerivatives": fn(Component, *mut f64, usize) -> Status;
    get_event_indicators = "fmi2GetEventIndicators": fn(Component, *mut f64, usize) -> Status;
    get_continuous_states = "fmi2GetContinuousStates": fn(Component, *mut f64, usize) -> Status;
    get_nominals = "fmi2GetNominalsOfContinuousStates": fn(Component, *mut f64, usize) -> Status;
    set_real_input_derivatives = "fmi2SetRealInputDerivatives": fn(Component, *const Vr, usize, *const c_int, *const f64) -> Status;
    get_real_output_derivatives = "fmi2GetRealOutputDerivatives": fn(Component, *const Vr, usize, *const c_int, *mut f64) -> Status;
    do_step = "fmi2DoStep": fn(Component, f64, f64, c_int) -> Status;
    cancel_step = "fmi2CancelStep": fn(Component) -> Status;
    get_status = "fmi2GetStatus": fn(Component, c_int, *mut c_int) -> Status;
    get_real_status = "fmi2GetRealStatus": fn(Component, c_int, *mut f64) -> Status;
    get_integer_status = "fmi2GetIntegerStatus": fn(Component, c_int, *mut c_int) -> Status;
    get_boolean_status = "fmi2GetBooleanStatus": fn(Component, c_int, *mut c_int) -> Status;
    get_string_status = "fmi2GetStringStatus": fn(Component, c_int, *mut Str) -> Status;
    }
}
