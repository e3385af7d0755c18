//! Kinematics of the three manipulators checked against independent computations:
//! forward kinematics written out here from the link geometry, loop closure, and
//! central finite differences of the inverse kinematics.

use nalgebra::{Matrix3, Vector2};
use robofmu_analyses::dexterity::parallel_2rrr::Parallel2Rrr;
use robofmu_analyses::dexterity::parallel_3rrr::Parallel3Rrr;
use robofmu_analyses::dexterity::serial_1rrr::Serial1Rrr;
use robofmu_analyses::dexterity::{DexterityError, Joints, Manipulator, Pose, Robot, RobotKind};

/// Step of the central differences (m and rad): truncation ~h^2, rounding ~1e-16/h.
const H: f64 = 1e-6;

fn unit(angle: f64) -> Vector2<f64> {
    Vector2::new(angle.cos(), angle.sin())
}

/// Poses of the paper's square at phi = 10 and 60 deg that every manipulator reaches
/// in at least one mode.
fn sample_poses() -> Vec<Pose> {
    let mut poses = Vec::new();
    for phi_deg in [10.0f64, 60.0] {
        for (x, y) in [
            (0.05, 0.08),
            (0.12, -0.12),
            (0.10, 0.10),
            (-0.03, 0.15),
            (0.15, 0.02),
        ] {
            poses.push(Pose::new(x, y, phi_deg.to_radians()));
        }
    }
    poses
}

/// Finite-difference derivative of the inverse kinematics, dTheta/dq (3x3).
fn ik_derivative(robot: &impl Manipulator, pose: Pose, mode: usize) -> Option<Matrix3<f64>> {
    let q = pose.to_vector();
    let mut d = Matrix3::zeros();
    for k in 0..3 {
        let mut plus = q;
        let mut minus = q;
        plus[k] += H;
        minus[k] -= H;
        let tp = robot
            .inverse_kinematics(Pose::from_vector(&plus), mode)
            .ok()?;
        let tm = robot
            .inverse_kinematics(Pose::from_vector(&minus), mode)
            .ok()?;
        let mut diff: Joints = tp - tm;
        diff.apply(|a| *a = a.sin().atan2(a.cos()));
        d.set_column(k, &(diff / (2.0 * H)));
    }
    Some(d)
}

#[test]
fn every_jacobian_inverts_the_finite_difference_of_its_inverse_kinematics() {
    // J maps joint rates to pose rates, so J * dTheta/dq = I (identity is the truth).
    let mut checked = 0;
    for kind in RobotKind::ALL {
        let robot = Robot::paper(kind);
        for pose in sample_poses() {
            for mode in 0..robot.working_modes() {
                let (Ok(j), Some(d)) = (
                    robot.jacobian(pose, mode),
                    ik_derivative(&robot, pose, mode),
                ) else {
                    continue;
                };
                let product = j * d;
                let error = (product - Matrix3::identity()).abs().max();
                // Relative to the conditioning: near-singular poses amplify FD error.
                let scale = j.abs().max() * d.abs().max();
                assert!(
                    error < 1e-6 * scale,
                    "{kind} {pose:?} mode {mode}: J dIK = {product}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 60, "only {checked} (pose, mode) pairs reachable");
}

#[test]
fn serial_jacobian_matches_finite_differences_of_forward_kinematics() {
    let arm = Serial1Rrr::default();
    for theta in [Joints::new(0.3, 1.1, -0.7), Joints::new(-1.2, -0.4, 2.0)] {
        let j = arm.jacobian_at(&theta);
        for k in 0..3 {
            let mut plus = theta;
            let mut minus = theta;
            plus[k] += H;
            minus[k] -= H;
            let fd = (arm.forward_kinematics(&plus).to_vector()
                - arm.forward_kinematics(&minus).to_vector())
                / (2.0 * H);
            assert!(
                (fd - j.column(k)).norm() < 1e-8,
                "column {k}: {fd} vs {}",
                j.column(k)
            );
        }
    }
}

#[test]
fn serial_inverse_kinematics_round_trips_in_both_modes() {
    let arm = Serial1Rrr::default();
    for pose in sample_poses() {
        for mode in 0..2 {
            let theta = arm.inverse_kinematics(pose, mode).unwrap();
            let back = arm.forward_kinematics(&theta);
            assert!((back.to_vector() - pose.to_vector()).norm() < 1e-12);
        }
        let t0 = arm.inverse_kinematics(pose, 0).unwrap();
        let t1 = arm.inverse_kinematics(pose, 1).unwrap();
        assert!(
            (t0[1] + t1[1]).abs() < 1e-12,
            "the two modes mirror the elbow angle"
        );
    }
}

#[test]
fn serial_homogeneous_jacobian_gives_velocities_of_points_a_and_b() {
    // A and B at e/2 on either side of O' on the normal to l3, u along BA: A = O' + (e/2) u
    // with u = (sin phi, -cos phi) (first row of R1), v = (cos phi, sin phi).
    let arm = Serial1Rrr::default();
    let h = arm.half_spacing;
    let points = |theta: &Joints| {
        let p = arm.forward_kinematics(theta);
        let u = Vector2::new(p.phi.sin(), -p.phi.cos());
        let o = Vector2::new(p.x, p.y);
        (o + h * u, o - h * u, u, unit(p.phi))
    };
    let theta = Joints::new(0.4, 0.9, -0.5);
    let pose = arm.forward_kinematics(&theta);
    let jh = arm.homogeneous_jacobian(pose, 0).unwrap();
    for k in 0..3 {
        let mut plus = theta;
        let mut minus = theta;
        plus[k] += H;
        minus[k] -= H;
        let (ap, bp, _, _) = points(&plus);
        let (am, bm, _, _) = points(&minus);
        let (_, _, u, v) = points(&theta);
        let va = (ap - am) / (2.0 * H);
        let vb = (bp - bm) / (2.0 * H);
        let want = [va.dot(&u), va.dot(&v), vb.dot(&v)];
        for (row, w) in want.iter().enumerate() {
            assert!((jh[(row, k)] - w).abs() < 1e-8, "row {row} column {k}");
        }
    }
}

/// 2-RRR forward kinematics written out from the linkage: B1 from leg 1, then phi from
/// `|B1 + R s'2 - A2| = l2` (the solution nearest `phi_hint`). Default reading: frame at B1.
fn parallel_2rrr_forward(r: &Parallel2Rrr, theta: &Joints, phi_hint: f64) -> Pose {
    let b1 = r.base[0] + r.proximal * unit(theta[0]) + r.distal * unit(theta[0] + theta[1]);
    let a2 = r.base[1] + r.proximal * unit(theta[2]);
    let d = a2 - b1;
    let side = r.platform[1].norm();
    let c = (side * side + d.norm_squared() - r.distal * r.distal) / (2.0 * side);
    let spread = (c / d.norm()).acos();
    let base_angle = d.y.atan2(d.x);
    let phi = [base_angle + spread, base_angle - spread]
        .into_iter()
        .min_by(|a, b| {
            let da = (a - phi_hint).sin().abs() + (1.0 - (a - phi_hint).cos());
            let db = (b - phi_hint).sin().abs() + (1.0 - (b - phi_hint).cos());
            da.total_cmp(&db)
        })
        .unwrap();
    Pose::new(b1.x, b1.y, phi)
}

#[test]
fn two_rrr_inverse_kinematics_round_trips_and_jacobian_matches_forward_differences() {
    let r = Parallel2Rrr::default();
    let mut checked = 0;
    for pose in sample_poses() {
        for mode in 0..4 {
            let Ok(theta) = r.inverse_kinematics(pose, mode) else {
                continue;
            };
            let back = parallel_2rrr_forward(&r, &theta, pose.phi);
            assert!((back.x - pose.x).abs() < 1e-12 && (back.y - pose.y).abs() < 1e-12);
            assert!(
                (back.phi - pose.phi).sin().abs() < 1e-10,
                "{pose:?} mode {mode}"
            );
            let j = r.jacobian(pose, mode).unwrap();
            for k in 0..3 {
                let mut plus = theta;
                let mut minus = theta;
                plus[k] += H;
                minus[k] -= H;
                let fd = (parallel_2rrr_forward(&r, &plus, pose.phi).to_vector()
                    - parallel_2rrr_forward(&r, &minus, pose.phi).to_vector())
                    / (2.0 * H);
                let error = (fd - j.column(k)).norm();
                assert!(error < 1e-6 * j.norm(), "{pose:?} mode {mode} column {k}");
            }
            checked += 1;
        }
    }
    assert!(checked >= 20, "only {checked} poses checked");
}

#[test]
fn three_rrr_inverse_kinematics_closes_every_leg() {
    // Closure: |O_i + l1 e(theta_i) - B_i| = l2 for each leg, in every reachable mode.
    let r = Parallel3Rrr::default();
    let mut checked = 0;
    for pose in sample_poses() {
        for mode in 0..8 {
            let Ok(theta) = r.inverse_kinematics(pose, mode) else {
                continue;
            };
            for leg in 0..3 {
                let elbow = r.base[leg] + r.proximal * unit(theta[leg]);
                let distal = (r.vertex(pose, leg) - elbow).norm();
                assert!(
                    (distal - r.distal).abs() < 1e-12,
                    "{pose:?} mode {mode} leg {leg}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 40, "only {checked} (pose, mode) pairs reachable");
}

/// Position of a platform vertex at a pose.
type VertexAt<'a> = dyn Fn(Pose, usize) -> Vector2<f64> + 'a;

#[test]
fn parallel_homogeneous_jacobians_give_velocities_of_b1_and_b3() {
    // v_B3 by finite differences of the vertex position along the pose rates J e_k.
    let r2 = Parallel2Rrr::default();
    let r3 = Parallel3Rrr::default();
    let pose = Pose::new(0.10, 0.10, 10f64.to_radians());
    let cases: [(&VertexAt, Matrix3<f64>, _); 2] = [
        (
            &|p, i| r2.vertex(p, i),
            r2.jacobian(pose, 0).unwrap(),
            r2.homogeneous_jacobian(pose, 0).unwrap(),
        ),
        (
            &|p, i| r3.vertex(p, i),
            r3.jacobian(pose, 0).unwrap(),
            r3.homogeneous_jacobian(pose, 0).unwrap(),
        ),
    ];
    for (vertex, j, jh) in cases {
        for k in 0..3 {
            let rate = j.column(k).into_owned();
            let at = |s: f64| Pose::from_vector(&(pose.to_vector() + s * rate));
            for (row, i) in [(0, 0), (2, 2)] {
                let v = (vertex(at(H), i) - vertex(at(-H), i)) / (2.0 * H);
                assert!((jh[(row, k)] - v.x).abs() < 1e-8 && (jh[(row + 1, k)] - v.y).abs() < 1e-8);
            }
        }
    }
}

#[test]
fn unreachable_poses_and_missing_modes_are_typed_errors() {
    // 50 cm from every base joint is beyond the 30 cm legs (45 cm for the serial arm).
    let far = Pose::new(0.5, 0.5, 0.0);
    for kind in RobotKind::ALL {
        let robot = Robot::paper(kind);
        assert_eq!(
            robot.inverse_kinematics(far, 0),
            Err(DexterityError::Unreachable)
        );
        assert_eq!(robot.lci(far, 0), Err(DexterityError::Unreachable));
        assert_eq!(robot.best_lci(far), None);
        let nan = Pose::new(f64::NAN, 0.1, 0.0);
        assert_eq!(robot.lci(nan, 0), Err(DexterityError::NonFinitePose));
        assert_eq!(robot.best_lci(nan), None);
        let modes = robot.working_modes();
        assert_eq!(
            robot.jacobian(Pose::new(0.1, 0.1, 0.2), modes),
            Err(DexterityError::NoSuchMode { mode: modes, modes })
        );
    }
}
