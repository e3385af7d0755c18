//! The FMI 3.0 rows of the instantiation class (`matrix::instantiate`):
//! fmi3InstantiateModelExchange, fmi3InstantiateCoSimulation and
//! fmi3InstantiateScheduledExecution with arguments FMI 3.0 section 2.3.1 forbids: null or empty instance names, a null or foreign instantiation
//! token, and an interface the FMU does not provide. The FMU returns NULL and its
//! logger says why. Without a logger (logMessage = NULL, accepted: the FMU then
//! cannot report) the instance must still refuse an illegal call without
//! crashing. The observed status is OK for an instance (or the status of that
//! illegal call) and Error for NULL.

use crate::Loaded;
use crate::binary::{ERROR, OK};
use crate::fmi3::host::{Interface3, logger};
use crate::host::{Log, c_string, take};
use crate::matrix::Expect;
use crate::matrix::Observed;
use crate::matrix::seam::Attempt;
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

pub fn attempts(l: &Loaded, m: usize) -> Vec<Attempt> {
    let token = l.fmus3[m].description.guid.clone();
    let mut cases = Vec::new();
    let interfaces = [
        Some(Interface3::ModelExchange),
        Some(Interface3::CoSimulation),
    ];
    for interface in interfaces {
        let ok = Args {
            interface,
            name: Some("probe"),
            token: Some(token.clone()),
            logger: true,
        };
        let with = |f: &dyn Fn(&mut Args)| {
            let mut a = ok.clone();
            f(&mut a);
            a
        };
        let table: Vec<(&str, Args, Expect, &'static str)> = vec![
            (
                "all arguments valid (control)",
                with(&|_| {}),
                Expect::ok(),
                WHY_ARGS,
            ),
            (
                "instanceName = NULL",
                with(&|a| a.name = None),
                Expect::error("instanceName"),
                WHY_ARGS,
            ),
            (
                "instanceName empty",
                with(&|a| a.name = Some("")),
                Expect::error("instanceName"),
                WHY_ARGS,
            ),
            (
                "instantiationToken = NULL",
                with(&|a| a.token = None),
                Expect::error("instantiationToken"),
                WHY_ARGS,
            ),
            (
                "instantiationToken of another model",
                with(&|a| a.token = Some("{00000000-0000-0000-0000-000000000000}".into())),
                Expect::error("instantiationToken"),
                WHY_ARGS,
            ),
            (
                "logMessage = NULL, then fmi3ExitInitializationMode in Instantiated",
                with(&|a| a.logger = false),
                Expect::silent_error(),
                WHY_NO_LOGGER,
            ),
        ];
        let short = interface.map_or("--", Interface3::short);
        for (name, args, expect, why) in table {
            cases.push(Attempt {
                interface: Some(short),
                name: name.to_string(),
                expect,
                why,
                probe: Box::new(move |l| attempt(l, m, &args)),
            });
        }
    }
    let scheduled = Args {
        interface: None,
        name: Some("probe"),
        token: Some(token),
        logger: true,
    };
    cases.push(Attempt {
        interface: None,
        name: "fmi3InstantiateScheduledExecution".into(),
        expect: Expect::error("Co-Simulation only"),
        why: WHY_SCHEDULED,
        probe: Box::new(move |l| attempt(l, m, &scheduled)),
    });
    cases
}
