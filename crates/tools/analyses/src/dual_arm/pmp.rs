//! Pontryagin's minimum principle for the least-effort joint path.
//!
//! State: the free joints `q` (n); constraints `g(q, t) = 0` with Jacobian `A` (4 x n),
//! `A q_dot = b = (0, 0, r_dot)`. With `A# = A^T (A A^T)^-1` and the null-space projector
//! `N = I - A# A`, every admissible velocity is `q_dot = A# b + N y`. Maximising
//! `H = -|q_dot|^2 + lambda^T q_dot` over `y` gives the optimal velocity
//! `F = A# b + N lambda / 2`, and the costate equation is
//! `lambda_dot = -dH/dq = (dF/dq)^T (2F - lambda)`, the derivative taken at fixed
//! lambda (the envelope theorem makes that equal to the derivative at fixed `y`).

use super::locks::Chain;
use super::paths::Path;
use nalgebra::{DMatrix, DVector, Vector4};

/// The pseudo-inverse `A#`, the projector `N` and `(A A^T)^-1` at one configuration.
pub struct Projection {
    pub a: DMatrix<f64>,
    pub pseudo_inverse: DMatrix<f64>,
    pub null_projector: DMatrix<f64>,
    gram_inverse: DMatrix<f64>,
}

impl Projection {
    /// `None` when `A` has lost rank (a singular configuration).
    pub fn new(chain: &Chain, q: &DVector<f64>) -> Option<Self> {
        let a = chain.jacobian(q);
        let gram_inverse = (&a * a.transpose()).cholesky()?.inverse();
        let pseudo_inverse = a.transpose() * &gram_inverse;
        let n = q.len();
        let null_projector = DMatrix::identity(n, n) - &pseudo_inverse * &a;
        Some(Self {
            a,
            pseudo_inverse,
            null_projector,
            gram_inverse,
        })
    }
}

/// The right-hand side `b = (0, 0, r_dot(t))` of `A q_dot = b`.
pub fn constraint_rate(path: &dyn Path, t: f64) -> DVector<f64> {
    let v = path.velocity(t);
    DVector::from_column_slice(Vector4::new(0.0, 0.0, v.x, v.y).as_slice())
}

/// Optimal joint velocity `F` and costate rate at `(t, q, lambda)`; `None` when singular.
pub fn rates(
    chain: &Chain,
    path: &dyn Path,
    t: f64,
    q: &DVector<f64>,
    lambda: &DVector<f64>,
) -> Option<(DVector<f64>, DVector<f64>)> {
    let p = Projection::new(chain, q)?;
    let b = constraint_rate(path, t);
    let velocity = &p.pseudo_inverse * &b + &p.null_projector * lambda * 0.5;
    // Column k of dF/dq = N dA_k^T (M c) - A# dA_k F with c = b - A lambda / 2 and
    // M = (A A^T)^-1 (from d(A#) = N dA^T M - A# dA A#).
    let mc = &p.gram_inverse * (&b - &p.a * lambda * 0.5);
    let weight = &velocity * 2.0 - lambda;
    let mut costate_rate = DVector::zeros(q.len());
    for (k, dak) in chain.jacobian_derivatives(q).iter().enumerate() {
        let column =
            &p.null_projector * (dak.transpose() * &mc) - &p.pseudo_inverse * (dak * &velocity);
        costate_rate[k] = column.dot(&weight);
    }
    let finite = velocity
        .iter()
        .chain(costate_rate.iter())
        .all(|v| v.is_finite());
    finite.then_some((velocity, costate_rate))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dual_arm::kinematics::{Elbow, LinkLengths};
    use crate::dual_arm::locks::Lock;
    use crate::dual_arm::paths::PaperPath;

    /// The optimal velocity as a function of q at fixed lambda, and the Hamiltonian.
    fn velocity(chain: &Chain, q: &DVector<f64>, lambda: &DVector<f64>) -> DVector<f64> {
        let p = Projection::new(chain, q).unwrap();
        let b = constraint_rate(&PaperPath::A, 0.3);
        &p.pseudo_inverse * &b + &p.null_projector * lambda * 0.5
    }

    #[test]
    fn costate_rate_is_minus_the_hamiltonian_gradient() {
        // H*(q, lambda) = -|F|^2 + lambda^T F with the optimal F; by the envelope theorem
        // lambda_dot = -dH*/dq, checked here by central differences of H*.
        let chain = Chain::for_lock(
            LinkLengths::default(),
            Lock::Unlocked,
            [Elbow::Negative, Elbow::Positive],
        )
        .unwrap();
        let q = DVector::from_vec(vec![0.2, 0.4, 1.0, -0.8, 1.5, -0.1, -0.9, 1.2]);
        let lambda = DVector::from_vec(vec![0.3, -0.2, 0.5, 0.1, -0.4, 0.25, 0.05, -0.3]);
        let hamiltonian = |q: &DVector<f64>| {
            let f = velocity(&chain, q, &lambda);
            -f.norm_squared() + lambda.dot(&f)
        };
        let (f, rate) = rates(&chain, &PaperPath::A, 0.3, &q, &lambda).unwrap();
        assert!((f - velocity(&chain, &q, &lambda)).norm() < 1e-15);
        let h = 1e-5;
        for k in 0..q.len() {
            let (mut up, mut down) = (q.clone(), q.clone());
            up[k] += h;
            down[k] -= h;
            let fd = -(hamiltonian(&up) - hamiltonian(&down)) / (2.0 * h);
            assert!(
                (fd - rate[k]).abs() < 1e-8,
                "joint {k}: {fd} vs {}",
                rate[k]
            );
        }
    }

    #[test]
    fn optimal_velocity_tracks_the_path_and_is_minimal_without_costate() {
        let chain = Chain::for_lock(
            LinkLengths::default(),
            Lock::One,
            [Elbow::Negative, Elbow::Positive],
        )
        .unwrap();
        let q = DVector::from_vec(vec![0.5, -1.2, 0.9, 0.02, 1.1, -0.7]);
        let lambda = DVector::from_vec(vec![0.3, -0.2, 0.5, 0.1, -0.4, 0.25]);
        let (f, _) = rates(&chain, &PaperPath::B, 0.4, &q, &lambda).unwrap();
        let b = constraint_rate(&PaperPath::B, 0.4);
        assert!((chain.jacobian(&q) * &f - &b).norm() < 1e-13);
        // With lambda = 0, F is the least-norm solution of A F = b: orthogonal to null(A).
        let (f0, _) = rates(&chain, &PaperPath::B, 0.4, &q, &DVector::zeros(6)).unwrap();
        let t = chain.tangent(&q).unwrap();
        assert!((t.transpose() * f0).norm() < 1e-13);
    }
}
