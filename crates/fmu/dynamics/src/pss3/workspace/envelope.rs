//! The tilt-versus-roll envelope: the largest reachable tilt per band of roll angle.

use super::WorkspacePoint;

/// One band (or one value) of roll angles with the largest tilt reached there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnvelopeBin {
    /// Centre of the band (or the roll value), rad.
    pub roll: f64,
    /// Largest tilt of the points, rad.
    pub max_tilt: f64,
    /// Number of points in the band.
    pub count: usize,
}

/// Bands of width `width` (rad) from the smallest roll up; empty bands are left out.
pub fn tilt_envelope(points: &[WorkspacePoint], width: f64) -> Vec<EnvelopeBin> {
    let Some(lo) = points.iter().map(|p| p.euler.z).reduce(f64::min) else {
        return Vec::new();
    };
    if !(width.is_finite() && width > 0.0) {
        return Vec::new();
    }
    let mut bins: Vec<EnvelopeBin> = Vec::new();
    for p in points {
        let k = ((p.euler.z - lo) / width).floor() as usize;
        if bins.len() <= k {
            bins.resize_with(k + 1, || EnvelopeBin {
                roll: 0.0,
                max_tilt: 0.0,
                count: 0,
            });
        }
        let bin = &mut bins[k];
        bin.roll = lo + (k as f64 + 0.5) * width;
        bin.max_tilt = bin.max_tilt.max(p.tilt);
        bin.count += 1;
    }
    bins.into_iter().filter(|b| b.count > 0).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn point(roll: f64, tilt: f64) -> WorkspacePoint {
        WorkspacePoint {
            l: Vector3::zeros(),
            euler: Vector3::new(0.0, 0.0, roll),
            tilt,
            det_j: 1.0,
            cond_j: 1.0,
            min_leg_projection: 1.0,
        }
    }

    #[test]
    fn bands_keep_the_largest_tilt() {
        // Truth: by hand, bands [1, 2) and [2, 3) of width 1 with an empty band [3, 4).
        let points = [
            point(1.0, 0.1),
            point(1.5, 0.3),
            point(2.2, 0.2),
            point(4.5, 0.4),
        ];
        let bins = tilt_envelope(&points, 1.0);
        let summary: Vec<_> = bins.iter().map(|b| (b.roll, b.max_tilt, b.count)).collect();
        assert_eq!(summary, vec![(1.5, 0.3, 2), (2.5, 0.2, 1), (4.5, 0.4, 1)]);
        assert!(tilt_envelope(&points, 0.0).is_empty());
    }
}
