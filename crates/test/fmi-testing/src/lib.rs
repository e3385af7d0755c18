//! The FMU crates' Rust tests' host: the one test host (`robofmu_fmi_host`) with its
//! FMI 2.0 function table filled with a model linked into the test ([`table`])
//! instead of looked up in a loaded library; its callbacks keep every log line.
//! [`Host`] adds calls that address variables by name.

use robofmu_fmi::core::Model;
use robofmu_fmi::fmi2::types::{FMI2_LAST_SUCCESSFUL_TIME, FMI2_TERMINATED, Fmi2Status};
use robofmu_fmi_host::fmi2::{self, EventInfo};
use std::ffi::c_int;

pub use robofmu_fmi_host::callbacks::{Callbacks, Environment, Keep, Line, Log};
pub use robofmu_fmi_host::instance::Fmi2Instance;

pub mod table;

/// fmi2Instantiate of `M` (fmi2Type `kind`, any C int) named "test", with every
/// callback and the logger keeping every line; the environment with its log when
/// refused.
pub fn instantiate<M: Model>(
    kind: c_int,
    guid: &str,
    logging_on: bool,
) -> Result<Fmi2Instance<'static>, Environment> {
    let env = Environment::keeping(Callbacks::ALL, Keep::Everything);
    Fmi2Instance::instantiate(table::binary::<M>(), "test", kind, guid, env, logging_on)
}

/// The layer's status of a C status the table returned.
pub fn status(s: fmi2::Status) -> Fmi2Status {
    match s {
        fmi2::OK => Fmi2Status::Ok,
        fmi2::WARNING => Fmi2Status::Warning,
        fmi2::DISCARD => Fmi2Status::Discard,
        fmi2::ERROR => Fmi2Status::Error,
        fmi2::FATAL => Fmi2Status::Fatal,
        5 => Fmi2Status::Pending,
        other => panic!("the layer returned status {other}, none of fmi2Status"),
    }
}

/// An instance of `M` in the test host (its calls reached through `Deref`), with
/// calls by variable name; freed on drop.
pub struct Host<M: Model> {
    instance: Fmi2Instance<'static>,
    _model: std::marker::PhantomData<M>,
}

impl<M: Model> std::ops::Deref for Host<M> {
    type Target = Fmi2Instance<'static>;
    fn deref(&self) -> &Fmi2Instance<'static> {
        &self.instance
    }
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
    pub fn new(kind: c_int) -> Self {
        Self::with_logging(kind, true)
    }

    /// Instantiated with loggingOn as given (errors are logged either way).
    pub fn with_logging(kind: c_int, logging_on: bool) -> Self {
        let instance = instantiate::<M>(kind, M::INFO.guid, logging_on)
            .unwrap_or_else(|env| panic!("instantiate failed: {}", env.take_log()));
        Host {
            instance,
            _model: std::marker::PhantomData,
        }
    }

    /// Enter and exit initialization mode; the status of the exit.
    pub fn initialize(&self) -> Fmi2Status {
        let entered = self.instance.enter_initialization(0.0, None);
        entered.unwrap_or_else(|e| panic!("{e}"));
        // SAFETY: a live component.
        status(unsafe { (self.binary.exit_initialization_mode)(self.c) })
    }

    pub fn real(&self, name: &str) -> f64 {
        let (s, v) = self.real_at(vr::<M>(name));
        assert_eq!(s, Fmi2Status::Ok, "get {name}: {}", self.last_message());
        v
    }

    pub fn integer(&self, name: &str) -> i32 {
        let (vr, mut v) = (vr::<M>(name), 0);
        // SAFETY: one value reference and one value.
        let s = status(unsafe { (self.binary.get_integer)(self.c, &vr, 1, &mut v) });
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
        let (s, v) = self.get_reals(&[vr]);
        (status(s), v[0])
    }

    /// fmi2SetReal of one value reference.
    pub fn set_real_at(&self, vr: u32, v: f64) -> Fmi2Status {
        status(self.instance.set_real(vr, v))
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
        let set = self.binary.set_real_input_derivatives;
        // SAFETY: one value reference, order and value.
        status(unsafe { set(self.c, &vr, 1, &order, &v) })
    }

    pub fn set_integer(&self, name: &str, v: i32) -> Fmi2Status {
        status(self.instance.set_integer(vr::<M>(name), v))
    }

    pub fn set_boolean(&self, name: &str, v: bool) -> Fmi2Status {
        status(self.instance.set_boolean(vr::<M>(name), v))
    }

    pub fn step(&self, t: f64, h: f64) -> Fmi2Status {
        status(self.instance.do_step(t, h))
    }

    pub fn states(&self) -> Vec<f64> {
        let mut x = vec![0.0; robofmu_fmi::core::declare::continuous_states(M::VARIABLES)];
        // SAFETY: an array of the given length.
        let s = unsafe { (self.binary.get_continuous_states)(self.c, x.as_mut_ptr(), x.len()) };
        assert_eq!(status(s), Fmi2Status::Ok, "{}", self.last_message());
        x
    }

    pub fn set_states(&self, x: &[f64]) -> Fmi2Status {
        // SAFETY: an array of the given length.
        status(unsafe { (self.binary.set_continuous_states)(self.c, x.as_ptr(), x.len()) })
    }

    /// Derivatives and the status of fmi2GetDerivatives.
    pub fn derivatives(&self) -> (Fmi2Status, Vec<f64>) {
        let mut dx = vec![0.0; robofmu_fmi::core::declare::continuous_states(M::VARIABLES)];
        // SAFETY: an array of the given length.
        let s = unsafe { (self.binary.get_derivatives)(self.c, dx.as_mut_ptr(), dx.len()) };
        (status(s), dx)
    }

    pub fn event_indicators(&self) -> (Fmi2Status, Vec<f64>) {
        let mut z = vec![0.0; M::INFO.number_of_event_indicators];
        // SAFETY: an array of the given length.
        let s = unsafe { (self.binary.get_event_indicators)(self.c, z.as_mut_ptr(), z.len()) };
        (status(s), z)
    }

    /// From the event mode after initialization into continuous-time mode.
    pub fn enter_continuous_time_mode(&self) {
        let mut info = EventInfo::default();
        // SAFETY: a live component and an event info to fill.
        let s = unsafe { (self.binary.new_discrete_states)(self.c, &mut info) };
        assert_eq!(status(s), Fmi2Status::Ok);
        // SAFETY: a live component.
        let s = unsafe { (self.binary.enter_continuous_time_mode)(self.c) };
        assert_eq!(status(s), Fmi2Status::Ok);
    }

    /// An event at the current point: event mode, new discrete states, back.
    pub fn handle_event(&self) {
        // SAFETY: a live component.
        let s = unsafe { (self.binary.enter_event_mode)(self.c) };
        assert_eq!(status(s), Fmi2Status::Ok);
        self.enter_continuous_time_mode();
    }

    pub fn directional(&self, unknown: &str, known: &str) -> f64 {
        let (u, k, seed, mut out) = (vr::<M>(unknown), vr::<M>(known), 1.0, 0.0);
        let derivative = self.binary.get_directional_derivative;
        // SAFETY: one unknown, one known, one seed and one output.
        let s = unsafe { derivative(self.c, &u, 1, &k, 1, &seed, &mut out) };
        assert_eq!(status(s), Fmi2Status::Ok, "{}", self.last_message());
        out
    }

    /// fmi2GetRealOutputDerivatives of the named outputs with their orders: the status
    /// and the values (still NaN where the layer wrote nothing).
    pub fn output_derivatives(&self, names: &[&str], orders: &[i32]) -> (Fmi2Status, Vec<f64>) {
        assert_eq!(names.len(), orders.len());
        let vrs: Vec<u32> = names.iter().map(|n| vr::<M>(n)).collect();
        let mut values = vec![f64::NAN; names.len()];
        let get = self.binary.get_real_output_derivatives;
        // SAFETY: arrays of equal length.
        let s = unsafe {
            get(
                self.c,
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_mut_ptr(),
            )
        };
        (status(s), values)
    }

    /// Serialized bytes of the current FMU state.
    pub fn serialize(&self) -> Vec<u8> {
        let (s, state) = self.get_state();
        assert_eq!(status(s), Fmi2Status::Ok, "{}", self.last_message());
        let bytes = self.instance.serialize(state);
        assert_eq!(status(self.free_state(state)), Fmi2Status::Ok);
        bytes.unwrap_or_else(|e| panic!("{e}"))
    }

    /// Restores an FMU state from serialized bytes.
    pub fn restore(&self, bytes: &[u8]) -> Fmi2Status {
        let mut state: fmi2::FmuState = std::ptr::null_mut();
        let (data, size) = (bytes.as_ptr().cast(), bytes.len());
        // SAFETY: a buffer of the given length and a null slot for a new state.
        let s = unsafe { (self.binary.deserialize)(self.c, data, size, &mut state) };
        if s != fmi2::OK {
            return status(s);
        }
        // SAFETY: a state the FMU just issued.
        let s = unsafe { (self.binary.set_fmu_state)(self.c, state) };
        self.free_state(state);
        status(s)
    }

    pub fn terminated(&self) -> bool {
        let mut v = 0;
        let get = self.binary.get_boolean_status;
        // SAFETY: one output.
        let s = unsafe { get(self.c, FMI2_TERMINATED, &mut v) };
        assert_eq!(status(s), Fmi2Status::Ok);
        v == 1
    }

    pub fn last_successful_time(&self) -> f64 {
        let mut v = f64::NAN;
        let get = self.binary.get_real_status;
        // SAFETY: one output.
        let s = unsafe { get(self.c, FMI2_LAST_SUCCESSFUL_TIME, &mut v) };
        assert_eq!(status(s), Fmi2Status::Ok);
        v
    }

    /// The message of the last log line, as the FMU passed it.
    pub fn last_message(&self) -> String {
        let lines = self.env.log.lock().unwrap();
        lines.last().map(|l| l.message.clone()).unwrap_or_default()
    }

    /// Messages logged with `status`.
    pub fn messages(&self, status: Fmi2Status) -> Vec<String> {
        let lines = self.env.log.lock().unwrap();
        lines
            .iter()
            .filter(|l| l.status == status as c_int)
            .map(|l| l.message.clone())
            .collect()
    }
}
