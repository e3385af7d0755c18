//! Position, velocity and acceleration kinematics of the 3-PSS robot checked against
//! independent truths: round trips through closed-form IK, finite differences and the
//! power balance of the statics. Random points come from a fixed-seed splitmix64.

use nalgebra::{Matrix3, Vector3};
use robofmu::pss3::rotation::{angular_acceleration, euler_rate_matrix, rotation};
use robofmu::pss3::{
    ActuatorState, FkOptions, Geometry, KinematicsError, assemble, forward_kinematics,
    forward_motion, inverse_kinematics, inverse_motion, jacobian, start_pose, velocity_product,
};

/// splitmix64: a tiny deterministic generator, enough to spread test points.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn between(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn vector(&mut self, lo: f64, hi: f64) -> Vector3<f64> {
        Vector3::new(
            self.between(lo, hi),
            self.between(lo, hi),
            self.between(lo, hi),
        )
    }

    /// Actuator displacements anywhere in the stroke box, m.
    fn stroke_point(&mut self, g: &Geometry) -> Vector3<f64> {
        self.vector(g.params.stroke_min, g.params.stroke_max)
    }
}

/// FK of random actuator positions, each from the default start pose.
fn random_poses(count: usize, seed: u64) -> Vec<robofmu::pss3::Assembly> {
    let g = Geometry::default();
    let mut rng = Random(seed);
    (0..count)
        .map(|_| {
            let l = rng.stroke_point(&g);
            forward_kinematics(&g, &l, &start_pose(), &FkOptions::default())
                .unwrap()
                .assembly
        })
        .collect()
}

#[test]
fn ik_after_fk_returns_the_actuator_displacements() {
    // Truth: the closed-form IK of the FK result must give back the input l.
    let g = Geometry::default();
    let mut rng = Random(1);
    for _ in 0..500 {
        let l = rng.stroke_point(&g);
        let fk = forward_kinematics(&g, &l, &start_pose(), &FkOptions::default()).unwrap();
        let back = inverse_kinematics(&g, &fk.assembly.euler).unwrap().l;
        assert!((back - l).amax() < 1e-12, "l = {l}, IK(FK(l)) = {back}");
    }
}

#[test]
fn fk_after_ik_returns_the_orientation() {
    // Truth: the orientation fed to closed-form IK, recovered by FK from the start pose.
    let g = Geometry::default();
    let mut rng = Random(2);
    let mut checked = 0;
    while checked < 500 {
        let euler = Vector3::new(
            rng.between(-0.2, 0.2),
            rng.between(-0.2, 0.2),
            rng.between(2.13, 2.69),
        );
        let Ok(ik) = inverse_kinematics(&g, &euler) else {
            continue; // outside the strokes
        };
        let fk = forward_kinematics(&g, &ik.l, &start_pose(), &FkOptions::default()).unwrap();
        assert!(
            (fk.assembly.euler - euler).amax() < 1e-12,
            "{euler} -> {}",
            fk.assembly.euler
        );
        checked += 1;
    }
}

#[test]
fn jacobian_matches_finite_differences_of_ik_everywhere() {
    // Truth: central differences of closed-form IK along random Euler rates, with
    // omega = E th_dot; relative error 1e-7.
    let g = Geometry::default();
    let mut rng = Random(3);
    for pose in random_poses(200, 4) {
        let rates = rng.vector(-1.0, 1.0);
        let h = 1e-6;
        let l = |s: f64| assemble(&g, &(pose.euler + s * rates)).unwrap().l;
        let fd = (l(h) - l(-h)) / (2.0 * h);
        let omega = euler_rate_matrix(&pose.euler) * rates;
        let l_dot = jacobian(&g, &pose).unwrap().actuator_rates(&omega);
        assert!((l_dot - fd).norm() < 1e-7 * l_dot.norm(), "{l_dot} vs {fd}");
    }
}

#[test]
fn e_matches_finite_differences_of_r_everywhere() {
    // Truth: the skew matrix R_dot R^T of central differences of R equals [omega]x.
    let mut rng = Random(5);
    for _ in 0..200 {
        let (euler, rates) = (rng.vector(-1.4, 1.4), rng.vector(-2.0, 2.0));
        let h = 1e-6;
        let r_dot = (rotation(&(euler + h * rates)) - rotation(&(euler - h * rates))) / (2.0 * h);
        let w: Matrix3<f64> = r_dot * rotation(&euler).transpose();
        let fd = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
        let omega = euler_rate_matrix(&euler) * rates;
        assert!((omega - fd).norm() < 1e-8 * omega.norm().max(1.0));
        assert!((w + w.transpose()).amax() < 1e-8, "R_dot R^T is skew");
    }
}

#[test]
fn statics_balance_power_everywhere() {
    // Truth: virtual power, f.l_dot = tau.omega with l_dot = J omega and tau = J^T f.
    let g = Geometry::default();
    let mut rng = Random(6);
    for pose in random_poses(200, 7) {
        let j = jacobian(&g, &pose).unwrap();
        let (f, omega) = (rng.vector(-100.0, 100.0), rng.vector(-2.0, 2.0));
        let tau = j.torque(&f);
        let power = f.dot(&j.actuator_rates(&omega));
        assert!((power - tau.dot(&omega)).abs() < 1e-12 * f.norm() * omega.norm());
        // f = J^-T tau inverts tau = J^T f.
        assert!((j.forces(&tau).unwrap() - f).norm() < 1e-10 * f.norm());
    }
}

#[test]
fn velocity_product_is_j_dot_omega() {
    // Truth: central differences of J along a motion with constant Euler rates, times
    // omega; and central second differences of closed-form IK for l_ddot.
    let g = Geometry::default();
    let mut rng = Random(8);
    for pose in random_poses(100, 9) {
        let rates = rng.vector(-1.0, 1.0);
        let at = |s: f64| assemble(&g, &(pose.euler + s * rates)).unwrap();
        let j_at = |s: f64| jacobian(&g, &at(s)).unwrap().matrix;
        let h = 1e-5;
        let omega = euler_rate_matrix(&pose.euler) * rates;
        let j = jacobian(&g, &pose).unwrap();
        let l_dot = j.actuator_rates(&omega);
        let c = velocity_product(&g, &pose, &j, &omega, &l_dot);
        let j_dot_omega = (j_at(h) - j_at(-h)) / (2.0 * h) * omega;
        assert!(
            (c - j_dot_omega).norm() < 1e-7 * c.norm(),
            "{c} vs {j_dot_omega}"
        );

        let omega_dot = angular_acceleration(&pose.euler, &rates, &Vector3::zeros());
        let motion = inverse_motion(&g, &pose.euler, &omega, &omega_dot).unwrap();
        let h = 1e-4;
        let l_ddot_fd = (at(h).l - 2.0 * pose.l + at(-h).l) / (h * h);
        assert!((motion.l_ddot - l_ddot_fd).norm() < 1e-6 * motion.l_ddot.norm());
    }
}

#[test]
fn forward_motion_matches_finite_differences_of_position_fk() {
    // Truth: Euler angles from position FK along l(t) = l0 + v t + a t^2 / 2, central
    // differences give th_dot and th_ddot, mapped to omega = E th_dot and
    // omega_dot = E th_ddot + E_dot th_dot.
    let g = Geometry::default();
    let mut rng = Random(10);
    let options = FkOptions::default();
    for _ in 0..100 {
        let l0 = rng.vector(0.02, 0.13);
        let (v, a) = (rng.vector(-0.1, 0.1), rng.vector(-0.5, 0.5));
        let l = |t: f64| l0 + v * t + a * (t * t / 2.0);
        let th = |t: f64| {
            forward_kinematics(&g, &l(t), &start_pose(), &options)
                .unwrap()
                .assembly
                .euler
        };
        let actuators = ActuatorState {
            l: l0,
            l_dot: v,
            l_ddot: a,
        };
        let motion = forward_motion(&g, &actuators, &start_pose(), &options).unwrap();
        let h = 1e-4;
        let (before, now, after) = (th(-h), th(0.0), th(h));
        let rates = (after - before) / (2.0 * h);
        let accelerations = (after - 2.0 * now + before) / (h * h);
        let omega = euler_rate_matrix(&now) * rates;
        let omega_dot = angular_acceleration(&now, &rates, &accelerations);
        assert!((motion.omega - omega).norm() < 1e-7 * omega.norm(), "omega");
        assert!(
            (motion.omega_dot - omega_dot).norm() < 1e-5 * omega_dot.norm().max(1e-2),
            "{} vs {omega_dot}",
            motion.omega_dot
        );
        assert!((motion.euler_rates().unwrap() - rates).norm() < 1e-7 * rates.norm());
    }
}

#[test]
fn inverse_motion_inverts_forward_motion() {
    // Truth: the forward motion's omega and omega_dot fed back through the inverse
    // relations must reproduce the actuator rates and accelerations.
    let g = Geometry::default();
    let mut rng = Random(11);
    for _ in 0..100 {
        let actuators = ActuatorState {
            l: rng.stroke_point(&g),
            l_dot: rng.vector(-0.1, 0.1),
            l_ddot: rng.vector(-1.0, 1.0),
        };
        let fwd = forward_motion(&g, &actuators, &start_pose(), &FkOptions::default()).unwrap();
        let inv = inverse_motion(&g, &fwd.assembly.euler, &fwd.omega, &fwd.omega_dot).unwrap();
        assert!((inv.l_dot - actuators.l_dot).amax() < 1e-14);
        assert!((inv.l_ddot - actuators.l_ddot).amax() < 1e-13);
    }
}

#[test]
fn forward_kinematics_failures_are_typed_errors() {
    let g = Geometry::default();
    let middle = Vector3::new(0.08, 0.05, 0.12);
    // Newton converges quadratically but not in one step from the start pose.
    let one_step = FkOptions {
        max_iterations: 1,
        ..FkOptions::default()
    };
    assert!(matches!(
        forward_kinematics(&g, &middle, &start_pose(), &one_step),
        Err(KinematicsError::NoConvergence { iterations: 1, .. })
    ));
    // 160 mm is beyond the 152 mm stroke: rejected unless the check is off.
    let long = Vector3::new(0.16, 0.1, 0.1);
    assert!(matches!(
        forward_kinematics(&g, &long, &start_pose(), &FkOptions::default()),
        Err(KinematicsError::OutsideStroke { leg: 1, .. })
    ));
    let unchecked = FkOptions {
        check_stroke: false,
        ..FkOptions::default()
    };
    let fk = forward_kinematics(&g, &long, &start_pose(), &unchecked).unwrap();
    assert!((fk.assembly.l - long).amax() < 1e-14);
    assert_eq!(
        forward_kinematics(
            &g,
            &Vector3::new(f64::NAN, 0.1, 0.1),
            &start_pose(),
            &unchecked
        ),
        Err(KinematicsError::NotFinite("actuator displacements"))
    );
    // A displacement no leg can reach from any orientation: 2 m along the actuator.
    assert!(
        forward_kinematics(&g, &Vector3::new(2.0, 0.1, 0.1), &start_pose(), &unchecked).is_err()
    );
}
