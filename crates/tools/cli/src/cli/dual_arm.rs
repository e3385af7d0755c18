//! `robofmu dual-arm`: optimal joint paths of the dual-arm cam-lock robot.

mod extremals;
mod output;

use super::report::usage;
use super::{CliError, io_at};
use clap::{Args, Subcommand, ValueEnum};
use robofmu_analyses::dual_arm::direct::{DirectOptions, DirectSolution, solve_direct};
use robofmu_analyses::dual_arm::kinematics::{Elbow, LinkLengths, joint_name};
use robofmu_analyses::dual_arm::locks::{Chain, Lock};
use robofmu_analyses::dual_arm::multistart::best_path;
use robofmu_analyses::dual_arm::paths::{PaperPath, Path, SampledPath};
use robofmu_analyses::dual_arm::shooting::{PmpSolution, Shooting, ShootingOptions};
use robofmu_analyses::dual_arm::trajectory::Trajectory;
use std::path::PathBuf;
use std::time::Instant;

/// Optimal joint paths of the dual-arm cam-lock robot (Pontryagin + shooting, or direct).
#[derive(Args)]
pub struct DualArmArgs {
    #[command(subcommand)]
    command: DualArmCommand,
}

#[derive(Subcommand)]
enum DualArmCommand {
    /// Solve one lock configuration on one path; the last line gives PI.
    Solve(SolveArgs),
    /// Solve with both methods and compare their PI and joint paths.
    Compare(ProblemArgs),
    /// List every extremal the multi-start search finds, each checked for a local
    /// minimum, as a Markdown table (all configurations unless --lock and --path).
    Extremals(extremals::ExtremalsArgs),
}

/// The problem: lock, path, initial guess, grid.
#[derive(Args)]
struct ProblemArgs {
    /// Lock configuration: none, 1, 2 or 3.
    #[arg(long, value_parser = parse_lock)]
    lock: Lock,
    /// End-effector path: A, B (the paper's) or a CSV file of t, x, y (s, m).
    #[arg(long)]
    path: String,
    /// Redundant joints at tf, rad, comma-separated, each -100 to 100 (default: the
    /// paper's guess).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = crate::cli::bounds::joint_angle)]
    guess: Option<Vec<f64>>,
    /// Intervals of the output grid (and of the direct method's grid), 10 to 1000.
    #[arg(long, default_value_t = 200, allow_hyphen_values = true,
          value_parser = crate::cli::bounds::count::<10, 1000>)]
    intervals: usize,
    /// Elbow branches of the right and left arm's inverse kinematics at tf (`negative`:
    /// clockwise bend, `positive`: counter-clockwise); the default makes the arms mirror
    /// images. Other pairs put both elbows on one side (docs/dual-arm.md).
    #[arg(long, value_delimiter = ',', value_parser = parse_elbow,
          default_value = "negative,positive")]
    elbows: Vec<Elbow>,
}

fn parse_elbow(text: &str) -> Result<Elbow, String> {
    match text.to_ascii_lowercase().as_str() {
        "negative" => Ok(Elbow::Negative),
        "positive" => Ok(Elbow::Positive),
        _ => Err(format!("unknown elbow {text:?}: use negative or positive")),
    }
}

#[derive(Args)]
struct SolveArgs {
    #[command(flatten)]
    problem: ProblemArgs,
    /// Solution method.
    #[arg(long, value_enum, default_value_t = Method::Best)]
    method: Method,
    /// Directory for CSV tables and PNG figures.
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Method {
    /// The cheapest extremal of the shooting method from several starts (the guess, the
    /// direct method's final joints, a spread about both), checked to be a local minimum.
    Best,
    /// Pontryagin's principle, one shooting run from the guess: an extremal, not
    /// necessarily the minimum.
    Pmp,
    /// Direct minimisation on a time grid.
    Direct,
}

fn parse_lock(text: &str) -> Result<Lock, String> {
    Lock::ALL
        .into_iter()
        .find(|l| l.name().eq_ignore_ascii_case(text))
        .ok_or_else(|| format!("unknown lock {text:?}: use none, 1, 2 or 3"))
}

/// Runs a `dual-arm` subcommand.
pub fn run(args: DualArmArgs) -> Result<(), CliError> {
    match args.command {
        DualArmCommand::Solve(a) => solve(a),
        DualArmCommand::Compare(p) => compare(p),
        DualArmCommand::Extremals(a) => extremals::run(&a),
    }
}

/// The chain, path and initial guess of a run.
type Problem = (Chain, Box<dyn Path>, Vec<f64>);

/// The paper's path `A` or `B`, or a path read from a CSV file.
fn read_path(name: &str) -> Result<Box<dyn Path>, CliError> {
    Ok(match name {
        "A" | "a" => Box::new(PaperPath::A),
        "B" | "b" => Box::new(PaperPath::B),
        file => {
            let text = std::fs::read_to_string(file).map_err(|e| {
                usage(format!(
                    "--path {file}: cannot read it ({e}); give A, B or a CSV file of t, x, y"
                ))
            })?;
            let path =
                SampledPath::from_csv(&text).map_err(|e| usage(format!("--path {file}: {e}")))?;
            Box::new(path)
        }
    })
}

/// The mirror-image elbow branches: right arm clockwise, left counter-clockwise.
const MIRROR_ELBOWS: [Elbow; 2] = [Elbow::Negative, Elbow::Positive];

/// The chain of a lock with the chosen lengths and the elbow branches of both arms.
fn chain_of(lock: Lock, elbows: [Elbow; 2]) -> Result<Chain, CliError> {
    Ok(Chain::for_lock(LinkLengths::default(), lock, elbows)?)
}

/// The chain, path and guess of the problem, with a header printed.
fn setup(p: &ProblemArgs) -> Result<Problem, CliError> {
    let path = read_path(&p.path)?;
    let elbows: [Elbow; 2] = p.elbows.as_slice().try_into().map_err(|_| {
        usage(format!(
            "--elbows needs two values (right, left), {} given",
            p.elbows.len()
        ))
    })?;
    let chain = chain_of(p.lock, elbows)?;
    let guess = p.guess.clone().unwrap_or_else(|| p.lock.paper_guess());
    if guess.len() != chain.redundancy() {
        return Err(usage(format!(
            "--guess needs {} values (the redundant joints at tf, rad) for lock {}, {} given",
            chain.redundancy(),
            p.lock.name(),
            guess.len()
        )));
    }
    let redundant: Vec<String> = chain
        .redundant_joints()
        .iter()
        .map(|&j| joint_name(j))
        .collect();
    outln!(
        "lock {}: {} free joints, mobility {}, redundancy {} ({})",
        p.lock.name(),
        chain.free_count(),
        chain.mobility(),
        chain.redundancy(),
        redundant.join(", ")
    );
    outln!(
        "link lengths (both arms) {:?} m; path on [{}, {}] s; guess {:?} rad",
        robofmu_analyses::dual_arm::kinematics::CHOSEN_LENGTHS,
        path.start(),
        path.end(),
        guess
    );
    Ok((chain, path, guess))
}

fn shooting_options(intervals: usize) -> ShootingOptions {
    ShootingOptions {
        intervals,
        ..ShootingOptions::default()
    }
}

fn direct_options(intervals: usize) -> DirectOptions {
    DirectOptions {
        intervals,
        ..DirectOptions::default()
    }
}

/// Prints the checks of a solution: path following and start condition.
fn print_checks(trajectory: &Trajectory, chain: &Chain, path: &dyn Path) {
    outln!(
        "max distance of the tips from the path {:.2e} m; at t0 {:.2e} m",
        trajectory.tracking_error(chain.lengths(), path),
        trajectory.start_error(chain.lengths(), path)
    );
}

fn solve(args: SolveArgs) -> Result<(), CliError> {
    let (chain, path, guess) = setup(&args.problem)?;
    let intervals = args.problem.intervals;
    let started = Instant::now();
    let (trajectory, iterations, residual, history) = match args.method {
        Method::Best => {
            let options = extremals::options(intervals);
            let best = best_path(&chain, path.as_ref(), &guess, options)?;
            extremals::print_search(&chain, &best, started.elapsed().as_secs_f64());
            let s = best.best().clone();
            (s.trajectory, s.iterations, s.residual, Some(s.history))
        }
        Method::Pmp => {
            outln!(
                "one shooting run from the guess: an extremal of Pontryagin's conditions, \
                 not necessarily the minimum (the default --method best searches several starts)"
            );
            let s =
                Shooting::new(&chain, path.as_ref(), shooting_options(intervals)).solve(&guess)?;
            outln!(
                "shooting: {} Newton iterations in {:.1} ms; redundant joints at tf {:?} rad",
                s.iterations,
                started.elapsed().as_secs_f64() * 1e3,
                s.redundant_final
            );
            for (i, step) in s.history.iter().enumerate() {
                outln!("  iteration {i}: ||e|| = {:.3e}", step.residual);
            }
            (s.trajectory, s.iterations, s.residual, Some(s.history))
        }
        Method::Direct => {
            let d = solve_direct(&chain, path.as_ref(), &guess, direct_options(intervals))?;
            outln!(
                "direct method on {intervals} intervals: {} Newton steps in {:.1} ms",
                d.iterations,
                started.elapsed().as_secs_f64() * 1e3
            );
            (d.trajectory, d.iterations, d.last_step, None)
        }
    };
    print_checks(&trajectory, &chain, path.as_ref());
    if let Some(dir) = &args.out {
        write_outputs(dir, &chain, path.as_ref(), &trajectory, history.as_deref())?;
        outln!("wrote CSV and PNG files to {}", dir.display());
    }
    outln!(
        "PI = {:.6} rad^2/s  iterations = {iterations}  residual = {residual:.1e}",
        trajectory.pi()
    );
    Ok(())
}

fn write_outputs(
    dir: &std::path::Path,
    chain: &Chain,
    path: &dyn Path,
    trajectory: &Trajectory,
    history: Option<&[robofmu_analyses::dual_arm::shooting::NewtonStep]>,
) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(io_at(dir))?;
    let file = dir.join("trajectory.csv");
    std::fs::write(&file, output::trajectory_csv(trajectory, path)).map_err(io_at(&file))?;
    output::joints_png(
        &dir.join("joints.png"),
        trajectory,
        chain.free_joints(),
        "Optimal joint paths",
    )?;
    output::cost_png(&dir.join("pi.png"), trajectory, "Cost PI(t)")?;
    output::snapshots_png(
        &dir.join("snapshots.png"),
        trajectory,
        chain.lengths(),
        path,
        6,
        "Arms along the path (right red, left blue, later darker)",
    )?;
    if let Some(history) = history {
        let redundant = chain.redundant_joints();
        let file = dir.join("newton.csv");
        std::fs::write(&file, output::newton_csv(history, &redundant)).map_err(io_at(&file))?;
        output::newton_png(&dir.join("newton.png"), history, "Newton residuals")?;
    }
    Ok(())
}

fn compare(p: ProblemArgs) -> Result<(), CliError> {
    let (chain, path, guess) = setup(&p)?;
    let path = path.as_ref();
    let n = p.intervals;
    let shooting = Shooting::new(&chain, path, shooting_options(n));
    let report = |label: &str, s: &PmpSolution| {
        outln!(
            "{label}: PI = {:.8} rad^2/s, {} iterations, ||e|| = {:.1e}, S_f = {:?}",
            s.pi(),
            s.iterations,
            s.residual,
            s.redundant_final
        );
    };
    match shooting.solve(&guess) {
        Ok(s) => report("shooting from the guess", &s),
        Err(e) => outln!("shooting from the guess failed: {e}"),
    }
    let coarse = solve_direct(&chain, path, &guess, direct_options(n))?;
    let fine = solve_direct(&chain, path, &guess, direct_options(2 * n))?;
    let extrapolated = (4.0 * fine.pi() - coarse.pi()) / 3.0;
    let print_direct = |k: usize, d: &DirectSolution| {
        outln!(
            "direct, {k} intervals: PI = {:.8} rad^2/s, {} Newton steps",
            d.pi(),
            d.iterations
        );
    };
    print_direct(n, &coarse);
    print_direct(2 * n, &fine);
    outln!("direct, Richardson extrapolation: PI = {extrapolated:.8} rad^2/s");
    // The shooting started from the direct method's redundant joints at tf.
    let last = fine.trajectory.joints.last().ok_or("empty direct path")?;
    let final_guess: Vec<f64> = chain.redundant_joints().iter().map(|&j| last[j]).collect();
    let pmp = shooting.solve(&final_guess)?;
    report("shooting from the direct optimum", &pmp);
    print_checks(&pmp.trajectory, &chain, path);
    let joint_gap = pmp
        .trajectory
        .max_joint_difference(&coarse.trajectory)
        .ok_or("the two methods' grids differ")?;
    outln!(
        "PI pmp = {:.6}  direct = {:.6}  relative difference = {:.1e}  (extrapolated {:.1e})  max joint difference = {joint_gap:.1e} rad",
        pmp.pi(),
        coarse.pi(),
        (coarse.pi() - pmp.pi()) / pmp.pi(),
        (extrapolated - pmp.pi()) / pmp.pi()
    );
    Ok(())
}
