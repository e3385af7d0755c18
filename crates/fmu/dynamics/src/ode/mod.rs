//! Explicit Runge-Kutta pairs with adaptive step size: Dormand and Prince's 5(4) pair
//! ([`dopri5`]) and their 8(5,3) pair ([`dop853`]), with the step-size control and the
//! starting step of Hairer, Norsett and Wanner, *Solving Ordinary Differential
//! Equations I* (2nd ed., Springer 1993), section II.4 and the codes DOPRI5 and DOP853
//! described there.
//!
//! Only what the robot library needs: the state at the end of an interval (no dense
//! output, no stiffness detection). A right-hand side that cannot be evaluated writes
//! NaN; the error estimate is then NaN, the step is rejected and retried with the
//! smallest allowed step ratio, so a model that fails in a trial stage shrinks the step
//! instead of poisoning the state.
//!
//! The arithmetic (step-size formulas, order of the sums, coefficient values) is that
//! of the crate ode_solvers 0.6.2 with the same settings, so results agree with it bit
//! for bit; differences: DOP853's twelfth stage is evaluated at the step end (`c12 = 1`,
//! Hairer's value; ode_solvers uses 0, which only autonomous systems do not notice), the
//! first derivative is evaluated once (ode_solvers evaluates it twice), and
//! `max_steps` bounds the step attempts of both pairs alike.

mod dop853;
mod dopri5;

pub use dop853::{dop853, dop853_observed};
pub use dopri5::dopri5;

use nalgebra::{DefaultAllocator, Dim, OVector, U1, allocator::Allocator};
use std::fmt;

/// Settings of an integration (Hairer's names in brackets).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance (RTOL).
    pub rtol: f64,
    /// Absolute tolerance (ATOL).
    pub atol: f64,
    /// Safety factor of the step-size control (SAFE).
    pub safety: f64,
    /// Exponent of the previous error in the stabilised control (BETA); 0: the
    /// classical control.
    pub beta: f64,
    /// Smallest ratio of a new step to the previous one (FAC1).
    pub fac_min: f64,
    /// Largest ratio of a new step to the previous one (FAC2).
    pub fac_max: f64,
    /// Largest step (HMAX).
    pub h_max: f64,
    /// First step to try; 0: chosen from the problem (Hairer's HINIT).
    pub h_initial: f64,
    /// Largest number of step attempts, accepted or rejected (NMAX).
    pub max_steps: u32,
}

impl Settings {
    /// DOPRI5's defaults with both tolerances `tol` and largest step `h_max`.
    pub fn dopri5(tol: f64, h_max: f64) -> Self {
        Self {
            rtol: tol,
            atol: tol,
            safety: 0.9,
            beta: 0.04,
            fac_min: 0.2,
            fac_max: 10.0,
            h_max,
            h_initial: 0.0,
            max_steps: 100_000,
        }
    }

    /// DOP853's defaults with both tolerances `tol` and largest step `h_max`.
    pub fn dop853(tol: f64, h_max: f64) -> Self {
        Self {
            rtol: tol,
            atol: tol,
            safety: 0.9,
            beta: 0.0,
            fac_min: 0.333,
            fac_max: 6.0,
            h_max,
            h_initial: 0.0,
            max_steps: 100_000,
        }
    }
}

/// Why an integration stopped before its end.
#[derive(Debug, Clone, PartialEq)]
pub enum OdeError {
    /// `max_steps` step attempts did not reach the end.
    TooManySteps { x: f64, steps: u32 },
    /// The step became too small to change the independent variable.
    StepSizeUnderflow { x: f64 },
}

impl fmt::Display for OdeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooManySteps { x, steps } => {
                write!(f, "stopped at x = {x}: more than {steps} steps needed")
            }
            Self::StepSizeUnderflow { x } => write!(f, "stopped at x = {x}: step size underflow"),
        }
    }
}

impl std::error::Error for OdeError {}

/// Counts of an integration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Stats {
    /// Right-hand side evaluations.
    pub evaluations: u32,
    /// Accepted steps.
    pub accepted: u32,
    /// Rejected steps (a NaN stage included).
    pub rejected: u32,
}

/// The end of a finished integration.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// The independent variable reached (the end, up to rounding of the step sums).
    pub x: f64,
    /// The state there.
    pub y: OVector<f64, D>,
    pub stats: Stats,
}

/// Hairer's step-size control (Solving ODEs I, II.4 (4.13) and the stabilised form of
/// IV.2 in DOPRI5): the new step is `h / fac` with `fac = err^alpha / fac_old^beta / safety`
/// clamped to `[1/fac_max, 1/fac_min]`; after a rejection the step may not grow.
struct Control {
    alpha: f64,
    beta: f64,
    /// 1 / fac_min and 1 / fac_max.
    inv_fac_min: f64,
    inv_fac_max: f64,
    safety: f64,
    h_max: f64,
    /// The error of the last accepted step (at least 1e-4).
    err_old: f64,
    rejected_last: bool,
    direction: f64,
}

/// What the control made of one step attempt.
struct Verdict {
    accepted: bool,
    h_new: f64,
}

impl Control {
    /// `alpha` is the exponent of the error: 1/(q+1) less `beta` times a pair's share.
    fn new(settings: &Settings, alpha: f64, direction: f64) -> Self {
        Self {
            alpha,
            beta: settings.beta,
            inv_fac_min: 1.0 / settings.fac_min,
            inv_fac_max: 1.0 / settings.fac_max,
            safety: settings.safety,
            h_max: settings.h_max.abs(),
            err_old: 1.0e-4,
            rejected_last: false,
            direction,
        }
    }

    /// Judges a step of size `h` with scaled error `err` (NaN: rejected with the
    /// smallest ratio).
    fn judge(&mut self, err: f64, h: f64) -> Verdict {
        let fac11 = err.powf(self.alpha);
        // f64::min/max ignore a NaN operand: a NaN error gives the clamp's bound.
        let fac = fac11 * self.err_old.powf(-self.beta);
        let fac = self
            .inv_fac_max
            .max(self.inv_fac_min.min(fac / self.safety));
        let mut h_new = h / fac;
        if err <= 1.0 {
            self.err_old = err.max(1.0e-4);
            if h_new.abs() > self.h_max {
                h_new = self.direction * self.h_max;
            }
            if self.rejected_last {
                h_new = self.direction * h_new.abs().min(h.abs());
            }
            self.rejected_last = false;
            Verdict {
                accepted: true,
                h_new,
            }
        } else {
            self.rejected_last = true;
            Verdict {
                accepted: false,
                h_new: h / self.inv_fac_min.min(fac11 / self.safety),
            }
        }
    }
}

/// `|a|` with the sign of `b` (Fortran's SIGN, 0 counting as negative).
fn with_sign(a: f64, b: f64) -> f64 {
    if b > 0.0 { a.abs() } else { -a.abs() }
}

/// Hairer's starting step (Solving ODEs I, II.4, "Starting step size"; HINIT in DOPRI5
/// and DOP853) for a method of order `order`, from `f0 = f(x, y)`; evaluates `f` once.
fn initial_step<D, F>(
    f: &mut F,
    x: f64,
    y: &OVector<f64, D>,
    f0: &OVector<f64, D>,
    settings: &Settings,
    direction: f64,
    order_inverse: f64,
) -> f64
where
    D: Dim,
    DefaultAllocator: Allocator<D>,
    F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
{
    let h_max = settings.h_max.abs();
    let scale = |yi: f64| settings.atol + yi.abs() * settings.rtol;
    let (mut dny, mut dnf) = (0.0, 0.0);
    for (&yi, &fi) in y.iter().zip(f0.iter()) {
        let sk = scale(yi);
        dny += (yi / sk) * (yi / sk);
        dnf += (fi / sk) * (fi / sk);
    }
    let h = if dny < 1.0e-10 || dnf < 1.0e-10 {
        1.0e-6
    } else {
        0.01 * (dny / dnf).sqrt()
    };
    let h = with_sign(h.min(h_max), direction);
    // An explicit Euler step, to estimate the second derivative.
    let mut y1 = y.clone();
    for (y1i, &fi) in y1.iter_mut().zip(f0.iter()) {
        *y1i += fi * h;
    }
    let mut f1 = f0.clone();
    f(x + h, &y1, &mut f1);
    let mut der2 = 0.0;
    for ((&yi, &f0i), &f1i) in y.iter().zip(f0.iter()).zip(f1.iter()) {
        let sk = scale(yi);
        der2 += ((f1i - f0i) / sk) * ((f1i - f0i) / sk);
    }
    let der2 = der2.sqrt() / h;
    let der12 = dnf.sqrt().max(der2.abs());
    let h1 = if der12 <= 1.0e-15 {
        1.0e-6_f64.max(h.abs() * 1.0e-3)
    } else {
        (0.01 / dnf.sqrt().max(der2)).powf(order_inverse)
    };
    with_sign((100.0 * h.abs()).min(h1.min(h_max)), direction)
}

/// One Runge-Kutta pair: its stages over a trial step and what an accepted step keeps.
trait Pair<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// The starting step's exponent 1 / IORD (Hairer's HINIT: 5 for DOPRI5, 8 for
    /// DOP853).
    const ORDER_INVERSE: f64;

    /// Workspace for states shaped like `y`.
    fn new(y: &OVector<f64, D>) -> Self;

    /// The exponent of the error in the step-size control for stabilisation `beta`.
    fn alpha(beta: f64) -> f64;

    /// Where the derivative at the step start lives.
    fn start_derivative(&mut self) -> &mut OVector<f64, D>;

    /// Runs the stages of a step of size `h` from `(x, y)` and returns its scaled error
    /// (NaN when a stage was NaN).
    fn attempt<F>(
        &mut self,
        f: &mut F,
        x: f64,
        y: &OVector<f64, D>,
        h: f64,
        settings: &Settings,
    ) -> f64
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>);

    /// Right-hand side evaluations of one attempt.
    const STAGE_EVALUATIONS: u32;

    /// Takes the attempted step: `y` becomes its end state, the start derivative that of
    /// the end `x_end = x + h`. Returns the evaluations spent (DOP853 evaluates there
    /// only now; DOPRI5 reuses its last stage).
    fn accept<F>(&mut self, f: &mut F, x_end: f64, y: &mut OVector<f64, D>) -> u32
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>);
}

/// Integrates `y' = f(x, y)` from `(x0, y0)` to `x_end` with pair `P`, showing
/// `observe` every accepted point.
fn integrate<D, F, O, P>(
    mut f: F,
    x0: f64,
    x_end: f64,
    y0: OVector<f64, D>,
    settings: &Settings,
    mut observe: O,
) -> Result<Solution<D>, OdeError>
where
    D: Dim,
    DefaultAllocator: Allocator<D>,
    F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    O: FnMut(f64, &OVector<f64, D>),
    P: Pair<D>,
{
    let mut stats = Stats::default();
    if x_end == x0 {
        return Ok(Solution {
            x: x0,
            y: y0,
            stats,
        });
    }
    let direction = with_sign(1.0, x_end - x0);
    let mut pair = P::new(&y0);
    let (mut x, mut y) = (x0, y0);
    f(x, &y, pair.start_derivative());
    stats.evaluations += 1;
    let mut h = if settings.h_initial == 0.0 {
        stats.evaluations += 1;
        let f0 = pair.start_derivative().clone();
        initial_step(&mut f, x, &y, &f0, settings, direction, P::ORDER_INVERSE)
    } else {
        settings.h_initial
    };
    let mut control = Control::new(settings, P::alpha(settings.beta), direction);
    let mut attempts = 0;
    loop {
        if attempts >= settings.max_steps {
            return Err(OdeError::TooManySteps { x, steps: attempts });
        }
        if 0.1 * h.abs() <= f64::EPSILON * x.abs() {
            return Err(OdeError::StepSizeUnderflow { x });
        }
        // Within 1 % of the end: land on it.
        let last = (x + 1.01 * h - x_end) * direction > 0.0;
        if last {
            h = x_end - x;
        }
        attempts += 1;
        let err = pair.attempt(&mut f, x, &y, h, settings);
        stats.evaluations += P::STAGE_EVALUATIONS;
        let verdict = control.judge(err, h);
        if verdict.accepted {
            stats.evaluations += pair.accept(&mut f, x + h, &mut y);
            stats.accepted += 1;
            x += h;
            observe(x, &y);
            if last {
                return Ok(Solution { x, y, stats });
            }
        } else {
            stats.rejected += 1;
        }
        h = verdict.h_new;
    }
}

/// A zero vector shaped like `y`.
fn zeros_like<D: Dim>(y: &OVector<f64, D>) -> OVector<f64, D>
where
    DefaultAllocator: Allocator<D>,
{
    OVector::zeros_generic(y.shape_generic().0, U1)
}

#[cfg(test)]
mod tests;
