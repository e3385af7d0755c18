//! A second, independent formulation for cross-checking: Lagrange's equations in the
//! Euler angles q = (thx, thy, thz), with every derivative taken exactly by nested dual
//! numbers from the body positions alone (no Jacobian, no E map, no velocity
//! kinematics of the main formulation):
//!
//!   T = 1/2 q_dot^T M_L(q) q_dot,  M_L = sum over point-mass-like terms of
//!   (dx/dq)^T m (dx/dq), where for each chain the slider (mass m_s at M_i), the leg's
//!   centre of mass (m_l at M_i + s (Q_i - M_i)) and the leg's rotation
//!   (I_t |n_dot|^2 / 2 with n = (Q_i - M_i) / a, since |w_leg| = |n_dot| for a leg
//!   without spin) contribute, and the platform contributes
//!   1/2 tr(R_dot Pi R_dot^T) with Pi = tr(I_P)/2 1 - I_P its second moment about P;
//!   V = -g . (sum of mass-weighted centres of mass);
//!   d/dt dT/dq_dot - dT/dq + dV/dq = M_L q_ddot + M_L_dot q_dot
//!     - 1/2 (q_dot^T dM_L/dq_i q_dot)_i + dV/dq = Q_L,
//!   Q_L = sum_k f_k dl_k/dq + tau . vee(dR/dq R^T) (virtual work).
//! Positions come from a scalar-generic restatement of R = Rz Ry Rx and the closed-form
//! inverse kinematics.

use super::dual::{Dual, Real};
use super::error::DynamicsError;
use super::euler_form::EulerAngleForm;
use super::model::Model;
use crate::pss3::{Geometry, KinematicsError};
use nalgebra::{Matrix3, Vector3};

type Vec3<S> = [S; 3];
type Mat3<S> = [[S; 3]; 3];

/// Loads for the Lagrange generalized force.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AppliedLoads {
    /// Actuator forces along u_i, N.
    pub actuator_forces: Vector3<f64>,
    /// Moment on the platform about P, in {A}, N m.
    pub platform_torque: Vector3<f64>,
    /// Viscous friction on the sliders, N s/m.
    pub slider_friction: f64,
    /// Viscous friction at P, N m s/rad.
    pub pivot_friction: f64,
}

/// Body positions at one orientation.
struct Placement<S> {
    rotation: Mat3<S>,
    displacements: Vec3<S>,
    sliders: [Vec3<S>; 3],
    joints: [Vec3<S>; 3],
}

impl<S: Real> Placement<S> {
    fn map<T>(&self, f: impl Fn(S) -> T + Copy) -> Placement<T> {
        let vec = |v: &Vec3<S>| v.map(f);
        Placement {
            rotation: self.rotation.map(|row| row.map(f)),
            displacements: vec(&self.displacements),
            sliders: self.sliders.each_ref().map(vec),
            joints: self.joints.each_ref().map(vec),
        }
    }
}

fn constant<S: Real>(v: &Vector3<f64>) -> Vec3<S> {
    [S::constant(v.x), S::constant(v.y), S::constant(v.z)]
}

fn add<S: Real>(a: Vec3<S>, b: Vec3<S>) -> Vec3<S> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub<S: Real>(a: Vec3<S>, b: Vec3<S>) -> Vec3<S> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale<S: Real>(k: S, a: Vec3<S>) -> Vec3<S> {
    [k * a[0], k * a[1], k * a[2]]
}

fn dot<S: Real>(a: Vec3<S>, b: Vec3<S>) -> S {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn mat_mul<S: Real>(a: &Mat3<S>, b: &Mat3<S>) -> Mat3<S> {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

fn mat_vec<S: Real>(a: &Mat3<S>, v: Vec3<S>) -> Vec3<S> {
    std::array::from_fn(|i| a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2])
}

/// Elementary rotation by `angle` about coordinate axis `axis` (0 = x, 1 = y, 2 = z).
fn axis_rotation<S: Real>(axis: usize, angle: S) -> Mat3<S> {
    let (zero, one) = (S::constant(0.0), S::constant(1.0));
    let (s, c) = (angle.sin(), angle.cos());
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = [[zero; 3]; 3];
    m[axis][axis] = one;
    m[a][a] = c;
    m[b][b] = c;
    m[a][b] = -s;
    m[b][a] = s;
    m
}

fn placement<S: Real>(geometry: &Geometry, q: Vec3<S>) -> Result<Placement<S>, DynamicsError> {
    let rotation = mat_mul(
        &axis_rotation(2, q[2]),
        &mat_mul(&axis_rotation(1, q[1]), &axis_rotation(0, q[0])),
    );
    let a = S::constant(geometry.params.a);
    let p = constant(&geometry.p);
    let mut displacements = [S::constant(0.0); 3];
    let mut sliders = [[S::constant(0.0); 3]; 3];
    let mut joints = [[S::constant(0.0); 3]; 3];
    for i in 0..3 {
        let (h, u) = (constant(&geometry.h[i]), constant(&geometry.u[i]));
        joints[i] = add(p, mat_vec(&rotation, constant(&geometry.b[i])));
        let d = sub(joints[i], h);
        let along = dot(d, u);
        let discriminant = along * along - dot(d, d) + a * a;
        if discriminant.value() < 0.0 {
            return Err(KinematicsError::CannotAssemble { leg: i + 1 }.into());
        }
        displacements[i] = along - discriminant.sqrt();
        sliders[i] = add(h, scale(displacements[i], u));
    }
    Ok(Placement {
        rotation,
        displacements,
        sliders,
        joints,
    })
}

/// The placement's partial derivatives along each Euler angle at `q`.
fn partials<S: Real>(geometry: &Geometry, q: Vec3<S>) -> Result<[Placement<S>; 3], DynamicsError> {
    let along = |j: usize| -> Result<Placement<S>, DynamicsError> {
        let seeded: Vec3<Dual<S>> = std::array::from_fn(|k| {
            let direction = if k == j { 1.0 } else { 0.0 };
            Dual::new(q[k], S::constant(direction))
        });
        Ok(placement(geometry, seeded)?.map(|x| x.du))
    };
    Ok([along(0)?, along(1)?, along(2)?])
}

/// M_L(q), the Euler-angle mass matrix from the kinetic energy of the body positions.
fn mass_matrix<S: Real>(model: &Model, q: Vec3<S>) -> Result<Mat3<S>, DynamicsError> {
    let inertia = &model.inertia;
    let d = partials(&model.geometry, q)?;
    let s = S::constant(inertia.leg_com_fraction);
    let inv_a = S::constant(1.0 / model.geometry.params.a);
    let i_p = inertia.platform_inertia;
    let pi = Matrix3::identity() * (0.5 * i_p.trace()) - i_p;
    let (ms, ml, it) = (
        S::constant(inertia.slider_mass),
        S::constant(inertia.leg_mass),
        S::constant(inertia.leg_transverse_inertia),
    );
    let entry = |j: usize, k: usize| -> S {
        let mut sum = S::constant(0.0);
        for a in 0..3 {
            for b in 0..3 {
                for c in 0..3 {
                    sum = sum + d[j].rotation[a][b] * S::constant(pi[(b, c)]) * d[k].rotation[a][c];
                }
            }
        }
        for i in 0..3 {
            let (mj, mk) = (d[j].sliders[i], d[k].sliders[i]);
            let (rel_j, rel_k) = (sub(d[j].joints[i], mj), sub(d[k].joints[i], mk));
            let (cj, ck) = (add(mj, scale(s, rel_j)), add(mk, scale(s, rel_k)));
            sum =
                sum + ms * dot(mj, mk) + ml * dot(cj, ck) + it * inv_a * inv_a * dot(rel_j, rel_k);
        }
        sum
    };
    Ok(std::array::from_fn(|j| {
        std::array::from_fn(|k| entry(j, k))
    }))
}

/// Potential energy of gravity at `q`, zero at height 0.
fn potential<S: Real>(model: &Model, q: Vec3<S>) -> Result<S, DynamicsError> {
    let inertia = &model.inertia;
    let place = placement(&model.geometry, q)?;
    let s = S::constant(inertia.leg_com_fraction);
    let p = constant(&model.geometry.p);
    let platform_com = add(p, mat_vec(&place.rotation, constant(&inertia.platform_com)));
    let mut weighted = scale(S::constant(inertia.platform_mass), platform_com);
    for i in 0..3 {
        let slider = place.sliders[i];
        let com = add(slider, scale(s, sub(place.joints[i], slider)));
        weighted = add(weighted, scale(S::constant(inertia.slider_mass), slider));
        weighted = add(weighted, scale(S::constant(inertia.leg_mass), com));
    }
    Ok(-dot(weighted, constant(&model.gravity)))
}

fn seeded(q: &Vector3<f64>, direction: &Vector3<f64>) -> Vec3<Dual<f64>> {
    std::array::from_fn(|k| Dual::new(q[k], direction[k]))
}

fn to_matrix(m: &Mat3<f64>) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| m[i][j])
}

/// M_L, the velocity terms M_L_dot q_dot - 1/2 (q_dot^T dM_L/dq_i q_dot)_i and dV/dq of
/// Lagrange's equations at angles `q` moving at rates `q_dot`.
pub fn lagrange_form(
    model: &Model,
    q: &Vector3<f64>,
    q_dot: &Vector3<f64>,
) -> Result<EulerAngleForm, DynamicsError> {
    let mass = to_matrix(&mass_matrix(model, [q.x, q.y, q.z])?);
    let derivative_along = |d: &Vector3<f64>| -> Result<Matrix3<f64>, DynamicsError> {
        let m = mass_matrix(model, seeded(q, d))?;
        Ok(to_matrix(&m.map(|row| row.map(|x| x.du))))
    };
    let mass_dot = derivative_along(q_dot)?;
    let mut velocity = mass_dot * q_dot;
    let mut gravity = Vector3::zeros();
    for i in 0..3 {
        let e = Vector3::ith(i, 1.0);
        velocity[i] -= 0.5 * q_dot.dot(&(derivative_along(&e)? * q_dot));
        gravity[i] = potential(model, seeded(q, &e))?.du;
    }
    Ok(EulerAngleForm {
        mass,
        velocity,
        gravity,
    })
}

/// Generalized force Q_L of `loads` at angles `q` moving at rates `q_dot`, by virtual
/// work: actuator and slider-friction forces through dl/dq, platform moments through
/// the virtual rotation vee(dR/dq R^T).
pub fn lagrange_generalized_force(
    model: &Model,
    q: &Vector3<f64>,
    q_dot: &Vector3<f64>,
    loads: &AppliedLoads,
) -> Result<Vector3<f64>, DynamicsError> {
    let rotation = to_matrix(&placement(&model.geometry, [q.x, q.y, q.z])?.rotation);
    let d = partials(&model.geometry, [q.x, q.y, q.z])?;
    let virtual_rotation = |i: usize| -> Vector3<f64> {
        let w = to_matrix(&d[i].rotation) * rotation.transpose();
        0.5 * Vector3::new(
            w[(2, 1)] - w[(1, 2)],
            w[(0, 2)] - w[(2, 0)],
            w[(1, 0)] - w[(0, 1)],
        )
    };
    let dl = |i: usize| Vector3::from(d[i].displacements);
    let l_dot: Vector3<f64> = (0..3).map(|i| q_dot[i] * dl(i)).sum();
    let omega: Vector3<f64> = (0..3).map(|i| q_dot[i] * virtual_rotation(i)).sum();
    let slider_forces = loads.actuator_forces - loads.slider_friction * l_dot;
    let platform_torque = loads.platform_torque - loads.pivot_friction * omega;
    Ok(Vector3::from_fn(|i, _| {
        slider_forces.dot(&dl(i)) + platform_torque.dot(&virtual_rotation(i))
    }))
}
