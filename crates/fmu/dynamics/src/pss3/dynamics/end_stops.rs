//! End stops of the actuators: a unilateral stiff spring-damper beyond each end of the
//! stroke, or (mode `Error`) a clean error that stops the simulation.
//!
//! Penetration d = l - l_max (upper stop) or l_min - l (lower stop), when positive,
//! gives the stop force f = -(k d + c d_dot) on the slider along u (sign towards the
//! stroke), clamped so that the stop pushes and never pulls. With c = 0 the stop is
//! conservative with potential k d^2 / 2.
//!
//! Defaults k = 1e6 N/m and c = 2e3 N s/m: the mass an actuator feels at the start pose
//! is of the order of 1..3 kg, so the stop rings at about sqrt(1e6 / 2) = 700 rad/s
//! (110 Hz) with a damping ratio c / (2 sqrt(k m)) of about 0.6..1, and a 500 N push
//! penetrates 0.5 mm.

use super::error::{DynamicsError, PlantParamError};
use crate::pss3::KinematicsError;

/// What an actuator running past its stroke does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndStopMode {
    /// A stiff spring-damper stop (physical; flagged in the outputs).
    Spring,
    /// The state is refused with `KinematicsError::OutsideStroke` (the step fails).
    Error,
}

/// End-stop constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndStops {
    /// Stiffness k, N/m.
    pub stiffness: f64,
    /// Damping c, N s/m.
    pub damping: f64,
    /// Spring-damper or error.
    pub mode: EndStopMode,
}

impl Default for EndStops {
    fn default() -> Self {
        Self {
            stiffness: 1e6,
            damping: 2e3,
            mode: EndStopMode::Spring,
        }
    }
}

/// Which stop, if any, an actuator is pressing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StopContact {
    /// Within the stroke.
    #[default]
    Free,
    /// Beyond the lower end of the stroke.
    Lower,
    /// Beyond the upper end of the stroke.
    Upper,
}

impl StopContact {
    /// Integer flag for an FMU output: -1 lower stop, 0 free, +1 upper stop.
    pub fn code(self) -> i32 {
        match self {
            Self::Free => 0,
            Self::Lower => -1,
            Self::Upper => 1,
        }
    }
}

/// The stop force on one actuator and its contact state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopForce {
    /// Force along u, N.
    pub force: f64,
    /// Which stop acts.
    pub contact: StopContact,
}

impl EndStops {
    /// Checks that the constants are finite and non-negative (stiffness positive for
    /// spring stops).
    pub fn validate(&self) -> Result<(), PlantParamError> {
        for (name, v) in [
            ("end_stop_stiffness", self.stiffness),
            ("end_stop_damping", self.damping),
        ] {
            if !v.is_finite() {
                return Err(PlantParamError::NotFinite(name));
            }
            if v < 0.0 {
                return Err(PlantParamError::Negative(name, v));
            }
        }
        if self.mode == EndStopMode::Spring && self.stiffness <= 0.0 {
            return Err(PlantParamError::NotPositive(
                "end_stop_stiffness",
                self.stiffness,
            ));
        }
        Ok(())
    }

    /// Stop force on actuator `leg` (0-based) at displacement `l`, velocity `l_dot`, for
    /// the stroke [min, max]; in mode `Error` a displacement outside the stroke is an error.
    pub fn force(
        &self,
        leg: usize,
        l: f64,
        l_dot: f64,
        (min, max): (f64, f64),
    ) -> Result<StopForce, DynamicsError> {
        let contact = if l > max {
            StopContact::Upper
        } else if l < min {
            StopContact::Lower
        } else {
            StopContact::Free
        };
        if contact != StopContact::Free && self.mode == EndStopMode::Error {
            return Err(KinematicsError::OutsideStroke {
                leg: leg + 1,
                l,
                min,
                max,
            }
            .into());
        }
        let force = match contact {
            StopContact::Free => 0.0,
            StopContact::Upper => (-self.stiffness * (l - max) - self.damping * l_dot).min(0.0),
            StopContact::Lower => (self.stiffness * (min - l) - self.damping * l_dot).max(0.0),
        };
        Ok(StopForce { force, contact })
    }

    /// Energy stored in the stop springs of actuator displacement `l`, J.
    pub fn potential_energy(&self, l: f64, (min, max): (f64, f64)) -> f64 {
        let penetration = (l - max).max(min - l).max(0.0);
        0.5 * self.stiffness * penetration * penetration
    }
}
