//! One channel of a PID controller with a first-order derivative filter, output limits
//! with conditional-integration anti-windup, feedforward and an optional measured-rate
//! path.
//!
//! Law (e = setpoint - measurement):
//!   u_raw = Kp e + Ki I + D + feedforward,   u = clamp(u_raw, u_min, u_max)
//!   dI/dt = e, except while the output is limited and e would drive it further out
//!           (conditional integration: then dI/dt = 0)
//! Derivative term D, two sources:
//!   * error path (default): filter state x with Tf dx/dt = e - x and
//!     D = Kd (e - x) / Tf, i.e. Kd s / (Tf s + 1) applied to e; needs Tf > 0.
//!   * rate path: the rate error r = setpoint_rate - measured_rate is given, filter
//!     Tf dx/dt = r - x and D = Kd x; with Tf = 0 the filter is bypassed (D = Kd r).
//!
//! Discrete step (co-simulation): inputs are held constant over the step (zero-order
//! hold). Under that assumption the filter update x(t+h) = w + (x - w) exp(-h/Tf) and the
//! integral update I(t+h) = I + e h are exact. The anti-windup decision is taken once
//! at the start of the step from the values there, and holds for the whole step.
//! Inputs that follow a quadratic over the step: `pid_ramp`.

/// Gains and options of one channel (default: all zero, unlimited, error path).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PidGains {
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    /// Derivative filter time constant, s (0 only with the rate path).
    pub tf: f64,
    /// Output limits (u_min, u_max), or None for an unlimited output.
    pub limits: Option<(f64, f64)>,
    /// Take the derivative from the rate inputs instead of filtering the error.
    pub use_rate_inputs: bool,
}

/// Inputs of one channel.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PidInputs {
    pub setpoint: f64,
    pub measurement: f64,
    pub setpoint_rate: f64,
    pub measured_rate: f64,
    pub feedforward: f64,
}

/// Continuous state of one channel: error integral and derivative-filter state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PidState {
    pub integral: f64,
    pub filter: f64,
}

/// Shortest positive derivative filter time constant, 1 ps: a faster filter pole
/// (1/Tf above 1e12 rad/s) is no filter at all for any step a simulation takes, and
/// toward Tf -> 0 the filter's state derivative (e - x)/Tf overflows.
pub const MIN_FILTER_TIME: f64 = 1e-12;

/// Why a set of gains is unusable.
#[derive(Debug, Clone, PartialEq)]
pub enum PidError {
    NonFinite(&'static str),
    NegativeFilterTime(f64),
    /// 0 < Tf below [`MIN_FILTER_TIME`]: the filter pole 1/Tf would overflow the model.
    FilterTooShort(f64),
    /// The error path differentiates through the filter: Tf must be positive.
    FilterNeeded,
    EmptyLimits {
        min: f64,
        max: f64,
    },
}

impl std::fmt::Display for PidError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PidError::NonFinite(what) => write!(f, "{what} is not a finite number"),
            PidError::NegativeFilterTime(tf) => {
                write!(
                    f,
                    "the derivative filter time constant Tf = {tf} s is negative"
                )
            }
            PidError::FilterTooShort(tf) => {
                write!(
                    f,
                    "the derivative filter time constant Tf = {tf} s is below {MIN_FILTER_TIME} s \
                     (use Tf = 0 with rate inputs for an unfiltered derivative)"
                )
            }
            PidError::FilterNeeded => write!(
                f,
                "Kd != 0 without rate inputs needs a derivative filter time constant Tf >= {MIN_FILTER_TIME} s"
            ),
            PidError::EmptyLimits { min, max } => {
                write!(
                    f,
                    "the output limits are empty: u_min = {min} >= u_max = {max}"
                )
            }
        }
    }
}

impl std::error::Error for PidError {}

impl PidGains {
    /// Checks that the gains define a well-posed controller.
    pub fn validate(&self) -> Result<(), PidError> {
        for (v, name) in [
            (self.kp, "Kp"),
            (self.ki, "Ki"),
            (self.kd, "Kd"),
            (self.tf, "Tf"),
        ] {
            if !v.is_finite() {
                return Err(PidError::NonFinite(name));
            }
        }
        if self.tf < 0.0 {
            return Err(PidError::NegativeFilterTime(self.tf));
        }
        if self.tf > 0.0 && self.tf < MIN_FILTER_TIME {
            return Err(PidError::FilterTooShort(self.tf));
        }
        if !self.use_rate_inputs && self.kd != 0.0 && self.tf <= 0.0 {
            return Err(PidError::FilterNeeded);
        }
        if let Some((min, max)) = self.limits {
            if !min.is_finite() || !max.is_finite() {
                return Err(PidError::NonFinite("an output limit"));
            }
            if min >= max {
                return Err(PidError::EmptyLimits { min, max });
            }
        }
        Ok(())
    }

    /// Whether the derivative filter has a state that moves.
    pub(crate) fn filter_active(&self) -> bool {
        self.tf > 0.0 && (self.use_rate_inputs || self.kd != 0.0)
    }
}

/// The output and its parts at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PidOutput {
    /// Limited control output.
    pub u: f64,
    /// Output before the limits.
    pub u_raw: f64,
    pub error: f64,
    pub derivative_term: f64,
}

/// The input w of the derivative filter (the error, or the rate error).
pub(crate) fn filter_input(g: &PidGains, i: &PidInputs) -> f64 {
    if g.use_rate_inputs {
        i.setpoint_rate - i.measured_rate
    } else {
        i.setpoint - i.measurement
    }
}

/// Output of the controller for the given state and inputs.
pub fn output(g: &PidGains, s: &PidState, i: &PidInputs) -> PidOutput {
    let e = i.setpoint - i.measurement;
    let derivative_term = if g.use_rate_inputs {
        let rate_error = i.setpoint_rate - i.measured_rate;
        g.kd * if g.tf > 0.0 { s.filter } else { rate_error }
    } else if g.kd != 0.0 {
        g.kd * (e - s.filter) / g.tf
    } else {
        0.0
    };
    let u_raw = g.kp * e + g.ki * s.integral + derivative_term + i.feedforward;
    let u = match g.limits {
        Some((min, max)) => u_raw.clamp(min, max),
        None => u_raw,
    };
    PidOutput {
        u,
        u_raw,
        error: e,
        derivative_term,
    }
}

/// True when conditional integration stops the integral: the output is at a limit and
/// the integral term would push it further beyond.
pub fn integration_stopped(g: &PidGains, out: &PidOutput) -> bool {
    let push = g.ki * out.error;
    match g.limits {
        Some((min, max)) => (out.u_raw >= max && push > 0.0) || (out.u_raw <= min && push < 0.0),
        None => false,
    }
}

/// Time derivatives (dI/dt, dx/dt) of the continuous state.
pub fn derivatives(g: &PidGains, s: &PidState, i: &PidInputs) -> PidState {
    let out = output(g, s, i);
    let integral = if integration_stopped(g, &out) {
        0.0
    } else {
        out.error
    };
    let filter = if g.filter_active() {
        (filter_input(g, i) - s.filter) / g.tf
    } else {
        0.0
    };
    PidState { integral, filter }
}

/// State after a step of length h with the inputs held constant (exact for that input).
pub fn step(g: &PidGains, s: &PidState, i: &PidInputs, h: f64) -> PidState {
    let out = output(g, s, i);
    let integral = if integration_stopped(g, &out) {
        s.integral
    } else {
        s.integral + out.error * h
    };
    let filter = if g.filter_active() {
        let w = filter_input(g, i);
        w + (s.filter - w) * (-h / g.tf).exp()
    } else {
        s.filter
    };
    PidState { integral, filter }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gains() -> PidGains {
        PidGains {
            kp: 2.0,
            ki: 0.5,
            kd: 0.3,
            tf: 0.05,
            limits: None,
            use_rate_inputs: false,
        }
    }

    #[test]
    fn step_response_to_a_constant_error_is_the_closed_form() {
        // Expected values: with e = 1 held and zero initial state,
        // u(t) = Kp + Ki t + Kd/Tf exp(-t/Tf) (Laplace inverse of the PID on a step).
        let g = gains();
        let inputs = PidInputs {
            setpoint: 1.0,
            ..PidInputs::default()
        };
        let mut s = PidState::default();
        let h = 0.013;
        for k in 1..=100 {
            s = step(&g, &s, &inputs, h);
            let t = k as f64 * h;
            let want = 2.0 + 0.5 * t + 0.3 / 0.05 * (-t / 0.05).exp();
            assert!((output(&g, &s, &inputs).u - want).abs() < 1e-12, "t={t}");
        }
    }

    #[test]
    fn rate_path_filters_the_rate_error() {
        // Expected values: D(t) = Kd r (1 - exp(-t/Tf)) for a constant rate error r.
        let g = PidGains {
            use_rate_inputs: true,
            kp: 0.0,
            ki: 0.0,
            ..gains()
        };
        let inputs = PidInputs {
            setpoint_rate: 0.25,
            measured_rate: -0.5,
            ..PidInputs::default()
        };
        let s = step(&g, &PidState::default(), &inputs, 0.1);
        let want = 0.3 * 0.75 * (1.0 - (-0.1f64 / 0.05).exp());
        assert!((output(&g, &s, &inputs).u - want).abs() < 1e-14);
        let unfiltered = PidGains { tf: 0.0, ..g };
        assert!((output(&unfiltered, &s, &inputs).u - 0.3 * 0.75).abs() < 1e-15);
    }

    #[test]
    fn discrete_step_agrees_with_fine_integration_of_the_derivatives() {
        // Second formulation: explicit Euler on `derivatives` with 1e5 substeps
        // converges to the exact step (error O(h)).
        let g = gains();
        let inputs = PidInputs {
            setpoint: 0.4,
            measurement: -0.2,
            feedforward: 0.1,
            ..PidInputs::default()
        };
        let s0 = PidState {
            integral: 0.3,
            filter: -0.1,
        };
        let exact = step(&g, &s0, &inputs, 0.2);
        let n = 100_000;
        let mut s = s0;
        for _ in 0..n {
            let d = derivatives(&g, &s, &inputs);
            s.integral += d.integral * 0.2 / n as f64;
            s.filter += d.filter * 0.2 / n as f64;
        }
        assert!((s.integral - exact.integral).abs() < 1e-9);
        assert!((s.filter - exact.filter).abs() < 1e-4);
    }

    #[test]
    fn conditional_integration_freezes_the_integral_at_the_limit() {
        // Expected values: Kp = 1, Ki = 2, e = 1: u_raw = 1 + 2 t reaches u_max = 3 at
        // t = 1 s; afterwards the integral stays at 1 and u at 3.
        let g = PidGains {
            kp: 1.0,
            ki: 2.0,
            kd: 0.0,
            tf: 0.0,
            limits: Some((-3.0, 3.0)),
            use_rate_inputs: false,
        };
        let inputs = PidInputs {
            setpoint: 1.0,
            ..PidInputs::default()
        };
        let mut s = PidState::default();
        for _ in 0..40 {
            s = step(&g, &s, &inputs, 0.125);
        }
        assert_eq!(s.integral, 1.0);
        assert_eq!(output(&g, &s, &inputs).u, 3.0);
        // A reversed error integrates again at once.
        let back = PidInputs {
            setpoint: -1.0,
            ..inputs
        };
        assert_eq!(step(&g, &s, &back, 0.125).integral, 1.0 - 0.125);
    }

    #[test]
    fn validation_rejects_ill_posed_gains() {
        let g = gains();
        assert_eq!(
            PidGains { tf: 0.0, ..g }.validate(),
            Err(PidError::FilterNeeded)
        );
        assert_eq!(
            PidGains { tf: -1.0, ..g }.validate(),
            Err(PidError::NegativeFilterTime(-1.0))
        );
        // The smallest subnormal: (e - x)/Tf overflows for any |e - x| > 1.8e-16.
        assert_eq!(
            PidGains { tf: 5e-324, ..g }.validate(),
            Err(PidError::FilterTooShort(5e-324))
        );
        assert!(
            PidGains {
                tf: MIN_FILTER_TIME,
                ..g
            }
            .validate()
            .is_ok()
        );
        assert_eq!(
            PidGains {
                limits: Some((1.0, 1.0)),
                ..g
            }
            .validate(),
            Err(PidError::EmptyLimits { min: 1.0, max: 1.0 })
        );
        assert_eq!(
            PidGains { kp: f64::NAN, ..g }.validate(),
            Err(PidError::NonFinite("Kp"))
        );
        assert!(g.validate().is_ok());
    }
}
