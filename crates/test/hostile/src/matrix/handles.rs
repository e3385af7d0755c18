//! Instance handles the FMU never issued (or no longer owns), passed to every
//! function that takes one and to fmiXFreeInstance: null, a zeroed and a random
//! heap block owned by the importer, a live instance of another FMU and, where the
//! standard's tables list them, an instance already freed and a live instance of
//! the FMU's other standard in the same loaded binary. Both standards leave this
//! undefined; the project checks every handle (a tag, a registry of live
//! instances keyed by standard) and answers an error, fmiXFreeInstance ignoring
//! it. No log text is required: without a valid instance there is no logger the
//! FMU could trust. Afterwards the block is intact (the importer frees it: a
//! double free would crash) and the other instances still answer.

use super::seam::{Handle, Standard};
use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::{OK, Status, status_name};
use crate::host::Probed;
use crate::rng::SplitMix64;
use crate::standard_interface::{Invoke, StandardInterface};
use std::ffi::c_void;

const BLOCK: usize = 4096;

/// A heap block owned by the importer.
fn block(random: bool) -> *mut c_void {
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

/// What a bad-handle probe works with: an instance of the model (whose function
/// table makes the call), one of its FMU states and the call arguments, and an
/// instance of the next model in Initialization Mode (which must still answer).
struct Scene<'a, I: StandardInterface> {
    own: I::Instance<'a>,
    state: *mut c_void,
    args: I::Args,
    other: I::Instance<'a>,
}

impl<'a, I: StandardInterface> Scene<'a, I> {
    fn new(l: &'a Loaded, m: usize, interface: I) -> Result<Scene<'a, I>, String> {
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
unsafe fn call_with_bad_handle<I: StandardInterface>(
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

/// The bad handle `handle` passed to `invoke` on model `m`; the other FMU's
/// instance must still answer.
fn probe<I: Standard>(
    l: &Loaded,
    m: usize,
    interface: I,
    handle: Handle,
    invoke: Option<Invoke<I>>,
) -> Observed {
    let scene = match Scene::new(l, m, interface) {
        Ok(scene) => scene,
        Err(e) => return Observed::broken(e),
    };
    let call = |c: *mut c_void, owned: bool| {
        // SAFETY: null, our block, or a live (or just freed) instance.
        unsafe { call_with_bad_handle::<I>((&scene.own, &scene.args), c, owned, invoke) }
    };
    let mut pass = |sibling: *mut c_void| match handle {
        Handle::Null => call(std::ptr::null_mut(), false),
        Handle::ZeroedBlock => call(block(false), true),
        Handle::RandomBlock => call(block(true), true),
        Handle::OtherFmuInstance => call(I::raw(&scene.other).1.into(), false),
        Handle::FreedInstance => {
            let gone = interface.instance(l, m);
            let c = I::raw(&gone).1.into();
            drop(gone);
            call(c, false)
        }
        Handle::Fmi2InstanceOfThisFmu => call(sibling, false),
    };
    // With a live instance of the other standard in the same binary (when the
    // tables name one), which must still answer afterwards.
    let status = match I::tables().other_standard {
        Some(with_other) => match with_other(l, m, interface, &mut pass) {
            Ok(s) => s,
            Err(e) => return Observed::broken(e),
        },
        None => pass(std::ptr::null_mut()),
    };
    let (s, values) = I::outputs(&scene.other);
    if s != OK || values.iter().any(|v| !v.is_finite()) {
        return Observed::broken(format!(
            "the other FMU's instance no longer answers: {} ({})",
            status_name(s),
            crate::host::take(scene.other.log())
        ));
    }
    scene.own.release_state(scene.state);
    let log = format!(
        "{} {}",
        crate::host::take(scene.own.log()),
        crate::host::take(scene.other.log())
    );
    Observed::of(status, log)
}

/// Every handle of the standard's tables passed to every call (and to the
/// functions of lacking capabilities) and to fmiXFreeInstance, on every
/// interface: an error without a log requirement, fmiXFreeInstance ignoring it.
pub fn cases<I: Standard>(_: &Loaded, m: usize) -> Vec<Case> {
    let tables = I::tables();
    let mut all: Vec<(&'static str, Option<Invoke<I>>)> = (tables.calls)()
        .into_iter()
        .map(|c| (c.name, Some(c.invoke)))
        .chain((tables.lacking)().into_iter().map(|(n, f)| (n, Some(f))))
        .collect();
    all.push((tables.free_instance, None));
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for &handle in tables.handles {
            for &(name, invoke) in &all {
                cases.push(Case::new(
                    ("bad instance handle", m, interface),
                    format!("{name}({handle:?})"),
                    (
                        if invoke.is_some() {
                            Expect::silent_error()
                        } else {
                            Expect::ok()
                        },
                        if handle == Handle::Null {
                            tables.reasons.handle_null
                        } else {
                            tables.reasons.handle_foreign
                        },
                    ),
                    move |l| probe(l, m, interface, handle, invoke),
                ));
            }
        }
    }
    cases
}
