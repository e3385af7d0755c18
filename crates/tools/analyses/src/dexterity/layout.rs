//! Readings of the paper's setup for the parallel manipulators: where the base frame
//! and the moving frame sit, and on which side the third vertex of each triangle lies.
//! The paper's text leaves these open; each choice is a documented reading, not a fit.

use nalgebra::{Matrix2, Matrix4x3, Vector2};

/// Side of the directed edge from the first to the second vertex on which the third
/// vertex of an equilateral triangle lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ApexSide {
    /// Counter-clockwise vertex order: the apex at +60 deg from the first edge.
    #[default]
    Left,
    /// Clockwise vertex order: the apex at -60 deg from the first edge.
    Right,
}

/// Where the origin of a frame lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Origin {
    /// At the first vertex (O1 for the base, B1 for the platform).
    #[default]
    FirstVertex,
    /// At the centroid of the triangle (the midpoint of O1O2 for the 2-RRR base).
    Centroid,
}

/// Direction of the base edge O1 -> O2 along the x axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BaseDirection {
    /// O2 on the positive x side of O1 (same order as B1 -> B2 at phi = 0).
    #[default]
    PlusX,
    /// O2 on the negative x side of O1: the base turned by 180 deg about its origin.
    MinusX,
}

/// One reading of the setup of a parallel manipulator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Reading {
    /// Origin of the base frame: O1, or the centroid of the base joints.
    pub base_origin: Origin,
    /// Direction of O1 -> O2 along the x axis.
    pub base_direction: BaseDirection,
    /// Side of O1O2 on which O3 lies (3-RRR only; the 2-RRR has two base joints).
    pub base_apex: ApexSide,
    /// Side of B1B2 on which B3 lies (the platform's vertex order).
    pub platform_apex: ApexSide,
    /// Origin of the moving frame whose position is `(x, y)`: B1 or the centroid.
    pub frame: Origin,
}

/// The three vertices of an equilateral triangle of side `side` with the first edge
/// along +x, expressed in a frame with origin `origin`.
pub fn triangle(side: f64, apex: ApexSide, origin: Origin) -> [Vector2<f64>; 3] {
    let height = side * 3f64.sqrt() / 2.0;
    let apex_y = match apex {
        ApexSide::Left => height,
        ApexSide::Right => -height,
    };
    let vertices = [
        Vector2::zeros(),
        Vector2::new(side, 0.0),
        Vector2::new(side / 2.0, apex_y),
    ];
    let shift = match origin {
        Origin::FirstVertex => Vector2::zeros(),
        Origin::Centroid => (vertices[0] + vertices[1] + vertices[2]) / 3.0,
    };
    vertices.map(|v| v - shift)
}

/// Base joints of a reading: the triangle of side `side` with its first edge along +x,
/// turned by 180 deg about the frame origin for `BaseDirection::MinusX`.
pub fn base_triangle(side: f64, reading: &Reading) -> [Vector2<f64>; 3] {
    let joints = triangle(side, reading.base_apex, reading.base_origin);
    match reading.base_direction {
        BaseDirection::PlusX => joints,
        BaseDirection::MinusX => joints.map(|v| -v),
    }
}

/// Homogenising matrix `[I, E R s'_a; I, E R s'_b]` (4x3): velocities of the two
/// platform points with moving-frame coordinates `a` and `b` from `(xdot, ydot, phidot)`.
pub fn two_point_matrix(phi: f64, a: Vector2<f64>, b: Vector2<f64>) -> Matrix4x3<f64> {
    let rot = rotation(phi);
    let (ea, eb) = (perp(rot * a), perp(rot * b));
    Matrix4x3::new(
        1.0, 0.0, ea.x, 0.0, 1.0, ea.y, 1.0, 0.0, eb.x, 0.0, 1.0, eb.y,
    )
}

/// Rotation matrix by `angle` (rad).
pub fn rotation(angle: f64) -> Matrix2<f64> {
    let (s, c) = angle.sin_cos();
    Matrix2::new(c, -s, s, c)
}

/// `E v`: `v` rotated by 90 deg.
pub fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_are_equilateral_with_requested_orientation() {
        for apex in [ApexSide::Left, ApexSide::Right] {
            for origin in [Origin::FirstVertex, Origin::Centroid] {
                let [a, b, c] = triangle(0.3, apex, origin);
                for d in [(a - b).norm(), (b - c).norm(), (c - a).norm()] {
                    assert!((d - 0.3).abs() < 1e-15);
                }
                // Sign of the cross product (b - a) x (c - a) is the vertex order.
                let cross = (b - a).perp(&(c - a));
                assert_eq!(cross > 0.0, apex == ApexSide::Left);
            }
        }
        let [a, b, c] = triangle(0.3, ApexSide::Left, Origin::Centroid);
        assert!((a + b + c).norm() < 1e-15);
    }
}
