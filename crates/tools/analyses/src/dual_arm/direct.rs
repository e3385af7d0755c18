//! The direct method, independent of Pontryagin's principle: the joint path is
//! discretised on a uniform grid `t_k`, the constraints hold exactly at every node (the
//! redundant joints `S_k` of each node are the unknowns, the others follow by inverse
//! kinematics), and `Phi = sum_k |q_{k+1} - q_k|^2 / dt` is minimised by Newton's method
//! with the exact Hessian (the inverse kinematics' curvature included), Levenberg
//! damping and a block-tridiagonal solve. `Phi` tends to PI as `O(dt^2)`.

use super::DualArmError;
use super::linalg::solve_block_tridiagonal;
use super::locks::Chain;
use super::paths::Path;
use super::pmp::Projection;
use super::trajectory::Trajectory;
use nalgebra::{DMatrix, DVector};

/// Settings of the direct method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectOptions {
    /// Intervals of the uniform time grid.
    pub intervals: usize,
    /// Converged when an undamped Newton step moves no redundant joint more than this, rad.
    pub tolerance: f64,
    /// Newton iterations allowed (damped trials included).
    pub max_iterations: usize,
}

impl Default for DirectOptions {
    fn default() -> Self {
        Self {
            intervals: 200,
            tolerance: 1e-10,
            max_iterations: 200,
        }
    }
}

/// The discrete optimum.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectSolution {
    /// Joint path at the grid nodes, with the accumulated discrete cost.
    pub trajectory: Trajectory,
    /// Accepted Newton steps.
    pub iterations: usize,
    /// Largest joint move of the last Newton step, rad.
    pub last_step: f64,
}

impl DirectSolution {
    /// The discrete cost `Phi`, an O(dt^2) approximation of PI, rad^2/s.
    pub fn pi(&self) -> f64 {
        self.trajectory.pi()
    }
}

/// Discrete cost of the node values.
fn cost(q: &[DVector<f64>], dt: f64) -> f64 {
    q.windows(2)
        .map(|w| (&w[1] - &w[0]).norm_squared() / dt)
        .sum()
}

/// The problem on its grid.
struct Grid<'a> {
    chain: &'a Chain,
    path: &'a dyn Path,
    times: Vec<f64>,
    dt: f64,
}

impl<'a> Grid<'a> {
    /// The grid of the uniform node times `times` (at least two).
    fn new(chain: &'a Chain, path: &'a dyn Path, times: Vec<f64>) -> Self {
        let dt = times[1] - times[0];
        Grid {
            chain,
            path,
            times,
            dt,
        }
    }

    /// Node values for redundant joints `s`, solved joints taken nearest to `reference`.
    fn complete(
        &self,
        s: &[DVector<f64>],
        reference: &[DVector<f64>],
    ) -> Result<Vec<DVector<f64>>, DualArmError> {
        self.times
            .iter()
            .zip(s.iter().zip(reference))
            .map(|(&t, (s, q))| {
                self.chain
                    .complete(s.as_slice(), self.path.position(t), Some(q), t)
            })
            .collect()
    }

    /// Gradient and Hessian blocks (diagonal, upper) of `Phi` in the redundant joints.
    #[allow(clippy::type_complexity)]
    fn derivatives(
        &self,
        q: &[DVector<f64>],
    ) -> Result<(Vec<DVector<f64>>, Vec<DMatrix<f64>>, Vec<DMatrix<f64>>), DualArmError> {
        let nodes = q.len();
        let scale = 2.0 / self.dt;
        let tangents: Vec<DMatrix<f64>> = q
            .iter()
            .zip(&self.times)
            .map(|(q, &t)| self.chain.tangent(q).ok_or(DualArmError::Singular { t }))
            .collect::<Result<_, _>>()?;
        let mut gradient = Vec::with_capacity(nodes);
        let mut diag = Vec::with_capacity(nodes);
        for k in 0..nodes {
            // dPhi/dq_k and the number of differences q_k enters.
            let mut w = DVector::zeros(q[k].len());
            let mut degree = 0.0;
            if k > 0 {
                w += (&q[k] - &q[k - 1]) * scale;
                degree += 1.0;
            }
            if k + 1 < nodes {
                w -= (&q[k + 1] - &q[k]) * scale;
                degree += 1.0;
            }
            let t = &tangents[k];
            let mut block = t.transpose() * t * (scale * degree);
            let curvature = self.chain.curvature(&q[k], t);
            for (i, row) in curvature.iter().enumerate() {
                for (j, c) in row.iter().enumerate() {
                    block[(i, j)] += w.dot(c);
                }
            }
            gradient.push(t.transpose() * w);
            diag.push(block);
        }
        let upper = tangents
            .windows(2)
            .map(|w| -(w[0].transpose() * &w[1]) * scale)
            .collect();
        Ok((gradient, diag, upper))
    }
}

/// The starting path: the guess at tf, then backwards node by node the least-norm
/// joint step `A# (0, 0, r_k - r_{k+1})` (resolved rates, no optimisation), its
/// redundant joints kept and the others re-solved by inverse kinematics.
fn initial_path(
    chain: &Chain,
    path: &dyn Path,
    times: &[f64],
    guess: &[f64],
) -> Result<Vec<DVector<f64>>, DualArmError> {
    let last = times.len() - 1;
    let mut q = vec![chain.complete(guess, path.position(times[last]), None, times[last])?];
    for k in (0..last).rev() {
        let (t, next) = (times[k], &q[q.len() - 1]);
        let projection = Projection::new(chain, next).ok_or(DualArmError::Singular { t })?;
        let dr = path.position(t) - path.position(times[k + 1]);
        let change = DVector::from_vec(vec![0.0, 0.0, dr.x, dr.y]);
        let predicted = next + &projection.pseudo_inverse * change;
        let s = chain.redundant_values(&predicted);
        let node = chain.complete(&s, path.position(t), Some(&predicted), t)?;
        q.push(node);
    }
    q.reverse();
    Ok(q)
}

/// The uniform grid of the options over the path's time interval.
fn grid_times(path: &dyn Path, options: &DirectOptions) -> Result<Vec<f64>, DualArmError> {
    if options.intervals < 2 {
        return Err(DualArmError::InvalidInput(
            "the direct method needs at least 2 intervals".into(),
        ));
    }
    let (t0, tf) = (path.start(), path.end());
    let dt = (tf - t0) / options.intervals as f64;
    Ok((0..=options.intervals)
        .map(|k| t0 + dt * k as f64)
        .collect())
}

/// Minimises the discrete cost from the resolved-rate path through the redundant
/// joints `guess` at tf (rad).
pub fn solve_direct(
    chain: &Chain,
    path: &dyn Path,
    guess: &[f64],
    options: DirectOptions,
) -> Result<DirectSolution, DualArmError> {
    let times = grid_times(path, &options)?;
    let q = initial_path(chain, path, &times, guess)?;
    minimise(chain, path, times, q, options)
}

/// Minimises the discrete cost from a joint path already sampled on a uniform grid (an
/// extremal of the shooting method, say): its nodes are the grid and its redundant
/// joints the start of the Newton iteration.
pub fn solve_direct_from(
    chain: &Chain,
    path: &dyn Path,
    start: &Trajectory,
    options: DirectOptions,
) -> Result<DirectSolution, DualArmError> {
    if start.times.len() < 3 {
        return Err(DualArmError::InvalidInput(
            "the direct method needs at least 2 intervals".into(),
        ));
    }
    let q = free_joints(chain, start);
    minimise(chain, path, start.times.clone(), q, options)
}

/// The free joints `q` of every sample of a trajectory.
fn free_joints(chain: &Chain, trajectory: &Trajectory) -> Vec<DVector<f64>> {
    trajectory
        .joints
        .iter()
        .map(|theta| {
            DVector::from_iterator(
                chain.free_count(),
                chain.free_joints().iter().map(|&j| theta[j]),
            )
        })
        .collect()
}

/// The diagonal and upper blocks of a block-tridiagonal Hessian.
pub(super) type HessianBlocks = (Vec<DMatrix<f64>>, Vec<DMatrix<f64>>);

/// Diagonal and upper blocks of the Hessian of `Phi` in the redundant joints of every
/// node (the cost restricted to the constraints) at the nodes of a joint path sampled
/// on a uniform grid.
pub(super) fn reduced_hessian(
    chain: &Chain,
    path: &dyn Path,
    trajectory: &Trajectory,
) -> Result<HessianBlocks, DualArmError> {
    let grid = Grid::new(chain, path, trajectory.times.clone());
    let (_, diag, upper) = grid.derivatives(&free_joints(chain, trajectory))?;
    Ok((diag, upper))
}

/// Damped Newton iteration on the redundant joints of every node from the path `q`.
fn minimise(
    chain: &Chain,
    path: &dyn Path,
    times: Vec<f64>,
    mut q: Vec<DVector<f64>>,
    options: DirectOptions,
) -> Result<DirectSolution, DualArmError> {
    let grid = Grid::new(chain, path, times);
    let dt = grid.dt;
    let mut s: Vec<DVector<f64>> = q
        .iter()
        .map(|q| DVector::from_vec(chain.redundant_values(q)))
        .collect();
    let mut phi = cost(&q, dt);
    let (mut iterations, mut trials, mut damping) = (0, 0, 0.0);
    let mut last_step = 0.0;
    let converged = chain.redundancy() == 0;
    let mut done = converged;
    while !done {
        let (gradient, diag, upper) = grid.derivatives(&q)?;
        loop {
            trials += 1;
            if trials > options.max_iterations {
                return Err(DualArmError::NotConverged {
                    method: "the direct method",
                    iterations,
                    residual: last_step,
                    tolerance: options.tolerance,
                });
            }
            let damped: Vec<DMatrix<f64>> = diag
                .iter()
                .map(|d| d + DMatrix::identity(d.nrows(), d.ncols()) * damping)
                .collect();
            let rhs: Vec<DVector<f64>> = gradient.iter().map(|g| -g).collect();
            let largest = diag.iter().map(|d| d.amax()).fold(0.0, f64::max);
            let raise = |damping: f64| (damping * 10.0).max(1e-8 * largest);
            let Some(step) = solve_block_tridiagonal(&damped, &upper, &rhs) else {
                damping = raise(damping);
                continue;
            };
            let trial_s: Vec<DVector<f64>> = s.iter().zip(&step).map(|(s, d)| s + d).collect();
            let trial = grid.complete(&trial_s, &q).ok().map(|q| (cost(&q, dt), q));
            match trial {
                Some((trial_phi, trial_q)) if trial_phi <= phi * (1.0 + 1e-14) => {
                    last_step = step.iter().map(|d| d.amax()).fold(0.0, f64::max);
                    done = damping == 0.0 && last_step < options.tolerance;
                    (s, q, phi) = (trial_s, trial_q, trial_phi);
                    iterations += 1;
                    damping = if damping < 1e-6 * largest {
                        0.0
                    } else {
                        damping / 10.0
                    };
                    break;
                }
                _ => damping = raise(damping),
            }
        }
    }
    let mut trajectory = Trajectory {
        times: grid.times.clone(),
        joints: q.iter().map(|q| chain.joints(q)).collect(),
        cost: Vec::with_capacity(q.len()),
    };
    let mut accumulated = 0.0;
    trajectory.cost.push(0.0);
    for w in q.windows(2) {
        accumulated += (&w[1] - &w[0]).norm_squared() / dt;
        trajectory.cost.push(accumulated);
    }
    Ok(DirectSolution {
        trajectory,
        iterations,
        last_step,
    })
}
