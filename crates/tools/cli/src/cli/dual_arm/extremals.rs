//! The multi-start search on the terminal: the extremals found by `dual-arm solve`
//! (default method) and the `dual-arm extremals` table of every configuration.

use super::{MIRROR_ELBOWS, chain_of, parse_lock, read_path};
use crate::cli::CliError;
use clap::Args;
use robofmu_analyses::dual_arm::locks::{Chain, Lock};
use robofmu_analyses::dual_arm::multistart::{
    BestPath, MultiStart, MultiStartOptions, multi_start,
};
use robofmu_analyses::dual_arm::optimality::{SecondOrder, check_local_minimum};
use robofmu_analyses::dual_arm::paths::Path;
use robofmu_analyses::dual_arm::shooting::ShootingOptions;
use std::time::Instant;

/// The multi-start settings with the output grid of `intervals`.
pub fn options(intervals: usize) -> MultiStartOptions {
    let defaults = MultiStartOptions::default();
    MultiStartOptions {
        shooting: ShootingOptions {
            intervals,
            ..defaults.shooting
        },
        ..defaults
    }
}

/// Prints the starts, the distinct extremals and the check of the returned one.
pub fn print_search(chain: &Chain, best: &BestPath, seconds: f64) {
    let search = &best.search;
    outln!(
        "multi-start shooting: {} starts, {} distinct extremals, in {:.0} ms",
        search.starts.len(),
        search.extremals.len(),
        seconds * 1e3
    );
    for (start, outcome) in &search.starts {
        match outcome {
            Ok(k) => outln!("  from {}: extremal {}", start.label, k + 1),
            Err(e) => outln!("  from {}: failed ({e})", start.label),
        }
    }
    for (k, e) in search.extremals.iter().enumerate() {
        outln!(
            "  extremal {}: PI = {:.6} rad^2/s  ||e|| = {:.1e}  redundant joints at tf {:?} rad",
            k + 1,
            e.solution.pi(),
            e.solution.residual,
            e.solution.redundant_final
        );
    }
    outln!(
        "returned: extremal 1 (lowest PI) of {} found; redundancy {}",
        search.extremals.len(),
        chain.redundancy()
    );
    match &best.check {
        Ok(check) => {
            let verdict = if check.is_local_minimum() {
                "a local minimum"
            } else {
                "NOT established as a local minimum"
            };
            outln!("returned path is {verdict}: {}", check.describe());
        }
        Err(e) => outln!("returned path NOT checked for a local minimum: {e}"),
    }
}

#[derive(Args)]
pub struct ExtremalsArgs {
    /// Only this lock configuration: none, 1, 2 or 3.
    #[arg(long, value_parser = parse_lock)]
    lock: Option<Lock>,
    /// Only this path: A or B.
    #[arg(long)]
    path: Option<String>,
}

/// Prints the Markdown table of every extremal of the chosen configurations.
pub fn run(args: &ExtremalsArgs) -> Result<(), CliError> {
    let locks: Vec<Lock> = args.lock.map_or(Lock::ALL.to_vec(), |l| vec![l]);
    let paths: Vec<String> = args
        .path
        .clone()
        .map_or(vec!["A".into(), "B".into()], |p| vec![p]);
    for name in &paths {
        read_path(name)?;
    }
    outln!(
        "| lock | path | extremal | PI [rad^2/s] | `||e||` | starts reaching it | joint move [rad] | direct PI (N=200) | reduced Hessian lambda_min [1/s] | local minimum | time [s] |"
    );
    outln!("|---|---|---|---|---|---|---|---|---|---|---|");
    for lock in &locks {
        for name in &paths {
            let chain = chain_of(*lock, MIRROR_ELBOWS)?;
            let path = read_path(name)?;
            print_configuration(&chain, *lock, name, path.as_ref());
        }
    }
    Ok(())
}

/// Rows of one configuration: every extremal with its check, or why none was found.
fn print_configuration(chain: &Chain, lock: Lock, name: &str, path: &dyn Path) {
    let started = Instant::now();
    let options = options(ShootingOptions::default().intervals);
    let search = match multi_start(chain, path, &lock.paper_guess(), options) {
        Ok(s) => s,
        Err(e) => {
            outln!(
                "| {} | {name} | none | - | - | - | - | - | - | {e} | - |",
                lock.name()
            );
            return;
        }
    };
    let seconds = started.elapsed().as_secs_f64();
    for (k, extremal) in search.extremals.iter().enumerate() {
        let s = &extremal.solution;
        let check = check_local_minimum(
            chain,
            path,
            &s.redundant_final,
            options.shooting,
            options.check,
        );
        let cells = match &check {
            Ok(c) => {
                let hessian = match c.second_order {
                    SecondOrder::NoRedundancy => "none (no redundancy)".to_string(),
                    SecondOrder::PositiveDefinite {
                        smallest_eigenvalue,
                    } => format!("{smallest_eigenvalue:.2e} (positive definite)"),
                    SecondOrder::NotPositiveDefinite => "not positive definite".into(),
                };
                let direct = match &c.neighbourhood {
                    Ok(n) => format!("{:.1e} | {:.6}", n.joint_move, n.direct_pi),
                    Err(_) => "direct method did not converge | -".into(),
                };
                let verdict = if c.is_local_minimum() { "yes" } else { "no" };
                format!("{direct} | {hessian} | {verdict}")
            }
            Err(e) => format!("- | - | - | not checked: {e}"),
        };
        outln!(
            "| {} | {name} | {}{} | {:.6} | {:.1e} | {} of {} | {cells} | {} |",
            lock.name(),
            k + 1,
            if k == 0 { " (returned)" } else { "" },
            s.pi(),
            s.residual,
            extremal.starts.len(),
            search.starts.len(),
            if k == 0 {
                format!("{seconds:.2}")
            } else {
                String::new()
            }
        );
    }
    print_failures(&search, lock, name);
}

/// A row counting the starts from which the shooting failed, if any.
fn print_failures(search: &MultiStart, lock: Lock, name: &str) {
    let failed = search.starts.iter().filter(|(_, o)| o.is_err()).count();
    if failed > 0 {
        outln!(
            "| {} | {name} | ({failed} of {} starts failed) | | | | | | | | |",
            lock.name(),
            search.starts.len()
        );
    }
}
