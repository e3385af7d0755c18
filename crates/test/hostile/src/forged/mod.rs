//! Forged FMU states and times the FMU cannot represent (issue 20, defects 3 and 4).
//!
//! A forged state is a serialized state edited and re-sealed: its checksum (FNV-1a
//! 64 over everything before it, as the FMU's serialize.rs documents) recomputed, so
//! that it is no longer damaged, only wrong. The edits: the time NaN or infinite, the
//! last successful time NaN, a stop time before the time, the terminated flag set,
//! and each scalar Real parameter 1e300 or NaN (found by its bytes after setting it
//! to a value no other field holds). Expected: DeserializeFMUState refuses each with
//! Error and a log line naming the field (issue 20: "every value read from a state
//! passes the same checks as the setters and the model's own checks"); the same
//! bytes re-sealed unedited are accepted (so the sealing is right).
//!
//! Times: with start time 1e308 a step of 1e308 ends at +inf; with start time 1e17
//! a step of 1 ms does not change the time (t + h == t in double precision). Both
//! steps must be refused with Error (issue 20: "a step ... whose end is not finite,
//! or does not advance time, is refused").

use crate::binary::{ERROR, OK};
use crate::description::VarType;
use crate::reentry::api::{Api, Handle};
use crate::reentry::calls::STEP;
use crate::reentry::host::Host;
use crate::reentry::{Outcome, expect, started};

/// One edit of a serialized state.
#[derive(Debug, Clone)]
pub enum Edit {
    /// Payload byte offset (after the writing standard byte), new bytes, the field
    /// the refusal must name.
    At(usize, Vec<u8>, &'static str),
    /// A stop time (defined) one second before the time (and the last successful
    /// time, equal to it after a Co-Simulation step).
    StopBeforeTime,
    /// The scalar Real parameter (value reference, name) set to this value.
    Parameter(u32, String, f64),
}

/// Payload offsets of the layout in the FMU's serialize.rs.
const TIME: usize = 1;
const STOP_FLAG: usize = 9;
const STOP: usize = 10;
const LAST: usize = 18;
const TERMINATED: usize = 26;

/// Every edit for the FMU of `api`, with the case name.
pub fn edits(api: &dyn Api) -> Vec<(String, Edit)> {
    let f = |x: f64| x.to_le_bytes().to_vec();
    let mut all = vec![
        ("time NaN".into(), Edit::At(TIME, f(f64::NAN), "time")),
        ("time +inf".into(), Edit::At(TIME, f(f64::INFINITY), "time")),
        (
            "time -inf".into(),
            Edit::At(TIME, f(f64::NEG_INFINITY), "time"),
        ),
        (
            "last successful time NaN".into(),
            Edit::At(LAST, f(f64::NAN), "last successful time"),
        ),
        ("stop time before the time".into(), Edit::StopBeforeTime),
        (
            "terminated flag set".into(),
            Edit::At(TERMINATED, vec![1], "terminated flag"),
        ),
    ];
    let parameters = api
        .description()
        .of_type(VarType::Real)
        .filter(|v| v.is_parameter() && v.size == 1);
    for v in parameters {
        for x in [1e300, f64::NAN] {
            all.push((
                format!("{} = {x:e}", v.name),
                Edit::Parameter(v.vr, v.name.clone(), x),
            ));
        }
    }
    all
}

/// FNV-1a 64 of `bytes` (the FMU's checksum).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Recomputes the checksum in the last 8 bytes.
fn reseal(bytes: &mut [u8]) {
    let body = bytes.len() - 8;
    let sum = fnv1a(&bytes[..body]);
    bytes[body..].copy_from_slice(&sum.to_le_bytes());
}

/// Where the payload starts: magic (8), version (4), guid length (4), guid, payload
/// length (8).
fn payload_start(bytes: &[u8]) -> usize {
    let guid = u32::from_le_bytes(bytes[12..16].try_into().unwrap_or_default()) as usize;
    16 + guid + 8
}

/// A value of parameter `vr` that no other field of a state holds: set before
/// initialization, so it can be found by its bytes.
fn marker(start: f64) -> f64 {
    start * (1.0 + 1.0 / 1048576.0) + 1.0 / 1073741824.0
}

/// An initialized instance after one step, its state serialized (with the marker
/// value in parameter `marked`, if given, and its name); the instance is returned.
fn serialized(
    api: &dyn Api,
    host: &Host,
    marked: Option<u32>,
) -> Result<(Handle, Vec<u8>, Option<f64>), String> {
    let h = api.instantiate(host);
    if h.is_null() {
        return Err(format!("instantiate refused: {}", host.log_text()));
    }
    host.handle.set(h);
    let mut value = None;
    if let Some(vr) = marked {
        let d = api.description();
        let start = d
            .variables
            .iter()
            .find(|v| v.vr == vr)
            .and_then(|v| v.start.as_ref()?.parse().ok());
        let x = marker(start.unwrap_or(0.0));
        if api.set_real(h, vr, x) == OK {
            value = Some(x);
        }
    }
    expect(api.initialize(h, 0.0), OK, "initialize", host)?;
    expect(api.do_step(h, 0.0, STEP), OK, "a step", host)?;
    let mut state = std::ptr::null_mut();
    expect(api.get_state(h, &mut state), OK, "GetFMUState", host)?;
    let bytes = api
        .serialize(h, state)
        .map_err(|s| format!("serialize returned {s}"))?;
    expect(api.free_state(h, &mut state), OK, "FreeFMUState", host)?;
    Ok((h, bytes, value))
}

/// Applies `edit`; Err when it cannot be made (the parameter's marker not found once),
/// Ok(field the refusal must name).
fn apply(bytes: &mut [u8], edit: &Edit, marker: Option<f64>) -> Result<String, String> {
    let p = payload_start(bytes);
    match edit {
        Edit::At(at, new, field) => {
            bytes[p + at..p + at + new.len()].copy_from_slice(new);
            Ok(field.to_string())
        }
        Edit::StopBeforeTime => {
            let time =
                f64::from_le_bytes(bytes[p + TIME..p + TIME + 8].try_into().unwrap_or_default());
            bytes[p + STOP_FLAG] = 1;
            bytes[p + STOP..p + STOP + 8].copy_from_slice(&(time - 1.0).to_le_bytes());
            // After a Co-Simulation step the last successful time is the time.
            Ok("last successful time".into())
        }
        Edit::Parameter(_, name, x) => {
            let m = marker
                .ok_or("the parameter cannot be set to its marker value")?
                .to_le_bytes();
            // Every copy (the plant starts its state at theta0): the parameter is read
            // first, so the refusal names it.
            let at: Vec<usize> = (p..bytes.len() - 8)
                .filter(|&i| bytes[i..].starts_with(&m))
                .collect();
            if at.is_empty() {
                return Err(format!("the marker value of {name} is not in the state"));
            }
            for i in at {
                bytes[i..i + 8].copy_from_slice(&x.to_le_bytes());
            }
            Ok(name.clone())
        }
    }
}

/// One forged state: refused with Error and a log line naming the field; the same
/// bytes re-sealed without the edit are accepted.
pub fn forged(api: &dyn Api, edit: &Edit) -> Outcome {
    let host = Host::new();
    let marked = match edit {
        Edit::Parameter(vr, ..) => Some(*vr),
        _ => None,
    };
    let (h, mut bytes, value) = serialized(api, &host, marked)?;
    let mut control = bytes.clone();
    reseal(&mut control);
    let (status, mut state) = api.deserialize(h, &control);
    let result = expect(
        status,
        OK,
        "DeserializeFMUState of the unedited state",
        &host,
    )
    .and_then(|()| expect(api.free_state(h, &mut state), OK, "FreeFMUState", &host))
    .and_then(|()| apply(&mut bytes, edit, value));
    let field = match result {
        Ok(field) => field,
        Err(e) => {
            api.free(h);
            return Err(e);
        }
    };
    reseal(&mut bytes);
    let (status, mut state) = api.deserialize(h, &bytes);
    if status == OK {
        api.free_state(h, &mut state);
    }
    api.free(h);
    expect(
        status,
        ERROR,
        "DeserializeFMUState of the forged state",
        &host,
    )?;
    if !host.logged(&format!("\"{field}\"")) {
        return Err(format!(
            "the refusal does not name \"{field}\": {}",
            host.log_text()
        ));
    }
    Ok(format!("Error naming \"{field}\""))
}

/// A step from `start` by `h` must be refused with Error.
fn step_refused(api: &dyn Api, start: f64, h: f64) -> Outcome {
    let host = Host::new();
    let c = match started_at(api, &host, start) {
        Ok(c) => c,
        // Refusing the start time already is as good (no step can be made).
        Err(e) if e.contains("returned 3") => return Ok(format!("start time {start:e} refused")),
        Err(e) => return Err(e),
    };
    let status = api.do_step(c, start, h);
    api.free(c);
    expect(status, ERROR, &format!("DoStep({start:e}, {h:e})"), &host)?;
    Ok(format!("DoStep({start:e}, {h:e}): Error"))
}

fn started_at(api: &dyn Api, host: &Host, start: f64) -> Result<Handle, String> {
    if start == 0.0 {
        return started(api, host);
    }
    let h = api.instantiate(host);
    if h.is_null() {
        return Err(format!("instantiate refused: {}", host.log_text()));
    }
    host.handle.set(h);
    expect(
        api.initialize(h, start),
        OK,
        &format!("initialize at {start:e}"),
        host,
    )?;
    Ok(h)
}

pub fn step_to_infinity(api: &dyn Api) -> Outcome {
    step_refused(api, 1e308, 1e308)
}

pub fn step_that_does_not_advance(api: &dyn Api) -> Outcome {
    step_refused(api, 1e17, 1e-3)
}
