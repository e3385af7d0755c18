//! The step time of a real-time host (issue 42): for every packaged FMU, FMI 2.0 and
//! FMI 3.0, Co-Simulation and Model Exchange, the calls of one controller period
//! (`robofmu_hostile::realtime`: inputs, the step or the derivatives, outputs) timed
//! one period at a time; prints the median and the 99.9th percentile per case.
//!
//! Usage: `robofmu-hostile-steps [periods]` (default 20,000 timed periods per case,
//! after 2,000 untimed ones). A benchmark, not a test: the figures depend on the
//! machine and its load (docs/performance.md).

use robofmu_hostile::Loaded;
use robofmu_hostile::realtime::steppers;
use std::time::Instant;

fn main() {
    let periods: usize = match std::env::args().nth(1).map(|a| a.parse()) {
        None => 20_000,
        Some(Ok(n)) if n > 0 => n,
        Some(_) => {
            eprintln!("usage: robofmu-hostile-steps [periods > 0]");
            std::process::exit(2);
        }
    };
    let loaded = Loaded::all();
    let mut cases = steppers(&loaded).unwrap_or_else(|e| {
        eprintln!("robofmu-hostile-steps: {e}");
        std::process::exit(1);
    });
    println!("| case | median (us) | 99.9th percentile (us) |");
    println!("|---|---|---|");
    let mut times = vec![0u64; periods];
    for case in &mut cases {
        let warm_up = 2_000;
        for k in 0..warm_up + periods {
            let start = Instant::now();
            if let Err(e) = case.step(k) {
                eprintln!("robofmu-hostile-steps: {}: {e}", case.name);
                std::process::exit(1);
            }
            if k >= warm_up {
                times[k - warm_up] = start.elapsed().as_nanos() as u64;
            }
        }
        times.sort_unstable();
        let at = |q: f64| times[((periods - 1) as f64 * q).round() as usize] as f64 / 1e3;
        println!("| {} | {:.2} | {:.2} |", case.name, at(0.5), at(0.999));
    }
}
