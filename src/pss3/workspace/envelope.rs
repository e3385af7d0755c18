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
