//! PID gains by pole placement on the linearised plant.
//!
//! With the gravity compensation G_x(theta) as feedforward and the coupling between the
//! axes neglected, each Euler angle is a pure inertia, m_i x_ddot = u_i, with m_i a
//! diagonal entry of M_x = E^T M E. The PID with its derivative taken from the rate
//! inputs (unfiltered), u = Kp e + Ki int(e) + Kd e_dot, closes the loop with the
//! characteristic polynomial m s^3 + Kd s^2 + Kp s + Ki. Placing a triple real pole at
//! s = -w (critically damped, bandwidth w) gives Kd = 3 m w, Kp = 3 m w^2, Ki = m w^3.
//! Using the largest m_i met on the motion keeps the loop stable where the real inertia
//! is smaller (the ratio would have to fall below 1/9 to destabilise it). The rule is
//! the "pid" rule of robofmu/closed_loop.toml, which the Python harness designs with.

use super::error::LoopError;
use super::form::FORM;
use crate::control::pid::PidGains;
use crate::pss3::dynamics::Plant;
use nalgebra::Vector3;

/// Gains of one channel for inertia `inertia` (kg m^2) and bandwidth `bandwidth` (rad/s).
pub fn triple_pole_gains(inertia: f64, bandwidth: f64) -> PidGains {
    let (kp, ki, kd) = FORM.pid_rule().gains(inertia, bandwidth);
    PidGains {
        kp,
        ki,
        kd,
        tf: 0.0,
        limits: None,
        use_rate_inputs: true,
    }
}

/// The per-axis design: the inertia used and the gains.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisDesign {
    /// Largest diagonal entry of M_x over the poses, per axis, kg m^2.
    pub inertia: Vector3<f64>,
    pub gains: [PidGains; 3],
}

/// Designs the three channels for the poses `poses` (Euler angles, rad) of a motion.
pub fn design_gains(
    plant: &Plant,
    poses: &[Vector3<f64>],
    bandwidth: f64,
) -> Result<AxisDesign, LoopError> {
    if !(bandwidth.is_finite() && bandwidth > 0.0) || poses.is_empty() {
        return Err(LoopError::Scenario(format!(
            "gain design needs a positive bandwidth (got {bandwidth}) and at least one pose"
        )));
    }
    let mut inertia = Vector3::zeros();
    for pose in poses {
        let form = plant.model().euler_angle_form(pose, &Vector3::zeros())?;
        inertia = inertia.zip_map(&form.mass.diagonal(), f64::max);
    }
    let gains = [0, 1, 2].map(|i| triple_pole_gains(inertia[i], bandwidth));
    Ok(AxisDesign { inertia, gains })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triple_pole_gains_place_all_poles_at_minus_bandwidth() {
        // Truth: (s + w)^3 = s^3 + 3 w s^2 + 3 w^2 s + w^3; the closed loop's
        // polynomial divided by m must have these coefficients, and -w is a root.
        let (m, w) = (0.37, 25.0);
        let g = triple_pole_gains(m, w);
        let poly = |s: f64| m * s.powi(3) + g.kd * s * s + g.kp * s + g.ki;
        assert!(poly(-w).abs() < 1e-9 * g.ki);
        assert!((g.kd / m - 3.0 * w).abs() < 1e-12 && (g.ki / m - w.powi(3)).abs() < 1e-9);
        // A triple root: the first and second derivatives vanish at -w as well.
        assert!((3.0 * m * w * w - 2.0 * g.kd * w + g.kp).abs() < 1e-9 * g.kp);
        assert!((-6.0 * m * w + 2.0 * g.kd).abs() < 1e-12);
    }
}
