//! The shooting method: guess the redundant joints at tf, complete theta(tf) by inverse
//! kinematics, integrate state, costate and cost backwards from tf with lambda(tf) = 0,
//! and correct the guess by Newton until the start transversality condition
//! `e = N(q(t0)) lambda(t0) = 0` holds.
//!
//! The start task condition `r(t0) = f(q(t0))` is not part of `e`: `A q_dot = b` keeps
//! the constraints exactly along the flow, so it holds by construction up to the
//! integration error and is checked on the solution instead.
//!
//! Sensitivity `de/dS`: central differences of the whole shooting map with step
//! `h = 1e-4` rad. The integrator's error on `e` is about `eps = 1e-11` (tolerances
//! 1e-12), so the derivative error is about `h^2 |e'''| / 6 + eps / h`, near 1e-7
//! relative: Newton still contracts by about that factor per step, and the final
//! accuracy of `e` depends only on how accurately `e` itself is evaluated.

use super::DualArmError;
use super::kinematics::JOINTS;
use super::locks::Chain;
use super::paths::Path;
use super::pmp::{Projection, rates};
use super::trajectory::Trajectory;
use crate::ode::{self, Settings};
use nalgebra::{DMatrix, DVector};
use std::cell::Cell;

/// Settings of the shooting method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShootingOptions {
    /// Relative and absolute tolerance of the Dop853 integrator.
    pub integration_tolerance: f64,
    /// Newton stops when `||e|| <` this.
    pub tolerance: f64,
    /// Newton iterations allowed.
    pub max_iterations: usize,
    /// Step of the central differences for `de/dS`, rad.
    pub difference_step: f64,
    /// Intervals of the returned trajectory's uniform time grid.
    pub intervals: usize,
}

impl Default for ShootingOptions {
    fn default() -> Self {
        Self {
            integration_tolerance: 1e-12,
            tolerance: 1e-10,
            max_iterations: 30,
            difference_step: 1e-4,
            intervals: 200,
        }
    }
}

/// One Newton iterate: the guess and the norm of its start error.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonStep {
    pub guess: Vec<f64>,
    pub residual: f64,
}

/// A converged optimal joint path from the shooting method.
#[derive(Debug, Clone, PartialEq)]
pub struct PmpSolution {
    /// Redundant joints at tf (in the order of `Chain::redundant_joints`), rad.
    pub redundant_final: Vec<f64>,
    /// Newton iterations performed.
    pub iterations: usize,
    /// Final `||N(q(t0)) lambda(t0)||`.
    pub residual: f64,
    /// Every iterate, the initial guess first.
    pub history: Vec<NewtonStep>,
    /// The optimal path on a uniform time grid.
    pub trajectory: Trajectory,
}

impl PmpSolution {
    /// The optimal cost PI, rad^2/s.
    pub fn pi(&self) -> f64 {
        self.trajectory.pi()
    }
}

/// The flow in reversed time `s = tf - t`: `y = (q, lambda, cost, s)`.
///
/// Time is carried as a state so that the system is autonomous: ode_solvers 0.6.2's
/// Dop853, integrated with before, evaluates its twelfth stage at the step start
/// instead of its end (node `c_12 = 0` instead of 1, srenevey/ode-solvers pull request
/// 42), which corrupts non-autonomous systems but cannot affect autonomous ones;
/// [`crate::ode`] has no such fault, and the form is kept so results stay bit for bit.
struct ReversedFlow<'a> {
    chain: &'a Chain,
    path: &'a dyn Path,
    end: f64,
    singular_at: &'a Cell<Option<f64>>,
}

impl ReversedFlow<'_> {
    /// The rates at `y`, NaN (and the time remembered) where the chain is singular.
    fn evaluate(&self, y: &DVector<f64>, dy: &mut DVector<f64>) {
        let n = self.chain.free_count();
        // The elapsed reversed time is the state's last component (autonomous form).
        let t = self.end - y[2 * n + 1];
        let q = y.rows(0, n).into_owned();
        let lambda = y.rows(n, n).into_owned();
        match rates(self.chain, self.path, t, &q, &lambda) {
            Some((velocity, costate_rate)) => {
                dy.rows_mut(0, n).copy_from(&(-&velocity));
                dy.rows_mut(n, n).copy_from(&(-costate_rate));
                dy[2 * n] = velocity.norm_squared();
                dy[2 * n + 1] = 1.0;
            }
            None => {
                self.singular_at.set(Some(t));
                dy.fill(f64::NAN);
            }
        }
    }
}

/// The end of one backward integration.
struct Shot {
    /// `N(q(t0)) lambda(t0)`.
    error: DVector<f64>,
}

/// Shooting solver for one chain and path.
pub struct Shooting<'a> {
    chain: &'a Chain,
    path: &'a dyn Path,
    options: ShootingOptions,
}

impl<'a> Shooting<'a> {
    pub fn new(chain: &'a Chain, path: &'a dyn Path, options: ShootingOptions) -> Self {
        Self {
            chain,
            path,
            options,
        }
    }

    /// Integrates backwards from tf; returns the states at t0 (`intervals = None`) or on
    /// a uniform grid, in increasing time. Each grid interval is its own integration so
    /// that every sample is an integrator end point (no dense-output interpolation).
    fn integrate(
        &self,
        guess: &[f64],
        intervals: Option<usize>,
    ) -> Result<Vec<(f64, DVector<f64>)>, DualArmError> {
        let (t0, tf) = (self.path.start(), self.path.end());
        let n = self.chain.free_count();
        let q_final = self
            .chain
            .complete(guess, self.path.position(tf), None, tf)?;
        let mut y = DVector::zeros(2 * n + 2);
        y.rows_mut(0, n).copy_from(&q_final);
        let span = tf - t0;
        let pieces = intervals.unwrap_or(1).max(1);
        let mut samples = vec![(tf, y.clone())];
        for k in 0..pieces {
            let (from, to) = (
                span * k as f64 / pieces as f64,
                span * (k + 1) as f64 / pieces as f64,
            );
            y = self.integrate_piece(y, from, to)?;
            samples.push((tf - to, y.clone()));
        }
        samples.reverse();
        Ok(samples)
    }

    /// Integrates the reversed flow from `y` at reversed time `from` to `to`.
    fn integrate_piece(
        &self,
        y: DVector<f64>,
        from: f64,
        to: f64,
    ) -> Result<DVector<f64>, DualArmError> {
        let singular_at = Cell::new(None);
        let flow = ReversedFlow {
            chain: self.chain,
            path: self.path,
            end: self.path.end(),
            singular_at: &singular_at,
        };
        let tol = self.options.integration_tolerance;
        let settings = Settings::dop853(tol, to - from);
        let outcome = ode::dop853(|_s, y, dy| flow.evaluate(y, dy), from, to, y, &settings);
        match outcome {
            Ok(end) if end.y.iter().all(|v| v.is_finite()) => Ok(end.y),
            outcome => Err(match (singular_at.get(), outcome) {
                (Some(t), _) => DualArmError::Singular { t },
                (None, Err(e)) => DualArmError::Integration(e.to_string()),
                (None, Ok(_)) => DualArmError::Integration("non-finite state".into()),
            }),
        }
    }

    /// Start error of one guess.
    fn shoot(&self, guess: &[f64]) -> Result<Shot, DualArmError> {
        let samples = self.integrate(guess, None)?;
        let (t0, y0) = &samples[0];
        let n = self.chain.free_count();
        let q0 = y0.rows(0, n).into_owned();
        let projection =
            Projection::new(self.chain, &q0).ok_or(DualArmError::Singular { t: *t0 })?;
        let error = &projection.null_projector * y0.rows(n, n);
        Ok(Shot { error })
    }

    /// Central-difference sensitivity `de/dS` (n x redundancy).
    fn sensitivity(&self, guess: &[f64]) -> Result<DMatrix<f64>, DualArmError> {
        let h = self.options.difference_step;
        let mut jac = DMatrix::zeros(self.chain.free_count(), guess.len());
        for i in 0..guess.len() {
            let (mut up, mut down) = (guess.to_vec(), guess.to_vec());
            up[i] += h;
            down[i] -= h;
            let column = (self.shoot(&up)?.error - self.shoot(&down)?.error) / (2.0 * h);
            jac.set_column(i, &column);
        }
        Ok(jac)
    }

    /// Newton iteration from `guess` (redundant joints at tf, rad) to the optimum.
    pub fn solve(&self, guess: &[f64]) -> Result<PmpSolution, DualArmError> {
        let tolerance = self.options.tolerance;
        let mut s = guess.to_vec();
        let mut shot = self.shoot(&s)?;
        let mut history = vec![NewtonStep {
            guess: s.clone(),
            residual: shot.error.norm(),
        }];
        let not_converged = |iterations, residual| DualArmError::NotConverged {
            method: "the shooting method",
            iterations,
            residual,
            tolerance,
        };
        while shot.error.norm() >= tolerance {
            let iterations = history.len() - 1;
            if iterations >= self.options.max_iterations {
                return Err(not_converged(iterations, shot.error.norm()));
            }
            let jac = self.sensitivity(&s)?;
            let step = jac
                .svd(true, true)
                .solve(&(-&shot.error), 1e-12)
                .map_err(|e| DualArmError::Integration(e.to_string()))?;
            // Damped step: halve until the start error decreases.
            let mut accepted = None;
            let mut factor = 1.0;
            for _ in 0..12 {
                let trial: Vec<f64> = s.iter().zip(&step).map(|(a, d)| a + factor * d).collect();
                if let Ok(trial_shot) = self.shoot(&trial)
                    && trial_shot.error.norm() < shot.error.norm()
                {
                    accepted = Some((trial, trial_shot));
                    break;
                }
                factor *= 0.5;
            }
            let (trial, trial_shot) =
                accepted.ok_or_else(|| not_converged(iterations + 1, shot.error.norm()))?;
            s = trial;
            shot = trial_shot;
            history.push(NewtonStep {
                guess: s.clone(),
                residual: shot.error.norm(),
            });
        }
        let trajectory = self.trajectory(&s)?;
        Ok(PmpSolution {
            redundant_final: s,
            iterations: history.len() - 1,
            residual: shot.error.norm(),
            history,
            trajectory,
        })
    }

    /// The path of a guess on the uniform output grid.
    fn trajectory(&self, guess: &[f64]) -> Result<Trajectory, DualArmError> {
        let samples = self.integrate(guess, Some(self.options.intervals))?;
        let n = self.chain.free_count();
        let total = samples[0].1[2 * n];
        let mut trajectory = Trajectory {
            times: Vec::with_capacity(samples.len()),
            joints: Vec::with_capacity(samples.len()),
            cost: Vec::with_capacity(samples.len()),
        };
        for (t, y) in samples {
            let q = y.rows(0, n).into_owned();
            let theta: [f64; JOINTS] = self.chain.joints(&q);
            trajectory.times.push(t);
            trajectory.joints.push(theta);
            trajectory.cost.push(total - y[2 * n]);
        }
        Ok(trajectory)
    }
}
