//! End-effector paths r(t): the paper's paths A and B, a path given by functions, and
//! a path sampled in a CSV file of (t, x, y), interpolated by natural cubic splines.

use super::DualArmError;
use nalgebra::Vector2;
use std::f64::consts::PI;

/// A time-parametrised end-effector path with its velocity, on `[start, end]`.
pub trait Path: Sync {
    /// Start time t0, s.
    fn start(&self) -> f64;
    /// Final time tf, s.
    fn end(&self) -> f64;
    /// Position r(t), m.
    fn position(&self, t: f64) -> Vector2<f64>;
    /// Velocity dr/dt, m/s.
    fn velocity(&self, t: f64) -> Vector2<f64>;
}

/// The two paths of the paper, on t in [0, 1] s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PaperPath {
    /// x = 0.5, y = 0.25 (1 - cos pi t).
    A,
    /// x = 0.25 + 0.15 (1 - cos pi t), y = 1.5 x.
    B,
}

impl Path for PaperPath {
    fn start(&self) -> f64 {
        0.0
    }

    fn end(&self) -> f64 {
        1.0
    }

    fn position(&self, t: f64) -> Vector2<f64> {
        let ramp = 1.0 - (PI * t).cos();
        match self {
            PaperPath::A => Vector2::new(0.5, 0.25 * ramp),
            PaperPath::B => {
                let x = 0.25 + 0.15 * ramp;
                Vector2::new(x, 1.5 * x)
            }
        }
    }

    fn velocity(&self, t: f64) -> Vector2<f64> {
        let ramp_rate = PI * (PI * t).sin();
        match self {
            PaperPath::A => Vector2::new(0.0, 0.25 * ramp_rate),
            PaperPath::B => Vector2::new(0.15 * ramp_rate, 0.225 * ramp_rate),
        }
    }
}

/// A path given by its position and velocity functions.
pub struct FunctionPath<P, V> {
    start: f64,
    end: f64,
    position: P,
    velocity: V,
}

impl<P, V> FunctionPath<P, V>
where
    P: Fn(f64) -> Vector2<f64> + Sync,
    V: Fn(f64) -> Vector2<f64> + Sync,
{
    /// The path `position(t)` with derivative `velocity(t)` on `[start, end]`.
    pub fn new(start: f64, end: f64, position: P, velocity: V) -> Result<Self, DualArmError> {
        check_interval(start, end)?;
        Ok(Self {
            start,
            end,
            position,
            velocity,
        })
    }
}

impl<P, V> Path for FunctionPath<P, V>
where
    P: Fn(f64) -> Vector2<f64> + Sync,
    V: Fn(f64) -> Vector2<f64> + Sync,
{
    fn start(&self) -> f64 {
        self.start
    }
    fn end(&self) -> f64 {
        self.end
    }
    fn position(&self, t: f64) -> Vector2<f64> {
        (self.position)(t)
    }
    fn velocity(&self, t: f64) -> Vector2<f64> {
        (self.velocity)(t)
    }
}

fn check_interval(start: f64, end: f64) -> Result<(), DualArmError> {
    if start.is_finite() && end.is_finite() && end > start {
        Ok(())
    } else {
        Err(DualArmError::InvalidInput(format!(
            "path time interval [{start}, {end}] is empty or not finite"
        )))
    }
}

/// A natural cubic spline through (t_i, v_i): C2 position, continuous velocity.
#[derive(Debug, Clone, PartialEq)]
struct Spline {
    t: Vec<f64>,
    v: Vec<f64>,
    second: Vec<f64>,
}

impl Spline {
    /// Second derivatives from the tridiagonal system of a natural spline (zero at ends).
    fn new(t: &[f64], v: &[f64]) -> Self {
        let n = t.len();
        let mut second = vec![0.0; n];
        let mut diag = vec![0.0; n];
        let mut rhs = vec![0.0; n];
        // Forward elimination (Thomas algorithm) on the interior equations.
        for i in 1..n - 1 {
            let (h0, h1) = (t[i] - t[i - 1], t[i + 1] - t[i]);
            let r = 6.0 * ((v[i + 1] - v[i]) / h1 - (v[i] - v[i - 1]) / h0);
            let d = 2.0 * (h0 + h1);
            if i == 1 {
                diag[i] = d;
                rhs[i] = r;
            } else {
                let w = h0 / diag[i - 1];
                diag[i] = d - w * h0;
                rhs[i] = r - w * rhs[i - 1];
            }
        }
        for i in (1..n - 1).rev() {
            let h1 = t[i + 1] - t[i];
            second[i] = (rhs[i] - h1 * second[i + 1]) / diag[i];
        }
        Self {
            t: t.to_vec(),
            v: v.to_vec(),
            second,
        }
    }

    /// Value and derivative at `x` (clamped to the sampled interval).
    fn eval(&self, x: f64) -> (f64, f64) {
        let n = self.t.len();
        let x = x.clamp(self.t[0], self.t[n - 1]);
        let i = self.t.partition_point(|ti| *ti <= x).clamp(1, n - 1) - 1;
        let h = self.t[i + 1] - self.t[i];
        let (a, b) = ((self.t[i + 1] - x) / h, (x - self.t[i]) / h);
        let (m0, m1) = (self.second[i], self.second[i + 1]);
        let value = a * self.v[i]
            + b * self.v[i + 1]
            + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0;
        let slope = (self.v[i + 1] - self.v[i]) / h
            + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0;
        (value, slope)
    }
}

/// A path sampled at increasing times, interpolated by natural cubic splines.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledPath {
    x: Spline,
    y: Spline,
}

impl SampledPath {
    /// The path through `(t_i, x_i, y_i)`; needs at least 4 samples at increasing times.
    pub fn new(samples: &[(f64, f64, f64)]) -> Result<Self, DualArmError> {
        if samples.len() < 4 {
            return Err(DualArmError::InvalidInput(format!(
                "a sampled path needs at least 4 samples, {} given",
                samples.len()
            )));
        }
        if samples
            .iter()
            .any(|s| !(s.0.is_finite() && s.1.is_finite() && s.2.is_finite()))
        {
            return Err(DualArmError::InvalidInput(
                "a path sample is not finite".into(),
            ));
        }
        if let Some(w) = samples.windows(2).find(|w| w[1].0 <= w[0].0) {
            return Err(DualArmError::InvalidInput(format!(
                "path times must increase; t = {} is followed by t = {}",
                w[0].0, w[1].0
            )));
        }
        let t: Vec<f64> = samples.iter().map(|s| s.0).collect();
        let x: Vec<f64> = samples.iter().map(|s| s.1).collect();
        let y: Vec<f64> = samples.iter().map(|s| s.2).collect();
        Ok(Self {
            x: Spline::new(&t, &x),
            y: Spline::new(&t, &y),
        })
    }

    /// Parses CSV text of lines `t, x, y` (SI units); a first line that is not numeric is
    /// taken as a header, blank lines and lines starting with `#` are skipped.
    pub fn from_csv(text: &str) -> Result<Self, DualArmError> {
        let mut samples = Vec::new();
        for (number, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields: Result<Vec<f64>, _> =
                line.split(',').map(|f| f.trim().parse::<f64>()).collect();
            match fields {
                Ok(f) if f.len() == 3 => samples.push((f[0], f[1], f[2])),
                Err(_) if samples.is_empty() && number == 0 => continue,
                _ => {
                    return Err(DualArmError::InvalidInput(format!(
                        "path CSV line {}: expected three numbers t, x, y: {line:?}",
                        number + 1
                    )));
                }
            }
        }
        Self::new(&samples)
    }
}

impl Path for SampledPath {
    fn start(&self) -> f64 {
        self.x.t[0]
    }
    fn end(&self) -> f64 {
        self.x.t[self.x.t.len() - 1]
    }
    fn position(&self, t: f64) -> Vector2<f64> {
        Vector2::new(self.x.eval(t).0, self.y.eval(t).0)
    }
    fn velocity(&self, t: f64) -> Vector2<f64> {
        Vector2::new(self.x.eval(t).1, self.y.eval(t).1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_path_velocities_match_central_differences() {
        let h = 1e-6;
        for path in [PaperPath::A, PaperPath::B] {
            for t in [0.1, 0.5, 0.83] {
                let fd = (path.position(t + h) - path.position(t - h)) / (2.0 * h);
                assert!((fd - path.velocity(t)).norm() < 1e-8);
            }
        }
        // End points from the spec's formulas: A goes (0.5, 0) to (0.5, 0.5).
        assert!((PaperPath::A.position(1.0) - Vector2::new(0.5, 0.5)).norm() < 1e-15);
        assert!((PaperPath::B.position(1.0) - Vector2::new(0.55, 0.825)).norm() < 1e-15);
    }

    #[test]
    fn spline_reproduces_lines_exactly_and_smooth_curves_closely() {
        // A natural spline reproduces linear data exactly; sin(pi t) sampled every 0.05
        // is matched to the interpolation error O(h^2) of the free end conditions.
        let samples: Vec<(f64, f64, f64)> = (0..=20)
            .map(|i| {
                let t = i as f64 / 20.0;
                (t, 2.0 * t + 1.0, (PI * t).sin())
            })
            .collect();
        let path = SampledPath::new(&samples).unwrap();
        for t in [0.013, 0.5, 0.77] {
            let p = path.position(t);
            let v = path.velocity(t);
            assert!((p.x - (2.0 * t + 1.0)).abs() < 1e-14 && (v.x - 2.0).abs() < 1e-13);
            assert!((p.y - (PI * t).sin()).abs() < 1e-4);
            assert!((v.y - PI * (PI * t).cos()).abs() < 1e-2);
        }
    }

    #[test]
    fn csv_parsing_accepts_a_header_and_rejects_bad_lines() {
        let text = "t,x,y\n0,0.5,0\n0.5,0.5,0.1\n1,0.5,0.2\n1.5,0.5,0.3\n";
        let path = SampledPath::from_csv(text).unwrap();
        assert_eq!((path.start(), path.end()), (0.0, 1.5));
        assert!((path.position(0.75).y - 0.15).abs() < 1e-14);
        assert!(SampledPath::from_csv("0,1,2\n1,2\n").is_err());
        assert!(SampledPath::from_csv("0,1,2\n0,1,2\n1,1,1\n2,2,2\n").is_err());
    }
}
