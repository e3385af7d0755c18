//! Forward kinematics: the orientation for given actuator displacements, by Newton's
//! method on the closed-form IK equations l_ik(th) - l = 0 from a seed orientation.
//!
//! The Newton matrix is d l_ik / d th = J E(th): the actuator Jacobian (l_dot = J omega)
//! times the Euler-rate map (omega = E th_dot). A step that would take the platform
//! where a leg cannot reach is halved until it assembles.

use super::error::KinematicsError;
use super::ik::{Assembly, assemble};
use super::jacobian::jacobian;
use super::params::Geometry;
use super::rotation::euler_rate_matrix;
use nalgebra::Vector3;

/// Roll angle of the default start pose (all actuators at 2 mm, thx = thy = 0), deg.
pub const START_ROLL_DEG: f64 = 122.07;

/// Halvings of one Newton step before giving up on it.
const MAX_STEP_HALVINGS: usize = 30;

/// The default seed: the start pose (0, 0, 122.07 deg) of docs/3pss-model.md, rad.
pub fn start_pose() -> Vector3<f64> {
    Vector3::new(0.0, 0.0, START_ROLL_DEG.to_radians())
}

/// Options of the Newton iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FkOptions {
    /// Converged when every |l_ik(th) - l| is below this, m.
    pub tolerance: f64,
    /// Newton iterations before reporting `NoConvergence`.
    pub max_iterations: usize,
    /// Reject actuator displacements outside the stroke before iterating.
    pub check_stroke: bool,
}

impl Default for FkOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-14,
            max_iterations: 50,
            check_stroke: true,
        }
    }
}

/// A converged forward-kinematics solution.
#[derive(Debug, Clone, PartialEq)]
pub struct ForwardSolution {
    /// The mechanism assembled at the solution (its `l` is the closed-form IK of it).
    pub assembly: Assembly,
    /// Newton iterations taken.
    pub iterations: usize,
    /// max |l_ik(th) - l| at the solution, m.
    pub residual: f64,
}

/// Orientation for actuator displacements `l` (m), by Newton's method from `seed` (rad).
pub fn forward_kinematics(
    geometry: &Geometry,
    l: &Vector3<f64>,
    seed: &Vector3<f64>,
    options: &FkOptions,
) -> Result<ForwardSolution, KinematicsError> {
    if l.iter().any(|v| !v.is_finite()) {
        return Err(KinematicsError::NotFinite("actuator displacements"));
    }
    if options.check_stroke {
        check_in_stroke(geometry, l)?;
    }
    let mut assembly = assemble(geometry, seed)?;
    let mut residual = (assembly.l - l).amax();
    for iterations in 0..=options.max_iterations {
        if residual < options.tolerance {
            return Ok(ForwardSolution {
                assembly,
                iterations,
                residual,
            });
        }
        if iterations == options.max_iterations {
            break;
        }
        let newton = jacobian(geometry, &assembly)?.matrix * euler_rate_matrix(&assembly.euler);
        let step = newton
            .lu()
            .solve(&(l - assembly.l))
            .ok_or(KinematicsError::Singular)?;
        assembly = assembled_step(geometry, &assembly.euler, &step)?;
        residual = (assembly.l - l).amax();
    }
    Err(KinematicsError::NoConvergence {
        iterations: options.max_iterations,
        residual,
    })
}

/// The assembly at euler + s step for the largest s in 1, 1/2, 1/4, ... that assembles.
fn assembled_step(
    geometry: &Geometry,
    euler: &Vector3<f64>,
    step: &Vector3<f64>,
) -> Result<Assembly, KinematicsError> {
    let mut scale = 1.0;
    let mut last = KinematicsError::NotFinite("Newton step");
    for _ in 0..=MAX_STEP_HALVINGS {
        match assemble(geometry, &(euler + scale * step)) {
            Ok(assembly) => return Ok(assembly),
            Err(e) => last = e,
        }
        scale *= 0.5;
    }
    Err(last)
}

fn check_in_stroke(geometry: &Geometry, l: &Vector3<f64>) -> Result<(), KinematicsError> {
    let (min, max) = (geometry.params.stroke_min, geometry.params.stroke_max);
    match l.iter().position(|v| !(min..=max).contains(v)) {
        Some(i) => Err(KinematicsError::OutsideStroke {
            leg: i + 1,
            l: l[i],
            min,
            max,
        }),
        None => Ok(()),
    }
}
