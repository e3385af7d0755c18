//! Gains of the computed-torque law by pole placement on its error dynamics.
//!
//! With the model exact the error of each axis obeys
//! e_ddot + Kd e_dot + Kp e + Ki int(e) = 0, a plant-independent linear system (unit
//! inertia: the gains are accelerations per error, Kp in 1/s^2, Kd in 1/s, Ki in 1/s^3).
//! Without integral action a double pole at -w: (s + w)^2, Kd = 2 w, Kp = w^2. With it a
//! triple pole at -w: (s + w)^3, Kd = 3 w, Kp = 3 w^2, Ki = w^3, the characteristic
//! polynomial the PID design places on the linearised plant (`closed_loop::gains`), so
//! both controllers have the same bandwidth w ("equal bandwidth").

use super::law::{AxisGains, ControllerError};

/// Gains of one axis for a double (`integral` false) or triple (`integral` true) real
/// pole at -`bandwidth` (rad/s), without output limits (a `const fn`: the ComputedTorque
/// FMU takes its default gains from it in its static variable table).
pub const fn pole_placement(bandwidth: f64, integral: bool) -> Result<AxisGains, ControllerError> {
    if !(bandwidth.is_finite() && bandwidth > 0.0) {
        return Err(ControllerError::Bandwidth(bandwidth));
    }
    let w = bandwidth;
    Ok(if integral {
        AxisGains {
            kp: 3.0 * w * w,
            kd: 3.0 * w,
            ki: w * w * w,
            limits: None,
        }
    } else {
        AxisGains {
            kp: w * w,
            kd: 2.0 * w,
            ki: 0.0,
            limits: None,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poles_are_repeated_at_minus_bandwidth() {
        // Truth: a repeated root of p(s) is a root of p'(s) (and of p''(s) for a triple
        // one); p(s) = s^2 + Kd s + Kp, or s^3 + Kd s^2 + Kp s + Ki.
        let w = 30.0;
        let g = pole_placement(w, false).unwrap();
        let s = -w;
        assert!((s * s + g.kd * s + g.kp).abs() < 1e-12 * g.kp);
        assert!((2.0 * s + g.kd).abs() < 1e-12 * g.kd);
        let g = pole_placement(w, true).unwrap();
        assert!((s.powi(3) + g.kd * s * s + g.kp * s + g.ki).abs() < 1e-12 * g.ki);
        assert!((3.0 * s * s + 2.0 * g.kd * s + g.kp).abs() < 1e-12 * g.kp);
        assert!((6.0 * s + 2.0 * g.kd).abs() < 1e-12 * g.kd);
        assert!(pole_placement(0.0, true).is_err());
        assert!(pole_placement(f64::NAN, false).is_err());
    }
}
