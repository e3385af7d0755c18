//! Handles the FMU never issued, passed to every function that takes one: null,
//! a zeroed and a random heap block owned by the importer, and a live instance of
//! another FMU. FMI 2.0 leaves this undefined; issue 12 item 4 asks a careful FMU
//! to check a tag in every instance and answer fmi2Error. No log text is required:
//! without a valid instance there is no logger the FMU could trust. Afterwards the
//! block must be intact (the importer frees it: a double free would crash) and the
//! other FMU's instance must still answer.

use super::calls::calls;
use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::{OK, Status, status_name};
use crate::host::{Interface, Probed};
use crate::rng::SplitMix64;
use crate::standard_interface::{Invoke, StandardInterface};
use std::ffi::c_void;

const WHY_NULL: &str = "null instance: undefined in FMI 2.0; fmi2Error (fmi2FreeInstance: ignored)";
const WHY_FOREIGN: &str = "handle not issued by this FMU: undefined in FMI 2.0; refused with fmi2Error after a tag check (issue 12 item 4)";

#[derive(Clone, Copy, Debug)]
enum Handle {
    Null,
    ZeroedBlock,
    RandomBlock,
    OtherFmuInstance,
}

const HANDLES: [Handle; 4] = [
    Handle::Null,
    Handle::ZeroedBlock,
    Handle::RandomBlock,
    Handle::OtherFmuInstance,
];

const BLOCK: usize = 4096;

/// A heap block owned by the importer (the FMI 3.0 probes use it too).
pub(crate) fn block(random: bool) -> *mut c_void {
    // SAFETY: calloc of a fixed size.
    let p = unsafe { libc::calloc(1, BLOCK) } as *mut u8;
    if random {
        let mut rng = SplitMix64::new(0x5eed);
        for i in 0..BLOCK {
            // SAFETY: within the block.
            unsafe { *p.add(i) = rng.next_u64() as u8 };
        }
    }
    p as *mut c_void
}

type Invoke2 = Invoke<Interface>;

fn probe(
    l: &Loaded,
    m: usize,
    interface: Interface,
    handle: Handle,
    invoke: Option<Invoke2>,
) -> Observed {
    let Scene {
        own,
        state,
        args,
        other,
    } = match Scene::new(l, m, interface) {
        Ok(scene) => scene,
        Err(e) => return Observed::broken(e),
    };
    let c = match handle {
        Handle::Null => std::ptr::null_mut(),
        Handle::ZeroedBlock => block(false),
        Handle::RandomBlock => block(true),
        Handle::OtherFmuInstance => other.c,
    };
    let owned = matches!(handle, Handle::ZeroedBlock | Handle::RandomBlock);
    // SAFETY: null, our block or another FMU's live instance.
    let status = unsafe { call_with_bad_handle::<Interface>((&own, &args), c, owned, invoke) };
    let (s, values) = other.get_reals(&[other.description.real_vrs()[0]]);
    if s != OK || !values[0].is_finite() {
        return Observed::broken(format!(
            "the other FMU's instance no longer answers: {} ({})",
            status_name(s),
            other.take_log()
        ));
    }
    own.free_state(state);
    let log = format!("{} {}", own.take_log(), other.take_log());
    Observed::of(status, log)
}

/// What a bad-handle probe works with: an instance of the model (whose function
/// table makes the call), one of its FMU states and the call arguments, and an
/// instance of the next model in Initialization Mode (which must still answer).
pub struct Scene<'a, I: StandardInterface> {
    pub own: I::Instance<'a>,
    pub state: *mut c_void,
    pub args: I::Args,
    pub other: I::Instance<'a>,
}

impl<'a, I: StandardInterface> Scene<'a, I> {
    pub fn new(l: &'a Loaded, m: usize, interface: I) -> Result<Scene<'a, I>, String> {
        let own = interface.instance(l, m);
        let (_, state) = own.new_state();
        let args = I::args(&own, state);
        let other = interface.instance(l, (m + 1) % crate::fmu::models().len());
        I::reach(&other, I::INITIALIZATION_MODE)?;
        Ok(Scene {
            own,
            state,
            args,
            other,
        })
    }
}

/// `invoke` (None: fmiXFreeInstance) through the function table of `own`, with
/// the bad handle `c`; then frees `c` when it is a block of the importer (`owned`):
/// a crash there means the FMU freed it. The status (OK for fmiXFreeInstance).
///
/// # Safety
/// `c` is null, a block of the importer (`owned`: freed here) or a live instance;
/// the call is the probe's point: the FMU must recognize it as foreign.
pub unsafe fn call_with_bad_handle<I: StandardInterface>(
    (own, args): (&I::Instance<'_>, &I::Args),
    c: *mut c_void,
    owned: bool,
    invoke: Option<Invoke<I>>,
) -> Status {
    let (binary, _) = I::raw(own);
    // SAFETY: the point of the probe: a handle this binary never issued.
    let status = match invoke {
        Some(f) => unsafe { f(binary, c.into(), args) },
        None => {
            unsafe { I::free_instance(binary)(c) };
            OK
        }
    };
    if owned {
        // SAFETY: our own block; a crash here means the FMU freed it.
        unsafe { libc::free(c) };
    }
    status
}

/// A probe of one bad handle passed to one call (None: to fmiXFreeInstance).
pub type HandleProbe<I, H> = fn(&Loaded, usize, I, H, Option<Invoke<I>>) -> Observed;

/// Every handle of `handles` passed to every call of `calls` and to
/// `free_instance` (named so), on every interface: an error without a log
/// requirement, fmiXFreeInstance ignoring it (both standards).
pub fn bad_handle_cases<I: StandardInterface, H: Copy + std::fmt::Debug + 'static>(
    m: usize,
    (class, free_instance): (&'static str, &'static str),
    (handles, why): (&[H], fn(H) -> &'static str),
    calls: Vec<(&'static str, Invoke<I>)>,
    probe: HandleProbe<I, H>,
) -> Vec<Case> {
    let mut all: Vec<(&'static str, Option<Invoke<I>>)> =
        calls.into_iter().map(|(n, f)| (n, Some(f))).collect();
    all.push((free_instance, None));
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for &handle in handles {
            for &(name, invoke) in &all {
                cases.push(Case {
                    class,
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{name}({handle:?})"),
                    expect: if invoke.is_some() {
                        Expect::silent_error()
                    } else {
                        Expect::ok()
                    },
                    why: why(handle),
                    probe: Box::new(move |l| probe(l, m, interface, handle, invoke)),
                });
            }
        }
    }
    cases
}

pub fn cases(_: &Loaded, m: usize) -> Vec<Case> {
    bad_handle_cases::<Interface, Handle>(
        m,
        ("bad instance handle", "fmi2FreeInstance"),
        (&HANDLES, |h| {
            if matches!(h, Handle::Null) {
                WHY_NULL
            } else {
                WHY_FOREIGN
            }
        }),
        calls().into_iter().map(|c| (c.name, c.invoke)).collect(),
        probe,
    )
}
