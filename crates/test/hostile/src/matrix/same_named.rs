//! Rows of the standards' tables whose calls read the same in FMI 2.0 and FMI 3.0,
//! because the two function tables (`binary::Binary`, `fmi3::binary::Binary3`)
//! and instances name the FMU-state and Model Exchange functions alike
//! (`get_fmu_state`, `serialize`, `get_continuous_states`, ...) and take the same
//! arguments but for the byte type of a serialized state. Each macro is expanded
//! in the standard's table with its spelling of the function names: the prefix
//! ("fmi2"), the noun ("FMUstate") and the deserializer's verb ("DeSerialize");
//! the rows, their order and their names are those the tables had when they were
//! written per standard.

/// The null-pointer rows of the six FMU-state functions, each in `$applies`'s
/// state, as a `Vec<seam::Row<_>>`.
macro_rules! fmu_state_null_rows {
    ($prefix:literal, $noun:literal, $de:literal, $byte:ty, $applies:expr) => {
        vec![
            (
                concat!($prefix, "Get", $noun, "(", $noun, "=null)"),
                $applies,
                |b, c, _| unsafe { (b.get_fmu_state)(c, null_mut()) },
            ),
            (
                concat!($prefix, "Free", $noun, "(", $noun, "=null)"),
                $applies,
                |b, c, _| unsafe { (b.free_fmu_state)(c, null_mut()) },
            ),
            (
                concat!($prefix, "Set", $noun, "(", $noun, "=null)"),
                $applies,
                |b, c, _| unsafe { (b.set_fmu_state)(c, null_mut()) },
            ),
            (
                concat!($prefix, "Serialized", $noun, "Size(", $noun, "=null)"),
                $applies,
                |b, c, _| unsafe { (b.serialized_size)(c, null_mut(), &mut 0) },
            ),
            (
                concat!($prefix, "Serialized", $noun, "Size(size=null)"),
                $applies,
                |b, c, a| unsafe { (b.serialized_size)(c, a.state, null_mut()) },
            ),
            (
                concat!($prefix, "Serialize", $noun, "(", $noun, "=null)"),
                $applies,
                |b, c, _| unsafe {
                    let mut bytes = [0 as $byte; 16];
                    (b.serialize)(c, null_mut(), bytes.as_mut_ptr(), 16)
                },
            ),
            (
                concat!($prefix, "Serialize", $noun, "(serializedState=null)"),
                $applies,
                |b, c, a| unsafe {
                    let mut n = 0usize;
                    (b.serialized_size)(c, a.state, &mut n);
                    (b.serialize)(c, a.state, null_mut(), n)
                },
            ),
            (
                concat!($prefix, $de, $noun, "(serializedState=null, size=64)"),
                $applies,
                |b, c, _| unsafe {
                    let mut s: FmuState = null_mut();
                    (b.deserialize)(c, null(), 64, &mut s)
                },
            ),
            (
                concat!($prefix, $de, $noun, "(", $noun, "=null)"),
                $applies,
                |b, c, a| unsafe {
                    let mut n = 0usize;
                    (b.serialized_size)(c, a.state, &mut n);
                    let mut bytes = vec![0 as $byte; n];
                    (b.serialize)(c, a.state, bytes.as_mut_ptr(), n);
                    (b.deserialize)(c, bytes.as_ptr(), n, null_mut())
                },
            ),
        ]
    };
}
pub(crate) use fmu_state_null_rows;

/// The null-pointer rows of the Model Exchange functions that write or read the
/// continuous states: fmiXCompletedIntegratorStep (both flags), the states, the
/// derivatives (`$derivatives` names the getter and its argument), the nominals
/// (`$nominals` names the argument) and the event indicators, in the states of
/// `seam_rows::me_continuous` and its variants.
macro_rules! model_exchange_null_rows {
    ($prefix:literal, $derivatives:literal, $nominals:literal, $get_derivatives:ident) => {
        vec![
            (
                concat!($prefix, "CompletedIntegratorStep(enterEventMode=null)"),
                me_continuous,
                |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, null_mut(), &mut 0) },
            ),
            (
                concat!($prefix, "CompletedIntegratorStep(terminateSimulation=null)"),
                me_continuous,
                |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, &mut 0, null_mut()) },
            ),
            (
                concat!($prefix, "SetContinuousStates(x=null)"),
                me_with_states,
                |b, c, a| unsafe { (b.set_continuous_states)(c, null(), a.nx) },
            ),
            (
                concat!($prefix, "GetContinuousStates(x=null)"),
                me_with_states,
                |b, c, a| unsafe { (b.get_continuous_states)(c, null_mut(), a.nx) },
            ),
            (
                concat!($prefix, $derivatives, "=null)"),
                me_with_states,
                |b, c, a| unsafe { (b.$get_derivatives)(c, null_mut(), a.nx) },
            ),
            (
                concat!(
                    $prefix,
                    "GetNominalsOfContinuousStates(",
                    $nominals,
                    "=null)"
                ),
                me_with_states,
                |b, c, a| unsafe { (b.get_nominals)(c, null_mut(), a.nx) },
            ),
            (
                concat!($prefix, "GetEventIndicators(eventIndicators=null)"),
                me_with_indicators,
                |b, c, a| unsafe { (b.get_event_indicators)(c, null_mut(), a.nz) },
            ),
        ]
    };
}
pub(crate) use model_exchange_null_rows;

/// The functions that take an FMU state, called on an instance with a state
/// (class `matrix::states`), as a `Vec<(&str, seam::Use<_>)>`.
macro_rules! fmu_state_use_rows {
    ($prefix:literal, $noun:literal, $byte:ty) => {
        vec![
            (concat!($prefix, "Set", $noun), |i, s| unsafe {
                (i.binary.set_fmu_state)(i.c, s)
            }),
            (concat!($prefix, "Free", $noun), |i, s| {
                let mut slot = s;
                unsafe { (i.binary.free_fmu_state)(i.c, &mut slot) }
            }),
            (
                concat!($prefix, "Serialized", $noun, "Size"),
                |i, s| unsafe { (i.binary.serialized_size)(i.c, s, &mut 0) },
            ),
            (concat!($prefix, "Serialize", $noun), |i, s| unsafe {
                let mut bytes = vec![0 as $byte; 256];
                (i.binary.serialize)(i.c, s, bytes.as_mut_ptr(), bytes.len())
            }),
            (
                concat!($prefix, "Get", $noun, "(slot holding it)"),
                |i, s| {
                    let mut slot = s;
                    unsafe { (i.binary.get_fmu_state)(i.c, &mut slot) }
                },
            ),
        ]
    };
}
pub(crate) use fmu_state_use_rows;

/// The call-table rows of fmiXGetFMUState, fmiXSetFMUState and
/// fmiXSerializedFMUStateSize, legal where `$legal` says, added with `$add`.
macro_rules! fmu_state_call_rows {
    ($add:expr, $legal:expr, $prefix:literal, $noun:literal) => {
        $add(concat!($prefix, "Get", $noun), $legal, |b, c, _| unsafe {
            let mut s: FmuState = std::ptr::null_mut();
            let status = (b.get_fmu_state)(c, &mut s);
            if !s.is_null() {
                (b.free_fmu_state)(c, &mut s);
            }
            status
        });
        $add(concat!($prefix, "Set", $noun), $legal, |b, c, a| unsafe {
            (b.set_fmu_state)(c, a.state)
        });
        $add(
            concat!($prefix, "Serialized", $noun, "Size"),
            $legal,
            |b, c, a| unsafe {
                let mut n = 0usize;
                (b.serialized_size)(c, a.state, &mut n)
            },
        );
    };
}
pub(crate) use fmu_state_call_rows;

/// The Model Exchange evaluations both standards have (class `matrix::pose`): the
/// state derivatives (`$derivatives` names the getter, `$get_derivatives` its
/// field) and the event indicators, as a `Vec<(&str, seam::Evaluate<_>)>`.
macro_rules! me_evaluation_rows {
    ($prefix:literal, $derivatives:literal, $get_derivatives:ident) => {
        vec![
            (concat!($prefix, $derivatives), |i| unsafe {
                let mut dx = vec![0.0; i.description.number_of_states];
                (i.binary.$get_derivatives)(i.c, dx.as_mut_ptr(), dx.len())
            }),
            (concat!($prefix, "GetEventIndicators"), |i| unsafe {
                let mut z = vec![0.0; i.description.number_of_event_indicators];
                (i.binary.get_event_indicators)(i.c, z.as_mut_ptr(), z.len())
            }),
        ]
    };
}
pub(crate) use me_evaluation_rows;
