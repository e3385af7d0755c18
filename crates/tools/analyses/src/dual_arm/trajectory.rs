//! A sampled joint path with its accumulated cost, and the checks run on it.

use super::kinematics::{self, JOINTS, LinkLengths, Side, nearest_angle};
use super::paths::Path;

/// Joint angles of both arms sampled in time, with the cost accumulated from t0.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Sample times, increasing, s.
    pub times: Vec<f64>,
    /// All eight joint angles (locked ones included) at each time, rad.
    pub joints: Vec<[f64; JOINTS]>,
    /// Cost `integral from t0 to t of |theta_dot|^2`, rad^2/s.
    pub cost: Vec<f64>,
}

impl Trajectory {
    /// The total cost PI, rad^2/s.
    pub fn pi(&self) -> f64 {
        self.cost.last().copied().unwrap_or(0.0)
    }

    /// Largest distance, over the samples and both arms, of an arm's tip from the path.
    pub fn tracking_error(&self, lengths: &LinkLengths, path: &dyn Path) -> f64 {
        self.times
            .iter()
            .zip(&self.joints)
            .map(|(t, theta)| tip_error(lengths, path, *t, theta))
            .fold(0.0, f64::max)
    }

    /// Distance of the tips from the path at the first sample (the start task condition).
    pub fn start_error(&self, lengths: &LinkLengths, path: &dyn Path) -> f64 {
        match (self.times.first(), self.joints.first()) {
            (Some(t), Some(theta)) => tip_error(lengths, path, *t, theta),
            _ => f64::NAN,
        }
    }

    /// Largest joint difference (modulo 2 pi) to another trajectory sampled at the same
    /// times, rad; `None` when the sample times differ.
    pub fn max_joint_difference(&self, other: &Trajectory) -> Option<f64> {
        let same_times = self.times.len() == other.times.len()
            && self
                .times
                .iter()
                .zip(&other.times)
                .all(|(a, b)| (a - b).abs() < 1e-9);
        same_times.then(|| {
            self.joints
                .iter()
                .zip(&other.joints)
                .flat_map(|(a, b)| {
                    a.iter()
                        .zip(b)
                        .map(|(x, y)| nearest_angle(x - y, 0.0).abs())
                })
                .fold(0.0, f64::max)
        })
    }
}

/// Larger of the two arms' tip distances from `r(t)`.
fn tip_error(lengths: &LinkLengths, path: &dyn Path, t: f64, theta: &[f64; JOINTS]) -> f64 {
    let r = path.position(t);
    Side::BOTH
        .iter()
        .map(|&side| {
            let o = side.offset();
            let arm = [theta[o], theta[o + 1], theta[o + 2], theta[o + 3]];
            (kinematics::tip(lengths.of(side), &arm) - r).norm()
        })
        .fold(0.0, f64::max)
}
