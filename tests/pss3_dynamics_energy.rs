//! Energy conservation with only conservative forces: gravity plus actuator springs
//! (integrated by DOP853 at a tight tolerance), and gravity plus undamped end stops
//! (integrated through the plant's own communication steps).

use nalgebra::Vector3;
use robofmu::ode::{self, Settings};
use robofmu::pss3::dynamics::{
    EndStopMode, EndStops, Method, Plant, PlantInputs, PlantParams, PlantState, StateVector,
    StepSettings, StopContact,
};
use robofmu::pss3::{Geometry, inverse_kinematics};

/// The plant driven by actuator springs f = -k (l - l0).
struct Springs<'a> {
    plant: &'a Plant,
    stiffness: f64,
    rest: Vector3<f64>,
}

impl Springs<'_> {
    fn forces(&self, state: &PlantState) -> Vector3<f64> {
        let l = self
            .plant
            .model()
            .terms(&state.euler, &state.omega)
            .unwrap()
            .assembly
            .l;
        -self.stiffness * (l - self.rest)
    }

    /// T + V_gravity + V_springs, and the actuator displacements.
    fn energy(&self, state: &PlantState) -> (f64, Vector3<f64>) {
        let model = self.plant.model();
        let terms = model.terms(&state.euler, &state.omega).unwrap();
        let stretch = terms.assembly.l - self.rest;
        let energy = terms.kinetic_energy(&state.omega)
            + model.potential_energy(&terms.assembly)
            + 0.5 * self.stiffness * stretch.norm_squared();
        (energy, terms.assembly.l)
    }

    fn rates(&self, y: &StateVector, dy: &mut StateVector) {
        let state = PlantState::from_vector(y);
        let inputs = PlantInputs {
            forces: self.forces(&state),
            ..PlantInputs::default()
        };
        let d = self.plant.derivative(&state, &inputs).unwrap();
        dy.fixed_rows_mut::<3>(0).copy_from(&d.euler_rates);
        dy.fixed_rows_mut::<3>(3).copy_from(&d.omega_dot);
    }
}

#[test]
fn gravity_and_actuator_springs_conserve_energy_over_10_s() {
    // Truth: with only conservative forces (gravity, springs f_i = -k (l_i - l0_i)),
    // no friction and no end-stop contact, T + V_gravity + V_springs is constant.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let start = Vector3::new(0.04, -0.03, 138f64.to_radians());
    let rest = inverse_kinematics(&Geometry::default(), &start).unwrap().l;
    let springs = Springs {
        plant: &plant,
        stiffness: 2e4,
        rest,
    };
    let state = PlantState {
        euler: start,
        omega: Vector3::new(0.5, -0.4, 0.8),
    };
    let (e0, _) = springs.energy(&state);
    let t0 = plant
        .model()
        .terms(&state.euler, &state.omega)
        .unwrap()
        .kinetic_energy(&state.omega);
    let settings = Settings {
        max_steps: 1_000_000,
        ..Settings::dop853(1e-13, 0.05)
    };
    let (mut drift, mut l_min, mut l_max) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    let mut observe = |y: &StateVector| {
        let (e, l) = springs.energy(&PlantState::from_vector(y));
        drift = drift.max((e - e0).abs());
        l_min = l_min.min(l.min());
        l_max = l_max.max(l.max());
    };
    observe(&state.to_vector());
    let end = ode::dop853_observed(
        |_t, y, dy| springs.rates(y, dy),
        0.0,
        10.0,
        state.to_vector(),
        &settings,
        |_t, y| observe(y),
    )
    .unwrap();
    println!(
        "{} steps, E0 = {e0:.6} J, T0 = {t0:.6} J, max |E - E0| = {drift:.2e} J \
         (relative to E0 {:.2e}, to T0 {:.2e}), l in [{:.2}, {:.2}] mm",
        end.stats.accepted,
        drift / e0,
        drift / t0,
        l_min * 1e3,
        l_max * 1e3
    );
    assert_eq!(end.x, 10.0);
    // Stays inside the stroke: the end stops never act.
    assert!(l_min > 0.002 && l_max < 0.152);
    assert!(drift / e0 < 1e-9 && drift / t0 < 1e-9);
}

#[test]
fn undamped_end_stops_conserve_energy_and_are_flagged() {
    // Truth: gravity and undamped stops (c = 0, potential k d^2 / 2) are conservative:
    // T + V_gravity + V_stops stays constant while the unforced platform turns into the
    // stops and rebounds. Measured through the plant's outputs after each
    // communication step (Dop853 at 1e-13).
    let params = PlantParams {
        end_stops: EndStops {
            damping: 0.0,
            ..EndStops::default()
        },
        ..PlantParams::default()
    };
    let plant = Plant::new(params).unwrap();
    let settings = StepSettings {
        method: Method::Dop853,
        tolerance: 1e-13,
        max_step: 1e-3,
        max_internal_steps: 1_000_000,
    };
    let inputs = PlantInputs::default();
    let mut state = plant
        .initial_state(
            Vector3::new(0.03, -0.02, 138f64.to_radians()),
            Vector3::new(0.1, 0.05, 2.0),
        )
        .unwrap();
    let energy = |s: &PlantState| {
        let o = plant.outputs(s, &inputs).unwrap();
        (o.kinetic_energy + o.potential_energy + o.end_stop_energy, o)
    };
    let (e0, _) = energy(&state);
    let (mut drift, mut upper, mut lower) = (0.0f64, 0, 0);
    for _ in 0..100 {
        state = plant.advance(&state, &inputs, 0.01, &settings).unwrap();
        let (e, outputs) = energy(&state);
        drift = drift.max((e - e0).abs());
        upper += outputs
            .end_stop_contacts
            .iter()
            .filter(|c| **c == StopContact::Upper)
            .count();
        lower += outputs
            .end_stop_contacts
            .iter()
            .filter(|c| **c == StopContact::Lower)
            .count();
    }
    println!(
        "E0 = {e0:.6} J, max |E - E0| = {drift:.2e} J ({:.2e} relative), \
         upper contacts {upper}, lower contacts {lower}",
        drift / e0
    );
    assert!(upper > 0 && lower > 0, "the run must hit both stops");
    assert!(drift / e0 < 1e-9);
}

#[test]
fn end_stops_in_error_mode_stop_the_run_cleanly() {
    // Truth: the same unforced run leaves the stroke within 0.1 s (the test above sees
    // a contact), so in mode Error a step fails with OutsideStroke and the last good
    // state stays within the stroke.
    let params = PlantParams {
        end_stops: EndStops {
            mode: EndStopMode::Error,
            ..EndStops::default()
        },
        ..PlantParams::default()
    };
    let plant = Plant::new(params).unwrap();
    let inputs = PlantInputs::default();
    let mut state = plant
        .initial_state(
            Vector3::new(0.03, -0.02, 138f64.to_radians()),
            Vector3::new(0.1, 0.05, 2.0),
        )
        .unwrap();
    let settings = StepSettings::default();
    let mut failure = None;
    for _ in 0..100 {
        match plant.advance(&state, &inputs, 0.01, &settings) {
            Ok(next) => state = next,
            Err(e) => {
                failure = Some(e);
                break;
            }
        }
    }
    let failure = failure.expect("the run must leave the stroke");
    let message = failure.to_string();
    println!("{message}");
    assert!(message.contains("outside its stroke"), "{message}");
    inverse_kinematics(&Geometry::default(), &state.euler).unwrap();
}
