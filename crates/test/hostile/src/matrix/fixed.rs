//! Every fixed parameter set again after initialization, in each state where its
//! setter is legal, once to the value it holds (its start value: nothing set it
//! before initialization) and once to a different one (-0.0 for 0.0, one ulp off
//! otherwise, the next integer, the other boolean; FMI 3.0: in the first element of
//! an array). The standards let a fixed parameter change only before initialization
//! ends (FMI 2.0 2.2.7, FMI 3.0 2.4.7.4) and leave a set after it to the FMU.
//! Project choice (issue 45, docs/reliability.md "A fixed parameter set again"): the
//! value it holds, bit for bit, is accepted without effect with Warning and a log
//! line (importers such as gemseo-fmu set every variable of a study again in step
//! mode); a different value is refused with Error naming the variable.

use super::seam::{Standard, Value};
use super::{Case, Expect, on_instance};
use crate::Loaded;
use crate::binary::WARNING;
use crate::description::{VarType, Variable};

const WHY_SAME: &str = "issue 45: a fixed parameter set after initialization to the value it holds, bit for bit, is accepted without effect: Warning and a log line naming it and the rule";
const WHY_CHANGED: &str = "FMI 2.0 2.2.7 / FMI 3.0 2.4.7.4: a fixed parameter cannot change after initialization; a different value (-0.0 differs from 0.0) is refused with Error naming it";

/// The start value of the first element of `v`, as the matrix sets it.
fn start(v: &Variable) -> Value {
    let first = v.start.as_deref().and_then(|s| s.split_whitespace().next());
    match v.var_type {
        VarType::Real => Value::Real(first.and_then(|s| s.parse().ok()).unwrap_or(0.0)),
        VarType::Integer => Value::Integer(first.and_then(|s| s.parse().ok()).unwrap_or(0)),
        VarType::Boolean => Value::Boolean(i32::from(first == Some("true"))),
    }
}

/// A value that differs from `value` bit for bit.
fn different(value: Value) -> Value {
    match value {
        Value::Real(x) if x.to_bits() == 0 => Value::Real(-0.0),
        Value::Real(x) => Value::Real(f64::from_bits(x.to_bits() + 1)),
        Value::Integer(n) => Value::Integer(n.wrapping_add(1)),
        Value::Boolean(b) => Value::Boolean(1 - b),
    }
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = I::description(loaded, m);
    let tables = I::tables();
    let fixed = d
        .variables
        .iter()
        .filter(|v| v.is_parameter() && v.variability == "fixed");
    let mut cases = Vec::new();
    for v in fixed {
        for &interface in I::INTERFACES {
            for &state in (tables.setter_states)(v.var_type) {
                if !interface.reachable(loaded, m, state) {
                    continue;
                }
                let quoted = format!("\"{}\" (causality parameter, variability fixed)", v.name);
                let same = start(v);
                let rows = [
                    (
                        "unchanged",
                        same,
                        Expect {
                            statuses: &[WARNING],
                            log: Some(format!(
                                "{quoted} set in {state:?} to the value it holds: accepted \
                                 without effect"
                            )),
                        },
                        WHY_SAME,
                    ),
                    (
                        "changed",
                        different(same),
                        Expect::error(&format!("{quoted} cannot be set in {state:?}")),
                        WHY_CHANGED,
                    ),
                ];
                for (label, value, expect, why) in rows {
                    let var = v.clone();
                    cases.push(Case::new(
                        ("fixed parameter", m, interface),
                        format!(
                            "{} {label} ({}) in {state:?}",
                            v.name,
                            value.label(tables.values.types)
                        ),
                        (expect, why),
                        move |l| {
                            on_instance(l, m, interface, state, |i| I::set_value(i, &var, value))
                        },
                    ));
                }
            }
        }
    }
    cases
}
