//! Load/instantiate/free/unload cycles of every packaged FMU with an RSS bound:
//! see `robofmu_hostile::cycles`. This process never loads an FMU itself; each
//! model is measured in a fresh forked child.

use robofmu_hostile::cycles::{CYCLES, RSS_BOUND, measure};
use robofmu_hostile::fmu::{Fmu, Standard, models};
use robofmu_hostile::isolate;

fn main() {
    let mut failed = false;
    for (standard, model) in Standard::BOTH
        .into_iter()
        .flat_map(|s| models().iter().map(move |m| (s, m.as_str())))
    {
        let fmu = Fmu::unpack(model, standard).unwrap_or_else(|e| panic!("{e}"));
        let model = format!("{model} ({})", standard.name());
        let result = isolate::run_one(&|| match measure(&fmu, standard) {
            Ok((before, after)) => format!("{before} {after}"),
            Err(e) => format!("error {e}"),
        });
        let numbers: Vec<u64> = match &result {
            Ok(line) => line.split(' ').filter_map(|n| n.parse().ok()).collect(),
            Err(_) => Vec::new(),
        };
        let [before, after] = numbers[..] else {
            println!("{model}: {result:?}");
            failed = true;
            continue;
        };
        let growth = after as i64 - before as i64;
        let ok = growth <= RSS_BOUND as i64;
        failed |= !ok;
        println!(
            "{model}: RSS {:.2} MB -> {:.2} MB over {CYCLES} cycles (growth {:.3} MB, bound {:.0} MB): {}",
            before as f64 / 1048576.0,
            after as f64 / 1048576.0,
            growth as f64 / 1048576.0,
            RSS_BOUND as f64 / 1048576.0,
            if ok { "ok" } else { "FAIL" }
        );
    }
    if failed {
        std::process::exit(1);
    }
}
