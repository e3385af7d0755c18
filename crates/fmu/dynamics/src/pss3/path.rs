//! Actuator paths: the three actuators driven linearly in time from l0 to lf, and the
//! platform motion that follows (forward kinematics at position, velocity and
//! acceleration level, each sample seeded with the previous pose).

use super::error::KinematicsError;
use super::fk::{FkOptions, start_pose};
use super::motion::{ActuatorState, Motion, forward_motion};
use super::params::Geometry;
use nalgebra::Vector3;
use std::fmt;

/// Timing of a sampled path: duration and sampling step, s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub duration: f64,
    pub dt: f64,
}

/// Most samples [`Timing::times`] gives (10 million, 80 MB of times alone): a smaller
/// dt is refused rather than exhausting memory.
pub const MAX_SAMPLES: f64 = 1e7;

impl Timing {
    /// Sample times 0, dt, 2 dt, ... and always the end time `duration` (the last step
    /// is shorter when dt does not divide the duration).
    pub fn times(&self) -> Result<Vec<f64>, PathError> {
        let Timing { duration, dt } = *self;
        if !(duration.is_finite() && duration > 0.0) {
            return Err(PathError::BadTiming("duration must be positive and finite"));
        }
        if !(dt.is_finite() && dt > 0.0 && dt <= duration) {
            return Err(PathError::BadTiming(
                "dt must be positive and at most the duration",
            ));
        }
        if duration / dt > MAX_SAMPLES {
            return Err(PathError::BadTiming(
                "more than 1e7 samples: dt too small for the duration",
            ));
        }
        // Relative slack so that round-off in duration / dt does not add a tiny last step.
        let steps = (duration / dt * (1.0 - 1e-12)).ceil() as usize;
        Ok((0..steps)
            .map(|k| k as f64 * dt)
            .chain(std::iter::once(duration))
            .collect())
    }
}

/// One sample of a path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSample {
    /// Time, s.
    pub time: f64,
    /// The platform motion at this time.
    pub motion: Motion,
}

/// A path that cannot be sampled.
#[derive(Debug, Clone, PartialEq)]
pub enum PathError {
    /// Duration or step not positive and finite.
    BadTiming(&'static str),
    /// The kinematics failed at time `time`, s.
    Kinematics { time: f64, source: KinematicsError },
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadTiming(why) => write!(f, "bad path timing: {why}"),
            Self::Kinematics { time, source } => write!(f, "at t = {time} s: {source}"),
        }
    }
}

impl std::error::Error for PathError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Kinematics { source, .. } => Some(source),
            Self::BadTiming(_) => None,
        }
    }
}

/// Actuators at l(t) = l0 + (lf - l0) t / T with constant rates and zero acceleration;
/// the first pose is found from the default start pose, each later one from the
/// previous sample.
pub fn linear_actuator_path(
    geometry: &Geometry,
    l0: &Vector3<f64>,
    lf: &Vector3<f64>,
    timing: &Timing,
    options: &FkOptions,
) -> Result<Vec<PathSample>, PathError> {
    let times = timing.times()?;
    let l_dot = (lf - l0) / timing.duration;
    let mut seed = start_pose();
    let mut samples = Vec::with_capacity(times.len());
    for time in times {
        let s = time / timing.duration;
        let actuators = ActuatorState {
            l: l0 * (1.0 - s) + lf * s,
            l_dot,
            l_ddot: Vector3::zeros(),
        };
        let motion = forward_motion(geometry, &actuators, &seed, options)
            .map_err(|source| PathError::Kinematics { time, source })?;
        seed = motion.assembly.euler;
        samples.push(PathSample { time, motion });
    }
    Ok(samples)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_end_at_the_duration() {
        // Truth: counting by hand, 0, 0.3, 0.6, 0.9 and the end 1.0 (shorter last step);
        // 2 s at 0.04 s is 50 steps (51 samples) despite 2 / 0.04 = 50.000000000000004.
        let t = Timing {
            duration: 1.0,
            dt: 0.3,
        }
        .times()
        .unwrap();
        assert_eq!(t.len(), 5);
        assert!((t[3] - 0.9).abs() < 1e-15 && t[4] == 1.0);
        let t = Timing {
            duration: 2.0,
            dt: 0.04,
        };
        assert_eq!(t.times().unwrap().len(), 51);
    }

    #[test]
    fn bad_timing_and_unreachable_ends_are_errors() {
        let g = Geometry::default();
        let bad = |duration, dt| Timing { duration, dt }.times().unwrap_err();
        assert!(matches!(bad(0.0, 0.1), PathError::BadTiming(_)));
        assert!(matches!(bad(1.0, f64::NAN), PathError::BadTiming(_)));
        assert!(matches!(bad(1.0, 2.0), PathError::BadTiming(_)));
        // Truth: 2 s / 1e-300 s = 2e300 samples and 1 s / 0.99e-7 s = 1.01e7 samples
        // exceed the 1e7 bound; 1 s / 2e-7 s = 5e6 is within it.
        assert!(matches!(bad(2.0, 1e-300), PathError::BadTiming(_)));
        assert!(matches!(bad(1.0, 0.99e-7), PathError::BadTiming(_)));
        assert!(
            Timing {
                duration: 1.0,
                dt: 2e-7
            }
            .times()
            .is_ok()
        );
        // The end displacement 0.2 m lies beyond the 152 mm stroke: the last sample fails.
        let timing = Timing {
            duration: 1.0,
            dt: 0.5,
        };
        let (l0, lf) = (Vector3::repeat(0.002), Vector3::new(0.002, 0.002, 0.2));
        let e = linear_actuator_path(&g, &l0, &lf, &timing, &FkOptions::default()).unwrap_err();
        assert!(matches!(
            e,
            PathError::Kinematics {
                source: KinematicsError::OutsideStroke { leg: 3, .. },
                ..
            }
        ));
    }
}
