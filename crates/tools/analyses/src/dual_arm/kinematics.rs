//! Forward kinematics of the planar four-joint arms, their derivatives and the
//! two-joint inverse kinematics used to close the chain.
//!
//! Joint angles are relative (`theta_i` between link `i-1` and link `i`); the absolute
//! angle of link `i` is `phi_i = theta_1 + ... + theta_i`, and the tip of an arm is
//! `sum_i l_i (cos phi_i, sin phi_i)`, both arms starting at the base origin.

use super::DualArmError;
use nalgebra::{Matrix2x4, Vector2};
use std::f64::consts::PI;

/// Joints of one arm.
pub const ARM_JOINTS: usize = 4;
/// Joints of the robot: `theta_R1..theta_R4` then `theta_L1..theta_L4`.
pub const JOINTS: usize = 2 * ARM_JOINTS;

/// One of the two arms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Right,
    Left,
}

impl Side {
    /// Both arms, right first (the order of the joint vector).
    pub const BOTH: [Side; 2] = [Side::Right, Side::Left];

    /// Index of the arm's first joint in the robot's joint vector.
    pub fn offset(self) -> usize {
        match self {
            Side::Right => 0,
            Side::Left => ARM_JOINTS,
        }
    }

    /// Lower-case name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            Side::Right => "right",
            Side::Left => "left",
        }
    }

    /// The arm that owns a joint of the robot's joint vector.
    pub fn of_joint(joint: usize) -> Side {
        if joint < ARM_JOINTS {
            Side::Right
        } else {
            Side::Left
        }
    }
}

/// Name of a joint of the robot's joint vector, as in the paper (`theta_R1`...).
pub fn joint_name(joint: usize) -> String {
    let side = if joint < ARM_JOINTS { 'R' } else { 'L' };
    format!("theta_{side}{}", joint % ARM_JOINTS + 1)
}

/// Link lengths of both arms, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkLengths {
    right: [f64; ARM_JOINTS],
    left: [f64; ARM_JOINTS],
}

/// The link lengths chosen for this project (both arms alike, mirror images), metres.
/// They satisfy the reachability statements of the source: see docs/dual-arm.md.
pub const CHOSEN_LENGTHS: [f64; ARM_JOINTS] = [0.7, 0.1, 0.35, 0.3];

impl LinkLengths {
    /// Lengths of the right and left arm; each must be positive and finite.
    pub fn new(right: [f64; ARM_JOINTS], left: [f64; ARM_JOINTS]) -> Result<Self, DualArmError> {
        let all = right.iter().chain(left.iter());
        if let Some(bad) = all.copied().find(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(DualArmError::InvalidInput(format!(
                "link length {bad} m is not a positive finite number"
            )));
        }
        Ok(Self { right, left })
    }

    /// Both arms with the same lengths (mirror images).
    pub fn mirrored(lengths: [f64; ARM_JOINTS]) -> Result<Self, DualArmError> {
        Self::new(lengths, lengths)
    }

    /// Lengths of one arm.
    pub fn of(&self, side: Side) -> &[f64; ARM_JOINTS] {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }
}

impl Default for LinkLengths {
    fn default() -> Self {
        Self {
            right: CHOSEN_LENGTHS,
            left: CHOSEN_LENGTHS,
        }
    }
}

fn unit(angle: f64) -> Vector2<f64> {
    Vector2::new(angle.cos(), angle.sin())
}

/// Absolute link angles `phi_i` of an arm.
fn absolute_angles(theta: &[f64; ARM_JOINTS]) -> [f64; ARM_JOINTS] {
    let mut phi = [0.0; ARM_JOINTS];
    let mut sum = 0.0;
    for (p, t) in phi.iter_mut().zip(theta) {
        sum += t;
        *p = sum;
    }
    phi
}

/// The base and the four joint ends of an arm (the last one is the tip).
pub fn joint_points(l: &[f64; ARM_JOINTS], theta: &[f64; ARM_JOINTS]) -> [Vector2<f64>; 5] {
    let mut points = [Vector2::zeros(); 5];
    for (i, phi) in absolute_angles(theta).iter().enumerate() {
        points[i + 1] = points[i] + l[i] * unit(*phi);
    }
    points
}

/// Tip position of an arm.
pub fn tip(l: &[f64; ARM_JOINTS], theta: &[f64; ARM_JOINTS]) -> Vector2<f64> {
    joint_points(l, theta)[ARM_JOINTS]
}

/// Terms `l_i (cos phi_i, sin phi_i)` summed from link `from` to the tip.
fn tail(l: &[f64; ARM_JOINTS], phi: &[f64; ARM_JOINTS], from: usize) -> Vector2<f64> {
    (from..ARM_JOINTS).map(|i| l[i] * unit(phi[i])).sum()
}

/// Jacobian `d tip / d theta` of an arm (2 x 4): column `j` is the tail from link `j`
/// turned by a right angle.
pub fn jacobian(l: &[f64; ARM_JOINTS], theta: &[f64; ARM_JOINTS]) -> Matrix2x4<f64> {
    let phi = absolute_angles(theta);
    let mut jac = Matrix2x4::zeros();
    for j in 0..ARM_JOINTS {
        let t = tail(l, &phi, j);
        jac[(0, j)] = -t.y;
        jac[(1, j)] = t.x;
    }
    jac
}

/// Second derivatives `d^2 tip / d theta_j d theta_k` of an arm, indexed `[j][k]`:
/// minus the tail from link `max(j, k)`.
pub fn hessian(
    l: &[f64; ARM_JOINTS],
    theta: &[f64; ARM_JOINTS],
) -> [[Vector2<f64>; ARM_JOINTS]; ARM_JOINTS] {
    let phi = absolute_angles(theta);
    let tails: Vec<Vector2<f64>> = (0..ARM_JOINTS).map(|i| -tail(l, &phi, i)).collect();
    let mut h = [[Vector2::zeros(); ARM_JOINTS]; ARM_JOINTS];
    for (j, row) in h.iter_mut().enumerate() {
        for (k, entry) in row.iter_mut().enumerate() {
            *entry = tails[j.max(k)];
        }
    }
    h
}

/// Which of the two inverse-kinematics branches an arm takes: the sign of the relative
/// bend at its second solved joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Elbow {
    /// Counter-clockwise bend (bend angle in [0, pi]).
    Positive,
    /// Clockwise bend (bend angle in [-pi, 0]).
    Negative,
}

/// The angle equal to `angle` modulo 2 pi that is nearest to `reference`.
pub fn nearest_angle(angle: f64, reference: f64) -> f64 {
    angle - 2.0 * PI * ((angle - reference) / (2.0 * PI)).round()
}

/// Solves joints `a < b` of an arm so that its tip reaches `target`, the other joints
/// of `theta` held. The solved angles are taken nearest to their values in `theta` on
/// entry (continuity along a path). Returns `None` when the target is out of reach.
pub fn solve_two_joints(
    l: &[f64; ARM_JOINTS],
    theta: &mut [f64; ARM_JOINTS],
    (a, b): (usize, usize),
    target: Vector2<f64>,
    elbow: Elbow,
) -> Option<()> {
    let reference = (theta[a], theta[b]);
    // Pivot of joint a and the angle of the link before it.
    let mut head = *theta;
    for h in head.iter_mut().skip(a) {
        *h = 0.0;
    }
    let pivot = joint_points(l, &head)[a];
    let before: f64 = theta[..a].iter().sum();
    // In the frame of link a (theta_a = 0): W from pivot a to pivot b, Z from pivot b to
    // the tip with theta_b = 0; the tip is then W + rot(theta_b) Z.
    let mut frame = *theta;
    frame[..=a].iter_mut().for_each(|t| *t = 0.0);
    frame[b] = 0.0;
    let points = joint_points(l, &frame);
    let w = points[b] - points[a];
    let z = points[ARM_JOINTS] - points[b];
    let d = target - pivot;
    let (wn, zn) = (w.norm(), z.norm());
    let cos_bend = (d.norm_squared() - wn * wn - zn * zn) / (2.0 * wn * zn);
    if !cos_bend.is_finite() || cos_bend.abs() > 1.0 {
        return None;
    }
    let bend = match elbow {
        Elbow::Positive => cos_bend.acos(),
        Elbow::Negative => -cos_bend.acos(),
    };
    let (alpha, beta) = (w.y.atan2(w.x), z.y.atan2(z.x));
    let theta_b = bend + alpha - beta;
    let v = w + nalgebra::Rotation2::new(theta_b) * z;
    let theta_a = d.y.atan2(d.x) - v.y.atan2(v.x) - before;
    theta[a] = nearest_angle(theta_a, reference.0);
    theta[b] = nearest_angle(theta_b, reference.1);
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: [f64; 4] = [0.7, 0.1, 0.35, 0.3];
    const THETA: [f64; 4] = [0.3, -0.4, 1.1, -0.7];

    #[test]
    fn tip_of_straight_arm_is_the_total_length() {
        // All joints zero: links along x, tip at (sum l, 0).
        let p = tip(&L, &[0.0; 4]);
        assert!((p - Vector2::new(1.45, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn jacobian_and_hessian_match_central_differences() {
        let h = 1e-6;
        let jac = jacobian(&L, &THETA);
        let hess = hessian(&L, &THETA);
        for j in 0..4 {
            let (mut up, mut down) = (THETA, THETA);
            up[j] += h;
            down[j] -= h;
            let fd = (tip(&L, &up) - tip(&L, &down)) / (2.0 * h);
            assert!((fd - jac.column(j)).norm() < 1e-9, "column {j}");
            let fd2 = (jacobian(&L, &up) - jacobian(&L, &down)) / (2.0 * h);
            for (k, h_jk) in hess[j].iter().enumerate() {
                assert!((fd2.column(k) - h_jk).norm() < 1e-9, "[{j}][{k}]");
            }
        }
    }

    #[test]
    fn two_joint_solution_reaches_the_target_on_both_branches() {
        // Target: the tip of a configuration that differs only in joints a and b, so it
        // is reachable by construction (one branch recovers that configuration).
        for (a, b, locked) in [(2, 3, None), (1, 2, Some(0.0)), (0, 2, None)] {
            let mut start = THETA;
            if let Some(v) = locked {
                start[3] = v;
            }
            let mut truth = start;
            truth[a] += 0.3;
            truth[b] -= 0.5;
            let target = tip(&L, &truth);
            for elbow in [Elbow::Positive, Elbow::Negative] {
                let mut theta = start;
                solve_two_joints(&L, &mut theta, (a, b), target, elbow).unwrap();
                assert!((tip(&L, &theta) - target).norm() < 1e-13, "joints {a}, {b}");
            }
        }
        let mut theta = THETA;
        let far = Vector2::new(3.0, 0.0);
        assert!(solve_two_joints(&L, &mut theta, (2, 3), far, Elbow::Positive).is_none());
    }

    #[test]
    fn nearest_angle_stays_within_pi_of_the_reference() {
        assert!((nearest_angle(3.0, -3.0) - (3.0 - 2.0 * PI)).abs() < 1e-15);
        assert!((nearest_angle(0.5, 0.0) - 0.5).abs() < 1e-15);
    }
}
