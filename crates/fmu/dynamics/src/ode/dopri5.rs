//! Dormand and Prince's explicit Runge-Kutta pair of orders 5(4) (J. R. Dormand,
//! P. J. Prince, "A family of embedded Runge-Kutta formulae", J. Comp. Appl. Math. 6,
//! 1980; tableau as in Hairer, Norsett, Wanner, Solving ODEs I, table II.5.2): seven
//! stages, the last at the step end and reused as the next step's first (FSAL).

use super::{OdeError, Pair, Settings, Solution, integrate, zeros_like};
use nalgebra::{DefaultAllocator, Dim, OVector, allocator::Allocator};

/// Nodes c2..c7 (c1 = 0).
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

/// Coupling coefficients a_ij, row i = stage 2..7; row 7 is the fifth-order weights b.
const A: [&[f64]; 7] = [
    &[],
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];

/// Error weights e_i = b_i - b^_i (the fifth- less the fourth-order weights); e2 = 0.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

/// Integrates `y' = f(x, y)` from `(x0, y0)` to `x_end` with DOPRI5, landing on `x_end`.
/// `f` writes the derivative (NaN where it cannot be evaluated).
pub fn dopri5<D, F>(
    f: F,
    x0: f64,
    x_end: f64,
    y0: OVector<f64, D>,
    settings: &Settings,
) -> Result<Solution<D>, OdeError>
where
    D: Dim,
    DefaultAllocator: Allocator<D>,
    F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
{
    integrate::<D, F, _, Dopri5<D>>(f, x0, x_end, y0, settings, |_, _| {})
}

/// The stages of one step and its end state.
struct Dopri5<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    k: [OVector<f64, D>; 7],
    y_new: OVector<f64, D>,
}

impl<D: Dim> Pair<D> for Dopri5<D>
where
    DefaultAllocator: Allocator<D>,
{
    const ORDER_INVERSE: f64 = 1.0 / 5.0;
    const STAGE_EVALUATIONS: u32 = 6;

    fn new(y: &OVector<f64, D>) -> Self {
        Self {
            k: std::array::from_fn(|_| zeros_like(y)),
            y_new: zeros_like(y),
        }
    }

    fn alpha(beta: f64) -> f64 {
        0.2 - beta * 0.75
    }

    fn start_derivative(&mut self) -> &mut OVector<f64, D> {
        &mut self.k[0]
    }

    fn attempt<F>(
        &mut self,
        f: &mut F,
        x: f64,
        y: &OVector<f64, D>,
        h: f64,
        settings: &Settings,
    ) -> f64
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    {
        let Self { k, y_new } = self;
        for stage in 1..7 {
            y_new.copy_from(y);
            for (j, &a) in A[stage].iter().enumerate() {
                for (yi, &kj) in y_new.iter_mut().zip(k[j].iter()) {
                    *yi += kj * h * a;
                }
            }
            f(x + h * C[stage], y_new, &mut k[stage]);
        }
        // The fifth-order end state is the argument of stage 7: y_new.
        let mut sum = 0.0;
        for i in 0..y.len() {
            let estimate = (k[0][i] * E1
                + k[2][i] * E3
                + k[3][i] * E4
                + k[4][i] * E5
                + k[5][i] * E6
                + k[6][i] * E7)
                * h;
            let scale = settings.atol + y[i].abs().max(y_new[i].abs()) * settings.rtol;
            sum += (estimate / scale) * (estimate / scale);
        }
        (sum / y.len() as f64).sqrt()
    }

    fn accept<F>(&mut self, _f: &mut F, _x_end: f64, y: &mut OVector<f64, D>) -> u32
    where
        F: FnMut(f64, &OVector<f64, D>, &mut OVector<f64, D>),
    {
        std::mem::swap(y, &mut self.y_new);
        // First same as last: stage 7 is the derivative at the new state.
        self.k.swap(0, 6);
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Truth: the simplifying and quadrature conditions of a fifth-order pair (Hairer,
    /// Norsett, Wanner, Solving ODEs I, II.5): each row of A sums to its node, the
    /// fifth-order weights (row 7) integrate c^(q-1) exactly for q = 1..5, and the error
    /// weights, a difference of a fifth- and a fourth-order rule, annihilate c^(q-1)
    /// for q = 1..4. A mistyped coefficient breaks one of them.
    #[test]
    fn coefficients_meet_the_order_conditions() {
        for (i, row) in A.iter().enumerate().skip(1) {
            let sum: f64 = row.iter().sum();
            assert!((sum - C[i]).abs() < 1e-14, "row {} sums to {sum}", i + 1);
        }
        let b = A[6];
        let e = [E1, 0.0, E3, E4, E5, E6, E7];
        for q in 1..=5 {
            let quadrature: f64 = (0..6).map(|i| b[i] * C[i].powi(q - 1)).sum();
            assert!((quadrature - 1.0 / f64::from(q)).abs() < 1e-14, "q = {q}");
        }
        for q in 1..=4 {
            let residual: f64 = (0..7).map(|i| e[i] * C[i].powi(q - 1)).sum();
            assert!(residual.abs() < 1e-15, "error weights, q = {q}: {residual}");
        }
    }
}
