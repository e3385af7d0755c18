//! Tracking figures of a simulated loop: the numbers the controllers are compared by.

use super::simulate::LoopSample;

/// Tracking error and actuator effort of one run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tracking {
    /// Root mean square over the samples of the error vector's norm |q - theta|, rad.
    pub rms_error: f64,
    /// Largest error of any axis at any sample, rad.
    pub max_error: f64,
    /// Largest actuator force magnitude at any sample, N.
    pub peak_force: f64,
}

/// The tracking figures of `samples` (communication points of one run; empty: zeros).
pub fn tracking(samples: &[LoopSample]) -> Tracking {
    let sum: f64 = samples.iter().map(|s| (s.q - s.theta).norm_squared()).sum();
    let count = samples.len().max(1) as f64;
    let max = |f: fn(&LoopSample) -> f64| samples.iter().map(f).fold(0.0, f64::max);
    Tracking {
        rms_error: (sum / count).sqrt(),
        max_error: max(|s| (s.q - s.theta).amax()),
        peak_force: max(|s| s.force.amax()),
    }
}
