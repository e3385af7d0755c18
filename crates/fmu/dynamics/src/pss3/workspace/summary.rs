//! Ranges of the angles and of the Jacobian measures over a set of workspace points.

use super::WorkspacePoint;

/// A closed interval [min, max].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    pub min: f64,
    pub max: f64,
}

impl Range {
    fn of(values: impl Iterator<Item = f64>) -> Option<Self> {
        values.fold(None, |acc: Option<Range>, v| {
            Some(match acc {
                None => Range { min: v, max: v },
                Some(r) => Range {
                    min: r.min.min(v),
                    max: r.max.max(v),
                },
            })
        })
    }
}

/// Ranges over a set of workspace points (angles in rad, det J in m^3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    pub thx: Range,
    pub thy: Range,
    pub thz: Range,
    pub tilt: Range,
    pub det_j: Range,
    pub cond_j: Range,
    pub min_leg_projection: f64,
}

/// The ranges over `points`, or `None` when there are none.
pub fn summarize(points: &[WorkspacePoint]) -> Option<Summary> {
    let range = |f: fn(&WorkspacePoint) -> f64| Range::of(points.iter().map(f));
    Some(Summary {
        thx: range(|p| p.euler.x)?,
        thy: range(|p| p.euler.y)?,
        thz: range(|p| p.euler.z)?,
        tilt: range(|p| p.tilt)?,
        det_j: range(|p| p.det_j)?,
        cond_j: range(|p| p.cond_j)?,
        min_leg_projection: range(|p| p.min_leg_projection)?.min,
    })
}
