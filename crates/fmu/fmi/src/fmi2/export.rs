//! `export_fmi2!`: defines the 44 C symbols of FMI 2.0 (Model Exchange and
//! Co-Simulation) in an FMU crate, each forwarding to the generic function of
//! `robofmu_fmi::fmi2::api` for the given model type.

/// Exports the FMI 2.0 binary interface of a model type implementing
/// `robofmu_fmi::core::Model` and, through [`share_index!`](crate::share_index),
/// `Library` (as [`export_fmu!`](crate::export_fmu) does). Use once per cdylib crate.
#[macro_export]
macro_rules! export_fmi2 {
    ($model:ty) => {
        mod fmi2_exports {
            #![allow(non_snake_case)]
            use super::*;
            use std::ffi::{c_char, c_int};
            use $crate::fmi2::api;
            use $crate::fmi2::types::*;
            type M = $model;

            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
                api::get_types_platform()
            }
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetVersion() -> *const c_char {
                api::get_version()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetDebugLogging(
                c: Fmi2Component,
                on: Fmi2Boolean,
                n: usize,
                cats: *const Fmi2String,
            ) -> Fmi2Status {
                unsafe { api::set_debug_logging::<M>(c, on, n, cats) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Instantiate(
                name: Fmi2String,
                kind: c_int,
                guid: Fmi2String,
                resources: Fmi2String,
                functions: *const Fmi2CallbackFunctions,
                visible: Fmi2Boolean,
                logging_on: Fmi2Boolean,
            ) -> Fmi2Component {
                unsafe {
                    api::instantiate_with::<M>(
                        $crate::core::instance::Index::shared,
                        name,
                        kind,
                        guid,
                        resources,
                        functions,
                        visible,
                        logging_on,
                    )
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeInstance(c: Fmi2Component) {
                unsafe { api::free_instance::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetupExperiment(
                c: Fmi2Component,
                tol_defined: Fmi2Boolean,
                tol: Fmi2Real,
                start: Fmi2Real,
                stop_defined: Fmi2Boolean,
                stop: Fmi2Real,
            ) -> Fmi2Status {
                unsafe {
                    api::setup_experiment::<M>(c, tol_defined, tol, start, stop_defined, stop)
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::enter_initialization_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::exit_initialization_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Terminate(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::terminate::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Reset(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::reset::<M>(c) }
            }
            $crate::__fmi2_values!(M, Fmi2Real, fmi2GetReal => get_real, fmi2SetReal => set_real);
            $crate::__fmi2_values!(M, Fmi2Integer, fmi2GetInteger => get_integer, fmi2SetInteger => set_integer);
            $crate::__fmi2_values!(M, Fmi2Boolean, fmi2GetBoolean => get_boolean, fmi2SetBoolean => set_boolean);
            $crate::__fmi2_values!(M, Fmi2String, fmi2GetString => get_string, fmi2SetString => set_string);
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetFMUstate(
                c: Fmi2Component,
                s: *mut Fmi2FmuState,
            ) -> Fmi2Status {
                unsafe { api::get_fmu_state::<M>(c, s) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetFMUstate(
                c: Fmi2Component,
                s: Fmi2FmuState,
            ) -> Fmi2Status {
                unsafe { api::set_fmu_state::<M>(c, s) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeFMUstate(
                c: Fmi2Component,
                s: *mut Fmi2FmuState,
            ) -> Fmi2Status {
                unsafe { api::free_fmu_state::<M>(c, s) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
                c: Fmi2Component,
                s: Fmi2FmuState,
                size: *mut usize,
            ) -> Fmi2Status {
                unsafe { api::serialized_fmu_state_size::<M>(c, s, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(
                c: Fmi2Component,
                s: Fmi2FmuState,
                bytes: *mut Fmi2Byte,
                size: usize,
            ) -> Fmi2Status {
                unsafe { api::serialize_fmu_state::<M>(c, s, bytes, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
                c: Fmi2Component,
                bytes: *const Fmi2Byte,
                size: usize,
                s: *mut Fmi2FmuState,
            ) -> Fmi2Status {
                unsafe { api::de_serialize_fmu_state::<M>(c, bytes, size, s) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
                c: Fmi2Component,
                unknown: *const Fmi2ValueReference,
                n_unknown: usize,
                known: *const Fmi2ValueReference,
                n_known: usize,
                dv_known: *const Fmi2Real,
                dv_unknown: *mut Fmi2Real,
            ) -> Fmi2Status {
                unsafe {
                    api::get_directional_derivative::<M>(
                        c, unknown, n_unknown, known, n_known, dv_known, dv_unknown,
                    )
                }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterEventMode(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::enter_event_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2NewDiscreteStates(
                c: Fmi2Component,
                info: *mut Fmi2EventInfo,
            ) -> Fmi2Status {
                unsafe { api::new_discrete_states::<M>(c, info) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::enter_continuous_time_mode::<M>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
                c: Fmi2Component,
                no_prior: Fmi2Boolean,
                enter_event: *mut Fmi2Boolean,
                terminate: *mut Fmi2Boolean,
            ) -> Fmi2Status {
                unsafe { api::completed_integrator_step::<M>(c, no_prior, enter_event, terminate) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetTime(c: Fmi2Component, time: Fmi2Real) -> Fmi2Status {
                unsafe { api::set_time::<M>(c, time) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetContinuousStates(
                c: Fmi2Component,
                x: *const Fmi2Real,
                n: usize,
            ) -> Fmi2Status {
                unsafe { api::set_continuous_states::<M>(c, x, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDerivatives(
                c: Fmi2Component,
                dx: *mut Fmi2Real,
                n: usize,
            ) -> Fmi2Status {
                unsafe { api::get_derivatives::<M>(c, dx, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetEventIndicators(
                c: Fmi2Component,
                z: *mut Fmi2Real,
                n: usize,
            ) -> Fmi2Status {
                unsafe { api::get_event_indicators::<M>(c, z, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetContinuousStates(
                c: Fmi2Component,
                x: *mut Fmi2Real,
                n: usize,
            ) -> Fmi2Status {
                unsafe { api::get_continuous_states::<M>(c, x, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
                c: Fmi2Component,
                x: *mut Fmi2Real,
                n: usize,
            ) -> Fmi2Status {
                unsafe { api::get_nominals_of_continuous_states::<M>(c, x, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
                c: Fmi2Component,
                vr: *const Fmi2ValueReference,
                n: usize,
                order: *const Fmi2Integer,
                v: *const Fmi2Real,
            ) -> Fmi2Status {
                unsafe { api::set_real_input_derivatives::<M>(c, vr, n, order, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
                c: Fmi2Component,
                vr: *const Fmi2ValueReference,
                n: usize,
                order: *const Fmi2Integer,
                v: *mut Fmi2Real,
            ) -> Fmi2Status {
                unsafe { api::get_real_output_derivatives::<M>(c, vr, n, order, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DoStep(
                c: Fmi2Component,
                t: Fmi2Real,
                h: Fmi2Real,
                no_prior: Fmi2Boolean,
            ) -> Fmi2Status {
                unsafe { api::do_step::<M>(c, t, h, no_prior) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CancelStep(c: Fmi2Component) -> Fmi2Status {
                unsafe { api::cancel_step::<M>(c) }
            }
            $crate::__fmi2_status!(M, Fmi2Status, fmi2GetStatus => get_status);
            $crate::__fmi2_status!(M, Fmi2Real, fmi2GetRealStatus => get_real_status);
            $crate::__fmi2_status!(M, Fmi2Integer, fmi2GetIntegerStatus => get_integer_status);
            $crate::__fmi2_status!(M, Fmi2Boolean, fmi2GetBooleanStatus => get_boolean_status);
            $crate::__fmi2_status!(M, Fmi2String, fmi2GetStringStatus => get_string_status);
        }
    };
}

/// `fmi2Get<Type>` and `fmi2Set<Type>` of one type (used by `export_fmi2!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_values {
    ($model:ty, $t:ty, $get:ident => $get_api:ident, $set:ident => $set_api:ident) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $get(
            c: $crate::fmi2::types::Fmi2Component,
            vr: *const $crate::fmi2::types::Fmi2ValueReference,
            n: usize,
            v: *mut $t,
        ) -> $crate::fmi2::types::Fmi2Status {
            unsafe { $crate::fmi2::api::$get_api::<$model>(c, vr, n, v) }
        }
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $set(
            c: $crate::fmi2::types::Fmi2Component,
            vr: *const $crate::fmi2::types::Fmi2ValueReference,
            n: usize,
            v: *const $t,
        ) -> $crate::fmi2::types::Fmi2Status {
            unsafe { $crate::fmi2::api::$set_api::<$model>(c, vr, n, v) }
        }
    };
}

/// `fmi2Get<Type>Status` of one type (used by `export_fmi2!`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_status {
    ($model:ty, $t:ty, $name:ident => $api:ident) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            c: $crate::fmi2::types::Fmi2Component,
            kind: std::ffi::c_int,
            v: *mut $t,
        ) -> $crate::fmi2::types::Fmi2Status {
            unsafe { $crate::fmi2::api::$api::<$model>(c, kind, v) }
        }
    };
}
