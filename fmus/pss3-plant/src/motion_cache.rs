//! The derivatives along the local motion of every output that `output_rates`
//! differentiates that way, evaluated together and kept for the point they belong to,
//! so that a request for several elements, both orders or a second request at the same
//! point costs one evaluation (one local motion and five evaluations of the outputs).
//! gravityCompensation, the slope a master asks every step, has its own cheaper pass
//! along the same local motion (five evaluations of the gravity torque alone), and so
//! has thetaDot (five evaluations of the Euler-angle rates alone).
//!
//! The point is what the local motion and the outputs along it depend on: the
//! parameters, the state and the inputs (the plant is time invariant; the input
//! derivatives play no part: the inputs are held). A stored result is used only when
//! all three equal the current ones, the state and the inputs bit for bit (so that
//! -0.0 and 0.0 differ), the parameters with `==` (a parameter that goes from 0.0 to
//! -0.0 and nothing else keeps the stored result; a NaN never matches): no setter,
//! step, restored FMU state or reset has to remember to invalidate it.

use nalgebra::{SVector, Vector3};
use robofmu_dynamics::pss3::dynamics::{LocalMotion, PlantInputs, PlantParams, PlantState};
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

/// The first and second derivatives of `V` along the motion, or why they cannot be
/// evaluated.
pub type Derivatives<V> = Result<[V; 2], String>;

/// What is kept for one point: its local motion and what was differentiated along it.
#[derive(Debug, Clone)]
pub struct Entry {
    pub motion: Result<LocalMotion, String>,
    /// Every output in `Along`, once one of them was asked for.
    pub all: Option<Derivatives<Along>>,
    /// gravityCompensation alone (a function of the Euler angles only, far cheaper than
    /// every output), once it was asked for.
    pub gravity: Option<Derivatives<Vector3<f64>>>,
    /// thetaDot alone (the Euler-angle rates, a function of the state without the
    /// dynamics: order 2 is what a master passing input derivatives of order 2 asks
    /// every step), once it was asked for.
    pub theta_dot: Option<Derivatives<Vector3<f64>>>,
}

/// The entry of the last point asked for (empty until the first request).
#[derive(Debug, Clone, Default)]
pub struct MotionCache(RefCell<Option<(Point, Entry)>>);

impl MotionCache {
    /// `read` of the entry of `point`: the stored one if it belongs to `point`, else a
    /// new one with the local motion `motion(&point)`, stored.
    pub fn with<R>(
        &self,
        point: Point,
        motion: impl FnOnce(&Point) -> Result<LocalMotion, String>,
        read: impl FnOnce(&mut Entry) -> R,
    ) -> R {
        let mut stored = self.0.borrow_mut();
        match stored.as_mut() {
            Some((p, entry)) if p.same(&point) => read(entry),
            _ => {
                let entry = Entry {
                    motion: motion(&point),
                    all: None,
                    gravity: None,
                    theta_dot: None,
                };
                read(&mut stored.insert((point, entry)).1)
            }
        }
    }
}
