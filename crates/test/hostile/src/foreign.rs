//! Handles given to the wrong library (issue 36): an importer that loads several
//! FMUs passes an instance or an FMU state of one to the functions of another. The
//! neighbour is another model, another copy of the same binary (the file copied to
//! another path and loaded again: its own statics, its own registry) or, in the
//! same binary, an instance of the other standard. Each case makes both objects
//! distinct (a settable Real moved off its start in each), then passes the
//! neighbour's live instance to every function of the calling library's table that
//! takes an instance (and to FreeInstance), or the neighbour's live FMU state to
//! every function that takes a state. Expected: every call Error (FreeInstance
//! ignores it), a state refused with the log line "not a live FMU state", and both
//! the caller's own instance and the neighbour's instance and state unchanged, value
//! for value, bit for bit. Before issue 36 every library numbered its handles from
//! the same base, so the first instance of each had the same handle and the call
//! acted on the caller's own instance.
//!
//! Every case runs in a fresh forked child (`tests/foreign.rs`), where each library
//! issues its first handles, the numbers that used to coincide; `scripts/memcheck.sh`
//! runs them in one process under valgrind (`robofmu-hostile-reentry`).

use crate::Loaded;
use crate::binary::{ERROR, OK, status_name};
use crate::description::VarType;
use crate::fmi3::host::Interface3;
use crate::host::{Interface, Probed, take};
use crate::matrix::seam::{Standard, Value};
use crate::standard_interface::StandardInterface;
use std::ffi::c_void;

/// What a case saw, or why the FMU failed it.
pub type Outcome = Result<String, String>;

/// What a case runs, given the loaded FMUs and their copies.
pub type Run = Box<dyn Fn(&Loaded, &Loaded) -> Outcome + Sync>;

/// One case: its name and what it runs.
pub struct ForeignCase {
    pub name: String,
    pub run: Run,
}

/// Every Real value of an instance, or why it no longer answers.
fn values<I: Standard>(inst: &I::Instance<'_>, whose: &str) -> Result<Vec<u64>, String> {
    let (s, v) = I::outputs(inst);
    if s != OK {
        return Err(format!(
            "{whose} instance no longer answers ({}): {}",
            status_name(s),
            take(inst.log())
        ));
    }
    Ok(v.iter().map(|x| x.to_bits()).collect())
}

/// Moves the first settable Real that accepts it off its start value by `shift`
/// (relative), so that two instances differ (none moved if none accepts).
fn mark<I: Standard>(inst: &I::Instance<'_>, d: &crate::description::Description, shift: f64) {
    for v in d.of_type(VarType::Real).filter(|v| v.is_settable()) {
        let start: f64 = v
            .start
            .as_deref()
            .and_then(|s| s.split_whitespace().next()?.parse().ok())
            .unwrap_or(0.0);
        let value = if start == 0.0 {
            shift
        } else {
            start * (1.0 + shift)
        };
        if I::set_value(inst, v, Value::Real(value)) == OK {
            return;
        }
    }
}

/// A fresh instance of model `m` of `loaded` in Initialization Mode, marked.
fn ready<I: Standard>(
    loaded: &Loaded,
    m: usize,
    interface: I,
    shift: f64,
) -> Result<I::Instance<'_>, String> {
    let inst = interface.instance(loaded, m);
    I::reach(&inst, I::INITIALIZATION_MODE)?;
    mark::<I>(&inst, I::description(loaded, m), shift);
    take(inst.log());
    Ok(inst)
}

/// Every function of `own`'s table that takes an instance, then FreeInstance, called
/// with `victim` (a live instance of a neighbour whose values `victim_values`
/// reads); Ok(number of calls) when every call returned Error and neither `own`
/// nor the neighbour changed.
fn instance_sweep<I: Standard>(
    own: &I::Instance<'_>,
    victim: *mut c_void,
    victim_values: &dyn Fn() -> Result<Vec<u64>, String>,
) -> Result<usize, String> {
    let (before_own, before_victim) = (values::<I>(own, "the caller's")?, victim_values()?);
    let (_, state) = own.new_state();
    let args = I::args(own, state);
    let (binary, _) = I::raw(own);
    let tables = I::tables();
    let calls = (tables.calls)().into_iter().map(|c| (c.name, c.invoke));
    let mut n = 0;
    for (name, invoke) in calls.chain((tables.lacking)()) {
        // SAFETY: well-formed arguments; the handle is the neighbour's, which the
        // library must refuse (the point of the probe).
        let status = unsafe { invoke(binary, victim.into(), &args) };
        if status != ERROR {
            return Err(format!(
                "{name} with the neighbour's instance returned {}, expected Error",
                status_name(status)
            ));
        }
        n += 1;
    }
    // SAFETY: as above; FreeInstance must ignore a handle it did not issue.
    unsafe { I::free_instance(binary)(victim) };
    own.release_state(state);
    if values::<I>(own, "the caller's")? != before_own {
        return Err("the caller's own instance changed".into());
    }
    if victim_values()? != before_victim {
        return Err("the neighbour's instance changed".into());
    }
    Ok(n + 1)
}

/// Every function of `own`'s table that takes an FMU state, called with `state` (a
/// live state of the neighbour `victim`); Ok(number of calls) when each returned
/// Error with "not a live FMU state", neither instance changed and the state still
/// restores its own instance.
fn state_sweep<I: Standard>(
    own: &I::Instance<'_>,
    victim: &I::Instance<'_>,
    state: *mut c_void,
) -> Result<usize, String> {
    let (before_own, before_victim) = (
        values::<I>(own, "the caller's")?,
        values::<I>(victim, "the neighbour's")?,
    );
    let uses = (I::tables().state_uses)();
    for &(name, use_it) in &uses {
        let status = use_it(own, state);
        let log = take(own.log());
        if status != ERROR || !log.contains("not a live FMU state") {
            return Err(format!(
                "{name} with the neighbour's FMU state returned {}, log: {log}",
                status_name(status)
            ));
        }
    }
    if values::<I>(own, "the caller's")? != before_own {
        return Err("the caller's own instance changed".into());
    }
    // SAFETY: the victim's own live state.
    let restored = unsafe { I::set_state(victim, state) };
    if restored != OK || values::<I>(victim, "the neighbour's")? != before_victim {
        return Err(format!(
            "the neighbour's state no longer restores its instance ({}): {}",
            status_name(restored),
            take(victim.log())
        ));
    }
    victim.release_state(state);
    Ok(uses.len())
}

/// Which neighbour a case takes its handle from.
#[derive(Clone, Copy)]
enum Neighbour {
    /// The next model, same standard.
    OtherModel,
    /// The same model in the other copy of its binary.
    OtherCopy,
}

/// Instance calls (`states` false) or state calls of model `m` (interface
/// `interface`) in `mine` with a neighbour's handle.
fn probe<I: Standard>(
    (l, copy): (&Loaded, &Loaded),
    m: usize,
    interface: I,
    neighbour: Neighbour,
    states: bool,
) -> Outcome {
    let victim_m = match neighbour {
        Neighbour::OtherModel => (m + 1) % crate::fmu::models().len(),
        Neighbour::OtherCopy => m,
    };
    let mine = match neighbour {
        Neighbour::OtherModel => l,
        Neighbour::OtherCopy => copy,
    };
    // The neighbour first: in a fresh child its first handle is the number the
    // caller's library gives its own first instance right after.
    let victim = ready(l, victim_m, interface, 0.25e-3)?;
    let own = ready(mine, m, interface, 0.5e-3)?;
    let n = if states {
        // Each takes a state, the neighbour first: again the same numbers before.
        let (s, state) = victim.new_state();
        let (s_own, own_state) = own.new_state();
        if s != OK || s_own != OK {
            return Err(format!(
                "GetFMUState: {} (neighbour), {} (caller)",
                status_name(s),
                status_name(s_own)
            ));
        }
        let n = state_sweep::<I>(&own, &victim, state)?;
        // SAFETY: the caller's own live state.
        if unsafe { I::set_state(&own, own_state) } != OK {
            return Err(format!(
                "the caller's own state no longer restores it: {}",
                take(own.log())
            ));
        }
        own.release_state(own_state);
        n
    } else {
        let victim_handle = I::raw(&victim).1.into();
        instance_sweep::<I>(&own, victim_handle, &|| {
            values::<I>(&victim, "the neighbour's")
        })?
    };
    Ok(format!("{n} calls: Error; both unchanged"))
}

/// FMI 2.0 functions of an FMU's FMI 3.0 binary given a live FMI 3.0 instance of
/// the same loaded binary.
fn other_standard(l: &Loaded, m: usize, interface: Interface) -> Outcome {
    let fmi2 = crate::binary::Binary::open(&l.fmus3[m].library)?;
    let three = if interface.is_me() {
        Interface3::MODEL_EXCHANGE
    } else {
        Interface3::CoSimulation
    };
    let victim = ready(l, m, three, 0.25e-3)?;
    let own = crate::host::Instance::new(&fmi2, &l.fmus[m].description, interface);
    Interface::reach(&own, Interface::INITIALIZATION_MODE)?;
    mark::<Interface>(&own, &l.fmus[m].description, 0.5e-3);
    let victim_handle = Interface3::raw(&victim).1;
    let n = instance_sweep::<Interface>(&own, victim_handle, &|| {
        values::<Interface3>(&victim, "the FMI 3.0")
    })?;
    Ok(format!("{n} calls: Error; both unchanged"))
}

fn cases_of<I: Standard>(standard: &'static str, out: &mut Vec<ForeignCase>) {
    let models = crate::fmu::models();
    for (m, model) in models.iter().enumerate() {
        for &interface in I::INTERFACES {
            for (neighbour, whose) in [
                (Neighbour::OtherModel, "another model's"),
                (Neighbour::OtherCopy, "another copy's"),
            ] {
                for (states, what) in [(false, "instance"), (true, "FMU state")] {
                    out.push(ForeignCase {
                        name: format!(
                            "{model} ({standard}, {}): {whose} {what}",
                            interface.short()
                        ),
                        run: Box::new(move |l, copy| {
                            probe((l, copy), m, interface, neighbour, states)
                        }),
                    });
                }
            }
        }
    }
}

/// Every case: for each model, standard and interface, another model's and another
/// copy's instance and FMU state; and the FMI 2.0 functions given the FMI 3.0
/// instance of the same binary (the FMI 3.0 matrix passes the FMI 2.0 instance to
/// every FMI 3.0 function).
pub fn cases() -> Vec<ForeignCase> {
    let mut all = Vec::new();
    cases_of::<Interface>("FMI 2.0", &mut all);
    cases_of::<Interface3>("FMI 3.0", &mut all);
    for (m, model) in crate::fmu::models().iter().enumerate() {
        for &interface in Interface::INTERFACES {
            all.push(ForeignCase {
                name: format!(
                    "{model} (FMI 2.0, {}): the FMI 3.0 instance of the same binary",
                    interface.short()
                ),
                run: Box::new(move |l, _| other_standard(l, m, interface)),
            });
        }
    }
    all
}
