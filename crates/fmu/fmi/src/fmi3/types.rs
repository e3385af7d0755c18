//! The C types of the FMI 3.0 binary interface (fmi3PlatformTypes.h and
//! fmi3FunctionTypes.h). Unlike FMI 2.0, fmi3Boolean is a C99 `bool` (one byte) and the
//! logger callback is not variadic.

use crate::core::frontend::status_code;
use std::ffi::{c_char, c_void};

pub type Fmi3Instance = *mut c_void;
pub type Fmi3InstanceEnvironment = *mut c_void;
pub type Fmi3FmuState = *mut c_void;
pub type Fmi3ValueReference = u32;
pub type Fmi3Float32 = f32;
pub type Fmi3Float64 = f64;
pub type Fmi3Int8 = i8;
pub type Fmi3UInt8 = u8;
pub type Fmi3Int16 = i16;
pub type Fmi3UInt16 = u16;
pub type Fmi3Int32 = i32;
pub type Fmi3UInt32 = u32;
pub type Fmi3Int64 = i64;
pub type Fmi3UInt64 = u64;
/// C99 `bool` (one byte), handled as a byte so that a host passing 2..255 cannot cause
/// undefined behaviour: any nonzero byte reads as true, the FMU writes 0 or 1.
pub type Fmi3Boolean = u8;
pub type Fmi3Char = c_char;
pub type Fmi3String = *const c_char;
pub type Fmi3Byte = u8;
pub type Fmi3Binary = *const u8;
pub type Fmi3Clock = u8;

pub const FMI3_TRUE: Fmi3Boolean = 1;
pub const FMI3_FALSE: Fmi3Boolean = 0;

/// The C value of a Rust bool.
pub fn fmi3_bool(value: bool) -> Fmi3Boolean {
    if value { FMI3_TRUE } else { FMI3_FALSE }
}

status_code!(
    /// Return status of every function (FMI 3.0 has no Pending).
    Fmi3Status,
    "fmi3"
);

/// fmi3DependencyKind, written by fmi3GetVariableDependencies.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fmi3DependencyKind {
    Independent = 0,
    Constant = 1,
    Fixed = 2,
    Tunable = 3,
    Discrete = 4,
    Dependent = 5,
}

/// fmi3IntervalQualifier (clocks).
pub type Fmi3IntervalQualifier = std::ffi::c_int;
/// fmi3IntervalNotYetKnown.
pub const FMI3_INTERVAL_NOT_YET_KNOWN: Fmi3IntervalQualifier = 0;
/// fmi3IntervalUnchanged.
pub const FMI3_INTERVAL_UNCHANGED: Fmi3IntervalQualifier = 1;
/// fmi3IntervalChanged.
pub const FMI3_INTERVAL_CHANGED: Fmi3IntervalQualifier = 2;

/// fmi3LogMessageCallback: the message is passed as it is (no format expansion). The
/// host's callbacks are `C-unwind`: they may unwind (core::callback says what the FMU
/// does then).
pub type Fmi3LogMessageCallback =
    unsafe extern "C-unwind" fn(Fmi3InstanceEnvironment, Fmi3Status, Fmi3String, Fmi3String);

/// fmi3IntermediateUpdateCallback (Co-Simulation).
pub type Fmi3IntermediateUpdateCallback = unsafe extern "C-unwind" fn(
    Fmi3InstanceEnvironment,
    Fmi3Float64,
    Fmi3Boolean,
    Fmi3Boolean,
    Fmi3Boolean,
    Fmi3Boolean,
    *mut Fmi3Boolean,
    *mut Fmi3Float64,
);

/// fmi3ClockUpdateCallback (Scheduled Execution, not supported).
pub type Fmi3ClockUpdateCallback = unsafe extern "C-unwind" fn(Fmi3InstanceEnvironment);
/// fmi3LockPreemptionCallback and fmi3UnlockPreemptionCallback.
pub type Fmi3PreemptionCallback = unsafe extern "C-unwind" fn();

/// Opaque pointers the standard passes around untouched.
pub type Fmi3Opaque = *mut c_void;
