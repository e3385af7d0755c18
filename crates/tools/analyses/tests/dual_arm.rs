//! Verification of the dual-arm optimal joint paths (issue 6): the shooting method's
//! tolerances, agreement with the independent direct method, lock 3 by inverse
//! kinematics alone, the workspace statements of the spec, and the CLI.

use nalgebra::Vector2;
use robofmu_analyses::dual_arm::DualArmError;
use robofmu_analyses::dual_arm::direct::{DirectOptions, solve_direct};
use robofmu_analyses::dual_arm::kinematics::{CHOSEN_LENGTHS, Elbow, LinkLengths};
use robofmu_analyses::dual_arm::locks::{Chain, Lock};
use robofmu_analyses::dual_arm::paths::{FunctionPath, PaperPath, Path, SampledPath};
use robofmu_analyses::dual_arm::shooting::{PmpSolution, Shooting, ShootingOptions};

const ELBOWS: [Elbow; 2] = [Elbow::Negative, Elbow::Positive];

fn chain(lock: Lock) -> Chain {
    Chain::for_lock(LinkLengths::default(), lock, ELBOWS).unwrap()
}

/// The paper's pairing: path A unlocked, path B under the locks.
fn paper_path(lock: Lock) -> PaperPath {
    if lock == Lock::Unlocked {
        PaperPath::A
    } else {
        PaperPath::B
    }
}

fn shoot(chain: &Chain, path: &dyn Path, guess: &[f64], intervals: usize) -> PmpSolution {
    let options = ShootingOptions {
        intervals,
        ..ShootingOptions::default()
    };
    Shooting::new(chain, path, options).solve(guess).unwrap()
}

#[test]
fn shooting_meets_the_path_and_start_conditions_to_1e_8() {
    // Truth: the spec's boundary conditions; the path is r(t) in closed form.
    for lock in Lock::ALL {
        let (c, path) = (chain(lock), paper_path(lock));
        let s = shoot(&c, &path, &lock.paper_guess(), 50);
        assert!(
            s.residual < 1e-10,
            "lock {}: ||e|| {}",
            lock.name(),
            s.residual
        );
        let tracking = s.trajectory.tracking_error(c.lengths(), &path);
        let start = s.trajectory.start_error(c.lengths(), &path);
        assert!(tracking < 1e-8 && start < 1e-8, "lock {}", lock.name());
        assert!(
            s.iterations <= 8,
            "lock {}: {} iterations",
            lock.name(),
            s.iterations
        );
    }
}

#[test]
fn direct_method_agrees_with_the_shooting_method_for_every_redundant_lock() {
    // Truth: an independent discretisation (no costate, no ODE) whose cost converges as
    // O(dt^2); its Richardson extrapolation from 100 and 200 intervals must match the
    // shooting method's PI far inside the required 0.5 %.
    for lock in [Lock::Unlocked, Lock::One, Lock::Two] {
        let (c, path) = (chain(lock), paper_path(lock));
        let guess = lock.paper_guess();
        let options = |intervals| DirectOptions {
            intervals,
            ..DirectOptions::default()
        };
        let coarse = solve_direct(&c, &path, &guess, options(100)).unwrap();
        let fine = solve_direct(&c, &path, &guess, options(200)).unwrap();
        let last = fine.trajectory.joints.last().unwrap();
        let final_joints: Vec<f64> = c.redundant_joints().iter().map(|&j| last[j]).collect();
        let pmp = shoot(&c, &path, &final_joints, 100);
        let relative = (coarse.pi() - pmp.pi()).abs() / pmp.pi();
        assert!(relative < 5e-3 * 0.1, "lock {}: {relative}", lock.name());
        let extrapolated = (4.0 * fine.pi() - coarse.pi()) / 3.0;
        assert!((extrapolated - pmp.pi()).abs() / pmp.pi() < 1e-6);
        let gap = pmp
            .trajectory
            .max_joint_difference(&coarse.trajectory)
            .unwrap();
        assert!(
            gap < 1e-4,
            "lock {}: joints differ by {gap} rad",
            lock.name()
        );
    }
}

#[test]
fn the_paper_guess_leads_to_a_costlier_unlocked_extremal() {
    // Truth: Pontryagin's conditions are necessary only. From the paper's guess the
    // shooting converges (||e|| < 1e-10) to an extremal that costs more than the
    // minimum found by the direct method from the same guess.
    let (c, path) = (chain(Lock::Unlocked), PaperPath::A);
    let from_paper = shoot(&c, &path, &Lock::Unlocked.paper_guess(), 10);
    let options = DirectOptions {
        intervals: 100,
        ..DirectOptions::default()
    };
    let direct = solve_direct(&c, &path, &Lock::Unlocked.paper_guess(), options).unwrap();
    assert!(from_paper.residual < 1e-10);
    assert!(direct.pi() < 0.9 * from_paper.pi());
}

#[test]
fn lock_3_cost_is_the_integral_along_the_inverse_kinematics_path() {
    // Truth: with no redundancy the path is q(t) = IK(r(t)); integrate |dq/dt|^2 by
    // Simpson's rule, dq/dt by central differences of the inverse kinematics.
    let (c, path) = (chain(Lock::Three), PaperPath::B);
    let pmp = shoot(&c, &path, &[], 10);
    let ik = |t: f64, reference: &nalgebra::DVector<f64>| {
        c.complete(&[], path.position(t), Some(reference), t)
            .unwrap()
    };
    let q0 = c.complete(&[], path.position(0.0), None, 0.0).unwrap();
    let (n, h) = (400, 1e-5);
    let rate = |t: f64| {
        let (up, down) = (ik((t + h).min(1.0), &q0), ik((t - h).max(0.0), &q0));
        let span = (t + h).min(1.0) - (t - h).max(0.0);
        ((up - down) / span).norm_squared()
    };
    let dt = 1.0 / n as f64;
    let simpson: f64 = (0..=n)
        .map(|k| {
            let w = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * rate(k as f64 * dt)
        })
        .sum::<f64>()
        * dt
        / 3.0;
    assert!(
        (simpson - pmp.pi()).abs() / pmp.pi() < 1e-7,
        "{simpson} vs {}",
        pmp.pi()
    );
}

#[test]
fn lock_3_costs_at_least_lock_1() {
    // Truth: lock 3 adds theta_R2 = theta_L2 = 0 to lock 1, a restriction of the same
    // problem on the same path, so its optimum cannot be cheaper.
    let one = shoot(
        &chain(Lock::One),
        &PaperPath::B,
        &Lock::One.paper_guess(),
        10,
    );
    let three = shoot(&chain(Lock::Three), &PaperPath::B, &[], 10);
    assert!(three.pi() > one.pi());
}

#[test]
fn chosen_lengths_satisfy_the_workspace_statements() {
    // Truth: the reach of a chain about its first moving pivot is an annulus; path A must
    // leave it under locks 1 and 3 and path B must stay in it. Under lock 2 the annulus
    // is centred at the base and path A's radii lie inside path B's, so path A stays
    // reachable whatever the lengths (documented in docs/dual-arm.md).
    let [l1, l2, l3, l4] = CHOSEN_LENGTHS;
    let samples = |p: PaperPath| (0..=100).map(move |k| p.position(k as f64 / 100.0));
    let inside = |centre: Vector2<f64>, inner: f64, outer: f64, r: Vector2<f64>| {
        let d = (r - centre).norm();
        d > inner && d < outer
    };
    let lock1 = |r| inside(Vector2::new(0.0, l1), 0.0, l2 + l3 + l4, r);
    let lock3 = |r| inside(Vector2::new(0.0, l1 + l2), (l3 - l4).abs(), l3 + l4, r);
    let lock2 = |r| {
        inside(
            Vector2::zeros(),
            (l3 + l4) - (l1 + l2),
            l1 + l2 + l3 + l4,
            r,
        )
    };
    let unlocked = |r: Vector2<f64>| r.norm() < l1 + l2 + l3 + l4;
    assert!(samples(PaperPath::A).all(unlocked));
    assert!(!samples(PaperPath::A).all(lock1) && !samples(PaperPath::A).all(lock3));
    assert!(samples(PaperPath::A).all(lock2));
    assert!(samples(PaperPath::B).all(|r| lock1(r) && lock2(r) && lock3(r)));
    // And the solver agrees: lock 3 cannot start path A.
    let e = chain(Lock::Three).complete(&[], PaperPath::A.position(0.0), None, 0.0);
    assert!(matches!(e, Err(DualArmError::Unreachable { .. })));
}

#[test]
fn function_and_sampled_paths_give_the_analytic_cost() {
    // Truth: the analytic path B. A function path with the same formulas must give the
    // same PI; a CSV of 201 samples, spline-interpolated, nearly the same.
    let c = chain(Lock::One);
    let guess = Lock::One.paper_guess();
    let exact = shoot(&c, &PaperPath::B, &guess, 10).pi();
    let function = FunctionPath::new(
        0.0,
        1.0,
        |t| PaperPath::B.position(t),
        |t| PaperPath::B.velocity(t),
    )
    .unwrap();
    assert!((shoot(&c, &function, &guess, 10).pi() - exact).abs() < 1e-12);
    let mut csv = String::from("t,x,y\n");
    for k in 0..=200 {
        let t = k as f64 / 200.0;
        let r = PaperPath::B.position(t);
        csv.push_str(&format!("{t},{},{}\n", r.x, r.y));
    }
    let sampled = SampledPath::from_csv(&csv).unwrap();
    assert!((shoot(&c, &sampled, &guess, 10).pi() - exact).abs() / exact < 1e-3);
}

#[test]
fn failures_are_reported_not_returned_as_answers() {
    let (c, path) = (chain(Lock::One), PaperPath::B);
    let options = ShootingOptions {
        max_iterations: 1,
        ..ShootingOptions::default()
    };
    let e = Shooting::new(&c, &path, options)
        .solve(&[0.5, 0.02])
        .unwrap_err();
    assert!(
        matches!(e, DualArmError::NotConverged { iterations: 1, .. }),
        "{e}"
    );
    assert!(
        Shooting::new(&c, &path, ShootingOptions::default())
            .solve(&[0.5])
            .is_err()
    );
}
