//! Byte format of serialized FMU states (fmi2SerializeFMUstate, fmi3SerializeFMUState),
//! shared by the front-ends.
//!
//! Layout, little endian:
//!   magic "RBFMUST\0" (8) | format version u32 | guid length u32 | guid bytes |
//!   payload length u64 | payload | FNV-1a 64 checksum of everything before it (8)
//! Payload: writing standard u8 (2: FMI 2.0, 3: FMI 3.0) | time f64 |
//!   stop time defined u8 | stop time f64 | last successful time f64 | terminated u8 |
//!   every writable variable in table order (Real f64, Integer i32, Boolean u8) |
//!   per continuous Real input in table order, its derivatives of order
//!   1 ..= `Model::MAX_INPUT_DERIVATIVE_ORDER` (f64 each; nothing for a model that
//!   takes none) |
//!   number of continuous states u32 | states f64... | extra length u64 | extra bytes.
//!
//! The checksum detects damage, not edits (anyone can recompute it), so
//! deserialization trusts nothing it reads: it rebuilds the model from start values
//! and writes every value back through the setters' check ([`value_check::write`]:
//! finite, magnitude, min/max, the writer's own check), reads times that are finite
//! (the last successful one not after the stop time), then runs the model's own checks of
//! ExitInitializationMode and checks the terminated flag against a step (`check_model`).
//! Foreign (other magic, version or model), truncated, padded, corrupted or edited
//! bytes are refused with a message naming the field.

use super::hooks::InputDerivative;
use super::input_derivatives::{interpolated_input, slot};
use super::instance::{Silent, Snapshot, Standard, TIME_MATCH, model_with_start_values};
use super::model::{Model, StepOutcome};
use super::value_check::{self, MAX_MAGNITUDE, Value};
use super::variables::{Kind, Variable};

const MAGIC: &[u8; 8] = b"RBFMUST\0";
/// Version of the layout above; bump it when the layout changes.
pub const FORMAT_VERSION: u32 = 3;

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Serialized bytes of a snapshot.
pub fn serialize<M: Model>(table: &[Variable<M>], s: &Snapshot<M>) -> Vec<u8> {
    let mut payload = vec![s.standard.code()];
    payload.extend_from_slice(&s.time.to_le_bytes());
    payload.push(s.stop_time.is_some() as u8);
    payload.extend_from_slice(&s.stop_time.unwrap_or(0.0).to_le_bytes());
    payload.extend_from_slice(&s.last_successful_time.to_le_bytes());
    payload.push(s.terminated_by_model as u8);
    // Places and input-derivative slots are reached through `&mut`: read a copy.
    let mut model = s.model.clone();
    for v in table {
        match &v.kind {
            Kind::Real {
                get, set: Some(_), ..
            } => payload.extend_from_slice(&get.call(&mut model).to_le_bytes()),
            Kind::Integer {
                get, set: Some(_), ..
            } => payload.extend_from_slice(&get.call(&mut model).to_le_bytes()),
            Kind::Boolean {
                get, set: Some(_), ..
            } => payload.push(get.call(&mut model) as u8),
            _ => {}
        }
    }
    for (_, hook, index, order) in input_derivative_slots(table) {
        let value = slot(&mut model, hook, index, order).copied();
        payload.extend_from_slice(&value.unwrap_or(0.0).to_le_bytes());
    }
    let n = super::model_exchange_calls::states(&model);
    let mut x = vec![0.0; n];
    model.continuous_states(&mut x);
    payload.extend_from_slice(&(n as u32).to_le_bytes());
    for xi in &x {
        payload.extend_from_slice(&xi.to_le_bytes());
    }
    let mut extra = Vec::new();
    s.model.write_extra_state(&mut extra);
    payload.extend_from_slice(&(extra.len() as u64).to_le_bytes());
    payload.extend_from_slice(&extra);

    let guid = M::INFO.guid.as_bytes();
    let mut out = Vec::with_capacity(payload.len() + guid.len() + 40);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(guid.len() as u32).to_le_bytes());
    out.extend_from_slice(guid);
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(&payload);
    let checksum = fnv1a(&out);
    out.extend_from_slice(&checksum.to_le_bytes());
    out
}

/// (value reference, hook, order) of every input derivative a state of M holds.
type Slot<M> = (u32, Option<InputDerivative<M>>, usize, u32);

fn input_derivative_slots<M: Model>(table: &[Variable<M>]) -> Vec<Slot<M>> {
    let orders = 1..=M::MAX_INPUT_DERIVATIVE_ORDER;
    let inputs = table.iter().filter(|v| interpolated_input(v));
    inputs
        .flat_map(|v| {
            let (hook, index) = (v.input_hook(), v.index);
            orders
                .clone()
                .map(move |o| (v.value_reference, hook, index, o))
        })
        .collect()
}

/// Reads fixed-size pieces and fails cleanly at the end of the input.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| format!("truncated FMU state: {what} is missing"))?;
        let piece = &self.bytes[self.at..end];
        self.at = end;
        Ok(piece)
    }
    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], String> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N, what)?);
        Ok(a)
    }
    fn f64(&mut self, what: &str) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.array(what)?))
    }
    fn u32(&mut self, what: &str) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }
    fn u64(&mut self, what: &str) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.array(what)?))
    }
    fn flag(&mut self, what: &str) -> Result<bool, String> {
        match self.array::<1>(what)?[0] {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("corrupt FMU state: {what} has the byte {b}")),
        }
    }
}

/// Parses bytes written by `serialize` for the same model.
pub fn deserialize<M: Model>(table: &[Variable<M>], bytes: &[u8]) -> Result<Snapshot<M>, String> {
    let mut r = Reader { bytes, at: 0 };
    if r.take(8, "the header")? != MAGIC {
        return Err("these bytes are not a serialized robofmu FMU state".to_string());
    }
    let version = r.u32("the format version")?;
    if version != FORMAT_VERSION {
        return Err(format!(
            "FMU state format version {version}, this binary reads version {FORMAT_VERSION}"
        ));
    }
    let guid_len = r.u32("the model id length")? as usize;
    let guid = r.take(guid_len, "the model id")?;
    if guid != M::INFO.guid.as_bytes() {
        return Err(format!(
            "the FMU state belongs to model {}, not to {} ({})",
            String::from_utf8_lossy(guid),
            M::INFO.model_name,
            M::INFO.guid
        ));
    }
    let payload_len = r.u64("the payload length")?;
    let payload_len = usize::try_from(payload_len).map_err(|_| "payload too large")?;
    let payload = r.take(payload_len, "part of the payload")?;
    let body_end = r.at;
    let checksum = r.u64("the checksum")?;
    if r.at != bytes.len() {
        return Err(format!(
            "{} unexpected bytes after the FMU state",
            bytes.len() - r.at
        ));
    }
    if checksum != fnv1a(&bytes[..body_end]) {
        return Err("corrupt FMU state: checksum mismatch".to_string());
    }
    read_payload(table, payload)
}

/// The refusal of a state whose field `field` holds what the model could never be in.
fn refused(field: &str, why: impl std::fmt::Display) -> String {
    format!("FMU state refused: field \"{field}\": {why}")
}

/// Err unless the time `t` read from the field `field` is finite.
fn finite_time(t: f64, field: &str) -> Result<f64, String> {
    if t.is_finite() {
        Ok(t)
    } else {
        Err(refused(field, format!("{t} is not a finite time")))
    }
}

/// The times of a state: finite, and the last successful time not after the stop
/// time (the layer refuses steps beyond it; the time itself may be, in Model
/// Exchange, where an integrator evaluates past the stop time).
fn read_times(r: &mut Reader) -> Result<(f64, Option<f64>, f64), String> {
    let time = finite_time(r.f64("time")?, "time")?;
    let stop_defined = r.flag("stop time flag")?;
    let stop = r.f64("stop time")?;
    let stop_time = match stop_defined {
        true => Some(finite_time(stop, "stop time")?),
        false => None,
    };
    let last = finite_time(r.f64("last successful time")?, "last successful time")?;
    if let Some(stop) = stop_time {
        let slack = TIME_MATCH * stop.abs().max(1.0);
        if last > stop + slack {
            let why = format!("{last} s is after the stop time {stop} s");
            return Err(refused("last successful time", why));
        }
    }
    Ok((time, stop_time, last))
}

/// Every settable variable of the table read from `r` and written to `model` through
/// the setters' check ([`value_check::write`]).
fn read_values<M: Model>(
    table: &[Variable<M>],
    r: &mut Reader,
    model: &mut M,
) -> Result<(), String> {
    for v in table {
        let name = &v.name();
        let value = match &v.kind {
            Kind::Real { set: Some(_), .. } => Value::Real(r.f64(name)?),
            Kind::Integer { set: Some(_), .. } => {
                Value::Integer(i32::from_le_bytes(r.array(name)?))
            }
            Kind::Boolean { set: Some(_), .. } => Value::Boolean(r.flag(name)?),
            _ => continue,
        };
        value_check::write(model, v.declaration, v.index, v.value_reference, value)
            .map_err(|e| refused(name, e))?;
    }
    Ok(())
}

/// The model's own checks of a restored model: its parameters pass the checks of
/// ExitInitializationMode, and a state that says the model terminated it is one from
/// which a step is refused for good.
fn check_model<M: Model>(model: &M, time: f64, terminated: bool) -> Result<(), String> {
    model
        .clone()
        .exit_initialization(&Silent)
        .map_err(|e| refused("parameters", format!("the model refuses them: {e}")))?;
    if terminated {
        let h = M::INFO.default_experiment.step_size;
        let step = model.clone().do_step(time, h, &Silent);
        if !matches!(
            step,
            StepOutcome::Discarded {
                terminate: true,
                ..
            }
        ) {
            return Err(refused(
                "terminated flag",
                "set, but the model can go on from this state",
            ));
        }
    }
    Ok(())
}

fn read_payload<M: Model>(table: &[Variable<M>], payload: &[u8]) -> Result<Snapshot<M>, String> {
    let mut r = Reader {
        bytes: payload,
        at: 0,
    };
    let code = r.array::<1>("the writing standard")?[0];
    let standard = Standard::from_code(code)
        .ok_or_else(|| format!("corrupt FMU state: unknown writing standard {code}"))?;
    let (time, stop_time, last_successful_time) = read_times(&mut r)?;
    let terminated_by_model = r.flag("terminated flag")?;
    let mut model = model_with_start_values::<M>(table)?;
    read_values(table, &mut r, &mut model)?;
    for (vr, hook, index, order) in input_derivative_slots(table) {
        let value = r.f64("an input derivative")?;
        if value == 0.0 {
            continue; // a fresh model holds zeros
        }
        match slot(&mut model, hook, index, order) {
            Some(slot) if value.is_finite() && value.abs() <= MAX_MAGNITUDE => *slot = value,
            _ => {
                return Err(refused(
                    "input derivative",
                    format!("order {order} of value reference {vr} = {value}"),
                ));
            }
        }
    }
    let n = r.u32("number of states")? as usize;
    let states = super::model_exchange_calls::states(&model);
    if n != states {
        return Err(format!(
            "FMU state has {n} continuous states, the model {states}"
        ));
    }
    let x = (0..n)
        .map(|_| r.f64("a continuous state"))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(bad) = x.iter().find(|v| !v.is_finite()) {
        return Err(refused("continuous states", format!("contains {bad}")));
    }
    model.set_continuous_states(&x);
    let extra_len = usize::try_from(r.u64("extra length")?).map_err(|_| "extra too large")?;
    let extra = r.take(extra_len, "model-specific state")?;
    model.read_extra_state(extra)?;
    if r.at != payload.len() {
        return Err("corrupt FMU state: payload longer than the model's state".to_string());
    }
    model.set_time(time);
    check_model(&model, time, terminated_by_model)?;
    Ok(Snapshot {
        model,
        time,
        stop_time,
        last_successful_time,
        terminated_by_model,
        standard,
    })
}
