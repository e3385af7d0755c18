//! The calls the re-entrancy, reuse, thread and forged-state probes make, once for
//! both standards: [`Api`] is one packaged FMU (a model in one standard) as a
//! Co-Simulation importer sees it, implemented over the dlopen'd FMI 2.0 functions
//! ([`Api2`]) and FMI 3.0 functions ([`Api3`]).
//!
//! Handles are passed to the FMU as they are, dead or foreign ones included: the FMU
//! must refuse those (that is what the probes test), so the functions taking them are
//! safe to call (clippy's `not_unsafe_ptr_arg_deref` does not apply).
#![allow(clippy::not_unsafe_ptr_arg_deref)]

use super::host::Host;
use crate::binary::{Binary, Status};
use crate::description::{Description, VarType};
use crate::fmi3::binary::Binary3;
use crate::fmu::Fmu;
use robofmu_fmi_host::callbacks::c_string;
use robofmu_fmi_host::instance::instantiate3;
use std::ffi::c_void;

/// An instance or FMU state handle as the importer holds it.
pub type Handle = *mut c_void;

/// One packaged FMU in one standard, driven as Co-Simulation.
pub trait Api: Sync {
    /// "Model (FMI x.0)".
    fn name(&self) -> String;
    fn description(&self) -> &Description;
    /// The standard's name of DoStep (as logCalls spells it).
    fn do_step_name(&self) -> &'static str;
    /// A Co-Simulation instance with logging on and `host`'s logger.
    fn instantiate(&self, host: &Host) -> Handle;
    fn free(&self, h: Handle);
    /// Logging on with every category (logCalls included).
    fn log_all(&self, h: Handle) -> Status;
    /// Setup (FMI 2.0) and Initialization Mode from `start`, with the tolerance
    /// defined when Some.
    fn enter_initialization_with(&self, h: Handle, tolerance: Option<f64>, start: f64) -> Status;
    /// Setup (FMI 2.0) and Initialization Mode from `start`, no tolerance.
    fn enter_initialization(&self, h: Handle, start: f64) -> Status {
        self.enter_initialization_with(h, None, start)
    }
    fn exit_initialization(&self, h: Handle) -> Status;
    /// Initialization Mode from `start`, then exit.
    fn initialize(&self, h: Handle, start: f64) -> Status {
        match self.enter_initialization(h, start) {
            crate::binary::OK => self.exit_initialization(h),
            s => s,
        }
    }
    fn do_step(&self, h: Handle, t: f64, dt: f64) -> Status;
    fn reset(&self, h: Handle) -> Status;
    fn set_real(&self, h: Handle, vr: u32, x: f64) -> Status;
    fn get_real(&self, h: Handle, vr: u32) -> (Status, f64);
    fn get_state(&self, h: Handle, state: &mut Handle) -> Status;
    fn set_state(&self, h: Handle, state: Handle) -> Status;
    fn free_state(&self, h: Handle, state: &mut Handle) -> Status;
    /// SerializedFMUStateSize and SerializeFMUState; Err: the failing status.
    fn serialize(&self, h: Handle, state: Handle) -> Result<Vec<u8>, Status>;
    fn deserialize(&self, h: Handle, bytes: &[u8]) -> (Status, Handle);
    /// FMI 3.0 only: a Co-Simulation instance with `host`'s intermediateUpdate
    /// callback (None in FMI 2.0, which has none).
    fn instantiate_with_update(&self, host: &Host) -> Option<Handle>;
    /// FMI 3.0 only: a Co-Simulation instance given requiredIntermediateVariables
    /// (`vrs`, `n`) as they are (None in FMI 2.0).
    fn instantiate_required(&self, host: &Host, vrs: *const u32, n: usize) -> Option<Handle>;
    /// The FMI 3.0 functions (None in FMI 2.0).
    fn fmi3(&self) -> Option<&Binary3> {
        None
    }
}

/// The first Real parameter or input with a start value, and that value (of its
/// first element): what the probes set (every element, for an FMI 3.0 array).
pub fn settable_real(d: &Description) -> (u32, f64) {
    d.of_type(VarType::Real)
        .filter(|v| v.is_settable())
        .find_map(|v| {
            Some((
                v.vr,
                v.start.as_ref()?.split_whitespace().next()?.parse().ok()?,
            ))
        })
        .unwrap_or_else(|| panic!("{} has no settable Real with a start value", d.model_name))
}

/// The number of elements of variable `vr` (1 when unknown).
fn size(d: &Description, vr: u32) -> usize {
    d.variables
        .iter()
        .find(|v| v.vr == vr)
        .map_or(1, |v| v.size.max(1))
}

/// The FMI 2.0 functions of a loaded FMU.
pub struct Api2<'a> {
    pub fmu: &'a Fmu,
    pub binary: &'a Binary,
}

/// The FMI 3.0 functions of a loaded FMU.
pub struct Api3<'a> {
    pub fmu: &'a Fmu,
    pub binary: &'a Binary3,
}

/// Serialized size, then the bytes, through the standard's two functions.
fn serialize_with(
    size: impl FnOnce(&mut usize) -> Status,
    write: impl FnOnce(&mut [u8]) -> Status,
) -> Result<Vec<u8>, Status> {
    let mut n = 0;
    let s = size(&mut n);
    if s != crate::binary::OK {
        return Err(s);
    }
    let mut bytes = vec![0u8; n];
    match write(&mut bytes) {
        crate::binary::OK => Ok(bytes),
        s => Err(s),
    }
}

// SAFETY (every unsafe block below): the functions of the loaded binary with
// arguments valid for the call; a handle may be dead or foreign, which the FMU must
// refuse (that is what the probes test).
/// The three FMU-state calls, the same text for both standards (same field names,
/// same argument order).
macro_rules! fmu_state_calls {
    () => {
        fn get_state(&self, h: Handle, state: &mut Handle) -> Status {
            unsafe { (self.binary.get_fmu_state)(h, state) }
        }
        fn set_state(&self, h: Handle, state: Handle) -> Status {
            unsafe { (self.binary.set_fmu_state)(h, state) }
        }
        fn free_state(&self, h: Handle, state: &mut Handle) -> Status {
            unsafe { (self.binary.free_fmu_state)(h, state) }
        }
    };
}

impl Api for Api2<'_> {
    fn name(&self) -> String {
        format!("{} (FMI 2.0)", self.fmu.name())
    }
    fn description(&self) -> &Description {
        &self.fmu.description
    }
    fn do_step_name(&self) -> &'static str {
        "fmi2DoStep"
    }
    fn instantiate(&self, host: &Host) -> Handle {
        let (name, guid) = (c_string("reentry"), c_string(&self.fmu.description.guid));
        unsafe {
            (self.binary.instantiate)(
                name.as_ptr(),
                1,
                guid.as_ptr(),
                std::ptr::null(),
                &host.callbacks,
                0,
                1,
            )
        }
    }
    fn free(&self, h: Handle) {
        unsafe { (self.binary.free_instance)(h) }
    }
    fn log_all(&self, h: Handle) -> Status {
        unsafe { (self.binary.set_debug_logging)(h, 1, 0, std::ptr::null()) }
    }
    fn enter_initialization_with(&self, h: Handle, tolerance: Option<f64>, start: f64) -> Status {
        let b = self.binary;
        let (defined, tolerance) = (i32::from(tolerance.is_some()), tolerance.unwrap_or(0.0));
        unsafe {
            match (b.setup_experiment)(h, defined, tolerance, start, 0, 0.0) {
                crate::binary::OK => (b.enter_initialization_mode)(h),
                s => s,
            }
        }
    }
    fn exit_initialization(&self, h: Handle) -> Status {
        unsafe { (self.binary.exit_initialization_mode)(h) }
    }
    fn do_step(&self, h: Handle, t: f64, dt: f64) -> Status {
        unsafe { (self.binary.do_step)(h, t, dt, 1) }
    }
    fn reset(&self, h: Handle) -> Status {
        unsafe { (self.binary.reset)(h) }
    }
    fn set_real(&self, h: Handle, vr: u32, x: f64) -> Status {
        unsafe { (self.binary.set_real)(h, &vr, 1, &x) }
    }
    fn get_real(&self, h: Handle, vr: u32) -> (Status, f64) {
        let mut x = f64::NAN;
        let s = unsafe { (self.binary.get_real)(h, &vr, 1, &mut x) };
        (s, x)
    }
    fmu_state_calls!();
    fn serialize(&self, h: Handle, state: Handle) -> Result<Vec<u8>, Status> {
        let b = self.binary;
        serialize_with(
            |n| unsafe { (b.serialized_size)(h, state, n) },
            |out| unsafe { (b.serialize)(h, state, out.as_mut_ptr() as *mut _, out.len()) },
        )
    }
    fn deserialize(&self, h: Handle, bytes: &[u8]) -> (Status, Handle) {
        let mut state = std::ptr::null_mut();
        let p = bytes.as_ptr() as *const _;
        let s = unsafe { (self.binary.deserialize)(h, p, bytes.len(), &mut state) };
        (s, state)
    }
    fn instantiate_with_update(&self, _host: &Host) -> Option<Handle> {
        None
    }
    fn instantiate_required(&self, _host: &Host, _vrs: *const u32, _n: usize) -> Option<Handle> {
        None
    }
}

impl Api3<'_> {
    fn instantiate_cs(
        &self,
        host: &Host,
        update: *const c_void,
        vrs: *const u32,
        n: usize,
    ) -> Handle {
        let (name, token) = (c_string("reentry"), c_string(&self.fmu.description.guid));
        unsafe {
            (self.binary.instantiate_cs)(
                name.as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                0,
                1,
                0,
                0,
                vrs,
                n,
                host.environment(),
                super::host::logger3(),
                update,
            )
        }
    }
}

impl Api for Api3<'_> {
    fn name(&self) -> String {
        format!("{} (FMI 3.0)", self.fmu.name())
    }
    fn description(&self) -> &Description {
        &self.fmu.description
    }
    fn do_step_name(&self) -> &'static str {
        "fmi3DoStep"
    }
    fn instantiate(&self, host: &Host) -> Handle {
        self.instantiate_cs(host, std::ptr::null(), std::ptr::null(), 0)
    }
    fn free(&self, h: Handle) {
        unsafe { (self.binary.free_instance)(h) }
    }
    fn log_all(&self, h: Handle) -> Status {
        unsafe { (self.binary.set_debug_logging)(h, 1, 0, std::ptr::null()) }
    }
    fn enter_initialization_with(&self, h: Handle, tolerance: Option<f64>, start: f64) -> Status {
        let (defined, tolerance) = (u8::from(tolerance.is_some()), tolerance.unwrap_or(0.0));
        unsafe { (self.binary.enter_initialization_mode)(h, defined, tolerance, start, 0, 0.0) }
    }
    fn exit_initialization(&self, h: Handle) -> Status {
        unsafe { (self.binary.exit_initialization_mode)(h) }
    }
    fn do_step(&self, h: Handle, t: f64, dt: f64) -> Status {
        let (mut event, mut terminate, mut early, mut last) = (0u8, 0u8, 0u8, 0.0);
        unsafe {
            (self.binary.do_step)(
                h,
                t,
                dt,
                0,
                &mut event,
                &mut terminate,
                &mut early,
                &mut last,
            )
        }
    }
    fn reset(&self, h: Handle) -> Status {
        unsafe { (self.binary.reset)(h) }
    }
    fn set_real(&self, h: Handle, vr: u32, x: f64) -> Status {
        let values = vec![x; size(&self.fmu.description, vr)];
        unsafe { (self.binary.set_float64)(h, &vr, 1, values.as_ptr(), values.len()) }
    }
    fn get_real(&self, h: Handle, vr: u32) -> (Status, f64) {
        let mut values = vec![f64::NAN; size(&self.fmu.description, vr)];
        let n = values.len();
        let s = unsafe { (self.binary.get_float64)(h, &vr, 1, values.as_mut_ptr(), n) };
        (s, values[0])
    }
    fmu_state_calls!();
    fn serialize(&self, h: Handle, state: Handle) -> Result<Vec<u8>, Status> {
        let b = self.binary;
        serialize_with(
            |n| unsafe { (b.serialized_size)(h, state, n) },
            |out| unsafe { (b.serialize)(h, state, out.as_mut_ptr(), out.len()) },
        )
    }
    fn deserialize(&self, h: Handle, bytes: &[u8]) -> (Status, Handle) {
        let mut state = std::ptr::null_mut();
        let s = unsafe { (self.binary.deserialize)(h, bytes.as_ptr(), bytes.len(), &mut state) };
        (s, state)
    }
    fn instantiate_with_update(&self, host: &Host) -> Option<Handle> {
        let update = super::host::intermediate_update();
        Some(self.instantiate_cs(host, update, std::ptr::null(), 0))
    }
    fn instantiate_required(&self, host: &Host, vrs: *const u32, n: usize) -> Option<Handle> {
        Some(self.instantiate_cs(host, std::ptr::null(), vrs, n))
    }
    fn fmi3(&self) -> Option<&Binary3> {
        Some(self.binary)
    }
}

/// An FMI 3.0 Model Exchange instance with `host`'s logger.
pub fn instantiate_me(binary: &Binary3, d: &Description, host: &Host) -> Handle {
    let me = robofmu_fmi_host::instance::Interface3::ModelExchange;
    let (env, logger) = (host.environment(), super::host::logger3());
    instantiate3(
        binary,
        me,
        "reentry",
        &d.guid,
        env,
        logger,
        std::ptr::null(),
    )
}
