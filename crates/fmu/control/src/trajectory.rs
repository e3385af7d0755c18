//! Cubic and quintic point-to-point polynomials from boundary conditions at arbitrary
//! times t0 < tf.
//!
//! The coefficients are those of the 4x4 (cubic) and 6x6 (quintic) boundary-condition
//! systems, solved in closed form in the shifted time tau = t - t0. Shifting keeps the
//! solution well conditioned for any t0 (the system in absolute time has entries up
//! to tf^5 and loses digits when t0 is large).
//!
//! Outside [t0, tf] the trajectory holds still: before t0 the position is q0, after tf
//! it is qf, and in both cases velocity and acceleration are zero. At t0 and tf
//! themselves the polynomial is evaluated (so the boundary rates appear there), which
//! makes the held state the limit of a robot that rests before and after the motion.

/// Polynomial order of the trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// Position and velocity given at both ends (4 conditions).
    Cubic,
    /// Position, velocity and acceleration given at both ends (6 conditions).
    Quintic,
}

impl Order {
    /// Order from its polynomial degree (3 or 5).
    pub fn from_degree(degree: i32) -> Option<Order> {
        match degree {
            3 => Some(Order::Cubic),
            5 => Some(Order::Quintic),
            _ => None,
        }
    }
}

/// Boundary conditions of one axis. The accelerations are ignored by the cubic.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Boundary {
    pub q0: f64,
    pub qf: f64,
    pub qdot0: f64,
    pub qdotf: f64,
    pub qddot0: f64,
    pub qddotf: f64,
}

impl From<[f64; 6]> for Boundary {
    /// The conditions in the order of the fields: q0, qf, qdot0, qdotf, qddot0, qddotf.
    fn from([q0, qf, qdot0, qdotf, qddot0, qddotf]: [f64; 6]) -> Boundary {
        Boundary {
            q0,
            qf,
            qdot0,
            qdotf,
            qddot0,
            qddotf,
        }
    }
}

/// Position, velocity and acceleration at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub q: f64,
    pub qdot: f64,
    pub qddot: f64,
}

/// Why a trajectory cannot be built.
#[derive(Debug, Clone, PartialEq)]
pub enum TrajectoryError {
    /// tf must be strictly after t0.
    EmptyInterval { t0: f64, tf: f64 },
    /// A time or boundary value is NaN or infinite.
    NonFinite(&'static str),
}

impl std::fmt::Display for TrajectoryError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TrajectoryError::EmptyInterval { t0, tf } => {
                write!(
                    f,
                    "the final time tf = {tf} s must be after the start time t0 = {t0} s"
                )
            }
            TrajectoryError::NonFinite(what) => write!(f, "{what} is not a finite number"),
        }
    }
}

impl std::error::Error for TrajectoryError {}

/// One axis: q(t) = sum_k c_k (t - t0)^k on [t0, tf], held outside.
#[derive(Debug, Clone, PartialEq)]
pub struct Polynomial {
    t0: f64,
    tf: f64,
    /// Coefficients c_0..c_5 in the shifted time (c_4 = c_5 = 0 for the cubic).
    coefficients: [f64; 6],
}

impl Polynomial {
    /// Coefficients from the boundary conditions of one axis.
    pub fn new(
        order: Order,
        t0: f64,
        tf: f64,
        b: &Boundary,
    ) -> Result<Polynomial, TrajectoryError> {
        let checks = [
            (t0, "t0"),
            (tf, "tf"),
            (b.q0, "q0"),
            (b.qf, "qf"),
            (b.qdot0, "qdot0"),
            (b.qdotf, "qdotf"),
            (b.qddot0, "qddot0"),
            (b.qddotf, "qddotf"),
        ];
        if let Some((_, name)) = checks.iter().find(|(v, _)| !v.is_finite()) {
            return Err(TrajectoryError::NonFinite(name));
        }
        if tf - t0 <= 0.0 {
            return Err(TrajectoryError::EmptyInterval { t0, tf });
        }
        let coefficients = match order {
            Order::Cubic => cubic_coefficients(tf - t0, b),
            Order::Quintic => quintic_coefficients(tf - t0, b),
        };
        Ok(Polynomial {
            t0,
            tf,
            coefficients,
        })
    }

    /// Coefficients c_0..c_5 of the polynomial in tau = t - t0.
    pub fn shifted_coefficients(&self) -> [f64; 6] {
        self.coefficients
    }

    /// Whether the coefficients and the samples at 21 equally spaced times of [t0, tf]
    /// are finite.
    fn is_finite(&self) -> bool {
        let times = (0..=20).map(|k| self.t0 + (self.tf - self.t0) * f64::from(k) / 20.0);
        self.coefficients.iter().all(|c| c.is_finite())
            && times
                .map(|t| self.sample(t))
                .all(|s| s.q.is_finite() && s.qdot.is_finite() && s.qddot.is_finite())
    }

    /// Position, velocity and acceleration at time t (held outside [t0, tf]).
    pub fn sample(&self, t: f64) -> Sample {
        Sample {
            q: self.derivative(t, 0),
            qdot: self.derivative(t, 1),
            qddot: self.derivative(t, 2),
        }
    }

    /// The n-th time derivative of q at time t (n = 0: q itself): the polynomial's on
    /// [t0, tf], so at t0 the right-sided and at tf the left-sided derivative (from
    /// inside the motion, as `sample` gives the rates there); outside [t0, tf] the
    /// held position and zero for every n >= 1. Zero for n > 5 (jerk and snap of the
    /// cubic are constant and zero on [t0, tf]).
    pub fn derivative(&self, t: f64, n: usize) -> f64 {
        let inside = t.clamp(self.t0, self.tf);
        if n > 0 && inside != t {
            return 0.0;
        }
        let tau = inside - self.t0;
        let c = &self.coefficients;
        // Horner's scheme on the coefficients k!/(k-n)! c_k of the n-th derivative.
        (n..6).rev().fold(0.0, |acc, k| {
            let falling: usize = (k + 1 - n..=k).product();
            acc * tau + falling as f64 * c[k]
        })
    }
}

/// Closed-form solution of q(0)=q0, q'(0)=v0, q(T)=qf, q'(T)=vf.
fn cubic_coefficients(duration: f64, b: &Boundary) -> [f64; 6] {
    let t = duration;
    let dq = b.qf - b.q0;
    let c2 = (3.0 * dq - (2.0 * b.qdot0 + b.qdotf) * t) / (t * t);
    let c3 = (-2.0 * dq + (b.qdot0 + b.qdotf) * t) / (t * t * t);
    [b.q0, b.qdot0, c2, c3, 0.0, 0.0]
}

/// Closed-form solution of the quintic with position, velocity and acceleration at
/// tau = 0 and tau = T.
fn quintic_coefficients(duration: f64, b: &Boundary) -> [f64; 6] {
    let t = duration;
    let (t2, t3) = (t * t, t * t * t);
    let (t4, t5) = (t3 * t, t3 * t2);
    let dq = b.qf - b.q0;
    let (v0, vf, a0, af) = (b.qdot0, b.qdotf, b.qddot0, b.qddotf);
    let c3 = (20.0 * dq - (8.0 * vf + 12.0 * v0) * t - (3.0 * a0 - af) * t2) / (2.0 * t3);
    let c4 = (-30.0 * dq + (14.0 * vf + 16.0 * v0) * t + (3.0 * a0 - 2.0 * af) * t2) / (2.0 * t4);
    let c5 = (12.0 * dq - 6.0 * (vf + v0) * t + (af - a0) * t2) / (2.0 * t5);
    [b.q0, v0, 0.5 * a0, c3, c4, c5]
}

/// The trajectories of `N` axes that share the order and the times t0, tf: what a
/// planner of several joints evaluates.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan<const N: usize> {
    axes: [Polynomial; N],
}

impl<const N: usize> Plan<N> {
    /// Every axis's polynomial of degree `degree` (3 or 5). Err: the first reason, also
    /// where t0, tf and an axis's boundary values make the trajectory overflow (its
    /// coefficients or its samples at 21 equally spaced times of [t0, tf] are not
    /// finite, e.g. tf - t0 = 5e-324 s), naming the axis (from 1).
    pub fn new(degree: i32, t0: f64, tf: f64, boundary: &[Boundary; N]) -> Result<Self, String> {
        let order = Order::from_degree(degree)
            .ok_or_else(|| format!("order {degree} is neither 3 nor 5"))?;
        let mut axes = Vec::with_capacity(N);
        for (a, b) in boundary.iter().enumerate() {
            let p = Polynomial::new(order, t0, tf, b).map_err(|e| e.to_string())?;
            if !p.is_finite() {
                return Err(format!(
                    "t0 = {t0:e} s, tf = {tf:e} s and the boundary values of axis {} ({b:?}) \
                     make the trajectory overflow (its coefficients or samples are not finite)",
                    a + 1
                ));
            }
            axes.push(p);
        }
        let axes = axes
            .try_into()
            .unwrap_or_else(|_| unreachable!("one per axis"));
        Ok(Plan { axes })
    }

    /// The polynomial of axis `a` (from 0).
    pub fn axis(&self, a: usize) -> &Polynomial {
        &self.axes[a]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    fn boundary() -> Boundary {
        Boundary {
            q0: 0.3,
            qf: -1.1,
            qdot0: 0.7,
            qdotf: -0.2,
            qddot0: 1.5,
            qddotf: -0.4,
        }
    }

    /// Second formulation: the boundary-condition system of the spec in absolute time
    /// t (rows: q, qdot, qddot at t0 and tf), solved by LU. Returns c_k of t^k.
    fn absolute_time_solution(order: Order, t0: f64, tf: f64, b: &Boundary) -> Vec<f64> {
        let n = if order == Order::Cubic { 4 } else { 6 };
        let row = |t: f64, derivative: usize| -> Vec<f64> {
            (0..n)
                .map(|k| {
                    if k < derivative {
                        0.0
                    } else {
                        let falling: f64 = (0..derivative).map(|j| (k - j) as f64).product();
                        falling * t.powi((k - derivative) as i32)
                    }
                })
                .collect()
        };
        let mut rows = vec![row(t0, 0), row(t0, 1), row(tf, 0), row(tf, 1)];
        let mut rhs = vec![b.q0, b.qdot0, b.qf, b.qdotf];
        if order == Order::Quintic {
            rows.push(row(t0, 2));
            rows.push(row(tf, 2));
            rhs.push(b.qddot0);
            rhs.push(b.qddotf);
        }
        let a = DMatrix::from_row_iterator(n, n, rows.into_iter().flatten());
        let x = a
            .lu()
            .solve(&DVector::from_vec(rhs))
            .expect("regular system");
        x.iter().copied().collect()
    }

    #[test]
    fn boundary_conditions_hold_at_both_ends_for_any_t0() {
        // Expected values: the boundary conditions themselves.
        let b = boundary();
        for (t0, tf) in [(0.0, 2.0), (3.5, 4.25), (-2.0, 1.0)] {
            let p = Polynomial::new(Order::Quintic, t0, tf, &b).unwrap();
            let (s0, sf) = (p.sample(t0), p.sample(tf));
            for (got, want) in [
                (s0.q, b.q0),
                (s0.qdot, b.qdot0),
                (s0.qddot, b.qddot0),
                (sf.q, b.qf),
                (sf.qdot, b.qdotf),
                (sf.qddot, b.qddotf),
            ] {
                assert!((got - want).abs() < 1e-12, "{got} vs {want} (t0 {t0})");
            }
            let c = Polynomial::new(Order::Cubic, t0, tf, &b).unwrap();
            let (s0, sf) = (c.sample(t0), c.sample(tf));
            for (got, want) in [
                (s0.q, b.q0),
                (s0.qdot, b.qdot0),
                (sf.q, b.qf),
                (sf.qdot, b.qdotf),
            ] {
                assert!((got - want).abs() < 1e-12, "{got} vs {want} (t0 {t0})");
            }
        }
    }

    #[test]
    fn rest_to_rest_cubic_on_unit_interval_is_the_textbook_shortcut() {
        // Expected values: q0 + 3 dq t^2 - 2 dq t^3 (the thesis's special case).
        let b = Boundary {
            q0: 0.5,
            qf: 2.0,
            ..Boundary::default()
        };
        let p = Polynomial::new(Order::Cubic, 0.0, 1.0, &b).unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let want = 0.5 + 3.0 * 1.5 * t * t - 2.0 * 1.5 * t * t * t;
            assert!((p.sample(t).q - want).abs() < 1e-14);
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        // Expected values: central finite differences of q and qdot (error O(h^2)).
        let p = Polynomial::new(Order::Quintic, 0.4, 1.9, &boundary()).unwrap();
        let h = 1e-5;
        for i in 1..20 {
            let t = 0.4 + 1.5 * i as f64 / 20.0;
            let fd_v = (p.sample(t + h).q - p.sample(t - h).q) / (2.0 * h);
            let fd_a = (p.sample(t + h).qdot - p.sample(t - h).qdot) / (2.0 * h);
            assert!((p.sample(t).qdot - fd_v).abs() < 1e-7);
            assert!((p.sample(t).qddot - fd_a).abs() < 1e-7);
        }
    }

    #[test]
    fn closed_form_and_its_derivatives_match_the_boundary_condition_system_in_absolute_time() {
        // Expected values: sum c_k t^k (the LU solution of the 4x4 / 6x6 system of the
        // spec in absolute time) and its n-th derivatives, term by term
        // c_k k!/(k-n)! t^(k-n).
        let b = boundary();
        let (t0, tf) = (1.0, 2.5);
        for order in [Order::Cubic, Order::Quintic] {
            let p = Polynomial::new(order, t0, tf, &b).unwrap();
            let c = absolute_time_solution(order, t0, tf, &b);
            for i in 0..=30 {
                let t = t0 + (tf - t0) * i as f64 / 30.0;
                for n in 0..=5 {
                    let want: f64 = (n..c.len())
                        .map(|k| {
                            let falling: f64 = (k + 1 - n..=k).map(|j| j as f64).product();
                            c[k] * falling * t.powi((k - n) as i32)
                        })
                        .sum();
                    let got = p.derivative(t, n);
                    assert!(
                        (got - want).abs() < 1e-10 * (1.0 + want.abs()),
                        "{order:?} n={n} t={t}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn cubic_jerk_is_constant_snap_zero_and_rates_vanish_while_held() {
        // Expected values: q''' = 6 c3 for a cubic (closed form), q'''' = 0; the hold.
        let b = boundary();
        let p = Polynomial::new(Order::Cubic, 0.5, 2.0, &b).unwrap();
        let jerk = 6.0 * p.shifted_coefficients()[3];
        for t in [0.5, 0.9, 1.7, 2.0] {
            assert!((p.derivative(t, 3) - jerk).abs() < 1e-12 * jerk.abs());
            assert_eq!(p.derivative(t, 4), 0.0);
        }
        let q = Polynomial::new(Order::Quintic, 0.5, 2.0, &b).unwrap();
        for t in [0.2, 2.0 + 1e-9, 9.0] {
            for n in 1..=4 {
                assert_eq!((p.derivative(t, n), q.derivative(t, n)), (0.0, 0.0));
            }
        }
        // At tf the left-sided derivative (inside the motion): qdot(tf) = qdotf.
        assert!((q.derivative(2.0, 1) - b.qdotf).abs() < 1e-12);
        assert!((q.derivative(2.0, 2) - b.qddotf).abs() < 1e-12);
    }

    #[test]
    fn holds_still_outside_the_interval() {
        // Expected values: the documented hold (q0 / qf, zero rates).
        let b = boundary();
        let p = Polynomial::new(Order::Quintic, 1.0, 2.0, &b).unwrap();
        let before = p.sample(0.2);
        let after = p.sample(7.0);
        assert_eq!((before.q, before.qdot, before.qddot), (b.q0, 0.0, 0.0));
        assert!((after.q - b.qf).abs() < 1e-12);
        assert_eq!((after.qdot, after.qddot), (0.0, 0.0));
    }

    #[test]
    fn rejects_empty_interval_and_non_finite_values() {
        let b = boundary();
        assert_eq!(
            Polynomial::new(Order::Cubic, 2.0, 2.0, &b),
            Err(TrajectoryError::EmptyInterval { t0: 2.0, tf: 2.0 })
        );
        let bad = Boundary {
            qdotf: f64::NAN,
            ..b
        };
        assert_eq!(
            Polynomial::new(Order::Quintic, 0.0, 1.0, &bad),
            Err(TrajectoryError::NonFinite("qdotf"))
        );
        assert_eq!(Order::from_degree(4), None);
    }

    #[test]
    fn a_plan_is_one_polynomial_per_axis_and_names_the_axis_that_overflows() {
        // Truth: Polynomial::new axis by axis (the plan adds only the finiteness check).
        let b = [
            Boundary {
                qf: 0.5,
                ..Boundary::default()
            },
            Boundary {
                qf: -0.3,
                qdotf: 0.1,
                ..Boundary::default()
            },
        ];
        let plan = Plan::new(5, 1.0, 3.0, &b).unwrap();
        for (a, b) in b.iter().enumerate() {
            let p = Polynomial::new(Order::Quintic, 1.0, 3.0, b).unwrap();
            assert_eq!(plan.axis(a), &p);
        }
        assert_eq!(
            Plan::new(4, 1.0, 3.0, &b).unwrap_err(),
            "order 4 is neither 3 nor 5"
        );
        // tf - t0 = 1e-100 s: the cubic's c3 = -2 (qf - q0) / T^3 is -2e300 for a
        // step of 1 (finite) and -2e310 for a step of 1e10 (overflows): axis 2 only.
        let steps = [1.0, 1e10].map(|qf| Boundary {
            qf,
            ..Boundary::default()
        });
        let message = Plan::new(3, 0.0, 1e-100, &steps).unwrap_err();
        assert!(
            message.contains("axis 2") && message.contains("overflow"),
            "{message}"
        );
    }
}
