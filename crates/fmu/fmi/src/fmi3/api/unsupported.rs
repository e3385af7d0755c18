//! The functions of FMI 3.0 for what no model of this layer has: variables of the
//! types Float32, (U)Int8/16/64, UInt32, String and Binary, structural parameters
//! (Configuration Mode) and Scheduled Execution (clocks: module `clocks`). Each checks its
//! arguments and the state like the supported ones, then answers fmi3Error with a log
//! line that says what is missing (an empty request is fmi3OK).

use super::{input_slice, with_instance};
use crate::core::model::Model;
use crate::fmi3::mode::Call;
use crate::fmi3::table::type_name;
use crate::fmi3::types::*;

/// Why the value reference `vr` cannot be accessed as `type_name`.
fn no_variable_of_type<M: Model>(
    inst: &crate::fmi3::instance::Instance<M>,
    vr: u32,
    wanted: &str,
) -> String {
    match inst.extra.table.find(vr) {
        Some(v) => format!(
            "\"{}\" (value reference {vr}) is a {} variable, not {wanted}",
            v.name,
            type_name(v.variable_type)
        ),
        None => format!("unknown value reference {vr}"),
    }
}

/// `fmi3Get<Type>` / `fmi3Set<Type>` for a type no variable has.
pub unsafe fn access_unsupported_type<M: Model>(
    c: Fmi3Instance,
    function: &str,
    call: Call,
    wanted: &str,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values_null: bool,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, call, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            if nvr > 0 && values_null {
                return Err("values[] is a null pointer".to_string());
            }
            match vrs.first() {
                Some(&r) => Err(no_variable_of_type(inst, r, wanted)),
                None => Ok(Fmi3Status::Ok),
            }
        })
    }
}

/// A function of a capability the FMU does not have (the state check still comes
/// first, so a call in a state where it could never be legal says so).
pub unsafe fn unsupported<M: Model>(c: Fmi3Instance, function: &str, what: &str) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, Call::Unsupported, |_| {
            Err(format!("{} has no {what}", M::INFO.model_name))
        })
    }
}
