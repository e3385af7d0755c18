//! Binding of the computed-torque law (`robofmu_dynamics::computed_torque`) as the FMU
//! "ComputedTorque": inputs the planned Euler angles, rates and accelerations and the
//! measured angles and rates; output the Euler-angle generalized force, the plant's
//! `generalizedForceCommand` (the input the PID drives: the controllers are
//! interchangeable). Gains and output limits per axis are tunable; the controller's
//! model of the robot (the plant FMU's parameter names, `computed_torque::
//! MODEL_PARAMETERS`) is fixed, so a model mismatch is a parameter that differs from
//! the plant's. The error integral is the continuous state (Model Exchange); in
//! Co-Simulation it is stepped exactly under a zero-order hold of the inputs (I + e h),
//! with the PID's conditional-integration anti-windup decided at the start of the step.
//!
//! FMI 3.0 adds the sampled law as a clocked partition (module `clocked`): the input
//! clock `sampleClock` ticks every `samplePeriod` seconds, and at each tick the law
//! is evaluated on the inputs there with an error integral of its own, its output
//! `uSampled` held until the next tick (`robofmu_dynamics::computed_torque::sampled`).
//! The continuous output `u` and its state stay as they are: an importer that never
//! sets the clock runs the continuous law, as before.

mod clocked;
mod initial_dependencies;
mod partials;
mod variables;

use nalgebra::Vector3;
use robofmu_dynamics::computed_torque::{
    AxisGains, ComputedTorque, GEOMETRY, Inputs, controller_message, pole_placement,
};
use robofmu_dynamics::pss3::dynamics::{DynamicsError, PlantParams};
use robofmu_fmi::core::clocks::period_fraction;
use robofmu_fmi::prelude::*;

/// Euler-angle axes.
pub const AXES: usize = 3;

/// The default bandwidth of the gains, rad/s: a triple pole at -30 rad/s, the PID
/// design's bandwidth in the scenarios.
pub const DEFAULT_BANDWIDTH: f64 = 30.0;

static INFO: ModelInfo = ModelInfo {
    model_name: "ComputedTorque",
    model_identifier: "ComputedTorque",
    guid: "{3f1c9a52-7d4e-4b8a-9e61-0c2d5b7a8f14}",
    description: "Computed-torque controller of the 3-PSS robot: inverse dynamics of its own \
                  model at the measured state for the planned acceleration plus PID feedback \
                  on the Euler-angle error, output limits with conditional-integration \
                  anti-windup",
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 2.0,
        tolerance: 1e-8,
        step_size: 1e-3,
    },
    number_of_event_indicators: 0,
    log_categories: &[LOG],
};
const LOG: LogCategory = LogCategory::new(
    "logController",
    "Gains and model of the controller at initialization",
);

/// Parameters, inputs and the error integral of one controller instance.
#[derive(Clone)]
pub struct ComputedTorqueFmu {
    model: PlantParams,
    gains: [AxisGains; AXES],
    /// Limits as set; they apply only when `limited` is true.
    limits: [(f64, f64); AXES],
    limited: [bool; AXES],
    inputs: Inputs,
    integral: Vector3<f64>,
    /// The law for the current parameters (None: rebuild before use).
    law: Option<ComputedTorque>,
    /// What the controller computes at the current inputs and integral
    /// (`calculate_values`).
    output: Option<Evaluation>,
    /// The sampled law's error integral, the one its next tick starts from.
    sampled_integral: Vector3<f64>,
    /// The sampled law's output since its last tick (zero before the first).
    held: Vector3<f64>,
    /// The sample period, s (the FMI 3.0 parameter samplePeriod).
    sample_period: f64,
}

impl ComputedTorqueFmu {
    /// After a parameter is set: the law is rebuilt before its next use.
    fn rebuild_law(&mut self, _: usize) {
        self.law = None;
    }

    /// The law for the current parameters, or why there is none (FMU parameter names).
    fn build_law(&self) -> Result<ComputedTorque, String> {
        let gains = std::array::from_fn(|k| AxisGains {
            limits: self.limited[k].then_some(self.limits[k]),
            ..self.gains[k]
        });
        ComputedTorque::new(self.model, gains).map_err(|e| controller_message(&e))
    }

    /// The output at the current inputs and integral. Where the controller's model
    /// cannot be evaluated at the measured pose (its legs cannot reach it, or the
    /// Euler angles are singular), the law has no inverse dynamics: Err names the pose
    /// and the reason, which the layer returns as Discard from every getter and step
    /// (one status for a value the model cannot evaluate, docs/reliability.md).
    fn evaluate(&self) -> Result<Evaluation, String> {
        let built;
        let law = match &self.law {
            Some(law) => law,
            None => {
                built = self.build_law()?;
                &built
            }
        };
        self.evaluate_at(law, &self.integral)
    }

    /// The law's output and integral rate at the current inputs and the error
    /// integral `integral`, or why the law cannot be evaluated (see `evaluate`).
    fn evaluate_at(
        &self,
        law: &ComputedTorque,
        integral: &Vector3<f64>,
    ) -> Result<Evaluation, String> {
        match law.output(integral, &self.inputs) {
            Ok(output) => Ok(Evaluation {
                u: output.u,
                integral_rate: law.integral_rate(&output),
            }),
            Err(DynamicsError::Kinematics(e)) => {
                let theta = self.inputs.measurement.map(f64::to_degrees);
                Err(format!(
                    "measurement = ({:.4}, {:.4}, {:.4}) deg: the controller's model \
                     ({GEOMETRY}) cannot be evaluated at this pose: {e}",
                    theta[0], theta[1], theta[2]
                ))
            }
            Err(e) => Err(format!("the law cannot be evaluated: {e}")),
        }
    }

    fn u(&self, k: usize) -> f64 {
        self.output.map_or(f64::NAN, |o| o.u[k])
    }

    fn integral_rate(&self, k: usize) -> f64 {
        self.output.map_or(f64::NAN, |o| o.integral_rate[k])
    }
}

/// What the controller computes at its inputs and integral.
#[derive(Debug, Clone, Copy)]
struct Evaluation {
    /// The output, N m.
    u: Vector3<f64>,
    /// The time derivative of the error integral (anti-windup applied).
    integral_rate: Vector3<f64>,
}

impl Default for ComputedTorqueFmu {
    fn default() -> Self {
        let gains = pole_placement(DEFAULT_BANDWIDTH, true).expect("positive bandwidth");
        ComputedTorqueFmu {
            model: PlantParams::default(),
            gains: [gains; AXES],
            limits: [(-1.0, 1.0); AXES],
            limited: [false; AXES],
            inputs: Inputs::default(),
            integral: Vector3::zeros(),
            law: None,
            output: None,
            sampled_integral: Vector3::zeros(),
            held: Vector3::zeros(),
            sample_period: 1e-3,
        }
    }
}

impl Model for ComputedTorqueFmu {
    const INFO: &'static ModelInfo = &INFO;

    const VARIABLES: &'static [Declaration<Self>] = &variables::VARIABLES;
    const CLOCKS: &'static [InputClock<Self>] = clocked::CLOCKS;
    /// Directional and adjoint derivatives from the law's Jacobian (`partials`).
    const JACOBIAN: Option<Jacobian<Self>> =
        Some(Jacobian::Directional(partials::directional_derivative));
    /// FMI 3.0 intermediate update: each communication step split into 10 equal parts,
    /// the inputs settable at the 9 inner points (held over the next part).
    const INTERMEDIATE_UPDATE_POINTS: u32 = 10;
    fn set_time(&mut self, _time: f64) {
        // The law is time invariant.
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        let law = self.build_law()?;
        log.debug(
            LOG.name,
            &format!("gains {:?}, model {:?}", law.gains(), self.model),
        );
        self.law = Some(law);
        // The model must be evaluable at the start inputs: a geometry whose legs cannot
        // reach the measured pose is refused here, so that a getter in Initialization
        // Mode gives this reason as the parameters' (as ExitInitializationMode does).
        self.evaluate().map(|_| ())
    }

    fn calculate_values(&mut self) -> Result<(), String> {
        self.output = None;
        if self.law.is_none() {
            self.law = Some(self.build_law()?);
        }
        self.output = Some(self.evaluate()?);
        Ok(())
    }

    fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
        // Inputs held over the step: e is constant, so I + e h is exact; the
        // anti-windup decision is taken at the start of the step (as the PID's).
        match self.evaluate() {
            Ok(evaluation) => {
                self.integral += evaluation.integral_rate * step;
                StepOutcome::Completed
            }
            Err(reason) => StepOutcome::Discarded {
                reason,
                terminate: true,
            },
        }
    }

    // The continuous states: the layer's defaults, through the place of `integral`.

    fn derivatives(&self, dx: &mut [f64]) -> Result<(), String> {
        let evaluation = self.evaluate()?;
        dx.copy_from_slice(evaluation.integral_rate.as_slice());
        Ok(())
    }

    /// The sampled law's integral, held output and period (not variables of FMI 2.0,
    /// which has no clocks), 7 doubles.
    fn write_extra_state(&self, out: &mut Vec<u8>) {
        let values = self.sampled_integral.iter().chain(self.held.iter());
        for x in values.chain([&self.sample_period]) {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }

    fn read_extra_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        if bytes.len() != 56 {
            return Err(format!(
                "the sampled law's state is {} bytes, 56 (7 doubles) expected",
                bytes.len()
            ));
        }
        let values: Vec<f64> = bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect();
        // The period first, checked as its setter checks it (the message names it).
        period_fraction(values[6], clocked::CLOCKS[0].period.name)?;
        if let Some(bad) = values[..6].iter().find(|x| !x.is_finite()) {
            return Err(format!("the sampled law's integral or output is {bad}"));
        }
        self.sampled_integral = Vector3::from_column_slice(&values[..3]);
        self.held = Vector3::from_column_slice(&values[3..6]);
        self.sample_period = values[6];
        Ok(())
    }
}

// The exported fmi2* and fmi3* symbols of this FMU.
export_fmu!(ComputedTorqueFmu);
