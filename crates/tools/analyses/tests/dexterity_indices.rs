//! Properties of the condition and load indices that hold by construction of the
//! homogeneous Jacobians: invariance under base rotation (serial arm) and under a
//! uniform change of length scale (all three).

use robofmu_analyses::dexterity::parallel_2rrr::Parallel2Rrr;
use robofmu_analyses::dexterity::parallel_3rrr::Parallel3Rrr;
use robofmu_analyses::dexterity::serial_1rrr::Serial1Rrr;
use robofmu_analyses::dexterity::{Manipulator, Pose};

#[test]
fn serial_lci_is_invariant_under_rotation_about_the_base() {
    // Rotating the pose by alpha about the base adds alpha to theta1 only; J' = R1 J
    // expresses the velocities in the end-effector u-v frame, which rotates along.
    let arm = Serial1Rrr::default();
    let pose = Pose::new(0.12, -0.05, 0.4);
    for alpha in [0.3f64, 1.7, -2.5] {
        let (s, c) = alpha.sin_cos();
        let turned = Pose::new(
            c * pose.x - s * pose.y,
            s * pose.x + c * pose.y,
            pose.phi + alpha,
        );
        for mode in 0..2 {
            let a = arm.lci(pose, mode).unwrap();
            let b = arm.lci(turned, mode).unwrap();
            assert!(
                (a - b).abs() < 1e-12,
                "alpha {alpha} mode {mode}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn lci_is_invariant_under_a_uniform_length_scale() {
    // Every entry of a homogeneous Jacobian is a length, so scaling every length by k
    // scales all singular values by k and leaves their ratio unchanged.
    let k = 3.7;
    let pose = Pose::new(0.10, 0.10, 10f64.to_radians());
    let scaled = Pose::new(k * pose.x, k * pose.y, pose.phi);
    let arm = Serial1Rrr::default();
    let big_arm = Serial1Rrr {
        l1: k * arm.l1,
        l2: k * arm.l2,
        l3: k * arm.l3,
        half_spacing: k * arm.half_spacing,
    };
    let two = Parallel2Rrr::default();
    let big_two = Parallel2Rrr {
        base: two.base.map(|b| k * b),
        platform: two.platform.map(|p| k * p),
        proximal: k * two.proximal,
        distal: k * two.distal,
    };
    let three = Parallel3Rrr::default();
    let big_three = Parallel3Rrr {
        base: three.base.map(|b| k * b),
        platform: three.platform.map(|p| k * p),
        proximal: k * three.proximal,
        distal: k * three.distal,
    };
    let pairs: [(&dyn Manipulator, &dyn Manipulator); 3] =
        [(&arm, &big_arm), (&two, &big_two), (&three, &big_three)];
    for (small, big) in pairs {
        for mode in 0..small.working_modes() {
            let a = small.lci(pose, mode).unwrap();
            let b = big.lci(scaled, mode).unwrap();
            // Closed-form eigenvalues: absolute accuracy ~1e-11 near singular poses.
            assert!((a - b).abs() < 1e-9, "mode {mode}: {a} vs {b}");
            // The load index 1/sigma_max scales as 1/k.
            let la = small.load_index(pose, mode).unwrap();
            let lb = big.load_index(scaled, mode).unwrap();
            assert!((la - k * lb).abs() < 1e-9 * la, "load index mode {mode}");
        }
    }
}

#[test]
fn lci_equals_svd_ratio_and_lies_in_unit_interval() {
    // Independent truth: nalgebra's SVD of the homogeneous Jacobian.
    let pose = Pose::new(0.12, -0.12, 10f64.to_radians());
    let three = Parallel3Rrr::default();
    for mode in 0..8 {
        let jh = three.homogeneous_jacobian(pose, mode).unwrap();
        let sv = jh.singular_values();
        let lci = three.lci(pose, mode).unwrap();
        assert!((lci - sv.min() / sv.max()).abs() < 1e-10, "mode {mode}");
        assert!((0.0..=1.0).contains(&lci));
        let load = three.load_index(pose, mode).unwrap();
        assert!((load - 1.0 / sv.max()).abs() < 1e-9 * load);
    }
    let arm = Serial1Rrr::default();
    let jh = arm.homogeneous_jacobian(pose, 1).unwrap();
    let sv = jh.singular_values();
    assert!((arm.lci(pose, 1).unwrap() - sv.min() / sv.max()).abs() < 1e-10);
}

#[test]
fn serial_arm_is_singular_when_stretched() {
    // theta2 = 0 (wrist at l1 + l2 from the base): the first two columns of J' are
    // dependent, so the LCI vanishes (analytic: d = 1 in the inverse kinematics).
    let arm = Serial1Rrr::default();
    let phi = 0.3f64;
    let wrist = 0.30;
    let pose = Pose::new(wrist + arm.l3 * phi.cos(), arm.l3 * phi.sin(), phi);
    assert!(arm.lci(pose, 0).unwrap() < 1e-6);
}

#[test]
fn reversed_base_equals_the_forward_base_seen_from_a_half_turn() {
    // Turning the base by 180 deg about the origin is a rigid motion of the whole
    // manipulator when the pose turns too: (x, y, phi) -> (-x, -y, phi + pi). Rigid
    // motions keep the singular values of the B1/B3 velocity Jacobian and the branches.
    use robofmu_analyses::dexterity::layout::{BaseDirection, Reading};
    let reversed = Reading {
        base_direction: BaseDirection::MinusX,
        ..Reading::default()
    };
    let pose = Pose::new(-0.12, -0.05, 3.0);
    let turned = Pose::new(0.12, 0.05, 3.0 + std::f64::consts::PI);
    let two = (Parallel2Rrr::paper(reversed), Parallel2Rrr::default());
    let three = (Parallel3Rrr::paper(reversed), Parallel3Rrr::default());
    let pairs: [(&dyn Manipulator, &dyn Manipulator); 2] = [(&two.0, &two.1), (&three.0, &three.1)];
    let mut compared = 0;
    for (rev, fwd) in pairs {
        for mode in 0..rev.working_modes() {
            match (rev.lci(pose, mode), fwd.lci(turned, mode)) {
                (Ok(a), Ok(b)) => {
                    assert!((a - b).abs() < 1e-9, "mode {mode}: {a} vs {b}");
                    compared += 1;
                }
                (a, b) => assert_eq!(a.is_ok(), b.is_ok(), "mode {mode}"),
            }
        }
    }
    assert!(compared >= 4, "only {compared} modes reach the pose");
}
