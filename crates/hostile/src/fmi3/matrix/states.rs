//! FMU states the FMU never issued: a zeroed and a random block owned by the
//! importer, a state already freed, another FMU's state and the instance handle
//! itself, passed to every FMI 3.0 function that takes a state. FMI 3.0 leaves
//! this undefined; the layer checks a registry of live states and answers
//! fmi3Error with a log line, and the instance recovers with fmi3Reset.
//!
//! A live state of another instance of the same FMU is accepted (the project's
//! documented choice, fmus/pid/tests/handles.rs); so is one of an FMI 2.0 instance
//! of the same FMU in the same binary (the model state is the same), and the
//! outputs are then the FMI 2.0 instance's, bit for bit. Also: the serialized
//! state of each interface restores an instance of each other interface of the
//! same FMU, outputs bit for bit.

use super::serialized::{reference, reference_state, restore};
use super::{Case, Observed};
use crate::Loaded;
use crate::binary::{Binary, OK};
use crate::fmi3::host::{Instance, Interface3};
use crate::host::{Instance as Instance2, Interface};
use crate::matrix::Expect;
use crate::matrix::bad_states::{self, BadStateClass};

const WHY_BAD: &str = "FMU state not issued by this FMU or already freed: undefined in FMI 3.0; fmi3Error and a log line after a registry check; fmi3Reset recovers";
const BAD: BadStateClass = BadStateClass {
    class: "fmi3 bad FMU state",
    why: WHY_BAD,
    seed: 0xbad3,
};
const WHY_FMI2: &str = "live FMU state of an FMI 2.0 instance of the same FMU: accepted like one of another instance (project choice, fmus/pid/tests/handles.rs); outputs those of the FMI 2.0 instance, bit for bit";
const WHY_CROSS: &str = "the serialized state of one interface restores an instance of another interface of the same FMU (project choice: the model state is the same); outputs bit for bit";

type Use = bad_states::Use<Interface3>;

fn uses() -> [(&'static str, Use); 5] {
    [
        ("fmi3SetFMUState", |i, s| unsafe {
            (i.binary.set_fmu_state)(i.c, s)
        }),
        ("fmi3FreeFMUState", |i, s| i.free_state(s)),
        ("fmi3SerializedFMUStateSize", |i, s| unsafe {
            (i.binary.serialized_size)(i.c, s, &mut 0)
        }),
        ("fmi3SerializeFMUState", |i, s| unsafe {
            let mut bytes = vec![0u8; 256];
            (i.binary.serialize)(i.c, s, bytes.as_mut_ptr(), bytes.len())
        }),
        ("fmi3GetFMUState(slot holding it)", |i, s| {
            let mut slot = s;
            unsafe { (i.binary.get_fmu_state)(i.c, &mut slot) }
        }),
    ]
}

/// An FMI 2.0 CS instance of model `m` in the FMU's own binary, one step taken;
/// its state set into an FMI 3.0 instance; outputs compared by variable name
/// (FMI 2.0 names elements "theta[1]", FMI 3.0 reads the array "theta").
fn fmi2_state(l: &Loaded, m: usize, interface: Interface3) -> Observed {
    let fmi2 = match Binary::open(&l.fmus3[m].library) {
        Ok(b) => b,
        Err(e) => return Observed::broken(e),
    };
    let d2 = &l.fmus[m].description;
    let source = Instance2::new(&fmi2, d2, Interface::CoSimulation);
    if let Err(e) = source.reach(crate::host::State::StepComplete) {
        return Observed::broken(e);
    }
    if source.do_step(0.0, 1e-3) != OK {
        return Observed::broken(format!("fmi2DoStep: {}", source.take_log()));
    }
    let (_, state) = source.get_state();
    let inst = Instance::new(&l.binaries3[m], &l.fmus3[m].description, interface);
    if let Err(e) = inst.reach(crate::fmi3::host::State3::InitializationMode) {
        return Observed::broken(e);
    }
    // SAFETY: a live state of the same model (the probe's point).
    let status = unsafe { (inst.binary.set_fmu_state)(inst.c, state) };
    let log = inst.take_log();
    source.free_state(state);
    if status != OK {
        return Observed::of(status, log);
    }
    let mut compared = 0;
    for v in inst.description.of_type(crate::description::VarType::Real) {
        if v.causality == "independent" {
            continue;
        }
        let (s, x) = inst.get_float64(&[v.vr]);
        if s != OK {
            return Observed::broken(format!(
                "fmi3GetFloat64({}) after the restore: {}",
                v.name,
                crate::binary::status_name(s)
            ));
        }
        for (k, value) in x.iter().enumerate() {
            let name = if v.size > 1 {
                format!("{}[{}]", v.name, k + 1)
            } else {
                v.name.clone()
            };
            let Some(v2) = d2.variables.iter().find(|w| w.name == name) else {
                continue;
            };
            let (_, y) = source.get_reals(&[v2.vr]);
            compared += 1;
            if value.to_bits() != y[0].to_bits() {
                return Observed::broken(format!(
                    "{name}: {value} after the restore, {} in the FMI 2.0 instance",
                    y[0]
                ));
            }
        }
    }
    if compared == 0 {
        return Observed::broken("no Float64 element matched an FMI 2.0 variable by name".into());
    }
    Observed::of(status, log)
}

pub fn cases(l: &Loaded, m: usize) -> Vec<Case> {
    let mut cases = bad_states::cases::<Interface3>(m, &BAD, &uses());
    for interface in Interface3::ALL {
        cases.push(Case {
            class: "fmi3 cross-standard state",
            model: m,
            interface: Some(interface.short()),
            name: "fmi3SetFMUState(live state of an FMI 2.0 instance of this FMU)".into(),
            expect: Expect::ok(),
            why: WHY_FMI2,
            probe: Box::new(move |l| fmi2_state(l, m, interface)),
        });
    }
    for from in Interface3::ALL {
        let (bytes, outputs) = reference(l, m, from);
        for to in Interface3::ALL {
            if to == from {
                continue;
            }
            let (bytes, outputs) = (bytes.clone(), outputs.clone());
            cases.push(Case {
                class: "fmi3 cross-interface state",
                model: m,
                interface: Some(to.short()),
                name: format!(
                    "state serialized by a {} instance in {:?}",
                    from.short(),
                    reference_state(from)
                ),
                expect: Expect::ok(),
                why: WHY_CROSS,
                probe: Box::new(move |l| restore(l, m, to, &bytes, &outputs)),
            });
        }
    }
    cases
}
