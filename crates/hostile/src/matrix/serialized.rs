//! Serialized FMU states with every byte flipped, every truncation and one byte
//! too many. FMI 2.0 (section 2.1.8) requires only that an FMU can read back what
//! it serialized; the project's format carries a magic, a version, the GUID, the
//! lengths and a checksum, so each of these is refused with fmi2Error and a log
//! line about the FMU state. The unmodified bytes are the control: they restore
//! the outputs bit for bit.

use super::{Case, Expect, Observed, on_instance};
use crate::Loaded;
use crate::binary::{FmuState, OK, status_name};
use crate::host::{Instance, Interface, Probed, State, unlogged};
use crate::isolate;
use crate::standard_interface::StandardInterface;
use std::ffi::c_char;

const WHY_DAMAGED: &str = "damaged serialized state: refused with fmi2Error and a log line (project format with magic, version, GUID, lengths and checksum)";
const WHY_CONTROL: &str = "FMI 2.0 2.1.8: an FMU reads back its own serialized state; restored outputs are bit for bit those at serialization";

/// The state a reference instance is in when its state is serialized.
pub(crate) fn reference_state(interface: Interface) -> State {
    match interface {
        Interface::ModelExchange => State::EventMode,
        Interface::CoSimulation => State::StepComplete,
    }
}

/// Reference bytes and outputs, computed in a child (the parent never calls an FMU).
pub(crate) fn reference(loaded: &Loaded, m: usize, interface: Interface) -> (Vec<u8>, Vec<u64>) {
    in_child(m, &|| {
        let inst = Instance::new(&loaded.binaries[m], &loaded.fmus[m].description, interface);
        inst.reach(reference_state(interface))
            .unwrap_or_else(|e| panic!("{e}"));
        if interface == Interface::CoSimulation {
            assert_eq!(inst.do_step(0.0, 1e-3), OK, "{}", inst.take_log());
        }
        let (_, state) = inst.get_state();
        let bytes = inst.serialize(state).unwrap_or_else(|e| panic!("{e}"));
        let (_, outputs) = inst.get_reals(&inst.description.real_vrs());
        inst.free_state(state);
        (bytes, outputs)
    })
}

/// Runs `make` (serialized bytes and outputs of a reference instance) in a forked
/// child and returns the bytes and the outputs' bits (shared with FMI 3.0).
pub(crate) fn in_child(m: usize, make: &dyn Fn() -> (Vec<u8>, Vec<f64>)) -> (Vec<u8>, Vec<u64>) {
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

pub(crate) fn deserialize(inst: &Instance, bytes: &[u8]) -> (crate::binary::Status, FmuState) {
    let mut state: FmuState = std::ptr::null_mut();
    // SAFETY: a buffer of the given length and a null slot for a new state.
    let s = unsafe {
        (inst.binary.deserialize)(
            inst.c,
            bytes.as_ptr() as *const c_char,
            bytes.len(),
            &mut state,
        )
    };
    (s, state)
}

/// A damaged serialized state deserialized into an instance of `interface` in
/// `state`: refused with an error and a log line about the FMU state (both
/// standards).
pub(crate) fn damaged_case<I: StandardInterface>(
    (m, interface, state): (usize, I, I::State),
    (class, why): (&'static str, &'static str),
    name: String,
    bytes: Vec<u8>,
) -> Case {
    Case {
        class,
        model: m,
        interface: Some(interface.short()),
        name,
        expect: Expect::error("FMU state"),
        why,
        probe: Box::new(move |l| {
            on_instance(l, m, interface, state, |inst| {
                let (s, state) = I::deserialize(inst, &bytes);
                if !state.is_null() && s == OK {
                    unlogged(inst, || inst.release_state(state));
                }
                s
            })
        }),
    }
}

fn control_case(m: usize, interface: Interface, bytes: Vec<u8>, outputs: Vec<u64>) -> Case {
    Case {
        class: "serialized state",
        model: m,
        interface: Some(interface.short()),
        name: "unmodified bytes restore the outputs bit for bit".into(),
        expect: Expect::ok(),
        why: WHY_CONTROL,
        probe: Box::new(move |l| {
            let inst = Instance::new(&l.binaries[m], &l.fmus[m].description, interface);
            if let Err(e) = inst.reach(reference_state(interface)) {
                return Observed::broken(e);
            }
            let (s, state) = deserialize(&inst, &bytes);
            if s != OK {
                return Observed::of(s, inst.take_log());
            }
            // SAFETY: a state this instance just deserialized.
            let s = unsafe { (inst.binary.set_fmu_state)(inst.c, state) };
            inst.free_state(state);
            let (g, values) = inst.get_reals(&inst.description.real_vrs());
            let bits: Vec<u64> = values.iter().map(|x| x.to_bits()).collect();
            if s != OK || g != OK || bits != outputs {
                return Observed::broken(format!(
                    "set returned {}, get {}, outputs equal: {} ({})",
                    status_name(s),
                    status_name(g),
                    bits == outputs,
                    inst.take_log()
                ));
            }
            Observed::of(OK, inst.take_log())
        }),
    }
}

/// The damaged variants of serialized bytes: every byte flipped, every truncation
/// and one byte appended, each with its name (shared with the FMI 3.0 matrix).
pub(crate) fn damaged(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
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

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for interface in Interface::BOTH {
        let (bytes, outputs) = reference(loaded, m, interface);
        assert!(!bytes.is_empty(), "empty reference state");
        cases.push(control_case(m, interface, bytes.clone(), outputs));
        for (name, variant) in damaged(&bytes) {
            cases.push(damaged_case(
                (m, interface, reference_state(interface)),
                ("serialized state", WHY_DAMAGED),
                name,
                variant,
            ));
        }
    }
    cases
}
