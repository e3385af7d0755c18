//! Condition and load indices from the Gram matrix `Jh^T Jh` of a homogeneous Jacobian.
//!
//! The singular values of `Jh` are the square roots of the eigenvalues of its Gram
//! matrix, so `kappa = sigma_max / sigma_min = sqrt(lambda_max / lambda_min)`. The
//! eigenvalues of a symmetric 3x3 matrix have a closed form (trigonometric solution of
//! the characteristic cubic), which keeps the grid scans free of iterative SVDs.

use nalgebra::Matrix3;
use std::f64::consts::PI;

/// Eigenvalues of a symmetric 3x3 matrix in descending order.
pub fn symmetric_eigenvalues(a: &Matrix3<f64>) -> [f64; 3] {
    let off = a[(0, 1)].powi(2) + a[(0, 2)].powi(2) + a[(1, 2)].powi(2);
    let mean = a.trace() / 3.0;
    let spread = (a[(0, 0)] - mean).powi(2)
        + (a[(1, 1)] - mean).powi(2)
        + (a[(2, 2)] - mean).powi(2)
        + 2.0 * off;
    let p = (spread / 6.0).sqrt();
    if p <= f64::EPSILON * mean.abs() || p == 0.0 {
        return [mean; 3];
    }
    let b = (a - Matrix3::identity() * mean) / p;
    let half_det = (b.determinant() / 2.0).clamp(-1.0, 1.0);
    let angle = half_det.acos() / 3.0;
    let largest = mean + 2.0 * p * angle.cos();
    let smallest = mean + 2.0 * p * (angle + 2.0 * PI / 3.0).cos();
    let middle = 3.0 * mean - largest - smallest;
    [largest, middle, smallest]
}

/// Local condition index `1 / kappa = sigma_min / sigma_max` of a matrix whose Gram
/// matrix is `gram`; `0` for a singular matrix.
pub fn lci_from_gram(gram: &Matrix3<f64>) -> f64 {
    let [largest, _, smallest] = symmetric_eigenvalues(gram);
    if largest <= 0.0 || !largest.is_finite() {
        return 0.0;
    }
    (smallest.max(0.0) / largest).sqrt()
}

/// Load index `sqrt(min |lambda_i|)` of `(Jh^T Jh)^-1`, i.e. `1 / sigma_max(Jh)`.
pub fn load_index_from_gram(gram: &Matrix3<f64>) -> f64 {
    let [largest, _, _] = symmetric_eigenvalues(gram);
    if largest.is_finite() && largest > 0.0 {
        1.0 / largest.sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix4x3, Rotation3, Unit, Vector3};

    #[test]
    fn eigenvalues_match_a_constructed_spectrum() {
        // A = R diag(5, 2, 0.5) R^T has eigenvalues 5, 2, 0.5 by construction.
        let r = Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::new(1.0, 2.0, 0.5)), 0.7);
        let a = r.matrix() * Matrix3::from_diagonal(&Vector3::new(2.0, 5.0, 0.5)) * r.transpose();
        let e = symmetric_eigenvalues(&a);
        for (got, want) in e.iter().zip([5.0, 2.0, 0.5]) {
            assert!((got - want).abs() < 1e-12, "{e:?}");
        }
    }

    #[test]
    fn repeated_eigenvalues_are_handled() {
        // 3 I has the triple eigenvalue 3; diag(1, 1, 4) the double eigenvalue 1.
        assert_eq!(
            symmetric_eigenvalues(&(Matrix3::identity() * 3.0)),
            [3.0; 3]
        );
        let e = symmetric_eigenvalues(&Matrix3::from_diagonal(&Vector3::new(1.0, 4.0, 1.0)));
        assert!((e[0] - 4.0).abs() < 1e-12 && (e[1] - 1.0).abs() < 1e-12);
        assert!((e[2] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn lci_equals_singular_value_ratio_of_nalgebra_svd() {
        // Independent truth: nalgebra's SVD of the same 4x3 matrix.
        let j = Matrix4x3::new(
            0.3, -0.1, 0.05, 0.2, 0.4, -0.3, 0.1, 0.0, 0.25, -0.2, 0.15, 0.1,
        );
        let sv = j.singular_values();
        let want = sv.min() / sv.max();
        let got = lci_from_gram(&(j.transpose() * j));
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        let load = load_index_from_gram(&(j.transpose() * j));
        assert!((load - 1.0 / sv.max()).abs() < 1e-12);
    }

    #[test]
    fn load_index_is_root_of_smallest_eigenvalue_of_inverse_products() {
        // Square J: J^-1 J^-T = (J^T J)^-1; compare with its eigenvalues from nalgebra.
        let j = Matrix3::new(0.2, -0.1, 0.3, 0.05, 0.4, 0.1, 1.0, 1.0, 1.0);
        let inv = j.try_inverse().unwrap();
        let m = inv * inv.transpose();
        let smallest = m
            .symmetric_eigenvalues()
            .iter()
            .fold(f64::INFINITY, |a: f64, &b: &f64| a.min(b.abs()));
        let got = load_index_from_gram(&(j.transpose() * j));
        assert!((got - smallest.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn singular_matrix_has_zero_lci() {
        // Two equal columns: rank 2, sigma_min = 0.
        let j = Matrix3::new(1.0, 1.0, 0.0, 2.0, 2.0, 1.0, 0.0, 0.0, 3.0);
        assert!(lci_from_gram(&(j.transpose() * j)) < 1e-7);
    }
}
