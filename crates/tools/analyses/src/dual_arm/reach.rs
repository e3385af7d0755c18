//! Where an arm of a chain can reach: an annulus about its first free joint.
//!
//! The joints before an arm's first free joint are locked, so that joint sits at a fixed
//! pivot; between consecutive free joints (and from the last one to the tip) the locked
//! joints make rigid segments. A planar chain of freely turning segments `s_i` reaches
//! exactly the distances from `max(0, 2 max s_i - sum s_i)` to `sum s_i` from its pivot.

use super::DualArmError;
use super::kinematics::{ARM_JOINTS, Side, joint_points};
use super::locks::Chain;
use super::paths::Path;
use nalgebra::Vector2;

/// The reachable set of one arm's tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Annulus {
    pub centre: Vector2<f64>,
    pub inner: f64,
    pub outer: f64,
}

impl Annulus {
    /// Whether `r` lies in the closed annulus.
    pub fn contains(&self, r: Vector2<f64>) -> bool {
        let d = (r - self.centre).norm();
        d >= self.inner && d <= self.outer
    }
}

/// The annulus reached by the tip of one arm of `chain`.
pub fn reach(chain: &Chain, side: Side) -> Annulus {
    let o = side.offset();
    let mut theta = [0.0; ARM_JOINTS];
    for (i, t) in theta.iter_mut().enumerate() {
        *t = chain.locked_value(o + i).unwrap_or(0.0);
    }
    let points = joint_points(chain.lengths().of(side), &theta);
    let free: Vec<usize> = (0..ARM_JOINTS)
        .filter(|i| chain.locked_value(o + i).is_none())
        .collect();
    let ends: Vec<usize> = free.iter().skip(1).copied().chain([ARM_JOINTS]).collect();
    let segments: Vec<f64> = free
        .iter()
        .zip(&ends)
        .map(|(&a, &b)| (points[b] - points[a]).norm())
        .collect();
    let total: f64 = segments.iter().sum();
    let longest = segments.iter().copied().fold(0.0, f64::max);
    Annulus {
        centre: points[free.first().copied().unwrap_or(ARM_JOINTS)],
        inner: (2.0 * longest - total).max(0.0),
        outer: total,
    }
}

/// Checks that both arms can reach the path at `samples + 1` equally spaced times;
/// the first time one cannot is an `OutsideReach` error.
pub fn check_path_in_reach(
    chain: &Chain,
    path: &dyn Path,
    samples: usize,
) -> Result<(), DualArmError> {
    let annuli = Side::BOTH.map(|side| (side, reach(chain, side)));
    let (t0, tf) = (path.start(), path.end());
    for k in 0..=samples {
        let t = t0 + (tf - t0) * k as f64 / samples.max(1) as f64;
        let r = path.position(t);
        if let Some((side, a)) = annuli.iter().find(|(_, a)| !a.contains(r)) {
            return Err(DualArmError::OutsideReach {
                t,
                arm: side.name(),
                distance: (r - a.centre).norm(),
                inner: a.inner,
                outer: a.outer,
            });
        }
    }
    Ok(())
}
