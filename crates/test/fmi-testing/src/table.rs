//! The FMI 2.0 function table of the test host (`robofmu_fmi_host::fmi2::Binary`)
//! filled with a model linked into the test: each entry a C function over the
//! layer's generic function for `M` (what `export_fmi2!` exports as a symbol), its
//! status as the C int the host reads. Made once per model and kept for the process.

use robofmu_fmi::core::Model;
use robofmu_fmi::fmi2::api;
use robofmu_fmi_host::fmi2::{Binary, CallbackFunctions, Component, EventInfo, FmuState, Status};
use std::any::TypeId;
use std::ffi::{c_char, c_int, c_uint};
use std::sync::Mutex;

type Str = *const c_char;
type Vr = c_uint;

/// The table of `M`, made on the first call.
pub fn binary<M: Model>() -> &'static Binary {
    static TABLES: Mutex<Vec<(TypeId, &'static Binary)>> = Mutex::new(Vec::new());
    let mut tables = TABLES.lock().unwrap_or_else(|e| e.into_inner());
    let id = TypeId::of::<M>();
    if let Some((_, table)) = tables.iter().find(|(t, _)| *t == id) {
        return table;
    }
    let table: &'static Binary = Box::leak(Box::new(filled::<M>()));
    tables.push((id, table));
    table
}

fn filled<M: Model>() -> Binary {
    Binary {
        library: None,
        get_types_platform,
        get_version,
        set_debug_logging: set_debug_logging::<M>,
        instantiate: instantiate::<M>,
        free_instance: free_instance::<M>,
        setup_experiment: setup_experiment::<M>,
        enter_initialization_mode: enter_initialization_mode::<M>,
        exit_initialization_mode: exit_initialization_mode::<M>,
        terminate: terminate::<M>,
        reset: reset::<M>,
        get_real: get_real::<M>,
        get_integer: get_integer::<M>,
        get_boolean: get_boolean::<M>,
        get_string: get_string::<M>,
        set_real: set_real::<M>,
        set_integer: set_integer::<M>,
        set_boolean: set_boolean::<M>,
        set_string: set_string::<M>,
        get_fmu_state: get_fmu_state::<M>,
        set_fmu_state: set_fmu_state::<M>,
        free_fmu_state: free_fmu_state::<M>,
        serialized_size: serialized_size::<M>,
        serialize: serialize::<M>,
        deserialize: deserialize::<M>,
        get_directional_derivative: get_directional_derivative::<M>,
        enter_event_mode: enter_event_mode::<M>,
        new_discrete_states: new_discrete_states::<M>,
        enter_continuous_time_mode: enter_continuous_time_mode::<M>,
        completed_integrator_step: completed_integrator_step::<M>,
        set_time: set_time::<M>,
        set_continuous_states: set_continuous_states::<M>,
        get_derivatives: get_derivatives::<M>,
        get_event_indicators: get_event_indicators::<M>,
        get_continuous_states: get_continuous_states::<M>,
        get_nominals: get_nominals::<M>,
        set_real_input_derivatives: set_real_input_derivatives::<M>,
        get_real_output_derivatives: get_real_output_derivatives::<M>,
        do_step: do_step::<M>,
        cancel_step: cancel_step::<M>,
        get_status: get_status::<M>,
        get_real_status: get_real_status::<M>,
        get_integer_status: get_integer_status::<M>,
        get_boolean_status: get_boolean_status::<M>,
        get_string_status: get_string_status::<M>,
    }
}

// Each function: SAFETY: the host's arguments go to the layer's function of the
// same standard signature (the layer checks handle, pointers and state).

extern "C" fn get_types_platform() -> Str {
    api::get_types_platform()
}

extern "C" fn get_version() -> Str {
    api::get_version()
}

unsafe extern "C" fn set_debug_logging<M: Model>(
    c: Component,
    on: c_int,
    n: usize,
    categories: *const Str,
) -> Status {
    unsafe { api::set_debug_logging::<M>(c, on, n, categories) as Status }
}

unsafe extern "C" fn instantiate<M: Model>(
    name: Str,
    kind: c_int,
    guid: Str,
    resources: Str,
    functions: *const CallbackFunctions,
    visible: c_int,
    logging_on: c_int,
) -> Component {
    // The host's callback table has the layout of fmi2CallbackFunctions.
    let functions = functions.cast();
    unsafe { api::instantiate::<M>(name, kind, guid, resources, functions, visible, logging_on) }
}

unsafe extern "C" fn free_instance<M: Model>(c: Component) {
    unsafe { api::free_instance::<M>(c) }
}

unsafe extern "C" fn setup_experiment<M: Model>(
    c: Component,
    tolerance_defined: c_int,
    tolerance: f64,
    start: f64,
    stop_defined: c_int,
    stop: f64,
) -> Status {
    unsafe {
        api::setup_experiment::<M>(c, tolerance_defined, tolerance, start, stop_defined, stop)
            as Status
    }
}

unsafe extern "C" fn enter_initialization_mode<M: Model>(c: Component) -> Status {
    unsafe { api::enter_initialization_mode::<M>(c) as Status }
}

unsafe extern "C" fn exit_initialization_mode<M: Model>(c: Component) -> Status {
    unsafe { api::exit_initialization_mode::<M>(c) as Status }
}

unsafe extern "C" fn terminate<M: Model>(c: Component) -> Status {
    unsafe { api::terminate::<M>(c) as Status }
}

unsafe extern "C" fn reset<M: Model>(c: Component) -> Status {
    unsafe { api::reset::<M>(c) as Status }
}

unsafe extern "C" fn get_real<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *mut f64,
) -> Status {
    unsafe { api::get_real::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn get_integer<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *mut c_int,
) -> Status {
    unsafe { api::get_integer::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn get_boolean<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *mut c_int,
) -> Status {
    unsafe { api::get_boolean::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn get_string<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *mut Str,
) -> Status {
    unsafe { api::get_string::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn set_real<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *const f64,
) -> Status {
    unsafe { api::set_real::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn set_integer<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *const c_int,
) -> Status {
    unsafe { api::set_integer::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn set_boolean<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *const c_int,
) -> Status {
    unsafe { api::set_boolean::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn set_string<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    v: *const Str,
) -> Status {
    unsafe { api::set_string::<M>(c, vr, n, v) as Status }
}

unsafe extern "C" fn get_fmu_state<M: Model>(c: Component, state: *mut FmuState) -> Status {
    unsafe { api::get_fmu_state::<M>(c, state) as Status }
}

unsafe extern "C" fn set_fmu_state<M: Model>(c: Component, state: FmuState) -> Status {
    unsafe { api::set_fmu_state::<M>(c, state) as Status }
}

unsafe extern "C" fn free_fmu_state<M: Model>(c: Component, state: *mut FmuState) -> Status {
    unsafe { api::free_fmu_state::<M>(c, state) as Status }
}

unsafe extern "C" fn serialized_size<M: Model>(
    c: Component,
    state: FmuState,
    size: *mut usize,
) -> Status {
    unsafe { api::serialized_fmu_state_size::<M>(c, state, size) as Status }
}

unsafe extern "C" fn serialize<M: Model>(
    c: Component,
    state: FmuState,
    bytes: *mut c_char,
    size: usize,
) -> Status {
    unsafe { api::serialize_fmu_state::<M>(c, state, bytes, size) as Status }
}

unsafe extern "C" fn deserialize<M: Model>(
    c: Component,
    bytes: *const c_char,
    size: usize,
    state: *mut FmuState,
) -> Status {
    unsafe { api::de_serialize_fmu_state::<M>(c, bytes, size, state) as Status }
}

unsafe extern "C" fn get_directional_derivative<M: Model>(
    c: Component,
    unknowns: *const Vr,
    n_unknown: usize,
    knowns: *const Vr,
    n_known: usize,
    seed: *const f64,
    sensitivity: *mut f64,
) -> Status {
    unsafe {
        api::get_directional_derivative::<M>(
            c,
            unknowns,
            n_unknown,
            knowns,
            n_known,
            seed,
            sensitivity,
        ) as Status
    }
}

unsafe extern "C" fn enter_event_mode<M: Model>(c: Component) -> Status {
    unsafe { api::enter_event_mode::<M>(c) as Status }
}

unsafe extern "C" fn new_discrete_states<M: Model>(c: Component, info: *mut EventInfo) -> Status {
    // The host's EventInfo has the layout of fmi2EventInfo.
    unsafe { api::new_discrete_states::<M>(c, info.cast()) as Status }
}

unsafe extern "C" fn enter_continuous_time_mode<M: Model>(c: Component) -> Status {
    unsafe { api::enter_continuous_time_mode::<M>(c) as Status }
}

unsafe extern "C" fn completed_integrator_step<M: Model>(
    c: Component,
    no_prior: c_int,
    enter_event_mode: *mut c_int,
    terminate: *mut c_int,
) -> Status {
    unsafe {
        api::completed_integrator_step::<M>(c, no_prior, enter_event_mode, terminate) as Status
    }
}

unsafe extern "C" fn set_time<M: Model>(c: Component, time: f64) -> Status {
    unsafe { api::set_time::<M>(c, time) as Status }
}

unsafe extern "C" fn set_continuous_states<M: Model>(
    c: Component,
    x: *const f64,
    n: usize,
) -> Status {
    unsafe { api::set_continuous_states::<M>(c, x, n) as Status }
}

unsafe extern "C" fn get_derivatives<M: Model>(c: Component, dx: *mut f64, n: usize) -> Status {
    unsafe { api::get_derivatives::<M>(c, dx, n) as Status }
}

unsafe extern "C" fn get_event_indicators<M: Model>(c: Component, z: *mut f64, n: usize) -> Status {
    unsafe { api::get_event_indicators::<M>(c, z, n) as Status }
}

unsafe extern "C" fn get_continuous_states<M: Model>(
    c: Component,
    x: *mut f64,
    n: usize,
) -> Status {
    unsafe { api::get_continuous_states::<M>(c, x, n) as Status }
}

unsafe extern "C" fn get_nominals<M: Model>(c: Component, x: *mut f64, n: usize) -> Status {
    unsafe { api::get_nominals_of_continuous_states::<M>(c, x, n) as Status }
}

unsafe extern "C" fn set_real_input_derivatives<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    order: *const c_int,
    v: *const f64,
) -> Status {
    unsafe { api::set_real_input_derivatives::<M>(c, vr, n, order, v) as Status }
}

unsafe extern "C" fn get_real_output_derivatives<M: Model>(
    c: Component,
    vr: *const Vr,
    n: usize,
    order: *const c_int,
    v: *mut f64,
) -> Status {
    unsafe { api::get_real_output_derivatives::<M>(c, vr, n, order, v) as Status }
}

unsafe extern "C" fn do_step<M: Model>(c: Component, t: f64, h: f64, no_prior: c_int) -> Status {
    unsafe { api::do_step::<M>(c, t, h, no_prior) as Status }
}

unsafe extern "C" fn cancel_step<M: Model>(c: Component) -> Status {
    unsafe { api::cancel_step::<M>(c) as Status }
}

unsafe extern "C" fn get_status<M: Model>(c: Component, kind: c_int, v: *mut c_int) -> Status {
    // fmi2Status is a C int.
    unsafe { api::get_status::<M>(c, kind, v.cast()) as Status }
}

unsafe extern "C" fn get_real_status<M: Model>(c: Component, kind: c_int, v: *mut f64) -> Status {
    unsafe { api::get_real_status::<M>(c, kind, v) as Status }
}

unsafe extern "C" fn get_integer_status<M: Model>(
    c: Component,
    kind: c_int,
    v: *mut c_int,
) -> Status {
    unsafe { api::get_integer_status::<M>(c, kind, v) as Status }
}

unsafe extern "C" fn get_boolean_status<M: Model>(
    c: Component,
    kind: c_int,
    v: *mut c_int,
) -> Status {
    unsafe { api::get_boolean_status::<M>(c, kind, v) as Status }
}

unsafe extern "C" fn get_string_status<M: Model>(c: Component, kind: c_int, v: *mut Str) -> Status {
    unsafe { api::get_string_status::<M>(c, kind, v) as Status }
}
