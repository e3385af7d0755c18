//! The derivatives along the local motion of every output that `output_rates`
//! differentiates that way, evaluated together and kept for the point they belong to,
//! so that a request for several elements, both orders or a second request at the same
//! point costs one evaluation (one local motion and five evaluations of the outputs).
//!
//! The point is what the local motion and the outputs along it depend on: the
//! parameters, the state and the inputs (the plant is time invariant; the input
//! derivatives play no part: the inputs are held). A stored result is used only when
//! all three equal the current ones, the state and the inputs bit for bit (so that
//! -0.0 and 0.0 differ), the parameters by value: no setter, step, restored FMU state
//! or reset has to remember to invalidate it.

use nalgebra::SVector;
use robofmu::pss3::dynamics::{PlantInputs, PlantParams, PlantState};
use std::cell::RefCell;

/// How many outputs are differentiated along the motion: detJ, condJ, the two energies
/// and 7 vectors of 3.
pub const ALONG: usize = 4 + 7 * 3;

/// One value of each output differentiated along the motion (`output_rates::slot`).
pub type Along = SVector<f64, ALONG>;

/// What the derivatives along the motion depend on.
#[derive(Debug, Clone, Copy)]
pub struct Point {
    pub params: PlantParams,
    pub state: PlantState,
    pub inputs: PlantInputs,
}

impl Point {
    /// The state and the inputs, bit patterns in a fixed order.
    fn bits(&self) -> impl Iterator<Item = u64> + '_ {
        let (s, u) = (&self.state, &self.inputs);
        [s.euler, s.omega, u.forces, u.disturbance_torque]
            .into_iter()
            .chain([u.commanded_torque, u.generalized_force])
            .flat_map(|v| [v.x, v.y, v.z])
            .map(f64::to_bits)
    }

    /// Whether the derivatives at `self` are those at `other`.
    fn same(&self, other: &Point) -> bool {
        self.params == other.params && self.bits().eq(other.bits())
    }
}

/// The first and second derivatives along the motion, or why they cannot be evaluated.
type Derivatives = Result<[Along; 2], String>;

/// The last evaluation and its point (empty until the first request).
#[derive(Debug, Clone, Default)]
pub struct MotionCache(RefCell<Option<(Point, Derivatives)>>);

impl MotionCache {
    /// The derivatives at `point`: the stored ones if they belong to it, else
    /// `evaluate()`, stored.
    pub fn at(&self, point: Point, evaluate: impl FnOnce() -> Derivatives) -> Derivatives {
        if let Some((stored, derivatives)) = self.0.borrow().as_ref()
            && stored.same(&point)
        {
            return derivatives.clone();
        }
        let derivatives = evaluate();
        *self.0.borrow_mut() = Some((point, derivatives.clone()));
        derivatives
    }
}
