//! The Kane (omega) formulation against independent truths: Lagrange's equations with
//! exact dual-number derivatives of the body positions, the E-map relations between the
//! omega and Euler-angle forms, and the spectral properties of M over the workspace.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use robofmu::pss3::dynamics::lagrange::{AppliedLoads, lagrange_form, lagrange_generalized_force};
use robofmu::pss3::dynamics::{
    Friction, Inertia, Plant, PlantInputs, PlantParams, PlantState, euler_generalized_force,
};
use robofmu::pss3::rotation::{euler_accelerations, euler_rate_matrix, euler_rates};
use robofmu::pss3::{Geometry, inverse_kinematics};

fn deg(v: [f64; 3]) -> Vector3<f64> {
    Vector3::from(v).map(f64::to_radians)
}

/// Poses inside the stroke box with fast, mixed motion and loads.
fn cases() -> Vec<(PlantState, PlantInputs)> {
    let poses = [
        deg([0.0, 0.0, 138.0]),
        deg([6.0, -5.0, 137.0]),
        deg([-6.0, 3.0, 135.0]),
        deg([2.0, 6.0, 140.0]),
    ];
    let omegas = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(0.8, -1.1, 0.6),
        Vector3::new(-2.0, 0.4, -1.5),
        Vector3::new(0.3, 1.7, 2.2),
    ];
    let inputs = PlantInputs {
        forces: Vector3::new(35.0, -12.0, 20.0),
        disturbance_torque: Vector3::new(0.4, -0.7, 1.2),
        commanded_torque: Vector3::zeros(),
        generalized_force: Vector3::zeros(),
    };
    let geometry = Geometry::default();
    for euler in &poses {
        // Within the stroke, so that the end stops (absent from the loads) are idle.
        inverse_kinematics(&geometry, euler).unwrap();
    }
    poses
        .iter()
        .zip(omegas)
        .map(|(euler, omega)| {
            (
                PlantState {
                    euler: *euler,
                    omega,
                },
                inputs,
            )
        })
        .collect()
}

fn relative(a: &Matrix3<f64>, b: &Matrix3<f64>) -> f64 {
    (a - b).amax() / b.amax()
}

fn relative_vec(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    (a - b).amax() / b.amax().max(1e-300)
}

#[test]
fn kane_and_lagrange_formulations_agree_to_1e9() {
    // Truth: Lagrange's equations in Euler angles, every derivative exact (nested dual
    // numbers) from the body positions of the closed-form IK, independent of J, E and
    // the velocity kinematics of the Kane formulation. Friction is on to check its
    // generalized force too.
    // A second parameter set exercises a full platform tensor, an off-axis centre of
    // mass, an off-centre leg centre of mass and a tilted gravity vector.
    let skewed = PlantParams {
        inertia: Inertia {
            platform_com: Vector3::new(0.004, -0.003, 0.02),
            platform_inertia: Matrix3::new(
                0.0125, 0.0005, -0.0003, 0.0005, 0.0118, 0.0004, -0.0003, 0.0004, 0.0229,
            ),
            leg_com_fraction: 0.42,
            ..Inertia::default()
        },
        gravity: Vector3::new(0.5, -0.3, -9.7),
        ..PlantParams::default()
    };
    let mut worst: f64 = 0.0;
    for base in [PlantParams::default(), skewed] {
        let params = PlantParams {
            friction: Friction {
                slider: 15.0,
                pivot: 0.2,
            },
            ..base
        };
        worst = worst.max(worst_disagreement(&Plant::new(params).unwrap()));
    }
    println!("worst relative disagreement {worst:.2e}");
    assert!(worst < 1e-9, "worst relative disagreement {worst:.2e}");
}

/// Largest relative difference between the Kane and Lagrange terms over `cases()`.
fn worst_disagreement(plant: &Plant) -> f64 {
    let model = plant.model();
    let mut worst: f64 = 0.0;
    for (state, inputs) in cases() {
        let rates = euler_rates(&state.euler, &state.omega).unwrap();
        let kane = model.euler_angle_form(&state.euler, &rates).unwrap();
        let lagrange = lagrange_form(model, &state.euler, &rates).unwrap();
        let mass_error = relative(&kane.mass, &lagrange.mass);
        // G vanishes at the symmetric pose and C x_dot at rest: compare relative to the
        // platform's largest gravity moment m_p |g| |c| = 0.154 N m when smaller.
        let floor = 0.80057 * 9.81 * 0.01955;
        let gravity_error =
            (kane.gravity - lagrange.gravity).amax() / lagrange.gravity.amax().max(floor);
        let velocity_error =
            (kane.velocity - lagrange.velocity).amax() / lagrange.velocity.amax().max(floor);

        // Accelerations: the plant (omega form with friction, mapped to Euler angles)
        // against Lagrange's equations solved for the Euler-angle accelerations.
        let omega_dot = plant.derivative(&state, &inputs).unwrap().omega_dot;
        let x_ddot = euler_accelerations(&state.euler, &rates, &omega_dot).unwrap();
        let loads = AppliedLoads {
            actuator_forces: inputs.forces,
            platform_torque: inputs.disturbance_torque,
            slider_friction: 15.0,
            pivot_friction: 0.2,
        };
        let force = lagrange_generalized_force(model, &state.euler, &rates, &loads).unwrap();
        let x_ddot_lagrange = lagrange.accelerations(&force).unwrap();
        let acceleration_error = relative_vec(&x_ddot, &x_ddot_lagrange);
        println!(
            "M {mass_error:.1e}  C x_dot {velocity_error:.1e}  G {gravity_error:.1e}  \
             x_ddot {acceleration_error:.1e}"
        );
        for e in [
            mass_error,
            velocity_error,
            gravity_error,
            acceleration_error,
        ] {
            worst = worst.max(e);
        }
    }
    worst
}

#[test]
fn euler_angle_form_is_the_omega_form_through_e() {
    // Truth: omega = E x_dot, omega_dot = E x_ddot + E_dot x_dot and power balance
    // F = E^T Q: solving the Euler-angle form must give the plant's omega_dot mapped
    // by the core library's euler_accelerations; also M_x = E^T M E exactly.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let model = plant.model();
    for (state, inputs) in cases() {
        let rates = euler_rates(&state.euler, &state.omega).unwrap();
        let form = model.euler_angle_form(&state.euler, &rates).unwrap();
        let terms = model.terms(&state.euler, &state.omega).unwrap();
        let moment = terms.jacobian.torque(&inputs.forces) + inputs.disturbance_torque;
        let x_ddot = form
            .accelerations(&euler_generalized_force(&state.euler, &moment))
            .unwrap();
        let omega_dot = plant.derivative(&state, &inputs).unwrap().omega_dot;
        let expected = euler_accelerations(&state.euler, &rates, &omega_dot).unwrap();
        assert!(
            relative_vec(&x_ddot, &expected) < 1e-12,
            "{x_ddot} vs {expected}"
        );
        let e = euler_rate_matrix(&state.euler);
        assert!(relative(&form.mass, &(e.transpose() * terms.mass * e)) < 1e-15);
        // Kinetic energy is the same in both coordinates.
        let t_omega = terms.kinetic_energy(&state.omega);
        let t_euler = 0.5 * rates.dot(&(form.mass * rates));
        assert!((t_omega - t_euler).abs() <= 1e-14 * t_omega.max(1e-300));
    }
}

#[test]
fn mass_matrix_is_symmetric_positive_definite_over_the_workspace() {
    // Truth: M = sum A^T m A with a positive definite platform tensor is SPD; sampled
    // on a grid over the spec's workspace bounding box, keeping poses within the
    // stroke (inverse kinematics with stroke check).
    let plant = Plant::new(PlantParams::default()).unwrap();
    let geometry = Geometry::default();
    let (mut count, mut min_eigen, mut worst_asymmetry) = (0, f64::INFINITY, 0.0f64);
    for ix in 0..=12 {
        for iy in 0..=12 {
            for iz in 0..=16 {
                let euler = deg([
                    -14.0 + 28.0 * f64::from(ix) / 12.0,
                    -12.0 + 24.0 * f64::from(iy) / 12.0,
                    121.0 + 35.0 * f64::from(iz) / 16.0,
                ]);
                if inverse_kinematics(&geometry, &euler).is_err() {
                    continue;
                }
                let m = plant.model().terms(&euler, &Vector3::zeros()).unwrap().mass;
                worst_asymmetry = worst_asymmetry.max((m - m.transpose()).amax() / m.amax());
                min_eigen = min_eigen.min(SymmetricEigen::new(m).eigenvalues.min());
                count += 1;
            }
        }
    }
    println!(
        "{count} poses: min eigenvalue {min_eigen:.4e} kg m^2, asymmetry {worst_asymmetry:.1e}"
    );
    assert!(count > 300, "only {count} poses inside the stroke");
    assert!(worst_asymmetry <= 1e-15);
    // The platform alone contributes its smallest principal moment about P, 0.011824.
    assert!(min_eigen > 0.011824, "min eigenvalue {min_eigen}");
}
