//! Is an extremal a local minimum? Pontryagin's conditions are necessary only: a path
//! that satisfies them may be a saddle of the cost or a costlier local minimum. Two
//! checks on the discretised problem of the direct method (the redundant joints of every
//! node as coordinates, so the constraints hold exactly and the Hessian in these
//! coordinates is the Hessian of the cost restricted to the constraints), on the
//! extremal sampled on a uniform grid:
//!
//! - **second order**: the reduced Hessian at the sampled extremal is positive definite
//!   (its block Cholesky factorisation exists), the sufficient condition for a strict
//!   local minimum; its smallest eigenvalue, found by inverse iteration, is reported;
//! - **neighbourhood**: the direct method started from the sampled extremal does not
//!   descend away from it: it moves no joint more than `joint_tolerance` and lowers the
//!   cost by less than `cost_tolerance` (relative). The discrete optimum differs from the
//!   continuous one by O(dt^2): about 1e-5 rad and 5e-5 relative on 200 intervals for
//!   the paper's paths, far inside the tolerances (1e-3 each), while another extremal
//!   lies tenths of a radian away.
//!
//! The extremal is reported a local minimum when at least one check passed and none
//! failed (the direct method may fail to converge from a saddle: then only the
//! second-order check speaks).

use super::DualArmError;
use super::direct::{DirectOptions, reduced_hessian, solve_direct_from};
use super::linalg::solve_block_tridiagonal;
use super::locks::Chain;
use super::paths::Path;
use super::shooting::{Shooting, ShootingOptions};
use nalgebra::{DMatrix, DVector};

/// Settings of the local-minimum check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CheckOptions {
    /// The direct method run from the extremal (its `intervals` set the grid).
    pub direct: DirectOptions,
    /// Largest joint move (rad) of the direct method that still counts as staying put.
    pub joint_tolerance: f64,
    /// Largest relative cost decrease that still counts as not descending.
    pub cost_tolerance: f64,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self {
            direct: DirectOptions::default(),
            joint_tolerance: 1e-3,
            cost_tolerance: 1e-3,
        }
    }
}

/// The second-order condition at the sampled extremal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SecondOrder {
    /// No redundant joint: the joint path is fixed by the end-effector path alone.
    NoRedundancy,
    /// The reduced Hessian is positive definite; its smallest eigenvalue, 1/s.
    PositiveDefinite { smallest_eigenvalue: f64 },
    /// The reduced Hessian is not positive definite.
    NotPositiveDefinite,
}

/// Where the direct method started from the extremal stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbourhood {
    /// Its discrete cost, rad^2/s.
    pub direct_pi: f64,
    /// Its largest joint difference from the sampled extremal, rad.
    pub joint_move: f64,
}

/// Outcome of both checks on one extremal.
#[derive(Debug, Clone, PartialEq)]
pub struct MinimumCheck {
    /// Intervals of the grid both checks ran on.
    pub intervals: usize,
    /// The extremal's cost PI, rad^2/s.
    pub extremal_pi: f64,
    pub second_order: SecondOrder,
    /// The direct method from the extremal, or why it failed.
    pub neighbourhood: Result<Neighbourhood, DualArmError>,
    options: CheckOptions,
}

impl MinimumCheck {
    /// `Some(true)` when the direct method stayed at the extremal, `Some(false)` when it
    /// moved away or descended, `None` when it failed.
    pub fn neighbourhood_passed(&self) -> Option<bool> {
        let n = self.neighbourhood.as_ref().ok()?;
        Some(
            n.joint_move <= self.options.joint_tolerance
                && n.direct_pi >= self.extremal_pi * (1.0 - self.options.cost_tolerance),
        )
    }

    /// `Some(true)` for a positive definite reduced Hessian, `None` with no redundancy.
    pub fn second_order_passed(&self) -> Option<bool> {
        match self.second_order {
            SecondOrder::NoRedundancy => None,
            SecondOrder::PositiveDefinite { .. } => Some(true),
            SecondOrder::NotPositiveDefinite => Some(false),
        }
    }

    /// At least one check passed and none failed.
    pub fn is_local_minimum(&self) -> bool {
        let outcomes = [self.neighbourhood_passed(), self.second_order_passed()];
        outcomes.contains(&Some(true)) && !outcomes.contains(&Some(false))
    }

    /// One line naming each check and its outcome.
    pub fn describe(&self) -> String {
        let second = match self.second_order {
            SecondOrder::NoRedundancy => {
                "second-order check not needed (no redundant joint: the path is unique)".into()
            }
            SecondOrder::PositiveDefinite {
                smallest_eigenvalue,
            } => format!(
                "second-order check passed (reduced Hessian positive definite, smallest \
                 eigenvalue {smallest_eigenvalue:.3e} 1/s)"
            ),
            SecondOrder::NotPositiveDefinite => {
                "second-order check FAILED (reduced Hessian not positive definite)".into()
            }
        };
        let passed = self.neighbourhood_passed() == Some(true);
        let neighbourhood = match &self.neighbourhood {
            Ok(n) => format!(
                "neighbourhood check {} (the direct method started from it moves the joints \
                 by {:.1e} rad, PI {:.6} -> {:.6})",
                if passed { "passed" } else { "FAILED" },
                n.joint_move,
                self.extremal_pi,
                n.direct_pi
            ),
            Err(e) => format!("neighbourhood check not made (the direct method failed: {e})"),
        };
        format!("on {} intervals: {second}; {neighbourhood}", self.intervals)
    }
}

/// Checks whether the extremal through the redundant final joints `redundant_final`
/// (a converged shooting solution) is a local minimum. Errors only when the extremal
/// cannot be re-integrated on the check's grid or its Hessian not be formed.
pub fn check_local_minimum(
    chain: &Chain,
    path: &dyn Path,
    redundant_final: &[f64],
    shooting: ShootingOptions,
    options: CheckOptions,
) -> Result<MinimumCheck, DualArmError> {
    let intervals = options.direct.intervals;
    let on_grid = ShootingOptions {
        intervals,
        ..shooting
    };
    let extremal = Shooting::new(chain, path, on_grid).solve(redundant_final)?;
    let second_order = if chain.redundancy() == 0 {
        SecondOrder::NoRedundancy
    } else {
        let (diag, upper) = reduced_hessian(chain, path, &extremal.trajectory)?;
        match smallest_eigenvalue(&diag, &upper) {
            Some(smallest_eigenvalue) => SecondOrder::PositiveDefinite {
                smallest_eigenvalue,
            },
            None => SecondOrder::NotPositiveDefinite,
        }
    };
    let neighbourhood = solve_direct_from(chain, path, &extremal.trajectory, options.direct)
        .and_then(|d| {
            let joint_move = d
                .trajectory
                .max_joint_difference(&extremal.trajectory)
                .ok_or_else(|| {
                    DualArmError::InvalidInput("the grids of the check differ".into())
                })?;
            Ok(Neighbourhood {
                direct_pi: d.pi(),
                joint_move,
            })
        });
    Ok(MinimumCheck {
        intervals,
        extremal_pi: extremal.pi(),
        second_order,
        neighbourhood,
        options,
    })
}

/// Smallest eigenvalue of a symmetric block-tridiagonal matrix by inverse iteration
/// (Rayleigh quotient of the inverse), `None` if the matrix is not positive definite.
pub fn smallest_eigenvalue(diag: &[DMatrix<f64>], upper: &[DMatrix<f64>]) -> Option<f64> {
    let dot = |a: &[DVector<f64>], b: &[DVector<f64>]| -> f64 {
        a.iter().zip(b).map(|(a, b)| a.dot(b)).sum()
    };
    // A fixed start with no symmetry, so that it is not orthogonal to the eigenvector.
    let mut x: Vec<DVector<f64>> = diag
        .iter()
        .enumerate()
        .map(|(k, d)| DVector::from_fn(d.nrows(), |i, _| 1.0 + 0.3 * ((k * 7 + i) as f64).sin()))
        .collect();
    let mut largest_of_inverse = 0.0;
    for _ in 0..500 {
        let norm = dot(&x, &x).sqrt();
        x.iter_mut().for_each(|v| *v /= norm);
        let y = solve_block_tridiagonal(diag, upper, &x)?;
        let estimate = dot(&x, &y);
        let settled = (estimate - largest_of_inverse).abs() <= 1e-12 * estimate.abs();
        largest_of_inverse = estimate;
        x = y;
        if settled {
            break;
        }
    }
    (largest_of_inverse > 0.0).then(|| 1.0 / largest_of_inverse)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_iteration_finds_the_smallest_eigenvalue_of_a_dense_matrix() {
        // Truth: nalgebra's symmetric eigen-decomposition of the same matrix, assembled
        // densely from its blocks.
        let blocks = 5;
        let diag: Vec<DMatrix<f64>> = (0..blocks)
            .map(|k| DMatrix::from_row_slice(2, 2, &[3.0 + k as f64, 0.4, 0.4, 2.0]))
            .collect();
        let upper: Vec<DMatrix<f64>> = (0..blocks - 1)
            .map(|_| DMatrix::from_row_slice(2, 2, &[-0.9, 0.2, 0.1, -0.7]))
            .collect();
        let mut dense = DMatrix::zeros(2 * blocks, 2 * blocks);
        for k in 0..blocks {
            dense.view_mut((2 * k, 2 * k), (2, 2)).copy_from(&diag[k]);
            if k + 1 < blocks {
                dense
                    .view_mut((2 * k, 2 * k + 2), (2, 2))
                    .copy_from(&upper[k]);
                dense
                    .view_mut((2 * k + 2, 2 * k), (2, 2))
                    .copy_from(&upper[k].transpose());
            }
        }
        let expected = dense.symmetric_eigen().eigenvalues.min();
        let got = smallest_eigenvalue(&diag, &upper).unwrap();
        assert!(
            (got - expected).abs() < 1e-9 * expected,
            "{got} vs {expected}"
        );
        // Shifted below zero the matrix is indefinite: no eigenvalue, a failed check.
        let shifted: Vec<DMatrix<f64>> = diag
            .iter()
            .map(|d| d - DMatrix::identity(2, 2) * (expected + 0.5))
            .collect();
        assert!(smallest_eigenvalue(&shifted, &upper).is_none());
    }
}
