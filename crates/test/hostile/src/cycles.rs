//! dlopen -> instantiate -> initialize -> one step -> free instance -> dlclose,
//! repeated, through the FMI 2.0 or the FMI 3.0 interface: the resident set size
//! must stay flat (issue 12 item 1: a
//! variable table built per load and never freed grew RSS by 27 to 114 MB over
//! 2,000 cycles). Each model runs in its own forked child of a process that has
//! not loaded any FMU, so dlclose really unloads and nothing else pollutes RSS.

use crate::binary::{Binary, OK, status_name};
use crate::fmi3::binary::Binary3;
use crate::fmi3::host::{Instance as Instance3, Interface3, State3};
use crate::fmu::{Fmu, Standard};
use crate::host::{Instance, Interface, State};

/// Cycles measured, after `WARM_UP` cycles that fill the allocator's pools.
pub const CYCLES: usize = 2000;
pub const WARM_UP: usize = 50;
/// Largest accepted growth of the resident set over `CYCLES` cycles, in bytes.
pub const RSS_BOUND: u64 = 1 << 20;

/// Resident set size of this process in bytes (/proc/self/statm, second field).
pub fn resident_bytes() -> u64 {
    let statm = std::fs::read_to_string("/proc/self/statm").unwrap_or_default();
    let pages: u64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or(0);
    // SAFETY: sysconf has no preconditions.
    pages * unsafe { libc::sysconf(libc::_SC_PAGESIZE) } as u64
}

/// One full cycle through the interface of `standard`; Err when a call fails.
pub fn cycle(fmu: &Fmu, standard: Standard) -> Result<(), String> {
    match standard {
        Standard::Fmi2 => cycle2(fmu),
        Standard::Fmi3 => cycle3(fmu),
    }
}

fn cycle3(fmu: &Fmu) -> Result<(), String> {
    let binary = Binary3::open(&fmu.library)?;
    {
        let inst = Instance3::new(&binary, &fmu.description, Interface3::CoSimulation);
        inst.reach(State3::StepMode)?;
        let s = inst.do_step(0.0, 1e-3).status;
        if s != OK {
            return Err(format!(
                "fmi3DoStep returned {}: {}",
                status_name(s),
                inst.take_log()
            ));
        }
    }
    drop(binary);
    Ok(())
}

fn cycle2(fmu: &Fmu) -> Result<(), String> {
    let binary = Binary::open(&fmu.library)?;
    {
        let inst = Instance::new(&binary, &fmu.description, Interface::CoSimulation);
        inst.reach(State::StepComplete)?;
        let s = inst.do_step(0.0, 1e-3);
        if s != OK {
            return Err(format!("fmi2DoStep returned {s}: {}", inst.take_log()));
        }
    }
    drop(binary);
    Ok(())
}

/// RSS before and after `CYCLES` cycles (after the warm-up), as "before after".
pub fn measure(fmu: &Fmu, standard: Standard) -> Result<(u64, u64), String> {
    for _ in 0..WARM_UP {
        cycle(fmu, standard)?;
    }
    let before = resident_bytes();
    for _ in 0..CYCLES {
        cycle(fmu, standard)?;
    }
    Ok((before, resident_bytes()))
}
