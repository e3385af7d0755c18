//! Handles whose memory comes back (issue 20, defect 2, and defect 6's
//! requiredIntermediateVariables): a freed instance handle used after an
//! instantiation that likely got the same memory, a freed FMU state used after a new
//! state took its place, and an intermediateUpdate callback that frees its instance
//! and makes another. Expected: a freed handle is refused with Error, whatever the
//! allocator did, and the new instance or state is untouched.

use super::api::{Api, settable_real};
use super::calls::STEP;
use super::host::{Host, Trigger};
use super::{Outcome, expect, started};
use crate::binary::{ERROR, OK};
use std::cell::Cell;

/// Rounds of free + instantiate (glibc gives a freed block of the same size back to
/// the next allocation of that size; the issue saw 4 reuses in 5 rounds).
const ROUNDS: usize = 5;

pub fn freed_instance(api: &dyn Api) -> Outcome {
    let (vr, start) = settable_real(api.description());
    for round in 0..ROUNDS {
        let (host_a, host_b) = (Host::new(), Host::new());
        let a = api.instantiate(&host_a);
        api.free(a);
        let b = api.instantiate(&host_b);
        let status = api.set_real(a, vr, start + 1.0);
        let initialized = api.initialize(b, 0.0);
        let (got, value) = api.get_real(b, vr);
        api.free(b);
        expect(
            status,
            ERROR,
            &format!("round {round}: SetReal on the freed handle"),
            &host_a,
        )?;
        expect(initialized, OK, "initializing the new instance", &host_b)?;
        expect(got, OK, "GetReal on the new instance", &host_b)?;
        if value != start {
            return Err(format!(
                "round {round}: the new instance's value is {value}, not {start}"
            ));
        }
    }
    Ok(format!(
        "{ROUNDS} rounds: Error; the new instance untouched"
    ))
}

pub fn freed_state(api: &dyn Api) -> Outcome {
    let host = Host::new();
    let h = started(api, &host)?;
    let (mut first, mut second) = (std::ptr::null_mut(), std::ptr::null_mut());
    expect(api.get_state(h, &mut first), OK, "GetFMUState", &host)?;
    let freed = first;
    expect(api.free_state(h, &mut first), OK, "FreeFMUState", &host)?;
    expect(
        api.get_state(h, &mut second),
        OK,
        "a second GetFMUState",
        &host,
    )?;
    let status = api.set_state(h, freed);
    api.free(h);
    expect(status, ERROR, "SetFMUState with the freed state", &host)?;
    Ok("SetFMUState of a freed state: Error".into())
}

/// FMI 3.0, models with intermediate points: the callback frees the instance and
/// instantiates another; the step returns Error and the other instance is untouched.
pub fn freed_in_intermediate_update(api: &dyn Api) -> Outcome {
    let other = Cell::new(std::ptr::null_mut());
    let (other_host, host) = (Host::new(), Host::new());
    let Some(h) = api.instantiate_with_update(&host) else {
        return Ok("not applicable: FMI 2.0 has no intermediateUpdate".into());
    };
    host.handle.set(h);
    expect(api.initialize(h, 0.0), OK, "initialize", &host)?;
    host.arm(
        Trigger::Intermediate,
        Box::new(|h| {
            api.free(h);
            other.set(api.instantiate(&other_host));
            None
        }),
    );
    let status = api.do_step(h, 0.0, STEP);
    let other = other.get();
    if !host.fired.get() {
        api.free(h);
        return Ok("not applicable: the model has no intermediate points".into());
    }
    let result = expect(
        status,
        ERROR,
        "the step whose callback freed the instance",
        &host,
    )
    .and_then(|()| {
        expect(
            api.initialize(other, 0.0),
            OK,
            "initializing the instance made in the callback",
            &other_host,
        )
    });
    api.free(other);
    result.map(|()| "Error; the new instance untouched".into())
}

/// FMI 3.0: requiredIntermediateVariables a garbage pointer with n = 2^60: refused
/// (no instance, a log line) before the array is read.
pub fn garbage_required_variables(api: &dyn Api) -> Outcome {
    let host = Host::new();
    let garbage = 0x10 as *const u32;
    let Some(h) = api.instantiate_required(&host, garbage, 1 << 60) else {
        return Ok("not applicable: FMI 2.0".into());
    };
    if !h.is_null() {
        api.free(h);
        return Err("instantiated with nRequiredIntermediateVariables = 2^60".into());
    }
    if !host.logged("RequiredIntermediateVariables") {
        return Err(format!("refused without saying why: {}", host.log_text()));
    }
    Ok("refused, logged".into())
}
