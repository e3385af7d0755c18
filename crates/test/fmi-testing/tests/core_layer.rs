//! Tests of the version-neutral core through the FMI 2.0 front-end, with small test
//! models (no FMU crate is linked here): computed values once per change, the event
//! update result, the stop time.

use robofmu_fmi::core::{
    Declaration, DefaultExperiment, EventUpdate, Log, Model, ModelInfo, StepOutcome, Variability,
};
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::{Host, vr};

const INFO: DefaultExperiment = DefaultExperiment {
    start_time: 0.0,
    stop_time: 1.0,
    tolerance: 1e-6,
    step_size: 0.1,
};

/// y = 2 u, counting how often its values were calculated.
#[derive(Clone)]
struct Doubler {
    u: f64,
    y: f64,
    calculations: i32,
}

static DOUBLER: ModelInfo = ModelInfo {
    model_name: "Doubler",
    model_identifier: "Doubler",
    guid: "{doubler}",
    description: "y = 2 u",
    default_experiment: INFO,
    number_of_event_indicators: 0,
    log_categories: &[],
};

impl Default for Doubler {
    fn default() -> Self {
        Doubler {
            u: 0.0,
            y: f64::NAN,
            calculations: 0,
        }
    }
}

impl Model for Doubler {
    const INFO: &'static ModelInfo = &DOUBLER;
    // Deliberately out of value-reference order: the layer sorts the scalars.
    const VARIABLES: &'static [Declaration<Self>] = &[
        Declaration::<Doubler>::real("y", "output", |m, _| m.y)
            .at(2)
            .output(),
        Declaration::<Doubler>::integer("calculations", "count", |m, _| m.calculations)
            .at(3)
            .output(),
        Declaration::<Doubler>::real("u", "input", |m, _| m.u)
            .at(1)
            .input()
            .start_real(&[0.0])
            .set_real(|m, _, v| {
                m.u = v;
                Ok(())
            }),
    ];
    fn set_time(&mut self, _time: f64) {}
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        StepOutcome::Completed
    }
    fn calculate_values(&mut self) -> Result<(), String> {
        self.calculations += 1;
        // A model-specific domain limit, below the layer's 1e150 for set values.
        if self.u > 1e100 {
            return Err(format!("u = {} overflows y", self.u));
        }
        self.y = 2.0 * self.u;
        Ok(())
    }
}

#[test]
fn values_are_calculated_once_per_change_not_per_read() {
    let h: Host<Doubler> = Host::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    // Initialization calculated once (to check the values at the start).
    assert_eq!(h.integer("calculations"), 1);
    assert_eq!(h.set_real("u", 1.5), Fmi2Status::Ok);
    // Expected: y = 2 u = 3 exactly, three reads, one calculation.
    for _ in 0..3 {
        assert_eq!(h.real("y"), 3.0);
    }
    assert_eq!(h.integer("calculations"), 2);
    // A step is a change: one more calculation at its end, none for the reads.
    assert_eq!(h.step(0.0, 0.1), Fmi2Status::Ok);
    assert_eq!(h.real("y"), 3.0);
    assert_eq!(h.real("y"), 3.0);
    assert_eq!(h.integer("calculations"), 3);
    // Reading the input needs no calculation.
    assert_eq!(h.real("u"), 1.5);
    assert_eq!(h.integer("calculations"), 3);
}

#[test]
fn a_model_that_cannot_be_evaluated_makes_reads_discard_and_steps_discard() {
    // Logging on: Discard messages are logged only when enabled.
    let h: Host<Doubler> = Host::new(FMI2_CO_SIMULATION);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.set_real("u", 1e120), Fmi2Status::Ok);
    // The output cannot be read: Discard with the model's reason, not a NaN.
    assert_eq!(h.real_at(vr::<Doubler>("y")).0, Fmi2Status::Discard);
    assert!(
        h.last_message().contains("overflows y"),
        "{}",
        h.last_message()
    );
    // The input itself stays readable.
    assert_eq!(h.real("u"), 1e120);
    // A step with that input is discarded at its end (the getter never notices first).
    assert_eq!(h.step(0.0, 0.1), Fmi2Status::Discard);
    assert!(
        h.last_message().contains("overflows y"),
        "{}",
        h.last_message()
    );
}

/// x' = 1; at an event x > 1 is reset to 0, and after `maxResets` resets the model
/// asks to terminate.
#[derive(Clone)]
struct Sawtooth {
    x: f64,
    resets: i32,
    max_resets: i32,
}

static SAWTOOTH: ModelInfo = ModelInfo {
    model_name: "Sawtooth",
    model_identifier: "Sawtooth",
    guid: "{sawtooth}",
    description: "x' = 1, reset to 0 above 1",
    default_experiment: INFO,
    number_of_event_indicators: 1,
    log_categories: &[],
};

impl Default for Sawtooth {
    fn default() -> Self {
        Sawtooth {
            x: 0.0,
            resets: 0,
            max_resets: 2,
        }
    }
}

impl Model for Sawtooth {
    const INFO: &'static ModelInfo = &SAWTOOTH;
    const VARIABLES: &'static [Declaration<Self>] = &[
        Declaration::<Sawtooth>::real("x", "state", |m, _| m.x)
            .state()
            .start_real(&[0.0])
            .set_real(|m, _, v| {
                m.x = v;
                Ok(())
            }),
        Declaration::<Sawtooth>::real("der(x)", "rate", |_, _| 1.0).derivative_of("x"),
        Declaration::<Sawtooth>::integer("maxResets", "resets before terminating", |m, _| {
            m.max_resets
        })
        .parameter(Variability::Fixed)
        .start_integer(&[2])
        .set_integer(|m, _, v| {
            m.max_resets = v;
            Ok(())
        }),
    ];
    fn set_time(&mut self, _time: f64) {}
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        StepOutcome::Completed
    }
    fn continuous_states(&mut self, x: &mut [f64]) {
        x[0] = self.x;
    }
    fn set_continuous_states(&mut self, x: &[f64]) {
        self.x = x[0];
    }
    fn derivatives(&self, dx: &mut [f64]) -> Result<(), String> {
        dx[0] = 1.0;
        Ok(())
    }
    fn event_indicators(&self, z: &mut [f64]) -> Result<(), String> {
        z[0] = 1.0 - self.x;
        Ok(())
    }
    fn update_discrete_states(&mut self) -> EventUpdate {
        if self.x <= 1.0 {
            return EventUpdate::default();
        }
        self.x = 0.0;
        self.resets += 1;
        EventUpdate {
            values_of_continuous_states_changed: true,
            terminate_simulation: self.resets >= self.max_resets,
            ..EventUpdate::default()
        }
    }
}

fn new_discrete_states(h: &Host<Sawtooth>) -> Fmi2EventInfo {
    let mut info = Fmi2EventInfo {
        new_discrete_states_needed: 7,
        terminate_simulation: 7,
        nominals_of_continuous_states_changed: 7,
        values_of_continuous_states_changed: 7,
        next_event_time_defined: 7,
        next_event_time: 7.0,
    };
    let status = unsafe { api::new_discrete_states::<Sawtooth>(h.c, &mut info) };
    assert_eq!(status, Fmi2Status::Ok, "{}", h.last_message());
    info
}

#[test]
fn the_event_update_reports_reinitialized_states_and_termination() {
    let h: Host<Sawtooth> = Host::with_logging(FMI2_MODEL_EXCHANGE, false);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    // At the start (x = 0) the event iteration changes nothing.
    let info = new_discrete_states(&h);
    assert_eq!(
        (
            info.values_of_continuous_states_changed,
            info.terminate_simulation
        ),
        (FMI2_FALSE, FMI2_FALSE)
    );
    unsafe { api::enter_continuous_time_mode::<Sawtooth>(h.c) };
    for (reset, terminate) in [(1, FMI2_FALSE), (2, FMI2_TRUE)] {
        // The integrator crossed z = 1 - x = 0 at x = 1.25.
        assert_eq!(h.set_states(&[1.25]), Fmi2Status::Ok);
        assert_eq!(h.event_indicators().1, vec![-0.25]);
        unsafe { api::enter_event_mode::<Sawtooth>(h.c) };
        let info = new_discrete_states(&h);
        assert_eq!(
            info.values_of_continuous_states_changed, FMI2_TRUE,
            "{reset}"
        );
        assert_eq!(info.terminate_simulation, terminate, "reset {reset}");
        assert_eq!(info.new_discrete_states_needed, FMI2_FALSE);
        // The state was re-initialized to 0 by the event.
        assert_eq!(h.states(), vec![0.0]);
        unsafe { api::enter_continuous_time_mode::<Sawtooth>(h.c) };
    }
}

#[test]
fn a_step_past_the_stop_time_is_refused() {
    let h: Host<Doubler> = Host::with_logging(FMI2_CO_SIMULATION, false);
    unsafe {
        // stopTime 0.25 s defined, as a master does from the experiment.
        assert_eq!(
            api::setup_experiment::<Doubler>(h.c, 0, 0.0, 0.0, FMI2_TRUE, 0.25),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::enter_initialization_mode::<Doubler>(h.c),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::exit_initialization_mode::<Doubler>(h.c),
            Fmi2Status::Ok
        );
    }
    assert_eq!(h.step(0.0, 0.1), Fmi2Status::Ok);
    assert_eq!(h.step(0.1, 0.1), Fmi2Status::Ok);
    // 0.2 + 0.1 = 0.3 > 0.25: refused, as the reference FMUs refuse it.
    assert_eq!(h.step(0.2, 0.1), Fmi2Status::Error);
    assert!(
        h.last_message().contains("stopTime = 0.25"),
        "{}",
        h.last_message()
    );
}

#[test]
fn a_step_ending_at_the_stop_time_despite_round_off_is_accepted() {
    let h: Host<Doubler> = Host::with_logging(FMI2_CO_SIMULATION, false);
    unsafe {
        api::setup_experiment::<Doubler>(h.c, 0, 0.0, 0.0, FMI2_TRUE, 0.3);
        api::enter_initialization_mode::<Doubler>(h.c);
        assert_eq!(
            api::exit_initialization_mode::<Doubler>(h.c),
            Fmi2Status::Ok
        );
    }
    // 0.1 + 0.1 + 0.1 = 0.30000000000000004 in binary: within the tolerance.
    let mut t = 0.0;
    for _ in 0..3 {
        assert_eq!(h.step(t, 0.1), Fmi2Status::Ok, "{}", h.last_message());
        t += 0.1;
    }
    assert_eq!(h.last_successful_time(), 0.1 + 0.1 + 0.1);
}

#[test]
fn a_model_that_takes_no_input_derivatives_refuses_them_naming_itself() {
    // Doubler keeps the default MAX_INPUT_DERIVATIVE_ORDER = 0 (canInterpolateInputs
    // absent from its description): any order of its continuous input is an error.
    let h: Host<Doubler> = Host::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.set_input_derivative("u", 1, 0.5), Fmi2Status::Error);
    assert_eq!(
        h.last_message(),
        "fmi2SetRealInputDerivatives: Doubler takes no input derivatives (its inputs are \
         held over a step)"
    );
    let d = robofmu_fmi::description::describe::<Doubler>().unwrap();
    let xml = robofmu_fmi_build::fmi2::model_description(&d).unwrap();
    assert!(!xml.contains("canInterpolateInputs"), "{xml}");
}

/// The header `export_fmu!` exports for Doubler, as the packager reads it.
fn header() -> robofmu_fmi::description::Header {
    robofmu_fmi::description::Header::of::<Doubler>()
}

#[test]
fn the_description_header_lends_the_description_of_its_own_build() {
    // Expected: the header of this build passes its own check and lends Doubler's
    // ModelInfo (the static the model declares) and its scalars by value reference.
    let lend = header().check().unwrap();
    let mut seen = None;
    lend(&mut |d| {
        let d = d.unwrap();
        let names: Vec<&str> = d.scalars.iter().map(|s| s.name.as_str()).collect();
        seen = Some((d.info.model_name, names.len()));
    });
    let table = robofmu_fmi::core::instance::sorted_table::<Doubler>().unwrap();
    assert_eq!(seen, Some((Doubler::INFO.model_name, table.len())));
}

#[test]
fn the_description_header_refuses_another_layer_build_naming_the_fix() {
    // Expected: a header from another layer version, another build (fingerprint) or
    // no header at all is refused before its Rust function is called.
    let mut other_version = header();
    other_version.layer_version = [0; 32];
    other_version.layer_version[..5].copy_from_slice(b"0.0.9");
    let e = other_version.check().err().unwrap();
    assert!(
        e.starts_with("built with FMI layer 0.0.9 but the packager has "),
        "{e}"
    );
    assert!(e.ends_with("rebuild both with one `cargo build --release --workspace`"));
    extern "C" fn another_build() -> u64 {
        7
    }
    let other_build = robofmu_fmi::description::Header {
        fingerprint: another_build,
        ..header()
    };
    let e = other_build.check().err().unwrap();
    assert!(
        e.starts_with("built from other sources or by another build of the FMI layer"),
        "{e}"
    );
    let not_a_header = robofmu_fmi::description::Header {
        magic: *b"notours\0",
        ..header()
    };
    let e = not_a_header.check().err().unwrap();
    assert_eq!(
        e,
        "robofmu_fmu_description is not a robofmu description header"
    );
}
