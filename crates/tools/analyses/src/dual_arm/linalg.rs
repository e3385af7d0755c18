//! Block-tridiagonal symmetric solves for the direct method's Newton steps.

use nalgebra::{DMatrix, DVector};

/// Solves `H x = rhs` for a symmetric positive definite block-tridiagonal `H` with
/// diagonal blocks `diag[k]` and upper blocks `upper[k] = H[k][k+1]`, by block Cholesky
/// elimination. `None` when `H` is not positive definite.
pub fn solve_block_tridiagonal(
    diag: &[DMatrix<f64>],
    upper: &[DMatrix<f64>],
    rhs: &[DVector<f64>],
) -> Option<Vec<DVector<f64>>> {
    let n = diag.len();
    let mut factors = Vec::with_capacity(n);
    let mut z = Vec::with_capacity(n);
    for k in 0..n {
        let (mut c, mut y) = (diag[k].clone(), rhs[k].clone());
        if k > 0 {
            let previous: &nalgebra::Cholesky<f64, nalgebra::Dyn> = &factors[k - 1];
            let u = &upper[k - 1];
            // X = U^T C^-1: eliminate the sub-diagonal block of row k.
            let x = previous.solve(u).transpose();
            c -= &x * u;
            y -= &x * &z[k - 1];
        }
        factors.push(c.cholesky()?);
        z.push(y);
    }
    let mut solution = vec![DVector::zeros(0); n];
    for k in (0..n).rev() {
        let mut y = z[k].clone();
        if k + 1 < n {
            y -= &upper[k] * &solution[k + 1];
        }
        solution[k] = factors[k].solve(&y);
    }
    Some(solution)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_solution_matches_a_dense_solve() {
        // A diagonally dominant symmetric block-tridiagonal matrix, solved densely by LU.
        let m = 2;
        let blocks = 4;
        let diag: Vec<DMatrix<f64>> = (0..blocks)
            .map(|k| DMatrix::from_row_slice(2, 2, &[4.0 + k as f64, 0.5, 0.5, 3.0]))
            .collect();
        let upper: Vec<DMatrix<f64>> = (0..blocks - 1)
            .map(|k| DMatrix::from_row_slice(2, 2, &[0.3, -0.2, 0.1 * k as f64, 0.4]))
            .collect();
        let rhs: Vec<DVector<f64>> = (0..blocks)
            .map(|k| DVector::from_vec(vec![1.0 + k as f64, -0.5]))
            .collect();
        let mut dense = DMatrix::zeros(m * blocks, m * blocks);
        for k in 0..blocks {
            dense.view_mut((m * k, m * k), (m, m)).copy_from(&diag[k]);
            if k + 1 < blocks {
                dense
                    .view_mut((m * k, m * k + m), (m, m))
                    .copy_from(&upper[k]);
                dense
                    .view_mut((m * k + m, m * k), (m, m))
                    .copy_from(&upper[k].transpose());
            }
        }
        let stacked =
            DVector::from_iterator(m * blocks, rhs.iter().flat_map(|v| v.iter().copied()));
        let expected = dense.lu().solve(&stacked).unwrap();
        let got = solve_block_tridiagonal(&diag, &upper, &rhs).unwrap();
        for (k, x) in got.iter().enumerate() {
            assert!((x - expected.rows(m * k, m)).norm() < 1e-13);
        }
        let negative = vec![DMatrix::from_element(1, 1, -1.0)];
        let one = vec![DVector::from_element(1, 1.0)];
        assert!(solve_block_tridiagonal(&negative, &[], &one).is_none());
    }
}
