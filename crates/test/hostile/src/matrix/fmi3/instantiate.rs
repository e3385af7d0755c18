//! FMI 3.0 in the instantiation class (`matrix::instantiate`):
//! fmi3InstantiateModelExchange and fmi3InstantiateCoSimulation with the names
//! they are given, and the rows only FMI 3.0 has (section 2.3.1): no logger
//! (logMessage = NULL, accepted: the FMU then cannot report, but the instance
//! must still refuse an illegal call without crashing; the observed status is
//! that call's), and fmi3InstantiateScheduledExecution, an interface the FMU does
//! not provide.

use crate::Loaded;
use crate::binary::{ERROR, OK};
use crate::fmi3::host::{Interface3, logger};
use crate::host::{Log, c_string, take};
use crate::matrix::Expect;
use crate::matrix::Observed;
use crate::matrix::seam::{Attempt, Instantiation, Names};
use std::ffi::c_void;
use std::sync::Mutex;

const WHY_ARGS: &str =
    "FMI 3.0 2.3.1: instanceName non-empty, instantiationToken of this FMU: NULL and a log line";
const WHY_NO_LOGGER: &str = "logMessage = NULL: accepted (project choice), nothing can be logged; an illegal call is still refused with fmi3Error";
const WHY_SCHEDULED: &str =
    "Scheduled Execution is not provided (no <ScheduledExecution> element): NULL and a log line";

#[derive(Clone)]
struct Args {
    interface: Option<Interface3>,
    name: Option<&'static str>,
    token: Option<String>,
    logger: bool,
}

fn attempt(l: &Loaded, m: usize, a: &Args) -> Observed {
    let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
    let name = a.name.map(c_string);
    let token = a.token.as_deref().map(c_string);
    let ptr = |s: &Option<std::ffi::CString>| s.as_ref().map_or(std::ptr::null(), |s| s.as_ptr());
    let env = &*log as *const Log as *mut c_void;
    let cb = if a.logger { logger() } else { std::ptr::null() };
    let b = &l.binaries3[m];
    let null = std::ptr::null();
    // SAFETY: strings and callbacks are valid or null.
    let c = unsafe {
        match a.interface {
            Some(Interface3::ModelExchange) => {
                (b.instantiate_me)(ptr(&name), ptr(&token), null, 0, 1, env, cb)
            }
            Some(i) => (b.instantiate_cs)(
                ptr(&name),
                ptr(&token),
                null,
                0,
                1,
                u8::from(i == Interface3::CoSimulationEvents),
                0,
                std::ptr::null(),
                0,
                env,
                cb,
                std::ptr::null(),
            ),
            None => {
                let none = std::ptr::null();
                (b.instantiate_se)(
                    ptr(&name),
                    ptr(&token),
                    null,
                    0,
                    1,
                    env,
                    cb,
                    none,
                    none,
                    none,
                )
            }
        }
    };
    if c.is_null() {
        return Observed::of(ERROR, take(&log));
    }
    // SAFETY: an instance of this binary.
    let status = unsafe {
        let s = if a.logger {
            OK
        } else {
            (b.exit_initialization_mode)(c)
        };
        (b.free_instance)(c);
        s
    };
    Observed::of(status, take(&log))
}

/// The instantiation function of `interface` with `names`, with a logger.
fn with_names(l: &Loaded, m: usize, interface: Option<Interface3>, names: &Names) -> Observed {
    let args = Args {
        interface,
        name: names.name,
        token: names.token.clone(),
        logger: true,
    };
    attempt(l, m, &args)
}

/// The instantiation rows of FMI 3.0: Model Exchange and Co-Simulation.
pub const INSTANTIATION: Instantiation<Interface3> = Instantiation {
    kinds: &[
        Some(Interface3::ModelExchange),
        Some(Interface3::CoSimulation),
    ],
    token: ("instantiationToken", "instantiationToken"),
    why: WHY_ARGS,
    attempt: with_names,
    own: attempts,
};

/// The rows only FMI 3.0 has.
fn attempts(l: &Loaded, m: usize) -> Vec<Attempt> {
    let token = l.fmus3[m].description.guid.clone();
    let args = |interface, logger| Args {
        interface,
        name: Some("probe"),
        token: Some(token.clone()),
        logger,
    };
    let mut attempts = Vec::new();
    for interface in [Interface3::ModelExchange, Interface3::CoSimulation] {
        let silent = args(Some(interface), false);
        attempts.push(Attempt {
            interface: Some(interface.short()),
            name: "logMessage = NULL, then fmi3ExitInitializationMode in Instantiated".into(),
            expect: Expect::silent_error(),
            why: WHY_NO_LOGGER,
            probe: Box::new(move |l| attempt(l, m, &silent)),
        });
    }
    let scheduled = args(None, true);
    attempts.push(Attempt {
        interface: None,
        name: "fmi3InstantiateScheduledExecution".into(),
        expect: Expect::error("Co-Simulation only"),
        why: WHY_SCHEDULED,
        probe: Box::new(move |l| attempt(l, m, &scheduled)),
    });
    attempts
}
