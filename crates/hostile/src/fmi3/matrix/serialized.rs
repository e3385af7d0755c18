//! Serialized FMU states with every byte flipped, every truncation and one byte
//! too many (the variants of `crate::matrix::serialized::damaged`), given to
//! fmi3DeserializeFMUState. FMI 3.0 (section 2.2.9) requires only that an FMU reads
//! back what it serialized; the project's format carries a magic, a version, the
//! instantiation token, the lengths and a checksum, so each variant is refused with
//! fmi3Error and a log line about the FMU state, and the instance recovers with
//! fmi3Reset. The unmodified bytes are the control: they restore the outputs bit
//! for bit.

use super::{Case, Observed};
use crate::Loaded;
use crate::binary::{OK, status_name};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::matrix::Expect;
use crate::matrix::serialized::{damaged, damaged_case, in_child};

const WHY_DAMAGED: &str = "damaged serialized state: refused with fmi3Error and a log line (project format with magic, version, token, lengths and checksum); fmi3Reset recovers";
const WHY_CONTROL: &str = "FMI 3.0 2.2.9: an FMU reads back its own serialized state; restored outputs are bit for bit those at serialization";

/// The state a reference instance is in when its state is serialized (after a step
/// in Co-Simulation).
pub(crate) fn reference_state(interface: Interface3) -> State3 {
    match interface {
        Interface3::ModelExchange => State3::EventMode,
        _ => State3::StepMode,
    }
}

/// Reference bytes and outputs of model `m`, computed in a child.
pub(crate) fn reference(l: &Loaded, m: usize, interface: Interface3) -> (Vec<u8>, Vec<u64>) {
    in_child(m, &|| {
        let inst = Instance::new(&l.binaries3[m], &l.fmus3[m].description, interface);
        inst.reach(reference_state(interface))
            .unwrap_or_else(|e| panic!("{e}"));
        if !interface.is_me() {
            let s = inst.do_step(0.0, 1e-3).status;
            assert_eq!(s, OK, "{}", inst.take_log());
        }
        let (_, state) = inst.get_state();
        let bytes = inst.serialize(state).unwrap_or_else(|e| panic!("{e}"));
        let (_, outputs) = inst.get_all();
        inst.free_state(state);
        (bytes, outputs)
    })
}

/// Deserializes `bytes` into a fresh instance in the reference state, sets the
/// state and compares the outputs with `outputs` (bits).
pub(crate) fn restore(
    l: &Loaded,
    m: usize,
    to: Interface3,
    bytes: &[u8],
    outputs: &[u64],
) -> Observed {
    let inst = Instance::new(&l.binaries3[m], &l.fmus3[m].description, to);
    if let Err(e) = inst.reach(reference_state(to)) {
        return Observed::broken(e);
    }
    let (s, state) = inst.deserialize(bytes);
    if s != OK {
        return Observed::of(s, inst.take_log());
    }
    // SAFETY: a state this instance just deserialized.
    let s = unsafe { (inst.binary.set_fmu_state)(inst.c, state) };
    inst.free_state(state);
    let (g, values) = inst.get_all();
    let same = values
        .iter()
        .map(|x| x.to_bits())
        .eq(outputs.iter().copied());
    if s != OK || g != OK || !same {
        return Observed::broken(format!(
            "set returned {}, get {}, outputs equal: {same} ({})",
            status_name(s),
            status_name(g),
            inst.take_log()
        ));
    }
    Observed::of(OK, inst.take_log())
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for interface in Interface3::ALL {
        let (bytes, outputs) = reference(loaded, m, interface);
        assert!(!bytes.is_empty(), "empty reference state");
        let (control, expected) = (bytes.clone(), outputs.clone());
        cases.push(Case {
            class: "fmi3 serialized state",
            model: m,
            interface: Some(interface.short()),
            name: "unmodified bytes restore the outputs bit for bit".into(),
            expect: Expect::ok(),
            why: WHY_CONTROL,
            probe: Box::new(move |l| restore(l, m, interface, &control, &expected)),
        });
        for (name, variant) in damaged(&bytes) {
            cases.push(damaged_case(
                (m, interface, reference_state(interface)),
                ("fmi3 serialized state", WHY_DAMAGED),
                name,
                variant,
            ));
        }
    }
    cases
}
