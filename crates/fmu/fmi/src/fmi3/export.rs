//! `export_fmi3!`: defines the C symbols of FMI 3.0 (Model Exchange, Co-Simulation,
//! the clock functions and the refusing stubs of Scheduled Execution and of the types and capabilities no
//! model has) in an FMU crate, each forwarding to the generic function of
//! `robofmu_fmi::fmi3::api` for the given model type. The fmi3* names never clash with
//! the fmi2* ones of `export_fmi2!`, so one cdylib exports both.

/// Exports the FMI 3.0 binary interface of a model type implementing
/// `robofmu_fmi::core::Model` and, through [`share_index!`](crate::share_index),
/// `Library` (as [`export_fmu!`](crate::export_fmu) does). Use once per cdylib crate.
#[macro_export]
macro_rules! export_fmi3 {
    ($model:ty) => {
        mod fmi3_exports {
            #![allow(non_snake_case)]
            use super::*;
            use std::ffi::c_char;
            use $crate::fmi3::api;
            use $crate::fmi3::mode::Call;
            use $crate::fmi3::types::*;
            type M = $model;

            #[unsafe(no_mangle)]
            pub extern "C" fn fmi3GetVersion() -> *const c_char {
                api::get_version()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetDebugLogging(
                c: Fmi3Instance,
                on: Fmi3Boolean,
                n: usize,
                categories: *const Fmi3String,
            ) -> Fmi3Status {
                unsafe { api::set_debug_logging::<M>(c, on, n, categories) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateModelExchange(
                instance_name: Fmi3String,
                token: Fmi3String,
                _resource_path: Fmi3String,
                _visible: Fmi3Boolean,
                logging_on: Fmi3Boolean,
                environment: Fmi3InstanceEnvironment,
                log_message: Option<Fmi3LogMessageCallback>,
            ) -> Fmi3Instance {
                unsafe {
                    api::instantiate_with::<M>($crate::core::instance::Index::shared, api::Instantiation {
                        function: "fmi3InstantiateModelExchange",
                        instance_name,
                        token,
                        logging_on,
                        environment,
                        log_message,
                        interface: $crate::fmi3::mode::Interface::ModelExchange,
                        intermediate_update: None,
                    }, (std::ptr::null(), 0))
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
                instance_name: Fmi3String,
                token: Fmi3String,
                _resource_path: Fmi3String,
                _visible: Fmi3Boolean,
                logging_on: Fmi3Boolean,
                event_mode_used: Fmi3Boolean,
                early_return_allowed: Fmi3Boolean,
                required_intermediate_variables: *const Fmi3ValueReference,
                n_required_intermediate_variables: usize,
                environment: Fmi3InstanceEnvironment,
                log_message: Option<Fmi3LogMessageCallback>,
                intermediate_update: Option<Fmi3IntermediateUpdateCallback>,
            ) -> Fmi3Instance {
                unsafe {
                    api::instantiate_with::<M>($crate::core::instance::Index::shared, api::Instantiation {
                        function: "fmi3InstantiateCoSimulation",
                        instance_name,
                        token,
                        logging_on,
                        environment,
                        log_message,
                        interface: $crate::fmi3::mode::Interface::CoSimulation {
                            event_mode_used: event_mode_used != FMI3_FALSE,
                            early_return_allowed: early_return_allowed != FMI3_FALSE,
                        },
                        intermediate_update: $crate::fmi3::intermediate::IntermediateUpdate::new(
                            intermediate_update,
                            environment,
                        ),
                    }, (required_intermediate_variables, n_required_intermediate_variables))
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
                _instance_name: Fmi3String,
                _token: Fmi3String,
                _resource_path: Fmi3String,
                _visible: Fmi3Boolean,
                logging_on: Fmi3Boolean,
                environment: Fmi3InstanceEnvironment,
                log_message: Option<Fmi3LogMessageCallback>,
                _clock_update: Option<Fmi3ClockUpdateCallback>,
                _lock_preemption: Option<Fmi3PreemptionCallback>,
                _unlock_preemption: Option<Fmi3PreemptionCallback>,
            ) -> Fmi3Instance {
                unsafe { api::refuse_scheduled_execution::<M>(logging_on, environment, log_message) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3FreeInstance(c: Fmi3Instance) {
                unsafe { api::free_instance::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterInitializationMode(
                c: Fmi3Instance,
                tolerance_defined: Fmi3Boolean,
                tolerance: Fmi3Float64,
                start_time: Fmi3Float64,
                stop_time_defined: Fmi3Boolean,
                stop_time: Fmi3Float64,
            ) -> Fmi3Status {
                unsafe {
                    api::enter_initialization_mode::<M>(
                        c,
                        tolerance_defined,
                        tolerance,
                        start_time,
                        stop_time_defined,
                        stop_time,
                    )
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3ExitInitializationMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::exit_initialization_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterEventMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::enter_event_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3Terminate(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::terminate::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3Reset(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::reset::<M>(c) }
            }

            $crate::__fmi3_values!(M, Fmi3Float64, fmi3GetFloat64 => get_float64, fmi3SetFloat64 => set_float64);
            $crate::__fmi3_values!(M, Fmi3Int32, fmi3GetInt32 => get_int32, fmi3SetInt32 => set_int32);
            $crate::__fmi3_values!(M, Fmi3Boolean, fmi3GetBoolean => get_boolean, fmi3SetBoolean => set_boolean);
            $crate::__fmi3_values!(M, Fmi3Float32, fmi3GetFloat32, fmi3SetFloat32, "Float32");
            $crate::__fmi3_values!(M, Fmi3Int8, fmi3GetInt8, fmi3SetInt8, "Int8");
            $crate::__fmi3_values!(M, Fmi3UInt8, fmi3GetUInt8, fmi3SetUInt8, "UInt8");
            $crate::__fmi3_values!(M, Fmi3Int16, fmi3GetInt16, fmi3SetInt16, "Int16");
            $crate::__fmi3_values!(M, Fmi3UInt16, fmi3GetUInt16, fmi3SetUInt16, "UInt16");
            $crate::__fmi3_values!(M, Fmi3UInt32, fmi3GetUInt32, fmi3SetUInt32, "UInt32");
            $crate::__fmi3_values!(M, Fmi3Int64, fmi3GetInt64, fmi3SetInt64, "Int64");
            $crate::__fmi3_values!(M, Fmi3UInt64, fmi3GetUInt64 => get_uint64, fmi3SetUInt64 => set_uint64);
            $crate::__fmi3_values!(M, Fmi3String, fmi3GetString, fmi3SetString, "String");

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetBinary(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                _value_sizes: *mut usize,
                values: *mut Fmi3Binary,
                _n_values: usize,
            ) -> Fmi3Status {
                unsafe {
                    api::access_unsupported_type::<M>(
                        c, "fmi3GetBinary", Call::GetValues, "Binary", vr, nvr, values.is_null(),
                    )
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetBinary(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                _value_sizes: *const usize,
                values: *const Fmi3Binary,
                _n_values: usize,
            ) -> Fmi3Status {
                unsafe {
                    api::access_unsupported_type::<M>(
                        c, "fmi3SetBinary", Call::SetDiscrete, "Binary", vr, nvr, values.is_null(),
                    )
                }
            }

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetClock(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                values: *mut Fmi3Clock,
            ) -> Fmi3Status {
                unsafe { api::get_clock::<M>(c, vr, nvr, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetClock(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                values: *const Fmi3Clock,
            ) -> Fmi3Status {
                unsafe { api::set_clock::<M>(c, vr, nvr, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetIntervalDecimal(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                intervals: *mut Fmi3Float64,
                qualifiers: *mut Fmi3IntervalQualifier,
            ) -> Fmi3Status {
                unsafe { api::get_interval_decimal::<M>(c, vr, nvr, intervals, qualifiers) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetIntervalFraction(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                counters: *mut Fmi3UInt64,
                resolutions: *mut Fmi3UInt64,
                qualifiers: *mut Fmi3IntervalQualifier,
            ) -> Fmi3Status {
                unsafe {
                    api::get_interval_fraction::<M>(c, vr, nvr, counters, resolutions, qualifiers)
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetShiftDecimal(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                shifts: *mut Fmi3Float64,
            ) -> Fmi3Status {
                unsafe { api::get_shift_decimal::<M>(c, vr, nvr, shifts) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetShiftFraction(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                counters: *mut Fmi3UInt64,
                resolutions: *mut Fmi3UInt64,
            ) -> Fmi3Status {
                unsafe { api::get_shift_fraction::<M>(c, vr, nvr, counters, resolutions) }
            }
            $crate::__fmi3_set_clock_timing!(M, fmi3SetIntervalDecimal, "interval");
            $crate::__fmi3_set_clock_timing!(M, fmi3SetShiftDecimal, "shift");
            $crate::__fmi3_set_clock_timing!(M, fmi3SetIntervalFraction, "interval", fraction);
            $crate::__fmi3_set_clock_timing!(M, fmi3SetShiftFraction, "shift", fraction);
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterConfigurationMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::enter_configuration_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3ExitConfigurationMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::exit_configuration_mode::<M>(c) }
            }
            $crate::__fmi3_lacking!(M, fmi3EvaluateDiscreteStates, "fmi3EvaluateDiscreteStates (providesEvaluateDiscreteStates=\"false\")");
            $crate::__fmi3_lacking!(M, fmi3ActivateModelPartition, "Scheduled Execution", clock: Fmi3ValueReference, activation_time: Fmi3Float64);

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
                c: Fmi3Instance,
                vr: Fmi3ValueReference,
                n: *mut usize,
            ) -> Fmi3Status {
                unsafe { api::get_number_of_variable_dependencies::<M>(c, vr, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetVariableDependencies(
                c: Fmi3Instance,
                dependent: Fmi3ValueReference,
                element_indices_of_dependent: *mut usize,
                independents: *mut Fmi3ValueReference,
                element_indices_of_independents: *mut usize,
                dependency_kinds: *mut Fmi3DependencyKind,
                n_dependencies: usize,
            ) -> Fmi3Status {
                unsafe {
                    api::get_variable_dependencies::<M>(
                        c,
                        dependent,
                        api::DependencyArrays {
                            element_indices_of_dependent,
                            independents,
                            element_indices_of_independents,
                            dependency_kinds,
                            n_dependencies,
                        },
                    )
                }
            }

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetFMUState(
                c: Fmi3Instance,
                state: *mut Fmi3FmuState,
            ) -> Fmi3Status {
                unsafe { api::get_fmu_state::<M>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetFMUState(
                c: Fmi3Instance,
                state: Fmi3FmuState,
            ) -> Fmi3Status {
                unsafe { api::set_fmu_state::<M>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3FreeFMUState(
                c: Fmi3Instance,
                state: *mut Fmi3FmuState,
            ) -> Fmi3Status {
                unsafe { api::free_fmu_state::<M>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
                c: Fmi3Instance,
                state: Fmi3FmuState,
                size: *mut usize,
            ) -> Fmi3Status {
                unsafe { api::serialized_fmu_state_size::<M>(c, state, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SerializeFMUState(
                c: Fmi3Instance,
                state: Fmi3FmuState,
                bytes: *mut Fmi3Byte,
                size: usize,
            ) -> Fmi3Status {
                unsafe { api::serialize_fmu_state::<M>(c, state, bytes, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3DeserializeFMUState(
                c: Fmi3Instance,
                bytes: *const Fmi3Byte,
                size: usize,
                state: *mut Fmi3FmuState,
            ) -> Fmi3Status {
                unsafe { api::deserialize_fmu_state::<M>(c, bytes, size, state) }
            }

            $crate::__fmi3_derivative!(M, fmi3GetDirectionalDerivative => get_directional_derivative);
            $crate::__fmi3_derivative!(M, fmi3GetAdjointDerivative => get_adjoint_derivative);

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
                c: Fmi3Instance,
                discrete_states_need_update: *mut Fmi3Boolean,
                terminate_simulation: *mut Fmi3Boolean,
                nominals_changed: *mut Fmi3Boolean,
                values_changed: *mut Fmi3Boolean,
                next_event_time_defined: *mut Fmi3Boolean,
                next_event_time: *mut Fmi3Float64,
            ) -> Fmi3Status {
                unsafe {
                    api::update_discrete_states::<M>(
                        c,
                        api::DiscreteStatesUpdate {
                            discrete_states_need_update,
                            terminate_simulation,
                            nominals_changed,
                            values_changed,
                            next_event_time_defined,
                            next_event_time,
                        },
                    )
                }
            }

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::enter_continuous_time_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
                c: Fmi3Instance,
                no_set_prior: Fmi3Boolean,
                enter_event_mode: *mut Fmi3Boolean,
                terminate_simulation: *mut Fmi3Boolean,
            ) -> Fmi3Status {
                unsafe {
                    api::completed_integrator_step::<M>(
                        c,
                        no_set_prior,
                        enter_event_mode,
                        terminate_simulation,
                    )
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetTime(c: Fmi3Instance, time: Fmi3Float64) -> Fmi3Status {
                unsafe { api::set_time::<M>(c, time) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetContinuousStates(
                c: Fmi3Instance,
                x: *const Fmi3Float64,
                nx: usize,
            ) -> Fmi3Status {
                unsafe { api::set_continuous_states::<M>(c, x, nx) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
                c: Fmi3Instance,
                dx: *mut Fmi3Float64,
                nx: usize,
            ) -> Fmi3Status {
                unsafe { api::get_continuous_state_derivatives::<M>(c, dx, nx) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetEventIndicators(
                c: Fmi3Instance,
                z: *mut Fmi3Float64,
                nz: usize,
            ) -> Fmi3Status {
                unsafe { api::get_event_indicators::<M>(c, z, nz) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetContinuousStates(
                c: Fmi3Instance,
                x: *mut Fmi3Float64,
                nx: usize,
            ) -> Fmi3Status {
                unsafe { api::get_continuous_states::<M>(c, x, nx) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
                c: Fmi3Instance,
                nominals: *mut Fmi3Float64,
                nx: usize,
            ) -> Fmi3Status {
                unsafe { api::get_nominals_of_continuous_states::<M>(c, nominals, nx) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(
                c: Fmi3Instance,
                n: *mut usize,
            ) -> Fmi3Status {
                unsafe { api::get_number_of_event_indicators::<M>(c, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(
                c: Fmi3Instance,
                n: *mut usize,
            ) -> Fmi3Status {
                unsafe { api::get_number_of_continuous_states::<M>(c, n) }
            }

            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterStepMode(c: Fmi3Instance) -> Fmi3Status {
                unsafe { api::enter_step_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetOutputDerivatives(
                c: Fmi3Instance,
                vr: *const Fmi3ValueReference,
                nvr: usize,
                orders: *const Fmi3Int32,
                values: *mut Fmi3Float64,
                n_values: usize,
            ) -> Fmi3Status {
                unsafe { api::get_output_derivatives::<M>(c, vr, nvr, orders, values, n_values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3DoStep(
                c: Fmi3Instance,
                current_communication_point: Fmi3Float64,
                communication_step_size: Fmi3Float64,
                no_set_prior: Fmi3Boolean,
                event_handling_needed: *mut Fmi3Boolean,
                terminate_simulation: *mut Fmi3Boolean,
                early_return: *mut Fmi3Boolean,
                last_successful_time: *mut Fmi3Float64,
            ) -> Fmi3Status {
                unsafe {
                    api::do_step::<M>(
                        c,
                        current_communication_point,
                        communication_step_size,
                        no_set_prior,
                        api::StepResult {
                            event_handling_needed,
                            terminate_simulation,
                            early_return,
                            last_successful_time,
                        },
                    )
                }
            }
        }
    };
}

/// `fmi3Get<Type>` and `fmi3Set<Type>` (used by `export_fmi3!`): of a type the models
/// use, forwarding to the typed functions of `api`; of a type no variable has (with
/// its name), answering with `api::access_unsupported_type`.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_values {
    ($model:ty, $t:ty, $get:ident => $get_api:ident, $set:ident => $set_api:ident) => {
        $crate::__fmi3_values!(@define $t, $get, $set, (c, vr, nvr, values, n_values),
            $crate::fmi3::api::$get_api::<$model>(c, vr, nvr, values, n_values),
            $crate::fmi3::api::$set_api::<$model>(c, vr, nvr, values, n_values));
    };
    ($model:ty, $t:ty, $get:ident, $set:ident, $name:literal) => {
        $crate::__fmi3_values!(@define $t, $get, $set, (c, vr, nvr, values, _n_values),
            $crate::fmi3::api::access_unsupported_type::<$model>(
                c, stringify!($get), $crate::fmi3::mode::Call::GetValues, $name, vr, nvr,
                values.is_null()),
            $crate::fmi3::api::access_unsupported_type::<$model>(
                c, stringify!($set), $crate::fmi3::mode::Call::SetDiscrete, $name, vr, nvr,
                values.is_null()));
    };
    (@define $t:ty, $get:ident, $set:ident,
     ($c:ident, $vr:ident, $nvr:ident, $values:ident, $n_values:ident),
     $get_body:expr, $set_body:expr) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $get(
            $c: $crate::fmi3::types::Fmi3Instance,
            $vr: *const $crate::fmi3::types::Fmi3ValueReference,
            $nvr: usize,
            $values: *mut $t,
            $n_values: usize,
        ) -> $crate::fmi3::types::Fmi3Status {
            unsafe { $get_body }
        }
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $set(
            $c: $crate::fmi3::types::Fmi3Instance,
            $vr: *const $crate::fmi3::types::Fmi3ValueReference,
            $nvr: usize,
            $values: *const $t,
            $n_values: usize,
        ) -> $crate::fmi3::types::Fmi3Status {
            unsafe { $set_body }
        }
    };
}

/// fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative, which take the same
/// arguments (used by `export_fmi3!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_derivative {
    ($model:ty, $name:ident => $api:ident) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: $crate::fmi3::types::Fmi3Instance,
            unknowns: *const $crate::fmi3::types::Fmi3ValueReference,
            n_unknowns: usize,
            knowns: *const $crate::fmi3::types::Fmi3ValueReference,
            n_knowns: usize,
            seed: *const $crate::fmi3::types::Fmi3Float64,
            n_seed: usize,
            sensitivity: *mut $crate::fmi3::types::Fmi3Float64,
            n_sensitivity: usize,
        ) -> $crate::fmi3::types::Fmi3Status {
            let request = $crate::fmi3::api::DerivativeRequest {
                unknowns,
                n_unknowns,
                knowns,
                n_knowns,
                seed,
                n_seed,
                sensitivity,
                n_sensitivity,
            };
            unsafe { $crate::fmi3::api::$api::<$model>(c, request) }
        }
    };
}

/// A function of a capability the FMU does not have, by argument list (used by
/// `export_fmi3!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_lacking {
    ($model:ty, $name:ident, $what:literal $(, $arg:ident: $t:ty)*) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: $crate::fmi3::types::Fmi3Instance
            $(, $arg: $t)*
        ) -> $crate::fmi3::types::Fmi3Status {
            $(let _ = $arg;)*
            unsafe { $crate::fmi3::api::unsupported::<$model>(c, stringify!($name), $what) }
        }
    };
}

/// fmi3SetIntervalDecimal / fmi3SetShiftDecimal and the Fraction forms (used by
/// `export_fmi3!`): arguments checked, then refused for the fixed clocks of this layer
/// (`api::set_interval_or_shift`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi3_set_clock_timing {
    ($model:ty, $name:ident, $what:literal) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: $crate::fmi3::types::Fmi3Instance,
            vr: *const $crate::fmi3::types::Fmi3ValueReference,
            nvr: usize,
            values: *const $crate::fmi3::types::Fmi3Float64,
        ) -> $crate::fmi3::types::Fmi3Status {
            unsafe {
                $crate::fmi3::api::set_interval_or_shift::<$model>(
                    c,
                    stringify!($name),
                    $what,
                    vr,
                    nvr,
                    |n| {
                        let v = $crate::ffi::input_slice(values, n, "values[]")?;
                        Ok($crate::fmi3::api::Setting::Decimal(v))
                    },
                )
            }
        }
    };
    ($model:ty, $name:ident, $what:literal, fraction) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: $crate::fmi3::types::Fmi3Instance,
            vr: *const $crate::fmi3::types::Fmi3ValueReference,
            nvr: usize,
            counters: *const $crate::fmi3::types::Fmi3UInt64,
            resolutions: *const $crate::fmi3::types::Fmi3UInt64,
        ) -> $crate::fmi3::types::Fmi3Status {
            unsafe {
                $crate::fmi3::api::set_interval_or_shift::<$model>(
                    c,
                    stringify!($name),
                    $what,
                    vr,
                    nvr,
                    |n| {
                        let counters = $crate::ffi::input_slice(counters, n, "counters[]")?;
                        let resolutions =
                            $crate::ffi::input_slice(resolutions, n, "resolutions[]")?;
                        Ok($crate::fmi3::api::Setting::Fraction(counters, resolutions))
                    },
                )
            }
        }
    };
}
