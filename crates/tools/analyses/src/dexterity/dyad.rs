//! The two-link dyad shared by the legs of the parallel manipulators: a proximal link
//! of length `l1` from a base joint and a distal link of length `l2` to a platform
//! vertex at `r` relative to that base joint.

use nalgebra::Vector2;

/// Inverse kinematics of one dyad in one branch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dyad {
    /// Unit vector along the proximal link, `(cos theta, sin theta)`.
    pub proximal: Vector2<f64>,
    /// Unit vector along the distal link, from the elbow to the platform vertex.
    pub distal: Vector2<f64>,
    /// `delta sqrt(Gamma)` (m): its sign is the branch; zero at a leg singularity.
    pub root: f64,
}

/// Solves `cos(theta) r_x + sin(theta) r_y = p` with `p = (|r|^2 + l1^2 - l2^2) / (2 l1)`
/// in branch `delta = +-1`; `None` when `Gamma = |r|^2 - p^2 < 0` (out of reach).
pub fn solve(r: Vector2<f64>, l1: f64, l2: f64, delta: f64) -> Option<Dyad> {
    let rr = r.norm_squared();
    let p = (rr + l1 * l1 - l2 * l2) / (2.0 * l1);
    // Rounding may put a boundary pose (stretched or folded leg) just below Gamma = 0.
    let gamma = rr - p * p;
    if rr == 0.0 {
        return folded_on_base(l1, l2);
    }
    if gamma < -1e-12 * rr {
        return None;
    }
    let gamma = gamma.max(0.0);
    let root = delta * gamma.sqrt();
    let sin = (p * r.y + r.x * root) / rr;
    let cos = (p * r.x - r.y * root) / rr;
    let elbow = Vector2::new(l1 * cos, l1 * sin);
    Some(Dyad {
        proximal: Vector2::new(cos, sin),
        distal: (r - elbow) / l2,
        root,
    })
}

/// The vertex on the base joint (`r = 0`): reachable only with equal links, folded,
/// with any proximal angle (take 0); the leg is singular there (`root = 0`).
fn folded_on_base(l1: f64, l2: f64) -> Option<Dyad> {
    (l1 == l2).then(|| Dyad {
        proximal: Vector2::new(1.0, 0.0),
        distal: Vector2::new(-1.0, 0.0),
        root: 0.0,
    })
}

impl Dyad {
    /// Angle `theta` of the proximal link to the x axis (rad).
    pub fn angle(&self) -> f64 {
        self.proximal.y.atan2(self.proximal.x)
    }
}

/// Branch sign `delta_i` of leg `leg` in working mode `mode` (bit `leg` set: `-1`).
pub fn branch(mode: usize, leg: usize) -> f64 {
    if mode >> leg & 1 == 0 { 1.0 } else { -1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_branches_close_the_dyad() {
        // Closure is the defining property: |elbow| = l1 and |r - elbow| = l2.
        let r = Vector2::new(0.1, 0.2);
        for delta in [1.0, -1.0] {
            let d = solve(r, 0.15, 0.12, delta).unwrap();
            let elbow = 0.15 * Vector2::new(d.angle().cos(), d.angle().sin());
            assert!(((r - elbow).norm() - 0.12).abs() < 1e-12);
            assert!((d.distal.norm() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn vertex_on_the_base_joint_is_a_folded_singular_leg() {
        // Equal links fold back onto the base joint: reachable, zero root (singular).
        let d = solve(Vector2::zeros(), 0.15, 0.15, 1.0).unwrap();
        assert_eq!(d.root, 0.0);
        assert!(solve(Vector2::zeros(), 0.15, 0.10, 1.0).is_none());
    }

    #[test]
    fn out_of_reach_has_no_solution() {
        // |r| = 0.31 > l1 + l2 = 0.30.
        assert!(solve(Vector2::new(0.31, 0.0), 0.15, 0.15, 1.0).is_none());
    }

    #[test]
    fn root_is_minus_cross_of_proximal_direction_with_r() {
        // From cos/sin above: r . E (cos, sin) = -delta sqrt(Gamma), E = rotation by 90 deg.
        let r = Vector2::new(-0.05, 0.22);
        let d = solve(r, 0.15, 0.15, -1.0).unwrap();
        let (s, c) = d.angle().sin_cos();
        assert!((r.x * -s + r.y * c + d.root).abs() < 1e-12);
    }
}
