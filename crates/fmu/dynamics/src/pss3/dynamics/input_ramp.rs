//! Inputs that change along a quadratic over a step instead of being held: the
//! inputs at the start of the step and their first and second time derivatives
//! there, so that s seconds into the step the inputs are u + u' s + u'' s^2/2.
//! A caller that knows how its inputs move (a ramp, the slope of a sampled signal)
//! integrates the step with them instead of with their start values: the input
//! error per step falls from O(h) (held) to O(h^2) (rate) or O(h^3) (rate and
//! acceleration).

use super::plant::PlantInputs;
use nalgebra::Vector3;

/// Time derivatives of every plant input at the start of a step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InputRamp {
    /// First time derivatives (input unit per second).
    pub rate: PlantInputs,
    /// Second time derivatives (input unit per second squared).
    pub acceleration: PlantInputs,
}

impl InputRamp {
    /// True when every derivative is zero: the inputs are held over the step.
    pub fn is_held(&self) -> bool {
        *self == Self::default()
    }

    /// The inputs `s` seconds after the start of the step, where they were `start`.
    pub fn inputs_at(&self, start: &PlantInputs, s: f64) -> PlantInputs {
        let (r, a) = (&self.rate, &self.acceleration);
        let at = |u: Vector3<f64>, rate: Vector3<f64>, acceleration: Vector3<f64>| {
            u + (rate + acceleration * (0.5 * s)) * s
        };
        PlantInputs {
            forces: at(start.forces, r.forces, a.forces),
            disturbance_torque: at(
                start.disturbance_torque,
                r.disturbance_torque,
                a.disturbance_torque,
            ),
            commanded_torque: at(
                start.commanded_torque,
                r.commanded_torque,
                a.commanded_torque,
            ),
            generalized_force: at(
                start.generalized_force,
                r.generalized_force,
                a.generalized_force,
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inputs_follow_the_quadratic_of_their_derivatives() {
        // Expected values: u(s) = u + u' s + u'' s^2/2 at s = 0.5 by hand:
        // 2 + 4 * 0.5 + (-8) * 0.125 = 3; 1 + 0 + 6 * 0.125 = 1.75.
        let start = PlantInputs {
            forces: Vector3::new(2.0, 0.0, 0.0),
            generalized_force: Vector3::new(0.0, 0.0, 1.0),
            ..PlantInputs::default()
        };
        let mut ramp = InputRamp::default();
        assert!(ramp.is_held());
        ramp.rate.forces.x = 4.0;
        ramp.acceleration.forces.x = -8.0;
        ramp.acceleration.generalized_force.z = 6.0;
        assert!(!ramp.is_held());
        let u = ramp.inputs_at(&start, 0.5);
        assert_eq!(u.forces, Vector3::new(3.0, 0.0, 0.0));
        assert_eq!(u.generalized_force, Vector3::new(0.0, 0.0, 1.75));
        assert_eq!(ramp.inputs_at(&start, 0.0), start);
    }
}
