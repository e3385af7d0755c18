//! Exact co-simulation step of the PID law (`pid`) for inputs that follow a quadratic
//! over the step: every input q(s) = q + q' s + q'' s^2/2, s the time since the step
//! start, so the error is e(s) = e0 + e1 s + e2 s^2/2 and the filter input
//! w(s) = w0 + w1 s + w2 s^2/2 (w = e, or the rate error on the rate path).
//!
//! Integral: I(h) = I + e0 h + e1 h^2/2 + e2 h^3/6.
//!
//! Filter, Tf x' = w - x: with z = h/Tf,
//!   x(h) = w0 + (x - w0) exp(-z) + h (w1 F2(z) + w2 h F3(z)),
//!   F2(z) = z E2(z), F3(z) = z E3(z), E_k(z) = sum_{j >= 0} (-z)^j / (j + k)!,
//! the first two terms being the held-input step. Derivation (docs/pid-input-ramp.md):
//! the polynomial p with Tf p' + p = w is p(s) = a0 + a1 s + a2 s^2/2 with
//! a2 = w2, a1 = w1 - Tf w2, a0 = w0 - Tf w1 + Tf^2 w2, and x(h) = p(h) + (x - a0) exp(-z);
//! grouping the terms by w1 and w2 gives Tf (z - 1 + exp(-z)) = h F2(z) and
//! Tf^2 (z^2/2 - z + 1 - exp(-z)) = h^2 F3(z), which the series (z <= 1) and the
//! forms with expm1 (z > 1) evaluate without cancellation for any Tf.
//!
//! Conditional integration: as for held inputs, the decision is taken at the start
//! of the step from the values there and holds for the whole step: the integral takes
//! the whole polynomial or stays frozen. Where the saturation switches inside a step
//! the step is therefore not exact; its integral is off by at most the integral of |e|
//! over the rest of that step (below max|e| h), once per switch. Model Exchange
//! switches at the instant itself.

use crate::pid::{self, PidGains, PidInputs, PidState};

/// First and second time derivatives of a channel's inputs at the start of a step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PidInputRamp {
    pub rate: PidInputs,
    pub acceleration: PidInputs,
}

impl PidInputRamp {
    /// True when every derivative is zero: the inputs are held.
    pub fn is_held(&self) -> bool {
        *self == Self::default()
    }

    /// The input derivatives of order n: 1 the rates, 2 the accelerations (None for
    /// another order).
    pub fn order_mut(&mut self, n: u32) -> Option<&mut PidInputs> {
        match n {
            1 => Some(&mut self.rate),
            2 => Some(&mut self.acceleration),
            _ => None,
        }
    }
}

/// z E_k(z) for k = 2 and 3 (see the module documentation): (F2, F3).
fn ramp_weights(z: f64) -> (f64, f64) {
    if z <= 1.0 {
        // E_k(z) = sum_j (-z)^j / (j + k)!: 20 terms reach 1/22! < 1e-21 at z = 1.
        let series = |k: u32| {
            let (mut term, mut sum) = ((2..=k).map(f64::from).product::<f64>().recip(), 0.0);
            for j in 0..20 {
                sum += term;
                term *= -z / f64::from(j + k + 1);
            }
            z * sum
        };
        (series(2), series(3))
    } else {
        let m = (-z).exp_m1(); // exp(-z) - 1
        (1.0 + m / z, 0.5 - 1.0 / z - m / (z * z))
    }
}

/// State after a step of length h with the inputs starting at `i` and following `ramp`
/// (exact for that input, up to the anti-windup decision; a held ramp gives exactly
/// `pid::step`).
pub fn step_with_ramp(
    g: &PidGains,
    s: &PidState,
    i: &PidInputs,
    ramp: &PidInputRamp,
    h: f64,
) -> PidState {
    let held = pid::step(g, s, i, h);
    if ramp.is_held() {
        return held;
    }
    let (r, a) = (&ramp.rate, &ramp.acceleration);
    let integrating = !pid::integration_stopped(g, &pid::output(g, s, i));
    let integral = if integrating {
        let (e1, e2) = (r.setpoint - r.measurement, a.setpoint - a.measurement);
        held.integral + h * h * (e1 / 2.0 + e2 * h / 6.0)
    } else {
        held.integral
    };
    let filter = if g.filter_active() {
        let (f2, f3) = ramp_weights(h / g.tf);
        let (w1, w2) = (pid::filter_input(g, r), pid::filter_input(g, a));
        held.filter + h * (w1 * f2 + w2 * h * f3)
    } else {
        held.filter
    };
    PidState { integral, filter }
}

/// The n-th time derivative (n >= 1; 0: the output) of the output at state `s`, the
/// inputs `i` (as set) moving with the derivatives of `ramp` (a zero ramp: held): what
/// FMI output derivatives report at a communication point. With e, w (the filter's
/// input) and ff following the inputs, x^(k) = (w^(k-1) - x^(k-1)) / Tf and
/// I^(k) = e^(k-1), so u_raw^(n) = Kp e^(n) + Ki e^(n-1) + D^(n) + ff^(n), with
/// D^(n) = Kd (e^(n) - x^(n)) / Tf on the error path, Kd x^(n) on the rate path
/// (Kd w^(n) without its filter); input derivatives beyond the second are 0.
///
/// At a limit the output is the limit: every derivative is 0 where u_raw is beyond a
/// limit, or at it and not moving back inside (u_raw' pushing out or 0, which is also
/// where conditional integration holds the integral); at a limit and moving back
/// inside, the right derivatives, those of u_raw.
pub fn output_slope(g: &PidGains, s: &PidState, i: &PidInputs, ramp: &PidInputRamp, n: u32) -> f64 {
    let out = pid::output(g, s, i);
    if n == 0 {
        return out.u;
    }
    // Derivative k of the inputs (0: the inputs themselves).
    let input = |k: u32| match k {
        0 => *i,
        1 => ramp.rate,
        2 => ramp.acceleration,
        _ => PidInputs::default(),
    };
    let e = |k: u32| input(k).setpoint - input(k).measurement;
    let raw = |n: u32| {
        let mut x = s.filter;
        for k in 1..=n {
            x = (pid::filter_input(g, &input(k - 1)) - x) / g.tf;
        }
        let d = match (g.use_rate_inputs, g.filter_active()) {
            (true, true) => g.kd * x,
            (true, false) => g.kd * pid::filter_input(g, &input(n)),
            (false, true) => g.kd * (e(n) - x) / g.tf,
            (false, false) => 0.0,
        };
        g.kp * e(n) + g.ki * e(n - 1) + d + input(n).feedforward
    };
    let at_limit = match g.limits {
        Some((min, max)) => {
            let (u, rate) = (out.u_raw, raw(1));
            u > max || u < min || (u == max && rate >= 0.0) || (u == min && rate <= 0.0)
        }
        None => false,
    };
    if at_limit { 0.0 } else { raw(n) }
}
