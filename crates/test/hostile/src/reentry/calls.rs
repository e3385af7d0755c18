//! Calls from inside the instance's own log callback (issue 20, defect 1): a logger
//! that frees the instance when told of an Error, or at the logCalls line of a call
//! (and instantiates another, which the allocator likely places at the freed
//! address), or that resets it, sets an FMU state or calls a getter. Expected (issue
//! 20, "what to build"): the call from the callback is refused with Error and a log
//! line and changes nothing; a FreeInstance from it is done when the outer call
//! returns, which returns Error and touches neither the freed instance nor the new
//! one (whose initialization must then succeed).

use super::api::{Api, Handle, settable_real};
use super::host::{Host, Trigger};
use super::{Outcome, expect, started};
use crate::binary::{ERROR, OK};
use std::cell::Cell;

/// A value reference no model declares: every setter refuses it with Error.
pub const UNKNOWN_VR: u32 = u32::MAX - 7;

/// A communication step every model takes from t = 0.
pub const STEP: f64 = 1e-3;

/// The logger frees the instance at the trigger and instantiates another; the outer
/// call (`call`) must return Error and the other instance must be untouched.
fn free_and_replace(api: &dyn Api, trigger: Trigger, call: &dyn Fn(Handle) -> i32) -> Outcome {
    let other = Cell::new(std::ptr::null_mut());
    let other_host = Host::new();
    let host = Host::new();
    let h = started(api, &host)?;
    if matches!(trigger, Trigger::Call(_)) {
        expect(
            api.log_all(h),
            OK,
            "SetDebugLogging (all categories)",
            &host,
        )?;
    }
    host.arm(
        trigger,
        Box::new(|h| {
            api.free(h);
            other.set(api.instantiate(&other_host));
            None
        }),
    );
    let status = call(h);
    let other = other.get();
    if !host.fired.get() || other.is_null() {
        return Err(format!("the logger was not called: {}", host.log_text()));
    }
    other_host.handle.set(other);
    let result = expect(
        status,
        ERROR,
        "the call during which the logger freed",
        &host,
    )
    .and_then(|()| {
        expect(
            api.get_real(h, settable_real(api.description()).0).0,
            ERROR,
            "a call on the freed handle",
            &host,
        )
    })
    .and_then(|()| {
        expect(
            api.initialize(other, 0.0),
            OK,
            "initializing the instance made in the logger",
            &other_host,
        )
    });
    api.free(other);
    result.map(|()| "Error; freed after the call; the new instance untouched".into())
}

pub fn free_on_error(api: &dyn Api) -> Outcome {
    free_and_replace(api, Trigger::Error, &|h| api.set_real(h, UNKNOWN_VR, 1.0))
}

pub fn free_at_do_step_line(api: &dyn Api) -> Outcome {
    let trigger = Trigger::Call(api.do_step_name());
    free_and_replace(api, trigger, &|h| api.do_step(h, 0.0, STEP))
}

/// The logger makes `nested` at the first Error on the started instance `h`; it
/// must be refused with Error and a log line, and the instance must then recover
/// (Reset, initialize, step).
fn nested_on_error<'a>(
    api: &'a dyn Api,
    host: &Host<'a>,
    h: Handle,
    nested: impl FnOnce(Handle) -> i32 + 'a,
    what: &str,
) -> Outcome {
    host.arm(Trigger::Error, Box::new(move |h| Some(nested(h))));
    let status = api.set_real(h, UNKNOWN_VR, 1.0);
    expect(
        status,
        ERROR,
        "the call with the unknown value reference",
        host,
    )?;
    let got = host.nested.get().ok_or("the logger was not called")?;
    expect(got, ERROR, what, host)?;
    refusal_logged(host)?;
    expect(api.reset(h), OK, "Reset after the Error", host)?;
    expect(api.initialize(h, 0.0), OK, "initialize after Reset", host)?;
    expect(api.do_step(h, 0.0, STEP), OK, "a step after Reset", host)?;
    Ok(format!("{what}: Error, logged; the instance recovers"))
}

fn refusal_logged(host: &Host) -> Result<(), String> {
    if host.logged("called from a callback") {
        Ok(())
    } else {
        Err(format!(
            "no log line says why the nested call was refused: {}",
            host.log_text()
        ))
    }
}

pub fn reset_on_error(api: &dyn Api) -> Outcome {
    let host = Host::new();
    let h = started(api, &host)?;
    let result = nested_on_error(
        api,
        &host,
        h,
        move |h| api.reset(h),
        "Reset from the logger",
    );
    api.free(h);
    result
}

pub fn set_state_on_error(api: &dyn Api) -> Outcome {
    let host = Host::new();
    let h = started(api, &host)?;
    let mut state = std::ptr::null_mut();
    expect(api.get_state(h, &mut state), OK, "GetFMUState", &host)?;
    let nested = move |h| api.set_state(h, state);
    let result = nested_on_error(api, &host, h, nested, "SetFMUState from the logger");
    api.free(h); // frees the state too
    result
}

/// The logger calls a getter at the logCalls line of DoStep: refused with Error and
/// a log line; the step itself goes on (OK) and the next one too.
pub fn getter_at_do_step_line(api: &dyn Api) -> Outcome {
    let host = Host::new();
    let h = started(api, &host)?;
    expect(
        api.log_all(h),
        OK,
        "SetDebugLogging (all categories)",
        &host,
    )?;
    let vr = settable_real(api.description()).0;
    host.arm(
        Trigger::Call(api.do_step_name()),
        Box::new(move |h| Some(api.get_real(h, vr).0)),
    );
    let status = api.do_step(h, 0.0, STEP);
    let result = expect(
        status,
        OK,
        "the step whose logCalls line called a getter",
        &host,
    )
    .and_then(|()| {
        expect(
            host.nested.get().ok_or("the logger was not called")?,
            ERROR,
            "the getter from the logger",
            &host,
        )
    })
    .and_then(|()| refusal_logged(&host))
    .and_then(|()| expect(api.do_step(h, STEP, STEP), OK, "the next step", &host));
    api.free(h);
    result.map(|()| "getter from the logger: Error, logged; the step OK".into())
}
