//! Serialized FMU states with every byte flipped, every truncation and one byte
//! too many, given to fmiXDeserializeFMUState. Both standards (FMI 2.0 2.1.8,
//! FMI 3.0 2.2.9) require only that an FMU reads back what it serialized; the
//! project's format carries a magic, a version, the GUID (instantiation token),
//! the lengths and a checksum, so each variant is refused with an error and a log
//! line about the FMU state, and the instance stays usable as its standard
//! requires. The unmodified bytes are the control: they restore the outputs bit
//! for bit.

use super::seam::Standard;
use super::{Case, Expect, Observed, on_instance};
use crate::Loaded;
use crate::binary::{OK, status_name};
use crate::host::{Probed, take, unlogged};
use crate::isolate;

/// Reference bytes and outputs (bits) of model `m` with `interface`, computed in
/// a child (the parent never calls an FMU): the instance in its reference state
/// (after one step in Co-Simulation).
pub(crate) fn reference<I: Standard>(l: &Loaded, m: usize, interface: I) -> (Vec<u8>, Vec<u64>) {
    in_child(m, &|| {
        let inst = interface.instance(l, m);
        I::reach(&inst, interface.reference_state()).unwrap_or_else(|e| panic!("{e}"));
        if !interface.is_me() {
            assert_eq!(I::do_step(&inst, 0.0, 1e-3), OK, "{}", take(inst.log()));
        }
        let (_, state) = inst.new_state();
        let bytes = I::serialize(&inst, state).unwrap_or_else(|e| panic!("{e}"));
        let (_, outputs) = I::outputs(&inst);
        inst.release_state(state);
        (bytes, outputs)
    })
}

/// Runs `make` (serialized bytes and outputs of a reference instance) in a forked
/// child and returns the bytes and the outputs' bits.
fn in_child(m: usize, make: &dyn Fn() -> (Vec<u8>, Vec<f64>)) -> (Vec<u8>, Vec<u64>) {
    let text = isolate::run_one(&|| {
        let (bytes, outputs) = make();
        let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
        let bits: Vec<String> = outputs.iter().map(|x| x.to_bits().to_string()).collect();
        format!("{hex} {}", bits.join(","))
    })
    .unwrap_or_else(|e| panic!("reference state of model {m}: {e}"));
    let (hex, bits) = text.split_once(' ').unwrap_or((&text, ""));
    let bytes = (0..hex.len() / 2)
        .map(|i| u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).unwrap_or(0))
        .collect();
    let outputs = bits.split(',').filter_map(|b| b.parse().ok()).collect();
    (bytes, outputs)
}

/// Deserializes `bytes` into a fresh instance of `to` in its reference state,
/// sets the state and compares the outputs with `outputs` (bits).
pub(crate) fn restore<I: Standard>(
    l: &Loaded,
    m: usize,
    to: I,
    bytes: &[u8],
    outputs: &[u64],
) -> Observed {
    let inst = to.instance(l, m);
    if let Err(e) = I::reach(&inst, to.reference_state()) {
        return Observed::broken(e);
    }
    let (s, state) = I::deserialize(&inst, bytes);
    if s != OK {
        return Observed::of(s, take(inst.log()));
    }
    // SAFETY: a state this instance just deserialized.
    let s = unsafe { I::set_state(&inst, state) };
    inst.release_state(state);
    let (g, values) = I::outputs(&inst);
    let same = values
        .iter()
        .map(|x| x.to_bits())
        .eq(outputs.iter().copied());
    if s != OK || g != OK || !same {
        return Observed::broken(format!(
            "set returned {}, get {}, outputs equal: {same} ({})",
            status_name(s),
            status_name(g),
            take(inst.log())
        ));
    }
    Observed::of(OK, take(inst.log()))
}

/// A damaged serialized state deserialized into an instance of `interface` in
/// its reference state: refused with an error and a log line about the FMU state.
fn damaged_case<I: Standard>(m: usize, interface: I, name: String, bytes: Vec<u8>) -> Case {
    let why = I::tables().reasons.damaged;
    Case::new(
        ("serialized state", m, interface),
        name,
        (Expect::error("FMU state"), why),
        move |l| {
            on_instance(l, m, interface, interface.reference_state(), |inst| {
                let (s, state) = I::deserialize(inst, &bytes);
                if !state.is_null() && s == OK {
                    unlogged(inst, || inst.release_state(state));
                }
                s
            })
        },
    )
}

/// The damaged variants of serialized bytes: every byte flipped, every truncation
/// and one byte appended, each with its name.
fn damaged(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let n = bytes.len();
    let mut variants = Vec::with_capacity(2 * n + 1);
    for i in 0..n {
        let mut flipped = bytes.to_vec();
        flipped[i] ^= 0xff;
        variants.push((format!("byte {i} of {n} flipped"), flipped));
    }
    for len in 0..n {
        variants.push((
            format!("truncated to {len} of {n} bytes"),
            bytes[..len].to_vec(),
        ));
    }
    let mut longer = bytes.to_vec();
    longer.push(0);
    variants.push(("one byte appended".into(), longer));
    variants
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        let (bytes, outputs) = reference(loaded, m, interface);
        assert!(!bytes.is_empty(), "empty reference state");
        let control = bytes.clone();
        cases.push(Case::new(
            ("serialized state", m, interface),
            "unmodified bytes restore the outputs bit for bit".into(),
            (Expect::ok(), I::tables().reasons.control),
            move |l| restore(l, m, interface, &control, &outputs),
        ));
        for (name, variant) in damaged(&bytes) {
            cases.push(damaged_case(m, interface, name, variant));
        }
    }
    cases
}
