//! fmi2GetRealOutputDerivatives through the FMI 2.0 front-end with a small test model:
//! values, every refused argument (fmi2Error with a log line naming the variable and
//! order), and points where the model cannot be evaluated (fmi2Discard, nothing
//! written); fmi3GetOutputDerivatives on the same model (it shares the core's checks;
//! its argument checks and array serialization are tested on the real FMUs in
//! tests/python/test_output_derivatives.py).

use robofmu_fmi::core::{
    Declaration, DefaultExperiment, Log, Model, ModelInfo, OutputDerivativeError, StepOutcome,
    Variability,
};
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi::fmi3::api as api3;
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::fmi3::types::{FMI3_FALSE, FMI3_TRUE, Fmi3Instance, Fmi3Status};
use robofmu_fmi_testing::{Host, vr};

/// y = a t (derivatives a, 0); w = y^2, whose derivatives it declines to give; an
/// input u that the outputs cannot be evaluated with beyond 100.
#[derive(Clone)]
struct Ramp {
    a: f64,
    u: f64,
    t: f64,
    y: f64,
}

static RAMP: ModelInfo = ModelInfo {
    model_name: "Ramp",
    model_identifier: "Ramp",
    guid: "{ramp}",
    description: "y = a t",
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 1.0,
        tolerance: 1e-6,
        step_size: 0.1,
    },
    number_of_event_indicators: 0,
    log_categories: &[],
};

impl Default for Ramp {
    fn default() -> Self {
        Ramp {
            a: 0.0,
            u: 0.0,
            t: 0.0,
            y: 0.0,
        }
    }
}

impl Model for Ramp {
    const INFO: &'static ModelInfo = &RAMP;
    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;
    fn set_time(&mut self, time: f64) {
        self.t = time;
    }
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        StepOutcome::Completed
    }
    fn calculate_values(&mut self) -> Result<(), String> {
        if self.u > 100.0 {
            return Err(format!("u = {} is beyond 100", self.u));
        }
        self.y = self.a * self.t;
        Ok(())
    }
}

/// The derivatives of y: negative slopes deliberately give NaN (the layer must not
/// pass it on); slopes above 10 cannot be evaluated.
fn y_rates(m: &Ramp, _: usize, order: u32) -> Result<f64, OutputDerivativeError> {
    match m.a {
        a if a > 10.0 => Err(OutputDerivativeError::CannotEvaluate(
            "the slope is too steep".to_string(),
        )),
        a if a < 0.0 => Ok(f64::NAN),
        a => Ok(if order == 1 { a } else { 0.0 }),
    }
}

static VARIABLES: &[Declaration<Ramp>] = &[
    Declaration::<Ramp>::real("a", "slope", |m, _| m.a)
        .parameter(Variability::Tunable)
        .start_real(&[2.0])
        .set_real(|m, _, v| {
            m.a = v;
            Ok(())
        }),
    Declaration::<Ramp>::real("u", "input", |m, _| m.u)
        .input()
        .start_real(&[0.0])
        .set_real(|m, _, v| {
            m.u = v;
            Ok(())
        }),
    Declaration::<Ramp>::real("y", "a t", |m, _| m.y)
        .output()
        .output_derivative(2, y_rates),
    Declaration::<Ramp>::real("w", "y^2", |m, _| m.y * m.y)
        .output()
        .output_derivative(2, |_, _, _| {
            Err(OutputDerivativeError::NotProvided(
                "only y is differentiated".to_string(),
            ))
        }),
    Declaration::<Ramp>::integer("n", "an Integer output", |_, _| 7).output(),
];

type H = Host<Ramp>;

/// A Co-Simulation instance stepped to t = 0.5.
fn stepped() -> H {
    let h = H::new(FMI2_CO_SIMULATION);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 0.5), Fmi2Status::Ok);
    h
}

#[test]
fn derivatives_of_every_order_come_back_in_request_order() {
    // Expected: y = a t with a = 2, so dy/dt = 2 and d2y/dt2 = 0 (closed form).
    let h = stepped();
    assert_eq!(h.real("y"), 1.0);
    let (s, v) = h.output_derivatives(&["y", "y", "y"], &[2, 1, 2]);
    assert_eq!(s, Fmi2Status::Ok);
    assert_eq!(v, [0.0, 2.0, 0.0]);
    // An empty request is legal and touches nothing.
    assert_eq!(h.output_derivatives(&[], &[]).0, Fmi2Status::Ok);
}

/// The status and last log line of one bad request on a fresh stepped instance.
fn refusal(names: &[&str], orders: &[i32]) -> (Fmi2Status, Vec<f64>, String) {
    let h = stepped();
    let (s, v) = h.output_derivatives(names, orders);
    (s, v, h.last_message())
}

#[test]
fn refused_requests_are_errors_naming_the_variable_and_order() {
    for (names, orders, expected) in [
        (
            &["y", "w"][..],
            &[1, 2][..],
            "order 2 of \"w\" is not provided",
        ),
        (
            &["u"],
            &[1],
            "\"u\" (value reference 2) is not a Real output",
        ),
        (
            &["n"],
            &[1],
            "\"n\" (value reference 5) is not a Real output",
        ),
        (
            &["a"],
            &[1],
            "\"a\" (value reference 1) is not a Real output",
        ),
        (&["y"], &[0], "order 0 of \"y\" is outside 1..2"),
        (&["y"], &[3], "order 3 of \"y\" is outside 1..2"),
        (&["y"], &[-1], "order -1 of \"y\" is outside 1..2"),
    ] {
        let (s, v, message) = refusal(names, orders);
        assert_eq!(s, Fmi2Status::Error, "{names:?} {orders:?}");
        assert!(message.contains(expected), "{message}");
        assert!(
            message.starts_with("fmi2GetRealOutputDerivatives"),
            "{message}"
        );
        assert!(
            v.iter().all(|x| x.is_nan()),
            "written despite the error: {v:?}"
        );
    }
}

/// The log line of one raw call with a single (vr, order) on a fresh stepped instance,
/// which must be refused with fmi2Error.
fn raw_refusal(vr: *const u32, order: *const i32, value: *mut f64) -> String {
    let h = stepped();
    let status = unsafe { api::get_real_output_derivatives::<Ramp>(h.c, vr, 1, order, value) };
    assert_eq!(status, Fmi2Status::Error);
    h.last_message()
}

#[test]
fn null_arrays_and_unknown_references_are_errors() {
    let (y, unknown, order, mut value) = (vr::<Ramp>("y"), 99, 1, 0.0);
    let null_vr = raw_refusal(std::ptr::null(), &order, &mut value);
    assert!(null_vr.contains("vr[] is a null pointer"), "{null_vr}");
    let null_order = raw_refusal(&y, std::ptr::null(), &mut value);
    assert!(
        null_order.contains("order[] is a null pointer"),
        "{null_order}"
    );
    let null_value = raw_refusal(&y, &order, std::ptr::null_mut());
    assert!(
        null_value.contains("value[] is a null pointer"),
        "{null_value}"
    );
    let unknown = raw_refusal(&unknown, &order, &mut value);
    assert!(unknown.contains("unknown value reference 99"), "{unknown}");
}

#[test]
fn only_co_simulation_after_initialization_may_ask() {
    // Model Exchange has no output derivatives; before initialization there are none.
    for (kind, initialize) in [(FMI2_MODEL_EXCHANGE, true), (FMI2_CO_SIMULATION, false)] {
        let h = H::new(kind);
        if initialize {
            assert_eq!(h.initialize(), Fmi2Status::Ok);
        }
        assert_eq!(h.output_derivatives(&["y"], &[1]).0, Fmi2Status::Error);
        assert!(h.last_message().contains("illegal call sequence"));
    }
}

#[test]
fn points_the_model_cannot_evaluate_are_discarded_without_writing() {
    // Outputs not computable, the model's own refusal, and a NaN from the model.
    for (name, value, expected) in [
        ("u", 200.0, "u = 200 is beyond 100"),
        (
            "a",
            20.0,
            "order 1 of \"y\" cannot be evaluated here: the slope is too steep",
        ),
        ("a", -1.0, "order 1 of \"y\" evaluates to NaN"),
    ] {
        let h = stepped();
        assert_eq!(h.set_real(name, value), Fmi2Status::Ok);
        let (s, v) = h.output_derivatives(&["y"], &[1]);
        assert_eq!(s, Fmi2Status::Discard, "{name} = {value}");
        assert!(v[0].is_nan(), "written despite the Discard: {v:?}");
        assert!(h.last_message().contains(expected), "{}", h.last_message());
        // Discard is no error: the instance goes on.
        assert_eq!(h.set_real(name, 1.0), Fmi2Status::Ok);
        let slope = if name == "a" { 1.0 } else { 2.0 };
        assert_eq!(
            h.output_derivatives(&["y"], &[1]),
            (Fmi2Status::Ok, vec![slope])
        );
    }
}

/// The FMI 3.0 front-end on the same model: a Co-Simulation instance (no logger)
/// stepped to t = 0.5 s.
fn stepped_fmi3() -> Fmi3Instance {
    let c = unsafe {
        api3::instantiate::<Ramp>(api3::Instantiation {
            function: "fmi3InstantiateCoSimulation",
            instance_name: c"test".as_ptr(),
            token: c"{ramp}".as_ptr(),
            logging_on: FMI3_FALSE,
            environment: std::ptr::null_mut(),
            log_message: None,
            interface: Interface::CoSimulation {
                event_mode_used: false,
                early_return_allowed: false,
            },
            intermediate_update: None,
        })
    };
    assert!(!c.is_null());
    let (mut event, mut terminate, mut early, mut last) = (0, 0, 0, 0.0);
    unsafe {
        assert_eq!(
            api3::enter_initialization_mode::<Ramp>(c, 0, 0.0, 0.0, 0, 0.0),
            Fmi3Status::Ok
        );
        assert_eq!(api3::exit_initialization_mode::<Ramp>(c), Fmi3Status::Ok);
        let result = api3::StepResult {
            event_handling_needed: &mut event,
            terminate_simulation: &mut terminate,
            early_return: &mut early,
            last_successful_time: &mut last,
        };
        assert_eq!(
            api3::do_step::<Ramp>(c, 0.0, 0.5, FMI3_TRUE, result),
            Fmi3Status::Ok
        );
    }
    c
}

/// fmi3GetOutputDerivatives of the pairs (vrs[i], orders[i]) into n_values values
/// (NaN where nothing was written).
fn fmi3_derivatives(
    c: Fmi3Instance,
    vrs: &[u32],
    orders: &[i32],
    n_values: usize,
) -> (Fmi3Status, Vec<f64>) {
    let mut values = vec![f64::NAN; n_values];
    let status = unsafe {
        api3::get_output_derivatives::<Ramp>(
            c,
            vrs.as_ptr(),
            vrs.len(),
            orders.as_ptr(),
            values.as_mut_ptr(),
            n_values,
        )
    };
    (status, values)
}

#[test]
fn fmi3_serves_the_same_values_and_discards_alike() {
    // Expected: dy/dt = a = 2, d2y/dt2 = 0 (closed form); a slope above 10 cannot be
    // evaluated (Discard, nothing written); nValues must count the values.
    let y = vr::<Ramp>("y");
    let c = stepped_fmi3();
    assert_eq!(
        fmi3_derivatives(c, &[y, y], &[1, 2], 2),
        (Fmi3Status::Ok, vec![2.0, 0.0])
    );
    let a = vr::<Ramp>("a");
    assert_eq!(
        unsafe { api3::set_float64::<Ramp>(c, &a, 1, &20.0, 1) },
        Fmi3Status::Ok
    );
    let (status, values) = fmi3_derivatives(c, &[y], &[1], 1);
    assert_eq!(status, Fmi3Status::Discard);
    assert!(
        values[0].is_nan(),
        "written despite the Discard: {values:?}"
    );
    assert_eq!(fmi3_derivatives(c, &[y], &[1], 2).0, Fmi3Status::Error);
    unsafe { api3::free_instance::<Ramp>(c) };
}
