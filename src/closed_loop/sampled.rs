//! The loop with a sampled controller: the PID or the computed-torque law evaluated only
//! at ticks of a clock (robofmu_control::sampled::SampleClock, tick k at start +
//! k Ts from an integer counter, no drift), its output held between ticks (zero-order
//! hold), the plant integrated with Dop853 from tick to tick under the held output.
//! The reference for a co-simulation of a clocked controller beside the continuous
//! plant; the continuous loop (`simulate`) is unchanged.
//!
//! At a tick the controller samples the planned motion and the plant's angles, rates
//! and gravity compensation at that instant, and its new output drives the plant from
//! there on. Samples are taken at the communication points, which must fall on ticks
//! (the step size an integer multiple of the period); a sample's controller output is
//! the one its tick computed (the value held after the tick).

use super::controller::Controller;
use super::error::LoopError;
use super::scenario::LoopSpec;
use super::simulate::{LoopSample, pid_inputs};
use crate::computed_torque::{Inputs, SampledComputedTorque};
use crate::control::pid::PidGains;
use crate::control::sampled::{SampleClock, SampledPid};
use crate::control::trajectory::Sample;
use crate::ode::{self, Settings};
use crate::pss3::dynamics::{DynamicsError, Plant, PlantInputs, PlantState};
use crate::pss3::rotation::euler_rates;
use nalgebra::{SVector, Vector3};

/// t, theta (3), omega (3): the controller's state is discrete.
type PlantVector = SVector<f64, 7>;

/// A sampled controller with its state (both boxed: one allocation per run).
enum Sampled {
    Pid(Box<[SampledPid; 3]>),
    ComputedTorque(Box<SampledComputedTorque>),
}

fn scenario_error(message: String) -> LoopError {
    LoopError::Scenario(message)
}

impl Sampled {
    fn new(controller: &Controller, period: f64) -> Result<Self, LoopError> {
        match controller {
            Controller::Pid([a, b, c]) => {
                let channel = |g: &PidGains| {
                    SampledPid::new(*g, period).map_err(|e| scenario_error(e.to_string()))
                };
                Ok(Self::Pid(Box::new([channel(a)?, channel(b)?, channel(c)?])))
            }
            Controller::ComputedTorque(law) => {
                let sampled = SampledComputedTorque::new((**law).clone(), period)
                    .map_err(|e| scenario_error(e.to_string()))?;
                Ok(Self::ComputedTorque(Box::new(sampled)))
            }
        }
    }
}

fn plant_state(y: &PlantVector) -> PlantState {
    PlantState {
        euler: y.fixed_rows::<3>(1).into_owned(),
        omega: y.fixed_rows::<3>(4).into_owned(),
    }
}

/// Ticks the controller at the state y (time y[0]): its new output and the loop's
/// signals there.
fn tick(
    spec: &LoopSpec,
    plant: &Plant,
    controller: &mut Sampled,
    y: &PlantVector,
) -> Result<LoopSample, LoopError> {
    let time = y[0];
    let state = plant_state(y);
    let trajectories = spec.trajectories_at(time);
    let planned: [Sample; 3] = std::array::from_fn(|i| trajectories[i].sample(time));
    let planned_vector = |f: fn(&Sample) -> f64| Vector3::from_fn(|i, _| f(&planned[i]));
    let theta_dot = euler_rates(&state.euler, &state.omega).map_err(DynamicsError::from)?;
    let gravity_compensation = plant.gravity_compensation(&state.euler)?;
    let u = match controller {
        Sampled::Pid(channels) => Vector3::from_fn(|axis, _| {
            let inputs = pid_inputs(axis, &planned, &state, &theta_dot, &gravity_compensation);
            channels[axis].tick(&inputs).u
        }),
        Sampled::ComputedTorque(law) => {
            let inputs = Inputs {
                setpoint: planned_vector(|s| s.q),
                setpoint_rate: planned_vector(|s| s.qdot),
                setpoint_acceleration: planned_vector(|s| s.qddot),
                measurement: state.euler,
                measured_rate: theta_dot,
            };
            law.tick(&inputs)?.u
        }
    };
    let outputs = plant.outputs(&state, &held(&u))?;
    Ok(LoopSample {
        time,
        q: planned_vector(|s| s.q),
        qdot: planned_vector(|s| s.qdot),
        qddot: planned_vector(|s| s.qddot),
        theta: state.euler,
        theta_dot,
        omega: state.omega,
        omega_dot: outputs.omega_dot,
        gravity_compensation,
        u,
        force: outputs.actuator_forces,
        l: outputs.actuator_displacements,
    })
}

fn held(u: &Vector3<f64>) -> PlantInputs {
    PlantInputs {
        generalized_force: *u,
        ..PlantInputs::default()
    }
}

/// Integrates the plant under the held output `u` from y over h; returns the end
/// state (time as the first state, t' = 1, as the continuous loop).
fn advance(
    plant: &Plant,
    u: &Vector3<f64>,
    y: &PlantVector,
    h: f64,
    tolerance: f64,
) -> Result<PlantVector, LoopError> {
    let inputs = held(u);
    let mut error = None;
    let rhs = |_s: f64, y: &PlantVector, dy: &mut PlantVector| {
        if y.iter().any(|v| !v.is_finite()) {
            dy.fill(f64::NAN);
            return;
        }
        match plant.derivative(&plant_state(y), &inputs) {
            Ok(d) => {
                dy[0] = 1.0;
                dy.fixed_rows_mut::<3>(1).copy_from(&d.euler_rates);
                dy.fixed_rows_mut::<3>(4).copy_from(&d.omega_dot);
            }
            Err(e) => {
                error = Some(e);
                dy.fill(f64::NAN);
            }
        }
    };
    let settings = Settings {
        max_steps: 1_000_000,
        ..Settings::dop853(tolerance, h)
    };
    let outcome = ode::dop853(rhs, 0.0, h, *y, &settings);
    let fail = |message: String| LoopError::Integration {
        time: y[0],
        message,
    };
    if let Some(e) = error {
        return Err(fail(e.to_string()));
    }
    let end = outcome.map_err(|e| fail(e.to_string()))?.y;
    if end.iter().any(|v| !v.is_finite()) {
        return Err(fail("the state became non-finite".into()));
    }
    Ok(end)
}

/// Ticks per communication step: the step size over the period, which must be a
/// whole number (within 1e-9 relative).
fn ticks_per_step(step_size: f64, period: f64) -> Result<u64, LoopError> {
    let ratio = step_size / period;
    let n = ratio.round();
    if !(n >= 1.0 && (ratio - n).abs() <= 1e-9 * n) {
        return Err(scenario_error(format!(
            "the step size {step_size} s is not a whole number of sample periods {period} s"
        )));
    }
    Ok(n as u64)
}

/// Simulates the loop of `spec` with its controller sampled every `period` seconds
/// (ticks from the start time), the plant integrated between ticks with relative and
/// absolute tolerance `tolerance`; sampled at every communication point.
pub fn simulate_sampled(
    spec: &LoopSpec,
    period: f64,
    tolerance: f64,
) -> Result<Vec<LoopSample>, LoopError> {
    let clock = SampleClock::from_period(spec.start_time, period)
        .map_err(|e| scenario_error(e.to_string()))?;
    let per_step = ticks_per_step(spec.step_size, period)?;
    let steps = ((spec.stop_time - spec.start_time) / spec.step_size).round() as u64;
    let mut controller = Sampled::new(&spec.controller, clock.period())?;
    let plant = Plant::new(spec.plant)?;
    let initial = plant.initial_state(spec.theta0, spec.omega0)?;
    let mut y = PlantVector::zeros();
    y[0] = clock.tick_time(0);
    y.fixed_rows_mut::<3>(1).copy_from(&initial.euler);
    y.fixed_rows_mut::<3>(4).copy_from(&initial.omega);
    let ticks = steps * per_step;
    let mut samples = Vec::with_capacity(steps as usize + 1);
    for k in 0..=ticks {
        let at_tick = tick(spec, &plant, &mut controller, &y)?;
        if k % per_step == 0 {
            samples.push(at_tick.clone());
        }
        if k < ticks {
            let next = clock.tick_time(k + 1);
            y = advance(&plant, &at_tick.u, &y, next - y[0], tolerance)?;
            y[0] = next;
        }
    }
    Ok(samples)
}
