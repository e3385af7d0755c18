//! Binding of the 3-PSS plant (`robofmu_dynamics::pss3::dynamics::Plant`) as the FMU "Pss3Plant":
//! Model Exchange and Co-Simulation.
//!
//! Continuous states: the Euler angles theta = (thx, thy, thz) and the angular velocity
//! omega in {A}, in that order. Euler angles because they are the thesis's and the
//! controller's coordinates and minimal; the workspace (|thy| < 12 deg) stays far from
//! their singularity at thy = +-90 deg. Inputs are held over a co-simulation step
//! (`Plant::advance`, adaptive Dormand-Prince 5(4)), or follow u + u' s + u'' s^2/2
//! when the master gave their first and second derivatives (`InputRamp`,
//! fmi2SetRealInputDerivatives); a commanded generalized force is held (or ramped)
//! in Euler-angle coordinates and mapped at the current orientation.
//!
//! Parameters are fixed: the plant is validated once at fmi2ExitInitializationMode and
//! an invalid value is refused with a message that names the FMU parameter.

mod initial_dependencies;
mod motion_cache;
mod output_rates;
mod parameters;
mod partials;
mod variables;

use nalgebra::Vector3;
use robofmu_dynamics::pss3::dynamics::{
    DynamicsError, InputRamp, Plant, PlantInputs, PlantOutputs, PlantParams, PlantState,
    StepSettings, StopContact,
};
use robofmu_dynamics::pss3::rotation::euler_rates;
use robofmu_dynamics::pss3::{FkOptions, assemble, forward_kinematics, start_pose};
use robofmu_fmi::prelude::*;

/// The geometry parameters that decide, with the start pose, whether the robot assembles.
const GEOMETRY: &str = "the geometry lp, ld, gamma, lb, alpha, beta, a";

static INFO: ModelInfo = ModelInfo {
    model_name: "Pss3Plant",
    model_identifier: "Pss3Plant",
    guid: "{66933d5c-c82b-4e7e-aaa5-b9c59a30f4c0}",
    description: "3-PSS spherical parallel robot: rigid-body dynamics of the platform, legs \
                  and sliders driven by actuator forces, commanded torques or Euler-angle \
                  generalized forces, with gravity, friction and end stops",
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 2.0,
        tolerance: 1e-8,
        step_size: 1e-3,
    },
    number_of_event_indicators: 6,
    log_categories: &[LOG],
};
const LOG: LogCategory = LogCategory::new(
    "logPlant",
    "Initial state and integration settings at initialization",
);

/// Displacement of every actuator in the default start pose, m: mid-stroke, 75 mm from
/// either end stop, so that a default run (an unstable equilibrium at rest) never drifts
/// onto a stop. At the stroke end itself, an ME integrator such as CVode drifts onto
/// the stiff stop and then tries poses that cannot assemble (seen with fmusim).
pub const START_DISPLACEMENT: f64 = 0.077;

/// The default start pose (theta0), rad: every actuator at `START_DISPLACEMENT`, i.e.
/// thx = thy = 0 and thz = 139.79 deg, the forward kinematics of the default geometry
/// ([`default_start_pose`], equal to it in a test), as a constant for the static table.
pub const START_POSE: [f64; 3] = [0.0, 0.0, 2.439784063985299];

/// How the initial state is given.
#[derive(Debug, Clone, Copy, PartialEq)]
struct InitialConditions {
    /// Initial Euler angles, rad (used unless `from_actuators`).
    theta0: Vector3<f64>,
    /// Take the initial pose from `l0` by forward kinematics.
    from_actuators: bool,
    /// Initial actuator displacements, m.
    l0: Vector3<f64>,
    /// Initial angular velocity in {A}, rad/s.
    omega0: Vector3<f64>,
}

/// Parameters, inputs and state of one plant instance.
#[derive(Clone)]
pub struct Pss3Plant {
    params: PlantParams,
    initial: InitialConditions,
    settings: StepSettings,
    inputs: PlantInputs,
    /// Derivatives of the inputs at the start of a step (zero: held).
    ramp: InputRamp,
    /// The plant of the parameters `built_from`, or why they are invalid.
    plant: Result<Plant, String>,
    built_from: Option<PlantParams>,
    /// The state; meaningful once `started` (after initialization).
    state: PlantState,
    started: bool,
    /// End-stop contacts as last updated at an event (ME) or after a step (CS).
    contacts: [StopContact; 3],
    /// Values computed by `calculate_values` for the current state and inputs, or why
    /// the model cannot be evaluated there.
    computed: Result<Computed, String>,
    /// The derivatives along the local motion of the last point asked for
    /// (`output_rates`).
    along: motion_cache::MotionCache,
}

/// Everything the outputs show, computed once per change.
#[derive(Clone)]
struct Computed {
    outputs: PlantOutputs,
    euler_rates: Vector3<f64>,
    gravity_compensation: Vector3<f64>,
}

/// Hysteresis of the contact flags, m: a contact begins `CONTACT_HYSTERESIS` beyond a
/// stroke end and ends as far inside, so that rounding at a stop edge (the default start
/// pose lies exactly on the lower one) cannot make the flags and events chatter. The
/// stop force itself acts from the edge on (1 nm: 1 mN at the default stiffness).
pub const CONTACT_HYSTERESIS: f64 = 1e-9;

/// Edges (lower, upper) at which the contact flag changes from `current`.
fn contact_edges(current: StopContact, (min, max): (f64, f64)) -> (f64, f64) {
    let lower = if current == StopContact::Lower {
        min + CONTACT_HYSTERESIS
    } else {
        min - CONTACT_HYSTERESIS
    };
    let upper = if current == StopContact::Upper {
        max - CONTACT_HYSTERESIS
    } else {
        max + CONTACT_HYSTERESIS
    };
    (lower, upper)
}

/// The contact flag at displacement `l` when it was `current`.
fn next_contact(current: StopContact, l: f64, stroke: (f64, f64)) -> StopContact {
    let (lower, upper) = contact_edges(current, stroke);
    if l < lower {
        StopContact::Lower
    } else if l > upper {
        StopContact::Upper
    } else {
        StopContact::Free
    }
}

/// The default start pose: every actuator at `START_DISPLACEMENT`, by forward
/// kinematics of the default geometry (thx = thy = 0, thz = 139.79 deg).
pub fn default_start_pose() -> Vector3<f64> {
    let plant = Plant::new(PlantParams::default());
    plant
        .ok()
        .and_then(|p| {
            forward_kinematics(
                &p.model().geometry,
                &Vector3::repeat(START_DISPLACEMENT),
                &start_pose(),
                &FkOptions::default(),
            )
            .ok()
        })
        // Equal displacements tilt nothing (3-fold symmetry): thx = thy = 0 exactly;
        // forward kinematics supplies the roll.
        .map_or_else(start_pose, |s| Vector3::new(0.0, 0.0, s.assembly.euler.z))
}

impl Pss3Plant {
    /// Rebuilds the plant after a parameter was written, if the parameters changed (a
    /// write of a parameter's current value, as every start value at instantiation,
    /// rebuilds nothing: the plant is a function of the parameters).
    fn rebuild(&mut self) {
        if self.built_from != Some(self.params) {
            self.plant = Plant::new(self.params).map_err(|e| parameters::fmu_message(&e));
            self.built_from = Some(self.params);
        }
    }

    /// After a parameter is set: the plant rebuilt.
    fn changed(&mut self, _: usize) {
        self.rebuild();
    }

    fn plant(&self) -> Result<&Plant, String> {
        self.plant.as_ref().map_err(Clone::clone)
    }

    /// The initial state from theta0 (or l0) and omega0, checked.
    /// The initial state from theta0 or l0. A failure names the start values and the
    /// geometry parameters together: whether a pose assembles depends on both.
    fn initial_state(&self) -> Result<PlantState, String> {
        let plant = self.plant()?;
        let (euler, source) = if self.initial.from_actuators {
            let solution = forward_kinematics(
                &plant.model().geometry,
                &self.initial.l0,
                &start_pose(),
                &FkOptions::default(),
            )
            .map_err(|e| {
                format!("l0: no initial pose for these actuator displacements with {GEOMETRY}: {e}")
            })?;
            (solution.assembly.euler, parameters::L0.name)
        } else {
            (self.initial.theta0, parameters::THETA0.name)
        };
        plant
            .initial_state(euler, self.initial.omega0)
            .map_err(|e| format!("{source}: the initial state is invalid with {GEOMETRY}: {e}"))
    }

    /// The state: the initial one until initialization ends.
    fn current_state(&self) -> Result<PlantState, String> {
        if self.started {
            Ok(self.state)
        } else {
            self.initial_state()
        }
    }

    /// Computes the outputs, Euler-angle rates and gravity compensation of the
    /// current state and inputs.
    fn compute(&self) -> Result<Computed, String> {
        self.compute_at(&self.current_state()?)
    }

    /// `compute` at `state` instead of the current state (same inputs).
    fn compute_at(&self, state: &PlantState) -> Result<Computed, String> {
        let state = *state;
        let plant = self.plant()?;
        let outputs = plant
            .outputs(&state, &self.inputs)
            .map_err(|e| e.to_string())?;
        // The rates alone: E^-1 omega, not a second evaluation of the dynamics.
        let euler_rates = euler_rates(&state.euler, &state.omega).map_err(|e| e.to_string())?;
        let gravity_compensation = plant
            .gravity_compensation(&state.euler)
            .map_err(|e| e.to_string())?;
        Ok(Computed {
            outputs,
            euler_rates,
            gravity_compensation,
        })
    }

    /// One computed value, NaN when the model could not be evaluated (the layer
    /// returns Discard with the reason before any getter runs in that case).
    fn computed(&self, f: impl Fn(&Computed) -> f64) -> f64 {
        self.computed.as_ref().map_or(f64::NAN, f)
    }

    /// One component of the computed outputs.
    fn output(&self, f: impl Fn(&PlantOutputs) -> f64) -> f64 {
        self.computed(|c| f(&c.outputs))
    }

    /// Actuator displacements l of the current state.
    fn displacements(&self) -> Result<Vector3<f64>, String> {
        let state = self.current_state()?;
        assemble(&self.plant()?.model().geometry, &state.euler)
            .map(|a| a.l)
            .map_err(|e| e.to_string())
    }

    /// Stroke [min, max], m.
    fn stroke(&self) -> (f64, f64) {
        let g = &self.params.geometry;
        (g.stroke_min, g.stroke_max)
    }

    /// Contacts after an event or a step (kept as they were if the state cannot be
    /// evaluated).
    fn refresh_contacts(&mut self) {
        if let Ok(l) = self.displacements() {
            for i in 0..3 {
                self.contacts[i] = next_contact(self.contacts[i], l[i], self.stroke());
            }
        }
    }

    /// The contact flag of actuator `i`: the stored one once started.
    fn contact(&self, i: usize) -> i32 {
        if self.started {
            self.contacts[i].code()
        } else {
            self.displacements()
                .map_or(StopContact::Free, |l| {
                    next_contact(StopContact::Free, l[i], self.stroke())
                })
                .code()
        }
    }

    fn check_settings(&self) -> Result<(), String> {
        let StepSettings {
            tolerance,
            max_step,
            ..
        } = self.settings;
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(format!(
                "parameter tolerance = {tolerance} must be positive"
            ));
        }
        if !(max_step.is_finite() && max_step > 0.0) {
            return Err(format!("parameter maxStep = {max_step} must be positive"));
        }
        Ok(())
    }
}

impl Default for Pss3Plant {
    fn default() -> Self {
        let params = PlantParams::default();
        let mut model = Pss3Plant {
            params,
            initial: InitialConditions {
                theta0: Vector3::from(START_POSE),
                from_actuators: false,
                l0: Vector3::repeat(START_DISPLACEMENT),
                omega0: Vector3::zeros(),
            },
            settings: StepSettings {
                max_step: 1e-3,
                ..StepSettings::default()
            },
            inputs: PlantInputs::default(),
            ramp: InputRamp::default(),
            plant: Err("not built yet".to_string()),
            built_from: None,
            state: PlantState {
                euler: Vector3::zeros(),
                omega: Vector3::zeros(),
            },
            started: false,
            contacts: [StopContact::Free; 3],
            computed: Err("not computed yet".to_string()),
            along: motion_cache::MotionCache::default(),
        };
        model.rebuild();
        model
    }
}

impl Model for Pss3Plant {
    const INFO: &'static ModelInfo = &INFO;

    const VARIABLES: &'static [Declaration<Self>] = &variables::VARIABLES;
    fn set_time(&mut self, _time: f64) {
        // The plant is time invariant.
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        self.plant()?;
        self.check_settings()?;
        self.state = self.initial_state()?;
        self.started = true;
        self.refresh_contacts();
        log.debug(
            LOG.name,
            &format!(
                "initial state theta = {:?} rad, omega = {:?} rad/s; {:?}",
                self.state.euler.as_slice(),
                self.state.omega.as_slice(),
                self.settings
            ),
        );
        Ok(())
    }

    fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
        let plant = match self.plant() {
            Ok(p) => p,
            Err(reason) => {
                return StepOutcome::Discarded {
                    reason,
                    terminate: true,
                };
            }
        };
        let (inputs, ramp) = (&self.inputs, &self.ramp);
        match plant.advance_with_ramp(&self.state, inputs, ramp, step, &self.settings) {
            Ok(state) => {
                self.state = state;
                self.refresh_contacts();
                StepOutcome::Completed
            }
            Err(e) => StepOutcome::Discarded {
                reason: e.to_string(),
                // A solver failure may pass with a smaller step or other inputs; a
                // state or input the model cannot evaluate at all cannot go on.
                terminate: !matches!(e, DynamicsError::Solver { .. }),
            },
        }
    }

    const MAX_INPUT_DERIVATIVE_ORDER: u32 = 2;

    /// FMI 3.0 intermediate update: with a callback, each communication step is split
    /// into 10 equal sub-intervals, and the importer may set the continuous inputs at
    /// the 9 inner points (held over the next sub-interval).
    const INTERMEDIATE_UPDATE_POINTS: u32 = 10;

    fn calculate_values(&mut self) -> Result<(), String> {
        self.computed = self.compute();
        self.computed.as_ref().map(|_| ()).map_err(Clone::clone)
    }

    fn continuous_states(&mut self, x: &mut [f64]) {
        x.copy_from_slice(self.state.to_vector().as_slice());
    }

    fn set_continuous_states(&mut self, x: &[f64]) {
        self.state = PlantState::from_vector(
            &robofmu_dynamics::pss3::dynamics::StateVector::from_column_slice(x),
        );
    }

    fn derivatives(&self, dx: &mut [f64]) -> Result<(), String> {
        let d = self
            .plant()?
            .derivative(&self.state, &self.inputs)
            .map_err(|e| e.to_string())?;
        dx[..3].copy_from_slice(d.euler_rates.as_slice());
        dx[3..].copy_from_slice(d.omega_dot.as_slice());
        Ok(())
    }

    /// Per actuator i: l_i - lower edge and upper edge - l_i, the edges of
    /// `contact_edges` (a sign change is a change of `atStop[i]`).
    fn event_indicators(&self, z: &mut [f64]) -> Result<(), String> {
        let l = self.displacements()?;
        for i in 0..3 {
            let (lower, upper) = contact_edges(self.contacts[i], self.stroke());
            z[2 * i] = l[i] - lower;
            z[2 * i + 1] = upper - l[i];
        }
        Ok(())
    }

    /// The contacts change; the continuous states never jump (the stops are springs).
    fn update_discrete_states(&mut self) -> EventUpdate {
        self.refresh_contacts();
        EventUpdate::default()
    }

    const JACOBIAN: Option<Jacobian<Self>> =
        Some(Jacobian::Directional(partials::directional_derivative));

    fn write_extra_state(&self, out: &mut Vec<u8>) {
        out.push(self.started as u8);
        out.extend(self.contacts.iter().map(|c| c.code() as i8 as u8));
    }

    fn read_extra_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        let [started, c1, c2, c3] = bytes else {
            return Err(format!("{} extra bytes, expected 4", bytes.len()));
        };
        self.started = match started {
            0 => false,
            1 => true,
            b => return Err(format!("started flag {b} is neither 0 nor 1")),
        };
        for (contact, &byte) in self.contacts.iter_mut().zip([c1, c2, c3]) {
            *contact = match byte as i8 {
                -1 => StopContact::Lower,
                0 => StopContact::Free,
                1 => StopContact::Upper,
                b => return Err(format!("contact flag {b} is not -1, 0 or 1")),
            };
        }
        Ok(())
    }
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Pss3Plant);
