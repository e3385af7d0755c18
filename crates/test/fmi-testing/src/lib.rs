//! A minimal FMI 2.0 host for Rust tests of an FMU binding: drives the layer's C-level
//! entry points (the functions the exported symbols forward to), addresses variables
//! by name and keeps the log.

use robofmu_fmi::core::Model;
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use std::ffi::{CStr, CString, c_char, c_void};
use std::sync::Mutex;

/// Log lines received: (status, category, message).
pub type Lines = Mutex<Vec<(Fmi2Status, String, String)>>;

extern "C" fn capture(
    env: Fmi2ComponentEnvironment,
    _name: Fmi2String,
    status: Fmi2Status,
    category: Fmi2String,
    message: Fmi2String,
) {
    // SAFETY: env is the &Lines the host passed; the strings come from the layer.
    let lines = unsafe { &*(env as *const Lines) };
    let text = |p: Fmi2String| {
        unsafe { CStr::from_ptr(p as *const c_char) }
            .to_string_lossy()
            .into_owned()
    };
    lines
        .lock()
        .unwrap()
        .push((status, text(category), text(message)));
}

/// fmi2CallbackAllocateMemory of the host: zeroed memory from the C heap.
pub extern "C-unwind" fn allocate(count: usize, size: usize) -> *mut c_void {
    // SAFETY: calloc accepts any sizes and returns null on failure.
    unsafe { libc::calloc(count, size) }
}

/// fmi2CallbackFreeMemory of the host.
///
/// # Safety
/// `pointer` is null or came from `allocate` and was not freed yet.
pub unsafe extern "C-unwind" fn free(pointer: *mut c_void) {
    // SAFETY: by the contract above.
    unsafe { libc::free(pointer) }
}

/// A raw fmi2Instantiate of `M` with the capturing logger: the component (null when
/// refused), its log and the callbacks, which must outlive the component.
pub fn instantiate<M: Model>(
    kind: i32,
    guid: &str,
    logging_on: bool,
) -> (Fmi2Component, Box<Lines>, Box<Fmi2CallbackFunctions>) {
    let lines: Box<Lines> = Box::new(Mutex::new(Vec::new()));
    // The non-variadic `capture` stands in for a variadic C logger: on x86-64 System V
    // both are called identically, and the layer never passes variadic arguments.
    let logger: Fmi2CallbackLogger = unsafe {
        std::mem::transmute::<
            extern "C" fn(Fmi2ComponentEnvironment, Fmi2String, Fmi2Status, Fmi2String, Fmi2String),
            Fmi2CallbackLogger,
        >(capture)
    };
    let functions = Box::new(Fmi2CallbackFunctions {
        logger: Some(logger),
        allocate_memory: Some(allocate),
        free_memory: Some(free),
        step_finished: None,
        component_environment: &*lines as *const Lines as *mut c_void,
    });
    let name = CString::new("test").unwrap();
    let guid = CString::new(guid).unwrap();
    let c = unsafe {
        api::instantiate::<M>(
            name.as_ptr(),
            kind,
            guid.as_ptr(),
            std::ptr::null(),
            &*functions,
            0,
            i32::from(logging_on),
        )
    };
    (c, lines, functions)
}

pub struct Host<M: Model> {
    pub c: Fmi2Component,
    pub lines: Box<Lines>,
    _functions: Box<Fmi2CallbackFunctions>,
    _model: std::marker::PhantomData<M>,
}

/// Value reference of the variable `name`.
pub fn vr<M: Model>(name: &str) -> u32 {
    robofmu_fmi::core::flatten::flatten(M::VARIABLES)
        .into_iter()
        .find(|v| v.name() == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
        .value_reference
}

/// The names of every Real output of `M`, in value-reference order.
pub fn real_outputs<M: Model>() -> Vec<String> {
    use robofmu_fmi::core::variables::{Causality, VariableType};
    robofmu_fmi::core::instance::sorted_table::<M>()
        .unwrap_or_else(|e| panic!("the variable table: {e}"))
        .into_iter()
        .filter(|v| v.causality == Causality::Output && v.variable_type() == VariableType::Real)
        .map(|v| v.name().into_owned())
        .collect()
}

impl<M: Model> Host<M> {
    /// Instantiated (kind FMI2_MODEL_EXCHANGE or FMI2_CO_SIMULATION), logging on.
    pub fn new(kind: i32) -> Self {
        Self::with_logging(kind, true)
    }

    /// Instantiated with loggingOn as given (errors are logged either way).
    pub fn with_logging(kind: i32, logging_on: bool) -> Self {
        let (c, lines, functions) = instantiate::<M>(kind, M::INFO.guid, logging_on);
        assert!(
            !c.is_null(),
            "instantiate failed: {:?}",
            lines.lock().unwrap()
        );
        Host {
            c,
            lines,
            _functions: functions,
            _model: std::marker::PhantomData,
        }
    }

    /// Enter and exit initialization mode; the status of the exit.
    pub fn initialize(&self) -> Fmi2Status {
        unsafe {
            assert_eq!(
                api::setup_experiment::<M>(self.c, 0, 0.0, 0.0, 0, 0.0),
                Fmi2Status::Ok
            );
            assert_eq!(api::enter_initialization_mode::<M>(self.c), Fmi2Status::Ok);
            api::exit_initialization_mode::<M>(self.c)
        }
    }

    pub fn real(&self, name: &str) -> f64 {
        let (vr, mut v) = (vr::<M>(name), 0.0);
        let s = unsafe { api::get_real::<M>(self.c, &vr, 1, &mut v) };
        assert_eq!(s, Fmi2Status::Ok, "get {name}: {}", self.last_message());
        v
    }

    pub fn integer(&self, name: &str) -> i32 {
        let (vr, mut v) = (vr::<M>(name), 0);
        let s = unsafe { api::get_integer::<M>(self.c, &vr, 1, &mut v) };
        assert_eq!(s, Fmi2Status::Ok, "get {name}: {}", self.last_message());
        v
    }

    /// Three components name[1..3].
    pub fn vector(&self, name: &str) -> [f64; 3] {
        [1, 2, 3].map(|i| self.real(&format!("{name}[{i}]")))
    }

    pub fn set_real(&self, name: &str, v: f64) -> Fmi2Status {
        self.set_real_at(vr::<M>(name), v)
    }

    /// fmi2GetReal of one value reference: the status and the value.
    pub fn real_at(&self, vr: u32) -> (Fmi2Status, f64) {
        let mut v = 0.0;
        let s = unsafe { api::get_real::<M>(self.c, &vr, 1, &mut v) };
        (s, v)
    }

    /// fmi2SetReal of one value reference.
    pub fn set_real_at(&self, vr: u32, v: f64) -> Fmi2Status {
        unsafe { api::set_real::<M>(self.c, &vr, 1, &v) }
    }

    pub fn set_vector(&self, name: &str, v: [f64; 3]) {
        for (i, x) in v.into_iter().enumerate() {
            let s = self.set_real(&format!("{name}[{}]", i + 1), x);
            assert_eq!(s, Fmi2Status::Ok, "set {name}: {}", self.last_message());
        }
    }

    /// fmi2SetRealInputDerivatives of one input: its derivative of `order`.
    pub fn set_input_derivative(&self, name: &str, order: i32, v: f64) -> Fmi2Status {
        let vr = vr::<M>(name);
        unsafe { api::set_real_input_derivatives::<M>(self.c, &vr, 1, &order, &v) }
    }

    pub fn set_integer(&self, name: &str, v: i32) -> Fmi2Status {
        let vr = vr::<M>(name);
        unsafe { api::set_integer::<M>(self.c, &vr, 1, &v) }
    }

    pub fn set_boolean(&self, name: &str, v: bool) -> Fmi2Status {
        let vr = vr::<M>(name);
        let v = if v { FMI2_TRUE } else { FMI2_FALSE };
        unsafe { api::set_boolean::<M>(self.c, &vr, 1, &v) }
    }

    pub fn step(&self, t: f64, h: f64) -> Fmi2Status {
        unsafe { api::do_step::<M>(self.c, t, h, FMI2_TRUE) }
    }

    pub fn states(&self) -> Vec<f64> {
        let mut x = vec![0.0; robofmu_fmi::core::declare::continuous_states(M::VARIABLES)];
        let s = unsafe { api::get_continuous_states::<M>(self.c, x.as_mut_ptr(), x.len()) };
        assert_eq!(s, Fmi2Status::Ok, "{}", self.last_message());
        x
    }

    pub fn set_states(&self, x: &[f64]) -> Fmi2Status {
        unsafe { api::set_continuous_states::<M>(self.c, x.as_ptr(), x.len()) }
    }

    /// Derivatives and the status of fmi2GetDerivatives.
    pub fn derivatives(&self) -> (Fmi2Status, Vec<f64>) {
        let mut dx = vec![0.0; robofmu_fmi::core::declare::continuous_states(M::VARIABLES)];
        let s = unsafe { api::get_derivatives::<M>(self.c, dx.as_mut_ptr(), dx.len()) };
        (s, dx)
    }

    pub fn event_indicators(&self) -> (Fmi2Status, Vec<f64>) {
        let mut z = vec![0.0; M::INFO.number_of_event_indicators];
        let s = unsafe { api::get_event_indicators::<M>(self.c, z.as_mut_ptr(), z.len()) };
        (s, z)
    }

    /// From the event mode after initialization into continuous-time mode.
    pub fn enter_continuous_time_mode(&self) {
        let mut info = Fmi2EventInfo {
            new_discrete_states_needed: 0,
            terminate_simulation: 0,
            nominals_of_continuous_states_changed: 0,
            values_of_continuous_states_changed: 0,
            next_event_time_defined: 0,
            next_event_time: 0.0,
        };
        unsafe {
            assert_eq!(
                api::new_discrete_states::<M>(self.c, &mut info),
                Fmi2Status::Ok
            );
            assert_eq!(api::enter_continuous_time_mode::<M>(self.c), Fmi2Status::Ok);
        }
    }

    /// An event at the current point: event mode, new discrete states, back.
    pub fn handle_event(&self) {
        unsafe {
            assert_eq!(api::enter_event_mode::<M>(self.c), Fmi2Status::Ok);
        }
        self.enter_continuous_time_mode();
    }

    pub fn directional(&self, unknown: &str, known: &str) -> f64 {
        let (u, k, seed, mut out) = (vr::<M>(unknown), vr::<M>(known), 1.0, 0.0);
        let s =
            unsafe { api::get_directional_derivative::<M>(self.c, &u, 1, &k, 1, &seed, &mut out) };
        assert_eq!(s, Fmi2Status::Ok, "{}", self.last_message());
        out
    }

    /// fmi2GetRealOutputDerivatives of the named outputs with their orders: the status
    /// and the values (still NaN where the layer wrote nothing).
    pub fn output_derivatives(&self, names: &[&str], orders: &[i32]) -> (Fmi2Status, Vec<f64>) {
        assert_eq!(names.len(), orders.len());
        let vrs: Vec<u32> = names.iter().map(|n| vr::<M>(n)).collect();
        let mut values = vec![f64::NAN; names.len()];
        let s = unsafe {
            api::get_real_output_derivatives::<M>(
                self.c,
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_mut_ptr(),
            )
        };
        (s, values)
    }

    /// Serialized bytes of the current FMU state.
    pub fn serialize(&self) -> Vec<u8> {
        unsafe {
            let mut state: Fmi2FmuState = std::ptr::null_mut();
            assert_eq!(api::get_fmu_state::<M>(self.c, &mut state), Fmi2Status::Ok);
            let mut size = 0;
            assert_eq!(
                api::serialized_fmu_state_size::<M>(self.c, state, &mut size),
                Fmi2Status::Ok
            );
            let mut bytes = vec![0u8; size];
            assert_eq!(
                api::serialize_fmu_state::<M>(self.c, state, bytes.as_mut_ptr() as _, size),
                Fmi2Status::Ok
            );
            assert_eq!(api::free_fmu_state::<M>(self.c, &mut state), Fmi2Status::Ok);
            bytes
        }
    }

    /// Restores an FMU state from serialized bytes.
    pub fn restore(&self, bytes: &[u8]) -> Fmi2Status {
        unsafe {
            let mut state: Fmi2FmuState = std::ptr::null_mut();
            let s = api::de_serialize_fmu_state::<M>(
                self.c,
                bytes.as_ptr() as _,
                bytes.len(),
                &mut state,
            );
            if s != Fmi2Status::Ok {
                return s;
            }
            let s = api::set_fmu_state::<M>(self.c, state);
            api::free_fmu_state::<M>(self.c, &mut state);
            s
        }
    }

    pub fn terminated(&self) -> bool {
        let mut v = FMI2_FALSE;
        let s = unsafe { api::get_boolean_status::<M>(self.c, FMI2_TERMINATED, &mut v) };
        assert_eq!(s, Fmi2Status::Ok);
        v == FMI2_TRUE
    }

    pub fn last_successful_time(&self) -> f64 {
        let mut v = f64::NAN;
        let s = unsafe { api::get_real_status::<M>(self.c, FMI2_LAST_SUCCESSFUL_TIME, &mut v) };
        assert_eq!(s, Fmi2Status::Ok);
        v
    }

    pub fn last_message(&self) -> String {
        let lines = self.lines.lock().unwrap();
        lines.last().map(|l| l.2.clone()).unwrap_or_default()
    }

    /// Messages logged with `status`.
    pub fn messages(&self, status: Fmi2Status) -> Vec<String> {
        let lines = self.lines.lock().unwrap();
        lines
            .iter()
            .filter(|l| l.0 == status)
            .map(|l| l.2.clone())
            .collect()
    }
}

impl<M: Model> Drop for Host<M> {
    fn drop(&mut self) {
        unsafe { api::free_instance::<M>(self.c) };
    }
}
