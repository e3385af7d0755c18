//! Forward-mode dual numbers a + b eps (eps^2 = 0), nestable, for exact derivatives in
//! the Lagrange cross-check: f(a + eps) = f(a) + f'(a) eps.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The scalar operations the Lagrange formulation needs.
pub(super) trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn constant(value: f64) -> Self;
    fn value(self) -> f64;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn sqrt(self) -> Self;
}

impl Real for f64 {
    fn constant(value: f64) -> Self {
        value
    }
    fn value(self) -> f64 {
        self
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

/// re + eps * du.
#[derive(Debug, Clone, Copy)]
pub(super) struct Dual<S> {
    pub re: S,
    pub du: S,
}

impl<S: Real> Dual<S> {
    /// A value at `re` moving with derivative `du`.
    pub fn new(re: S, du: S) -> Self {
        Self { re, du }
    }
}

impl<S: Real> Add for Dual<S> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self::new(self.re + o.re, self.du + o.du)
    }
}

impl<S: Real> Sub for Dual<S> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self::new(self.re - o.re, self.du - o.du)
    }
}

impl<S: Real> Mul for Dual<S> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self::new(self.re * o.re, self.re * o.du + self.du * o.re)
    }
}

impl<S: Real> Div for Dual<S> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let re = self.re / o.re;
        Self::new(re, (self.du - re * o.du) / o.re)
    }
}

impl<S: Real> Neg for Dual<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.re, -self.du)
    }
}

impl<S: Real> Real for Dual<S> {
    fn constant(value: f64) -> Self {
        Self::new(S::constant(value), S::constant(0.0))
    }
    fn value(self) -> f64 {
        self.re.value()
    }
    fn sin(self) -> Self {
        Self::new(self.re.sin(), self.re.cos() * self.du)
    }
    fn cos(self) -> Self {
        Self::new(self.re.cos(), -(self.re.sin() * self.du))
    }
    fn sqrt(self) -> Self {
        let root = self.re.sqrt();
        Self::new(root, self.du / (S::constant(2.0) * root))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nested_duals_give_exact_second_derivatives() {
        // Truth: f(x) = sin(x) sqrt(x) / (1 + cos x) differentiated by hand.
        fn f<S: Real>(x: S) -> S {
            x.sin() * x.sqrt() / (S::constant(1.0) + x.cos())
        }
        let x0 = 0.7_f64;
        let x = Dual::new(Dual::new(x0, 1.0), Dual::new(1.0, 0.0));
        let y = f(x);
        let (s, c, r) = (x0.sin(), x0.cos(), x0.sqrt());
        let g = s * r; // numerator
        let g1 = c * r + s / (2.0 * r);
        let g2 = -s * r + c / r - s / (4.0 * r * x0);
        let h = 1.0 + c;
        let (h1, h2) = (-s, -c);
        let f1 = (g1 * h - g * h1) / (h * h);
        let f2 = (g2 * h - g * h2) / (h * h) - 2.0 * h1 * (g1 * h - g * h1) / (h * h * h);
        assert!((y.re.re - g / h).abs() < 1e-15);
        assert!((y.re.du - f1).abs() < 1e-14 && (y.du.re - f1).abs() < 1e-14);
        assert!((y.du.du - f2).abs() < 1e-13, "{} vs {f2}", y.du.du);
    }
}
