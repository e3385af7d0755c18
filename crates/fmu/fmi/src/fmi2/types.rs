//! The C types of the FMI 2.0 binary interface (fmi2TypesPlatform.h and
//! fmi2FunctionTypes.h), with the exact widths of the "default" platform.

use crate::core::frontend::status_code;
use std::ffi::{c_char, c_int, c_uint, c_void};

pub type Fmi2Component = *mut c_void;
pub type Fmi2ComponentEnvironment = *mut c_void;
pub type Fmi2FmuState = *mut c_void;
pub type Fmi2ValueReference = c_uint;
pub type Fmi2Real = f64;
pub type Fmi2Integer = c_int;
/// A C int: 0 is false, anything else true.
pub type Fmi2Boolean = c_int;
pub type Fmi2Char = c_char;
pub type Fmi2String = *const c_char;
pub type Fmi2Byte = c_char;

pub const FMI2_TRUE: Fmi2Boolean = 1;
pub const FMI2_FALSE: Fmi2Boolean = 0;

status_code!(
    /// Return status of every function.
    Fmi2Status,
    "fmi2",
    Pending = 5
);

/// fmi2Type as passed to fmi2Instantiate (received as a C int and checked).
pub const FMI2_MODEL_EXCHANGE: c_int = 0;
pub const FMI2_CO_SIMULATION: c_int = 1;

/// fmi2StatusKind values (received as a C int and checked).
pub const FMI2_DO_STEP_STATUS: c_int = 0;
pub const FMI2_PENDING_STATUS: c_int = 1;
pub const FMI2_LAST_SUCCESSFUL_TIME: c_int = 2;
pub const FMI2_TERMINATED: c_int = 3;

/// fmi2CallbackLogger: variadic in C; we always pass a preformatted message with '%'
/// escaped, so no format arguments follow. The host's callbacks are `C-unwind`: they
/// may unwind (core::callback says what the FMU does then).
pub type Fmi2CallbackLogger = unsafe extern "C-unwind" fn(
    Fmi2ComponentEnvironment,
    Fmi2String,
    Fmi2Status,
    Fmi2String,
    Fmi2String,
    ...
);
pub type Fmi2CallbackAllocateMemory = unsafe extern "C-unwind" fn(usize, usize) -> *mut c_void;
pub type Fmi2CallbackFreeMemory = unsafe extern "C-unwind" fn(*mut c_void);
pub type Fmi2StepFinished = unsafe extern "C-unwind" fn(Fmi2ComponentEnvironment, Fmi2Status);

/// fmi2CallbackFunctions. Function pointers are nullable (Option) so that a null
/// pointer from the host is representable and can be rejected.
#[repr(C)]
pub struct Fmi2CallbackFunctions {
    pub logger: Option<Fmi2CallbackLogger>,
    pub allocate_memory: Option<Fmi2CallbackAllocateMemory>,
    pub free_memory: Option<Fmi2CallbackFreeMemory>,
    pub step_finished: Option<Fmi2StepFinished>,
    pub component_environment: Fmi2ComponentEnvironment,
}

/// fmi2EventInfo, filled by fmi2NewDiscreteStates.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct Fmi2EventInfo {
    pub new_discrete_states_needed: Fmi2Boolean,
    pub terminate_simulation: Fmi2Boolean,
    pub nominals_of_continuous_states_changed: Fmi2Boolean,
    pub values_of_continuous_states_changed: Fmi2Boolean,
    pub next_event_time_defined: Fmi2Boolean,
    pub next_event_time: Fmi2Real,
}
