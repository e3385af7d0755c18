//! Orientation of the platform: R = Rz(thz) Ry(thy) Rx(thx), and the maps between
//! Euler-angle rates and the angular velocity omega expressed in the base frame {A}.
//!
//! omega = thz_dot ez + thy_dot (Rz ey) + thx_dot (Rz Ry ex) = E(th) th_dot, with
//! E = [[cz cy, -sz, 0], [sz cy, cz, 0], [-sy, 0, 1]] (columns: thx, thy, thz), det E = cy.

use super::error::KinematicsError;
use nalgebra::{Matrix3, Vector3};

/// |cos thy| below which the Euler-angle representation is treated as singular.
const EULER_SINGULAR_COS: f64 = 1e-9;

/// Rotation matrix of {B} in {A} for Euler angles (thx, thy, thz), rad.
pub fn rotation(euler: &Vector3<f64>) -> Matrix3<f64> {
    let (sx, cx) = euler.x.sin_cos();
    let (sy, cy) = euler.y.sin_cos();
    let (sz, cz) = euler.z.sin_cos();
    Matrix3::new(
        cz * cy,
        cz * sy * sx - sz * cx,
        cz * sy * cx + sz * sx,
        sz * cy,
        sz * sy * sx + cz * cx,
        sz * sy * cx - cz * sx,
        -sy,
        cy * sx,
        cy * cx,
    )
}

/// Euler angles (thx, thy, thz) of a rotation matrix, with thy in [-90, 90] deg.
pub fn euler_from_rotation(r: &Matrix3<f64>) -> Vector3<f64> {
    let thy = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
    Vector3::new(r[(2, 1)].atan2(r[(2, 2)]), thy, r[(1, 0)].atan2(r[(0, 0)]))
}

/// E(th): omega = E th_dot, omega in {A}.
pub fn euler_rate_matrix(euler: &Vector3<f64>) -> Matrix3<f64> {
    let (sy, cy) = euler.y.sin_cos();
    let (sz, cz) = euler.z.sin_cos();
    Matrix3::new(cz * cy, -sz, 0.0, sz * cy, cz, 0.0, -sy, 0.0, 1.0)
}

/// dE/dt for Euler angles `euler` moving at `rates`.
pub fn euler_rate_matrix_dot(euler: &Vector3<f64>, rates: &Vector3<f64>) -> Matrix3<f64> {
    let (sy, cy) = euler.y.sin_cos();
    let (sz, cz) = euler.z.sin_cos();
    let (yd, zd) = (rates.y, rates.z);
    Matrix3::new(
        -cz * sy * yd - sz * cy * zd,
        -cz * zd,
        0.0,
        -sz * sy * yd + cz * cy * zd,
        -sz * zd,
        0.0,
        -cy * yd,
        0.0,
        0.0,
    )
}

/// Euler-angle rates th_dot = E^-1 omega, or an error at thy = +-90 deg.
pub fn euler_rates(
    euler: &Vector3<f64>,
    omega: &Vector3<f64>,
) -> Result<Vector3<f64>, KinematicsError> {
    let (sy, cy) = euler.y.sin_cos();
    let (sz, cz) = euler.z.sin_cos();
    if cy.abs() < EULER_SINGULAR_COS {
        return Err(KinematicsError::EulerSingular);
    }
    let thx_dot = (cz * omega.x + sz * omega.y) / cy;
    Ok(Vector3::new(
        thx_dot,
        -sz * omega.x + cz * omega.y,
        omega.z + sy * thx_dot,
    ))
}

/// The moment tau about P in {A} whose Euler-angle generalized force E^T tau is
/// `generalized_force` (N m): tau = E^-T Q, or an error at thy = +-90 deg.
pub fn moment_from_generalized_force(
    euler: &Vector3<f64>,
    generalized_force: &Vector3<f64>,
) -> Result<Vector3<f64>, KinematicsError> {
    // E^-1 = [[cz/cy, sz/cy, 0], [-sz, cz, 0], [sy cz/cy, sy sz/cy, 1]] (from
    // `euler_rates`); tau = (E^-1)^T Q.
    let (sy, cy) = euler.y.sin_cos();
    let (sz, cz) = euler.z.sin_cos();
    if cy.abs() < EULER_SINGULAR_COS {
        return Err(KinematicsError::EulerSingular);
    }
    let q = generalized_force;
    let tilt = (q.x + sy * q.z) / cy;
    Ok(Vector3::new(
        cz * tilt - sz * q.y,
        sz * tilt + cz * q.y,
        q.z,
    ))
}

/// Angular acceleration in {A}: omega_dot = E th_ddot + E_dot th_dot.
pub fn angular_acceleration(
    euler: &Vector3<f64>,
    rates: &Vector3<f64>,
    accelerations: &Vector3<f64>,
) -> Vector3<f64> {
    euler_rate_matrix(euler) * accelerations + euler_rate_matrix_dot(euler, rates) * rates
}

/// Euler-angle accelerations th_ddot = E^-1 (omega_dot - E_dot th_dot).
pub fn euler_accelerations(
    euler: &Vector3<f64>,
    rates: &Vector3<f64>,
    omega_dot: &Vector3<f64>,
) -> Result<Vector3<f64>, KinematicsError> {
    let rhs = omega_dot - euler_rate_matrix_dot(euler, rates) * rates;
    euler_rates(euler, &rhs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Rotation3, Unit};

    const TH: Vector3<f64> = Vector3::new(0.2, -0.15, 2.3);
    const RATES: Vector3<f64> = Vector3::new(0.4, -0.7, 1.1);

    #[test]
    fn generalized_force_maps_back_to_its_moment() {
        // Truth: the definition Q = E^T tau with E from `euler_rate_matrix`.
        let tau = Vector3::new(0.7, -1.3, 2.1);
        let q = euler_rate_matrix(&TH).tr_mul(&tau);
        let back = moment_from_generalized_force(&TH, &q).unwrap();
        assert!((back - tau).amax() < 1e-14, "{back} vs {tau}");
        let singular = Vector3::new(0.0, std::f64::consts::FRAC_PI_2, 0.0);
        assert_eq!(
            moment_from_generalized_force(&singular, &q),
            Err(KinematicsError::EulerSingular)
        );
    }

    #[test]
    fn rotation_is_rz_ry_rx() {
        // Independent truth: nalgebra's axis-angle rotations composed in the stated order.
        let axis = |v: Vector3<f64>, a: f64| Rotation3::from_axis_angle(&Unit::new_normalize(v), a);
        let expected =
            axis(Vector3::z(), TH.z) * axis(Vector3::y(), TH.y) * axis(Vector3::x(), TH.x);
        assert!((rotation(&TH) - expected.matrix()).amax() < 1e-15);
        assert!((euler_from_rotation(&rotation(&TH)) - TH).amax() < 1e-14);
    }

    #[test]
    fn e_matches_finite_differences_of_r() {
        // Truth: [omega]x = R_dot R^T, R_dot by central differences along th_dot.
        let dt = 1e-6;
        let r_dot = (rotation(&(TH + dt * RATES)) - rotation(&(TH - dt * RATES))) / (2.0 * dt);
        let w = r_dot * rotation(&TH).transpose();
        let omega_fd = Vector3::new(w[(2, 1)], w[(0, 2)], w[(1, 0)]);
        assert!((euler_rate_matrix(&TH) * RATES - omega_fd).amax() < 1e-9);
    }

    #[test]
    fn e_dot_matches_finite_differences_of_e() {
        let dt = 1e-6;
        let fd = (euler_rate_matrix(&(TH + dt * RATES)) - euler_rate_matrix(&(TH - dt * RATES)))
            / (2.0 * dt);
        assert!((euler_rate_matrix_dot(&TH, &RATES) - fd).amax() < 1e-9);
    }

    #[test]
    fn inverse_maps_round_trip() {
        let omega = euler_rate_matrix(&TH) * RATES;
        assert!((euler_rates(&TH, &omega).unwrap() - RATES).amax() < 1e-14);
        let acc = Vector3::new(-0.3, 0.8, 0.05);
        let omega_dot = angular_acceleration(&TH, &RATES, &acc);
        assert!((euler_accelerations(&TH, &RATES, &omega_dot).unwrap() - acc).amax() < 1e-14);
        let gimbal = Vector3::new(0.0, std::f64::consts::FRAC_PI_2, 0.0);
        assert_eq!(
            euler_rates(&gimbal, &omega),
            Err(KinematicsError::EulerSingular)
        );
    }
}
