//! Every FMI 3.0 function that takes an instance, with well-formed arguments, and
//! the states in which the standard allows it (FMI 3.0.1, sections 2.3 "Common
//! states", 3.3 Model Exchange and 4.3 Co-Simulation state machines). Where the
//! standard leaves a choice (reading values in Error for diagnosis, FMU-state and
//! dependency queries in every state) the table follows the project's documented
//! one. Functions of capabilities the models lack (other variable types, clocks,
//! structural parameters, Scheduled Execution) are in `unsupported`: they are
//! refused in every state.

use crate::description::{Description, VarType, Variable};
use crate::fmi3::binary::{FmuState, Vr};
use crate::fmi3::host::{Interface3, State3};
use crate::matrix::same_named::fmu_state_call_rows;

/// A variable's reference and well-formed values for all its elements.
#[derive(Clone, Debug)]
pub struct Target {
    pub vr: Vr,
    pub size: usize,
}

impl Target {
    fn of(v: &Variable) -> Target {
        Target {
            vr: v.vr,
            size: v.size,
        }
    }
}

/// Well-formed arguments for the calls on one model.
pub struct Args {
    pub float: Target,
    pub input: Target,
    pub int: Target,
    pub boolean: Target,
    pub nx: usize,
    pub nz: usize,
    /// (derivative, state) for the directional and adjoint derivatives.
    pub partial: (Target, Target),
    /// A variable with a non-empty dependency list (or `float`).
    pub dependent: Vr,
    /// A valid FMU state of the instance (or null when none was taken).
    pub state: FmuState,
}

impl Args {
    pub fn new(d: &Description, state: FmuState) -> Args {
        let first = |t: VarType, settable: bool| {
            d.of_type(t)
                .find(|v| !settable || v.is_settable())
                .map(Target::of)
        };
        let float = d
            .of_type(VarType::Real)
            .find(|v| v.causality != "independent")
            .map(Target::of)
            .unwrap_or(Target { vr: 0, size: 1 });
        let input = d
            .variables
            .iter()
            .find(|v| v.causality == "input" && v.var_type == VarType::Real)
            .map(Target::of)
            .or(first(VarType::Real, true))
            .unwrap_or(float.clone());
        let pairs = d.state_derivative_pairs();
        let target = |vr: Vr| Target {
            vr,
            size: d.elements(&[vr]),
        };
        Args {
            int: first(VarType::Integer, true).unwrap_or(float.clone()),
            boolean: first(VarType::Boolean, true).unwrap_or(float.clone()),
            nx: d.number_of_states,
            nz: d.number_of_event_indicators,
            partial: pairs
                .first()
                .map(|&(x, dx)| (target(dx), target(x)))
                .unwrap_or((float.clone(), input.clone())),
            dependent: d.dependents.first().copied().unwrap_or(float.vr),
            float,
            input,
            state,
        }
    }
}

pub type Legal = crate::standard_interface::Legal<Interface3>;
pub type Invoke = crate::standard_interface::Invoke<Interface3>;
pub type Call = crate::standard_interface::Call<Interface3>;

use State3::*;

fn live(_: Interface3, _: State3) -> bool {
    true
}
fn readable(_: Interface3, s: State3) -> bool {
    s != Instantiated
}
fn me_only(i: Interface3, s: State3, states: &[State3]) -> bool {
    i.is_me() && states.contains(&s)
}
fn cs_only(i: Interface3, s: State3, states: &[State3]) -> bool {
    !i.is_me() && states.contains(&s)
}

/// The calls with their legal states.
pub fn calls() -> Vec<Call> {
    let mut v: Vec<Call> = Vec::new();
    let mut add = |name, legal: Legal, invoke: Invoke| {
        v.push(Call {
            name,
            legal,
            invoke,
        })
    };
    add("fmi3SetDebugLogging", live, |b, c, _| unsafe {
        (b.set_debug_logging)(c, 1, 0, std::ptr::null())
    });
    add(
        "fmi3EnterInitializationMode",
        |_, s| s == Instantiated,
        |b, c, _| unsafe { (b.enter_initialization_mode)(c, 0, 0.0, 0.0, 0, 0.0) },
    );
    add(
        "fmi3ExitInitializationMode",
        |_, s| s == InitializationMode,
        |b, c, _| unsafe { (b.exit_initialization_mode)(c) },
    );
    add(
        "fmi3EnterEventMode",
        |i, s| match i {
            Interface3::ModelExchange => s == ContinuousTimeMode,
            Interface3::CoSimulationEvents => s == StepMode,
            Interface3::CoSimulation => false,
        },
        |b, c, _| unsafe { (b.enter_event_mode)(c) },
    );
    add(
        "fmi3Terminate",
        |_, s| matches!(s, EventMode | ContinuousTimeMode | StepMode | StepDiscarded),
        |b, c, _| unsafe { (b.terminate)(c) },
    );
    add("fmi3Reset", live, |b, c, _| unsafe { (b.reset)(c) });
    add_values(&mut add);
    add_states_and_derivatives(&mut add);
    add_model_exchange(&mut add);
    add_co_simulation(&mut add);
    v
}

fn add_values(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    add("fmi3GetFloat64", readable, |b, c, a| unsafe {
        let mut x = vec![0.0; a.float.size];
        (b.get_float64)(c, &a.float.vr, 1, x.as_mut_ptr(), x.len())
    });
    add("fmi3GetInt32", readable, |b, c, a| unsafe {
        let mut x = vec![0i32; a.int.size];
        (b.get_int32)(c, &a.int.vr, 1, x.as_mut_ptr(), x.len())
    });
    add("fmi3GetBoolean", readable, |b, c, a| unsafe {
        let mut x = vec![0u8; a.boolean.size];
        (b.get_boolean)(c, &a.boolean.vr, 1, x.as_mut_ptr(), x.len())
    });
    add(
        "fmi3SetFloat64",
        |_, s| {
            matches!(
                s,
                Instantiated | InitializationMode | EventMode | ContinuousTimeMode | StepMode
            )
        },
        |b, c, a| unsafe {
            let x = vec![0.0; a.input.size];
            (b.set_float64)(c, &a.input.vr, 1, x.as_ptr(), x.len())
        },
    );
    let discrete: Legal =
        |_, s| matches!(s, Instantiated | InitializationMode | EventMode | StepMode);
    add("fmi3SetInt32", discrete, |b, c, a| unsafe {
        let x = vec![1i32; a.int.size];
        (b.set_int32)(c, &a.int.vr, 1, x.as_ptr(), x.len())
    });
    add("fmi3SetBoolean", discrete, |b, c, a| unsafe {
        let x = vec![0u8; a.boolean.size];
        (b.set_boolean)(c, &a.boolean.vr, 1, x.as_ptr(), x.len())
    });
    add(
        "fmi3GetNumberOfVariableDependencies",
        live,
        |b, c, a| unsafe {
            let mut n = 0usize;
            (b.get_number_of_variable_dependencies)(c, a.float.vr, &mut n)
        },
    );
    add("fmi3GetVariableDependencies", live, |b, c, a| unsafe {
        let mut n = 0usize;
        (b.get_number_of_variable_dependencies)(c, a.float.vr, &mut n);
        let (mut e, mut v, mut ei, mut k) = (vec![0; n], vec![0; n], vec![0; n], vec![0; n]);
        (b.get_variable_dependencies)(
            c,
            a.float.vr,
            e.as_mut_ptr(),
            v.as_mut_ptr(),
            ei.as_mut_ptr(),
            k.as_mut_ptr(),
            n,
        )
    });
}

fn add_states_and_derivatives(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    fmu_state_call_rows!(add, live, "fmi3", "FMUState");
    add("fmi3SerializeFMUState", live, |b, c, a| unsafe {
        let mut n = 0usize;
        (b.serialized_size)(c, a.state, &mut n);
        let mut bytes = vec![0u8; n.max(1)];
        (b.serialize)(c, a.state, bytes.as_mut_ptr(), n)
    });
    add("fmi3DeserializeFMUState", live, |b, c, a| unsafe {
        let mut n = 0usize;
        (b.serialized_size)(c, a.state, &mut n);
        let mut bytes = vec![0u8; n];
        (b.serialize)(c, a.state, bytes.as_mut_ptr(), n);
        let mut s: FmuState = std::ptr::null_mut();
        let status = (b.deserialize)(c, bytes.as_ptr(), n, &mut s);
        if !s.is_null() {
            (b.free_fmu_state)(c, &mut s);
        }
        status
    });
    add("fmi3FreeFMUState", live, |b, c, _| unsafe {
        let mut s: FmuState = std::ptr::null_mut();
        (b.get_fmu_state)(c, &mut s);
        (b.free_fmu_state)(c, &mut s)
    });
    let derivable: Legal = |_, s| {
        matches!(
            s,
            InitializationMode | EventMode | ContinuousTimeMode | StepMode | Terminated
        )
    };
    add(
        "fmi3GetDirectionalDerivative",
        derivable,
        |b, c, a| unsafe {
            let (u, k) = &a.partial;
            let seed = vec![1.0; k.size];
            let mut out = vec![0.0; u.size];
            (b.get_directional_derivative)(
                c,
                &u.vr,
                1,
                &k.vr,
                1,
                seed.as_ptr(),
                seed.len(),
                out.as_mut_ptr(),
                out.len(),
            )
        },
    );
    add("fmi3GetAdjointDerivative", derivable, |b, c, a| unsafe {
        let (u, k) = &a.partial;
        let seed = vec![1.0; u.size];
        let mut out = vec![0.0; k.size];
        (b.get_adjoint_derivative)(
            c,
            &u.vr,
            1,
            &k.vr,
            1,
            seed.as_ptr(),
            seed.len(),
            out.as_mut_ptr(),
            out.len(),
        )
    });
    add(
        "fmi3UpdateDiscreteStates",
        |_, s| s == EventMode,
        |b, c, _| unsafe {
            let mut f = [0u8; 5];
            let mut t = 0.0;
            let [a, b2, c2, d, e] = &mut f;
            (b.update_discrete_states)(c, a, b2, c2, d, e, &mut t)
        },
    );
}

fn add_model_exchange(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    let queryable: Legal = |i, s| {
        me_only(
            i,
            s,
            &[
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                Terminated,
            ],
        )
    };
    add(
        "fmi3EnterContinuousTimeMode",
        |i, s| me_only(i, s, &[EventMode]),
        |b, c, _| unsafe { (b.enter_continuous_time_mode)(c) },
    );
    add(
        "fmi3CompletedIntegratorStep",
        |i, s| me_only(i, s, &[ContinuousTimeMode]),
        |b, c, _| unsafe {
            let (mut enter, mut stop) = (0u8, 0u8);
            (b.completed_integrator_step)(c, 1, &mut enter, &mut stop)
        },
    );
    add(
        "fmi3SetTime",
        |i, s| me_only(i, s, &[EventMode, ContinuousTimeMode]),
        |b, c, _| unsafe { (b.set_time)(c, 0.0) },
    );
    add(
        "fmi3SetContinuousStates",
        |i, s| me_only(i, s, &[ContinuousTimeMode]),
        |b, c, a| unsafe {
            let mut x = vec![0.0; a.nx];
            (b.get_continuous_states)(c, x.as_mut_ptr(), a.nx);
            (b.set_continuous_states)(c, x.as_ptr(), a.nx)
        },
    );
    add(
        "fmi3GetContinuousStateDerivatives",
        queryable,
        |b, c, a| unsafe {
            let mut dx = vec![0.0; a.nx];
            (b.get_continuous_state_derivatives)(c, dx.as_mut_ptr(), a.nx)
        },
    );
    add("fmi3GetEventIndicators", queryable, |b, c, a| unsafe {
        let mut z = vec![0.0; a.nz];
        (b.get_event_indicators)(c, z.as_mut_ptr(), a.nz)
    });
    add("fmi3GetContinuousStates", queryable, |b, c, a| unsafe {
        let mut x = vec![0.0; a.nx];
        (b.get_continuous_states)(c, x.as_mut_ptr(), a.nx)
    });
    add(
        "fmi3GetNominalsOfContinuousStates",
        queryable,
        |b, c, a| unsafe {
            let mut x = vec![0.0; a.nx];
            (b.get_nominals)(c, x.as_mut_ptr(), a.nx)
        },
    );
    add(
        "fmi3GetNumberOfEventIndicators",
        |i, _| i.is_me(),
        |b, c, _| unsafe { (b.get_number_of_event_indicators)(c, &mut 0) },
    );
    add(
        "fmi3GetNumberOfContinuousStates",
        |i, _| i.is_me(),
        |b, c, _| unsafe { (b.get_number_of_continuous_states)(c, &mut 0) },
    );
}

fn add_co_simulation(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    add(
        "fmi3EnterStepMode",
        |i, s| i == Interface3::CoSimulationEvents && s == EventMode,
        |b, c, _| unsafe { (b.enter_step_mode)(c) },
    );
    add(
        "fmi3GetOutputDerivatives",
        |i, s| cs_only(i, s, &[StepMode, StepDiscarded, Terminated]),
        |b, c, a| unsafe {
            let orders = [1i32];
            let mut out = vec![0.0; a.float.size];
            (b.get_output_derivatives)(
                c,
                &a.float.vr,
                1,
                orders.as_ptr(),
                out.as_mut_ptr(),
                out.len(),
            )
        },
    );
    add(
        "fmi3DoStep",
        |i, s| cs_only(i, s, &[StepMode]),
        |b, c, _| unsafe {
            let (mut e, mut t, mut r) = (0u8, 0u8, 0u8);
            let mut last = 0.0;
            (b.do_step)(c, 0.0, 1e-3, 1, &mut e, &mut t, &mut r, &mut last)
        },
    );
}

/// The functions of capabilities no model has, each with a well-formed request of
/// one element: refused in every state with fmi3Error and a log line naming the
/// function (FMI 3.0 lets an FMU lack them; calling them is an error).
pub fn unsupported() -> Vec<(&'static str, Invoke)> {
    let v: Vec<(&'static str, Invoke)> = vec![
        ("fmi3GetFloat32", |b, c, a| unsafe {
            (b.get_float32)(c, &a.float.vr, 1, &mut 0.0, 1)
        }),
        ("fmi3GetInt8", |b, c, a| unsafe {
            (b.get_int8)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetUInt8", |b, c, a| unsafe {
            (b.get_uint8)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetInt16", |b, c, a| unsafe {
            (b.get_int16)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetUInt16", |b, c, a| unsafe {
            (b.get_uint16)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetUInt32", |b, c, a| unsafe {
            (b.get_uint32)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetInt64", |b, c, a| unsafe {
            (b.get_int64)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetUInt64", |b, c, a| unsafe {
            (b.get_uint64)(c, &a.float.vr, 1, &mut 0, 1)
        }),
        ("fmi3GetString", |b, c, a| unsafe {
            (b.get_string)(c, &a.float.vr, 1, &mut std::ptr::null(), 1)
        }),
        ("fmi3GetBinary", |b, c, a| unsafe {
            (b.get_binary)(c, &a.float.vr, 1, &mut 0, &mut std::ptr::null(), 1)
        }),
        ("fmi3GetClock", |b, c, a| unsafe {
            (b.get_clock)(c, &a.float.vr, 1, &mut 0)
        }),
        ("fmi3SetFloat32", |b, c, a| unsafe {
            (b.set_float32)(c, &a.float.vr, 1, &0.0, 1)
        }),
        ("fmi3SetInt8", |b, c, a| unsafe {
            (b.set_int8)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetUInt8", |b, c, a| unsafe {
            (b.set_uint8)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetInt16", |b, c, a| unsafe {
            (b.set_int16)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetUInt16", |b, c, a| unsafe {
            (b.set_uint16)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetUInt32", |b, c, a| unsafe {
            (b.set_uint32)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetInt64", |b, c, a| unsafe {
            (b.set_int64)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetUInt64", |b, c, a| unsafe {
            (b.set_uint64)(c, &a.float.vr, 1, &0, 1)
        }),
        ("fmi3SetString", |b, c, a| unsafe {
            (b.set_string)(c, &a.float.vr, 1, &c"x".as_ptr(), 1)
        }),
        ("fmi3SetBinary", |b, c, a| unsafe {
            (b.set_binary)(c, &a.float.vr, 1, &1, &[0u8].as_ptr(), 1)
        }),
        ("fmi3SetClock", |b, c, a| unsafe {
            (b.set_clock)(c, &a.float.vr, 1, &1)
        }),
    ];
    let mut v = v;
    v.extend(clocks_and_modes());
    v
}

fn clocks_and_modes() -> Vec<(&'static str, Invoke)> {
    vec![
        ("fmi3GetIntervalDecimal", |b, c, a| unsafe {
            (b.get_interval_decimal)(c, &a.float.vr, 1, &mut 0.0, &mut 0)
        }),
        ("fmi3GetIntervalFraction", |b, c, a| unsafe {
            (b.get_interval_fraction)(c, &a.float.vr, 1, &mut 0, &mut 0, &mut 0)
        }),
        ("fmi3GetShiftDecimal", |b, c, a| unsafe {
            (b.get_shift_decimal)(c, &a.float.vr, 1, &mut 0.0)
        }),
        ("fmi3GetShiftFraction", |b, c, a| unsafe {
            (b.get_shift_fraction)(c, &a.float.vr, 1, &mut 0, &mut 0)
        }),
        ("fmi3SetIntervalDecimal", |b, c, a| unsafe {
            (b.set_interval_decimal)(c, &a.float.vr, 1, &0.1)
        }),
        ("fmi3SetIntervalFraction", |b, c, a| unsafe {
            (b.set_interval_fraction)(c, &a.float.vr, 1, &1, &10)
        }),
        ("fmi3SetShiftDecimal", |b, c, a| unsafe {
            (b.set_shift_decimal)(c, &a.float.vr, 1, &0.0)
        }),
        ("fmi3SetShiftFraction", |b, c, a| unsafe {
            (b.set_shift_fraction)(c, &a.float.vr, 1, &0, &10)
        }),
        ("fmi3EnterConfigurationMode", |b, c, _| unsafe {
            (b.enter_configuration_mode)(c)
        }),
        ("fmi3ExitConfigurationMode", |b, c, _| unsafe {
            (b.exit_configuration_mode)(c)
        }),
        ("fmi3EvaluateDiscreteStates", |b, c, _| unsafe {
            (b.evaluate_discrete_states)(c)
        }),
        ("fmi3ActivateModelPartition", |b, c, a| unsafe {
            (b.activate_model_partition)(c, a.float.vr, 0.0)
        }),
    ]
}
