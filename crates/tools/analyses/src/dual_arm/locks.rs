//! Cam-lock configurations as equality constraints on the joints, and the closed chain
//! they leave: free joints `q`, the closure and task constraints
//! `g(q, t) = [f_R - f_L ; f_R - r(t)] = 0`, their Jacobian, and the completion of the
//! joints from the redundant ones by inverse kinematics.

use super::DualArmError;
use super::kinematics::{
    self, ARM_JOINTS, Elbow, JOINTS, LinkLengths, Side, hessian, jacobian, solve_two_joints,
};
use nalgebra::{DMatrix, DVector, Vector2, Vector4};
use std::f64::consts::FRAC_PI_2;

/// Number of constraints: closure (2) and task (2).
pub const CONSTRAINTS: usize = 4;

/// The four lock configurations of the paper.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lock {
    /// No lock.
    Unlocked,
    /// First links locked: theta_R1 = theta_L1 = pi/2.
    One,
    /// Third and fourth links locked: theta_R4 = theta_L4 = 0.
    Two,
    /// First and second links locked: theta_R1 = theta_L1 = pi/2, theta_R2 = theta_L2 = 0.
    Three,
}

impl Lock {
    /// All four, in the paper's order.
    pub const ALL: [Lock; 4] = [Lock::Unlocked, Lock::One, Lock::Two, Lock::Three];

    /// The equality constraints `theta_j = value` of the lock (joint index, value in rad).
    pub fn fixed_joints(self) -> Vec<(usize, f64)> {
        let (r1, r2, r4) = (0, 1, 3);
        let (l1, l2, l4) = (ARM_JOINTS, ARM_JOINTS + 1, ARM_JOINTS + 3);
        match self {
            Lock::Unlocked => vec![],
            Lock::One => vec![(r1, FRAC_PI_2), (l1, FRAC_PI_2)],
            Lock::Two => vec![(r4, 0.0), (l4, 0.0)],
            Lock::Three => vec![(r1, FRAC_PI_2), (l1, FRAC_PI_2), (r2, 0.0), (l2, 0.0)],
        }
    }

    /// The joints solved by inverse kinematics in each arm when not the last two free
    /// ones: under lock 2 the first and third, so that the redundant joint is the fold
    /// between the first two links and the inverse kinematics stays far from its
    /// singularities along path B (with theta_1 redundant it meets them).
    fn solved_joints(self) -> Option<[(usize, usize); 2]> {
        match self {
            Lock::Two => Some([(0, 2), (ARM_JOINTS, ARM_JOINTS + 2)]),
            _ => None,
        }
    }

    /// Short name as on the command line: none, 1, 2, 3.
    pub fn name(self) -> &'static str {
        match self {
            Lock::Unlocked => "none",
            Lock::One => "1",
            Lock::Two => "2",
            Lock::Three => "3",
        }
    }

    /// The initial guess of the redundant final joints (rad): the paper's values, except
    /// under lock 2, where the paper guesses one joint (0.3 rad for theta_R1) and we have
    /// two redundant joints, theta_R2 and theta_L2: we start them at 0.3 and -0.3.
    pub fn paper_guess(self) -> Vec<f64> {
        match self {
            Lock::Unlocked => vec![0.2, 0.4, 1.5, -0.09],
            Lock::One => vec![0.5, 0.02],
            Lock::Two => vec![0.3, -0.3],
            Lock::Three => vec![],
        }
    }
}

/// The closed chain left by a set of locks: which joints are free, which of them are
/// redundant (guessed by the shooting method) and which two per arm follow by inverse
/// kinematics.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    lengths: LinkLengths,
    fixed: [Option<f64>; JOINTS],
    free: Vec<usize>,
    redundant: Vec<usize>,
    solved: [(usize, usize); 2],
    elbows: [Elbow; 2],
}

impl Chain {
    /// The chain of one of the paper's lock configurations.
    pub fn for_lock(
        lengths: LinkLengths,
        lock: Lock,
        elbows: [Elbow; 2],
    ) -> Result<Self, DualArmError> {
        let chain = Self::new(lengths, &lock.fixed_joints(), elbows)?;
        match lock.solved_joints() {
            Some(solved) => chain.with_solved_joints(solved),
            None => Ok(chain),
        }
    }

    /// The same chain with other joints `(a, b)` (a < b, robot indices) of the right and
    /// left arm solved by inverse kinematics; all other free joints become redundant.
    pub fn with_solved_joints(self, solved: [(usize, usize); 2]) -> Result<Self, DualArmError> {
        for (&(a, b), side) in solved.iter().zip(Side::BOTH) {
            let valid = a < b
                && [a, b]
                    .iter()
                    .all(|j| self.free.contains(j) && Side::of_joint(*j) == side);
            if !valid {
                return Err(DualArmError::InvalidInput(format!(
                    "joints {a} and {b} are not two free joints of the {} arm",
                    side.name()
                )));
            }
        }
        let is_solved = |j: usize| solved.iter().any(|&(a, b)| j == a || j == b);
        let redundant = (0..self.free.len())
            .filter(|&i| !is_solved(self.free[i]))
            .collect();
        Ok(Self {
            solved,
            redundant,
            ..self
        })
    }

    /// The chain left by fixing `theta_j = value` for each `(j, value)`. The last two free
    /// joints of each arm are solved by inverse kinematics, the other free joints are the
    /// redundant ones. `elbows` are the branches of the right and left arm.
    pub fn new(
        lengths: LinkLengths,
        fixed_joints: &[(usize, f64)],
        elbows: [Elbow; 2],
    ) -> Result<Self, DualArmError> {
        let mut fixed = [None; JOINTS];
        for &(j, value) in fixed_joints {
            if j >= JOINTS || !value.is_finite() {
                return Err(DualArmError::InvalidInput(format!(
                    "lock theta[{j}] = {value} is not a joint and a finite angle"
                )));
            }
            fixed[j] = Some(value);
        }
        let free: Vec<usize> = (0..JOINTS).filter(|j| fixed[*j].is_none()).collect();
        let mut solved = [(0, 0); 2];
        for (slot, side) in solved.iter_mut().zip(Side::BOTH) {
            let arm: Vec<usize> = free
                .iter()
                .copied()
                .filter(|j| Side::of_joint(*j) == side)
                .collect();
            if arm.len() < 2 {
                return Err(DualArmError::InvalidInput(format!(
                    "the {} arm keeps {} free joints; it needs two to reach the path",
                    side.name(),
                    arm.len()
                )));
            }
            *slot = (arm[arm.len() - 2], arm[arm.len() - 1]);
        }
        let is_solved = |j: usize| solved.iter().any(|&(a, b)| j == a || j == b);
        let redundant = (0..free.len()).filter(|&i| !is_solved(free[i])).collect();
        Ok(Self {
            lengths,
            fixed,
            free,
            redundant,
            solved,
            elbows,
        })
    }

    /// Link lengths of the robot.
    pub fn lengths(&self) -> &LinkLengths {
        &self.lengths
    }

    /// Number of free joints (the length of `q`).
    pub fn free_count(&self) -> usize {
        self.free.len()
    }

    /// Degrees of freedom of the closed chain: free joints minus the two closure
    /// equations.
    pub fn mobility(&self) -> usize {
        self.free.len() - 2
    }

    /// Redundancy: free joints minus the four constraints (closure and task).
    pub fn redundancy(&self) -> usize {
        self.redundant.len()
    }

    /// Robot joint indices of the free joints, in the order of `q`.
    pub fn free_joints(&self) -> &[usize] {
        &self.free
    }

    /// The value of a locked joint, rad; `None` for a free joint.
    pub fn locked_value(&self, joint: usize) -> Option<f64> {
        self.fixed.get(joint).copied().flatten()
    }

    /// Smallest singular value of the constraint Jacobian's columns of the joints solved
    /// by inverse kinematics: how far `q` is from a fold of the inverse kinematics.
    pub fn inverse_kinematics_margin(&self, q: &DVector<f64>) -> f64 {
        let solved = self.jacobian(q).select_columns(&self.solved_positions());
        solved.singular_values().min()
    }

    /// Robot joint indices of the redundant joints, in the order of the guess `S`.
    pub fn redundant_joints(&self) -> Vec<usize> {
        self.redundant.iter().map(|&i| self.free[i]).collect()
    }

    /// All eight joint angles from the free ones.
    pub fn joints(&self, q: &DVector<f64>) -> [f64; JOINTS] {
        let mut theta = [0.0; JOINTS];
        for (j, value) in self.fixed.iter().enumerate() {
            theta[j] = value.unwrap_or(0.0);
        }
        for (i, &j) in self.free.iter().enumerate() {
            theta[j] = q[i];
        }
        theta
    }

    /// The joints of one arm.
    pub fn arm(&self, theta: &[f64; JOINTS], side: Side) -> [f64; ARM_JOINTS] {
        let o = side.offset();
        [theta[o], theta[o + 1], theta[o + 2], theta[o + 3]]
    }

    /// Tip position of one arm.
    pub fn tip(&self, q: &DVector<f64>, side: Side) -> Vector2<f64> {
        let theta = self.joints(q);
        kinematics::tip(self.lengths.of(side), &self.arm(&theta, side))
    }

    /// The constraints `[f_R - f_L ; f_R - r]`.
    pub fn constraint(&self, q: &DVector<f64>, r: Vector2<f64>) -> Vector4<f64> {
        let (right, left) = (self.tip(q, Side::Right), self.tip(q, Side::Left));
        let closure = right - left;
        let task = right - r;
        Vector4::new(closure.x, closure.y, task.x, task.y)
    }

    /// Rows 0-1 (closure) and 2-3 (task) of the constraint Jacobian column of an arm's
    /// joint whose tip derivative is `d`.
    fn column(side: Side, d: Vector2<f64>) -> Vector4<f64> {
        match side {
            Side::Right => Vector4::new(d.x, d.y, d.x, d.y),
            Side::Left => Vector4::new(-d.x, -d.y, 0.0, 0.0),
        }
    }

    /// Constraint Jacobian `A = dg/dq` (4 x n).
    pub fn jacobian(&self, q: &DVector<f64>) -> DMatrix<f64> {
        let theta = self.joints(q);
        let jacs = Side::BOTH.map(|s| jacobian(self.lengths.of(s), &self.arm(&theta, s)));
        let mut a = DMatrix::zeros(CONSTRAINTS, self.free.len());
        for (i, &j) in self.free.iter().enumerate() {
            let side = Side::of_joint(j);
            let jac = &jacs[side as usize];
            let d = jac.column(j - side.offset()).into_owned();
            a.set_column(i, &Self::column(side, d));
        }
        a
    }

    /// Derivatives `dA/dq_k` of the constraint Jacobian, one 4 x n matrix per free joint.
    pub fn jacobian_derivatives(&self, q: &DVector<f64>) -> Vec<DMatrix<f64>> {
        let theta = self.joints(q);
        let hess = Side::BOTH.map(|s| hessian(self.lengths.of(s), &self.arm(&theta, s)));
        let n = self.free.len();
        let mut out = vec![DMatrix::zeros(CONSTRAINTS, n); n];
        for (k, &jk) in self.free.iter().enumerate() {
            let side = Side::of_joint(jk);
            for (i, &ji) in self.free.iter().enumerate() {
                if Side::of_joint(ji) == side {
                    let o = side.offset();
                    let d = hess[side as usize][ji - o][jk - o];
                    out[k].set_column(i, &Self::column(side, d));
                }
            }
        }
        out
    }

    /// The redundant joints of `q`.
    pub fn redundant_values(&self, q: &DVector<f64>) -> Vec<f64> {
        self.redundant.iter().map(|&i| q[i]).collect()
    }

    /// The free joints with the redundant ones set to `s` and the others solved by
    /// inverse kinematics so that both tips reach `r`. Solved angles are taken nearest
    /// to their values in `reference` (or in (-pi, pi] without one).
    pub fn complete(
        &self,
        s: &[f64],
        r: Vector2<f64>,
        reference: Option<&DVector<f64>>,
        t: f64,
    ) -> Result<DVector<f64>, DualArmError> {
        if s.len() != self.redundant.len() || s.iter().any(|v| !v.is_finite()) {
            return Err(DualArmError::InvalidInput(format!(
                "{} finite redundant joint values needed, {} given",
                self.redundant.len(),
                s.len()
            )));
        }
        let mut q = match reference {
            Some(q) => q.clone(),
            None => DVector::zeros(self.free.len()),
        };
        for (&i, v) in self.redundant.iter().zip(s) {
            q[i] = *v;
        }
        let mut theta = self.joints(&q);
        for (side, (&(a, b), elbow)) in Side::BOTH.iter().zip(self.solved.iter().zip(self.elbows)) {
            let o = side.offset();
            let mut arm = self.arm(&theta, *side);
            solve_two_joints(self.lengths.of(*side), &mut arm, (a - o, b - o), r, elbow).ok_or(
                DualArmError::Unreachable {
                    t,
                    arm: side.name(),
                },
            )?;
            theta[a] = arm[a - o];
            theta[b] = arm[b - o];
        }
        Ok(DVector::from_iterator(
            self.free.len(),
            self.free.iter().map(|&j| theta[j]),
        ))
    }

    /// Positions in `q` of the solved joints.
    fn solved_positions(&self) -> Vec<usize> {
        (0..self.free.len())
            .filter(|i| !self.redundant.contains(i))
            .collect()
    }

    /// Tangent `dq/dS` of the completed joints to the redundant ones (n x redundancy),
    /// from `A dq = 0` with the redundant rows the identity; `None` at a singularity of
    /// the inverse kinematics.
    pub fn tangent(&self, q: &DVector<f64>) -> Option<DMatrix<f64>> {
        let a = self.jacobian(q);
        let solved = self.solved_positions();
        let a_solved = a.select_columns(&solved);
        let a_redundant = a.select_columns(&self.redundant);
        let lu = a_solved.lu();
        let dependent = lu.solve(&(-a_redundant))?;
        let mut t = DMatrix::zeros(self.free.len(), self.redundant.len());
        for (c, &i) in self.redundant.iter().enumerate() {
            t[(i, c)] = 1.0;
        }
        for (row, &i) in solved.iter().enumerate() {
            t.set_row(i, &dependent.row(row));
        }
        t.iter().all(|v| v.is_finite()).then_some(t)
    }

    /// Second derivatives `d^2 q / dS_i dS_j` of the completed joints, indexed `[i][j]`,
    /// from differentiating `A(q(S)) dq/dS_i = 0` once more.
    pub fn curvature(&self, q: &DVector<f64>, tangent: &DMatrix<f64>) -> Vec<Vec<DVector<f64>>> {
        let a = self.jacobian(q);
        let solved = self.solved_positions();
        let lu = a.select_columns(&solved).lu();
        let da = self.jacobian_derivatives(q);
        let m = self.redundant.len();
        let n = self.free.len();
        let mut out = vec![vec![DVector::zeros(n); m]; m];
        for j in 0..m {
            let mut da_j = DMatrix::zeros(CONSTRAINTS, n);
            for (k, dak) in da.iter().enumerate() {
                da_j += dak * tangent[(k, j)];
            }
            for (i, row) in out.iter_mut().enumerate() {
                let rhs = -(&da_j * tangent.column(i));
                if let Some(x) = lu.solve(&rhs) {
                    for (r, &p) in solved.iter().enumerate() {
                        row[j][p] = x[r];
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain(lock: Lock) -> Chain {
        let elbows = [Elbow::Negative, Elbow::Positive];
        Chain::for_lock(LinkLengths::default(), lock, elbows).unwrap()
    }

    #[test]
    fn redundancy_follows_from_the_constraints() {
        // 8 joints - locked - 2 closure - 2 task (counted by hand from the spec).
        let counts: Vec<(usize, usize)> = Lock::ALL
            .iter()
            .map(|l| {
                let c = chain(*l);
                (c.mobility(), c.redundancy())
            })
            .collect();
        assert_eq!(counts, vec![(6, 4), (4, 2), (4, 2), (2, 0)]);
    }

    #[test]
    fn completion_satisfies_the_constraints() {
        let r = Vector2::new(0.4, 0.6);
        for lock in Lock::ALL {
            let c = chain(lock);
            let q = c.complete(&lock.paper_guess(), r, None, 0.0).unwrap();
            assert!(c.constraint(&q, r).norm() < 1e-13, "lock {}", lock.name());
        }
    }

    #[test]
    fn jacobian_derivatives_match_central_differences() {
        let c = chain(Lock::Unlocked);
        let q = DVector::from_vec(vec![0.2, 0.4, 1.0, -0.8, 1.5, -0.1, -0.9, 1.2]);
        let da = c.jacobian_derivatives(&q);
        let h = 1e-6;
        for (k, dak) in da.iter().enumerate() {
            let mut up = q.clone();
            let mut down = q.clone();
            up[k] += h;
            down[k] -= h;
            let fd = (c.jacobian(&up) - c.jacobian(&down)) / (2.0 * h);
            assert!((fd - dak).norm() < 1e-8, "joint {k}");
        }
    }

    #[test]
    fn tangent_and_curvature_match_finite_differences_of_the_completion() {
        let c = chain(Lock::One);
        let r = Vector2::new(0.4, 0.6);
        let s = [0.5, 0.02];
        let q = c.complete(&s, r, None, 0.0).unwrap();
        let t = c.tangent(&q).unwrap();
        let curv = c.curvature(&q, &t);
        let h = 1e-5;
        for i in 0..2 {
            let (mut up, mut down) = (s, s);
            up[i] += h;
            down[i] -= h;
            let qu = c.complete(&up, r, Some(&q), 0.0).unwrap();
            let qd = c.complete(&down, r, Some(&q), 0.0).unwrap();
            let fd = (&qu - &qd) / (2.0 * h);
            assert!((fd - t.column(i)).norm() < 1e-8, "tangent {i}");
            let fd2 = (c.tangent(&qu).unwrap() - c.tangent(&qd).unwrap()) / (2.0 * h);
            for (j, c_ij) in curv[i].iter().enumerate() {
                assert!((fd2.column(j) - c_ij).norm() < 1e-6, "curvature {i} {j}");
            }
        }
    }
}
