//! FMI 2.0 in the instantiation class (`matrix::instantiate`): fmi2Instantiate
//! with the names it is given, and the rows only FMI 2.0 has (FMI 2.0 section
//! 2.1.5): missing callbacks, an unknown fmuType.

use crate::Loaded;
use crate::binary::{ERROR, OK};
use crate::host::Interface;
use crate::host::{Callbacks, Environment, c_string};
use crate::matrix::seam::{Attempt, Instantiation, Names};
use crate::matrix::{Expect, Observed};
use std::ffi::c_int;

const WHY_CALLBACKS: &str = "FMI 2.0 2.1.5: allocateMemory and freeMemory are required (not NULL): refuse with a log line (issue 12 item 5)";
const WHY_LOGGER: &str =
    "no logger: the FMU cannot report anything; refuses silently (project choice)";
pub const WHY_ARGS: &str = "FMI 2.0 2.1.5: instanceName non-empty, fmuGUID of this FMU, fmuType 0 or 1: refuse with a log line";

struct Args {
    name: Option<&'static str>,
    fmu_type: c_int,
    guid: Option<String>,
    callbacks: Option<Callbacks>,
}

fn attempt(l: &Loaded, m: usize, a: &Args) -> Observed {
    let env = Environment::new(a.callbacks.unwrap_or(Callbacks::ALL));
    let name = a.name.map(c_string);
    let guid = a.guid.as_deref().map(c_string);
    let b = &l.binaries[m];
    let ptr = |s: &Option<std::ffi::CString>| s.as_ref().map_or(std::ptr::null(), |s| s.as_ptr());
    let functions = if a.callbacks.is_some() {
        &*env.functions as *const _
    } else {
        std::ptr::null()
    };
    // SAFETY: strings and callbacks are valid or null.
    let c = unsafe {
        (b.instantiate)(
            ptr(&name),
            a.fmu_type,
            ptr(&guid),
            std::ptr::null(),
            functions,
            0,
            1,
        )
    };
    let status = if c.is_null() { ERROR } else { OK };
    if !c.is_null() {
        // SAFETY: an instance of this binary.
        unsafe { (b.free_instance)(c) };
    }
    Observed::of(status, env.take_log())
}

/// fmi2Instantiate (Co-Simulation, all callbacks) with `names`.
fn with_names(l: &Loaded, m: usize, _: Option<Interface>, names: &Names) -> Observed {
    let args = Args {
        name: names.name,
        fmu_type: 1,
        guid: names.token.clone(),
        callbacks: Some(Callbacks::ALL),
    };
    attempt(l, m, &args)
}

/// The instantiation rows of FMI 2.0.
pub const INSTANTIATION: Instantiation<Interface> = Instantiation {
    kinds: &[None],
    token: ("fmuGUID", "GUID"),
    why: WHY_ARGS,
    attempt: with_names,
    own: attempts,
};

/// The rows only FMI 2.0 has.
fn attempts(l: &Loaded, m: usize) -> Vec<Attempt> {
    let guid = l.fmus[m].description.guid.clone();
    let ok = Args {
        name: Some("probe"),
        fmu_type: 1,
        guid: Some(guid.clone()),
        callbacks: Some(Callbacks::ALL),
    };
    let with = |f: &dyn Fn(&mut Args)| {
        let mut a = Args {
            guid: ok.guid.clone(),
            ..ok
        };
        f(&mut a);
        a
    };
    let no = |allocate: bool, free: bool, logger: bool| Callbacks {
        allocate,
        free,
        logger,
    };
    let table: Vec<(&str, Args, Expect, &'static str)> = vec![
        (
            "allocateMemory = NULL",
            with(&|a| a.callbacks = Some(no(false, true, true))),
            Expect::error("allocateMemory"),
            WHY_CALLBACKS,
        ),
        (
            "freeMemory = NULL",
            with(&|a| a.callbacks = Some(no(true, false, true))),
            Expect::error("freeMemory"),
            WHY_CALLBACKS,
        ),
        (
            "allocateMemory = freeMemory = NULL",
            with(&|a| a.callbacks = Some(no(false, false, true))),
            Expect::error("Memory"),
            WHY_CALLBACKS,
        ),
        (
            "logger = NULL",
            with(&|a| a.callbacks = Some(no(true, true, false))),
            Expect::silent_error(),
            WHY_LOGGER,
        ),
        (
            "functions = NULL",
            with(&|a| a.callbacks = None),
            Expect::silent_error(),
            WHY_LOGGER,
        ),
        (
            "fmuType = 2",
            with(&|a| a.fmu_type = 2),
            Expect::error("fmuType"),
            WHY_ARGS,
        ),
        (
            "fmuType = -1",
            with(&|a| a.fmu_type = -1),
            Expect::error("fmuType"),
            WHY_ARGS,
        ),
    ];
    table
        .into_iter()
        .map(|(name, args, expect, why)| Attempt {
            interface: None,
            name: name.to_string(),
            expect,
            why,
            probe: Box::new(move |l| attempt(l, m, &args)),
        })
        .collect()
}
