//! An FMU binary's FMI 3.0 functions (all 75 of fmi3FunctionTypes.h), looked up in the
//! same library that exports the fmi2* symbols. fmi3Boolean is a
//! C99 `bool`, passed here as a byte so that a corrupt value is observable.

use crate::fmi2::{Status, functions};
use std::ffi::{c_char, c_int, c_void};

pub type Instance3 = *mut c_void;
pub type FmuState = *mut c_void;
pub type Vr = u32;
pub type Bool = u8;
type Str = *const c_char;
type Env = *mut c_void;
type Logger = *const c_void;
type Cb = *const c_void;

functions! {
    /// The FMI 3.0 functions of one loaded binary (75).
    Binary3 {
    get_version = "fmi3GetVersion": fn() -> Str;
    set_debug_logging = "fmi3SetDebugLogging": fn(Instance3, Bool, usize, *const Str) -> Status;
    instantiate_me = "fmi3InstantiateModelExchange": fn(Str, Str, Str, Bool, Bool, Env, Logger) -> Instance3;
    instantiate_cs = "fmi3InstantiateCoSimulation": fn(Str, Str, Str, Bool, Bool, Bool, Bool, *const Vr, usize, Env, Logger, Cb) -> Instance3;
    instantiate_se = "fmi3InstantiateScheduledExecution": fn(Str, Str, Str, Bool, Bool, Env, Logger, Cb, Cb, Cb) -> Instance3;
    free_instance = "fmi3FreeInstance": fn(Instance3);
    enter_initialization_mode = "fmi3EnterInitializationMode": fn(Instance3, Bool, f64, f64, Bool, f64) -> Status;
    exit_initialization_mode = "fmi3ExitInitializationMode": fn(Instance3) -> Status;
    enter_event_mode = "fmi3EnterEventMode": fn(Instance3) -> Status;
    terminate = "fmi3Terminate": fn(Instance3) -> Status;
    reset = "fmi3Reset": fn(Instance3) -> Status;
    get_float32 = "fmi3GetFloat32": fn(Instance3, *const Vr, usize, *mut f32, usize) -> Status;
    get_float64 = "fmi3GetFloat64": fn(Instance3, *const Vr, usize, *mut f64, usize) -> Status;
    get_int8 = "fmi3GetInt8": fn(Instance3, *const Vr, usize, *mut i8, usize) -> Status;
    get_uint8 = "fmi3GetUInt8": fn(Instance3, *const Vr, usize, *mut u8, usize) -> Status;
    get_int16 = "fmi3GetInt16": fn(Instance3, *const Vr, usize, *mut i16, usize) -> Status;
    get_uint16 = "fmi3GetUInt16": fn(Instance3, *const Vr, usize, *mut u16, usize) -> Status;
    get_int32 = "fmi3GetInt32": fn(Instance3, *const Vr, usize, *mut i32, usize) -> Status;
    get_uint32 = "fmi3GetUInt32": fn(Instance3, *const Vr, usize, *mut u32, usize) -> Status;
    get_int64 = "fmi3GetInt64": fn(Instance3, *const Vr, usize, *mut i64, usize) -> Status;
    get_uint64 = "fmi3GetUInt64": fn(Instance3, *const Vr, usize, *mut u64, usize) -> Status;
    get_boolean = "fmi3GetBoolean": fn(Instance3, *const Vr, usize, *mut Bool, usize) -> Status;
    get_string = "fmi3GetString": fn(Instance3, *const Vr, usize, *mut Str, usize) -> Status;
    get_binary = "fmi3GetBinary": fn(Instance3, *const Vr, usize, *mut usize, *mut *const u8, usize) -> Status;
    get_clock = "fmi3GetClock": fn(Instance3, *const Vr, usize, *mut Bool) -> Status;
    set_float32 = "fmi3SetFloat32": fn(Instance3, *const Vr, usize, *const f32, usize) -> Status;
    set_float64 = "fmi3SetFloat64": fn(Instance3, *const Vr, usize, *const f64, usize) -> Status;
    set_int8 = "fmi3SetInt8": fn(Instance3, *const Vr, usize, *const i8, usize) -> Status;
    set_uint8 = "fmi3SetUInt8": fn(Instance3, *const Vr, usize, *const u8, usize) -> Status;
    set_int16 = "fmi3SetInt16": fn(Instance3, *const Vr, usize, *const i16, usize) -> Status;
    set_uint16 = "fmi3SetUInt16": fn(Instance3, *const Vr, usize, *const u16, usize) -> Status;
    set_int32 = "fmi3SetInt32": fn(Instance3, *const Vr, usize, *const i32, usize) -> Status;
    set_uint32 = "fmi3SetUInt32": fn(Instance3, *const Vr, usize, *const u32, usize) -> Status;
    set_int64 = "fmi3SetInt64": fn(Instance3, *const Vr, usize, *const i64, usize) -> Status;
    set_uint64 = "fmi3SetUInt64": fn(Instance3, *const Vr, usize, *const u64, usize) -> Status;
    set_boolean = "fmi3SetBoolean": fn(Instance3, *const Vr, usize, *const Bool, usize) -> Status;
    set_string = "fmi3SetString": fn(Instance3, *const Vr, usize, *const Str, usize) -> Status;
    set_binary = "fmi3SetBinary": fn(Instance3, *const Vr, usize, *const usize, *const *const u8, usize) -> Status;
    set_clock = "fmi3SetClock": fn(Instance3, *const Vr, usize, *const Bool) -> Status;
    get_number_of_variable_dependencies = "fmi3GetNumberOfVariableDependencies": fn(Instance3, Vr, *mut usize) -> Status;
    get_variable_dependencies = "fmi3GetVariableDependencies": fn(Instance3, Vr, *mut usize, *mut Vr, *mut usize, *mut c_int, usize) -> Status;
    get_fmu_state = "fmi3GetFMUState": fn(Instance3, *mut FmuState) -> Status;
    set_fmu_state = "fmi3SetFMUState": fn(Instance3, FmuState) -> Status;
    free_fmu_state = "fmi3FreeFMUState": fn(Instance3, *mut FmuState) -> Status;
    serialized_size = "fmi3SerializedFMUStateSize": fn(Instance3, FmuState, *mut usize) -> Status;
    serialize = "fmi3SerializeFMUState": fn(Instance3, FmuState, *mut u8, usize) -> Status;
    deserialize = "fmi3DeserializeFMUState": fn(Instance3, *const u8, usize, *mut FmuState) -> Status;
    get_directional_derivative = "fmi3GetDirectionalDerivative": fn(Instance3, *const Vr, usize, *const Vr, usize, *const f64, usize, *mut f64, usize) -> Status;
    get_adjoint_derivative = "fmi3GetAdjointDerivative": fn(Instance3, *const Vr, usize, *const Vr, usize, *const f64, usize, *mut f64, usize) -> Status;
    enter_configuration_mode = "fmi3EnterConfigurationMode": fn(Instance3) -> Status;
    exit_configuration_mode = "fmi3ExitConfigurationMode": fn(Instance3) -> Status;
    get_interval_decimal = "fmi3GetIntervalDecimal": fn(Instance3, *const Vr, usize, *mut f64, *mut c_int) -> Status;
    get_interval_fraction = "fmi3GetIntervalFraction": fn(Instance3, *const Vr, usize, *mut u64, *mut u64, *mut c_int) -> Status;
    get_shift_decimal = "fmi3GetShiftDecimal": fn(Instance3, *const Vr, usize, *mut f64) -> Status;
    get_shift_fraction = "fmi3GetShiftFraction": fn(Instance3, *const Vr, usize, *mut u64, *mut u64) -> Status;
    set_interval_decimal = "fmi3SetIntervalDecimal": fn(Instance3, *const Vr, usize, *const f64) -> Status;
    set_interval_fraction = "fmi3SetIntervalFraction": fn(Instance3, *const Vr, usize, *const u64, *const u64) -> Status;
    set_shift_decimal = "fmi3SetShiftDecimal": fn(Instance3, *const Vr, usize, *const f64) -> Status;
    set_shift_fraction = "fmi3SetShiftFraction": fn(Instance3, *const Vr, usize, *const u64, *const u64) -> Status;
    evaluate_discrete_states = "fmi3EvaluateDiscreteStates": fn(Instance3) -> Status;
    update_discrete_states = "fmi3UpdateDiscreteStates": fn(Instance3, *mut Bool, *mut Bool, *mut Bool, *mut Bool, *mut Bool, *mut f64) -> Status;
    enter_continuous_time_mode = "fmi3EnterContinuousTimeMode": fn(Instance3) -> Status;
    completed_integrator_step = "fmi3CompletedIntegratorStep": fn(Instance3, Bool, *mut Bool, *mut Bool) -> Status;
    set_time = "fmi3SetTime": fn(Instance3, f64) -> Status;
    set_continuous_states = "fmi3SetContinuousStates": fn(Instance3, *const f64, usize) -> Status;
    get_continuous_state_derivatives = "fmi3GetContinuousStateDerivatives": fn(Instance3, *mut f64, usize) -> Status;
    get_event_indicators = "fmi3GetEventIndicators": fn(Instance3, *mut f64, usize) -> Status;
    get_continuous_states = "fmi3GetContinuousStates": fn(Instance3, *mut f64, usize) -> Status;
    get_nominals = "fmi3GetNominalsOfContinuousStates": fn(Instance3, *mut f64, usize) -> Status;
    get_number_of_event_indicators = "fmi3GetNumberOfEventIndicators": fn(Instance3, *mut usize) -> Status;
    get_number_of_continuous_states = "fmi3GetNumberOfContinuousStates": fn(Instance3, *mut usize) -> Status;
    enter_step_mode = "fmi3EnterStepMode": fn(Instance3) -> Status;
    get_output_derivatives = "fmi3GetOutputDerivatives": fn(Instance3, *const Vr, usize, *const i32, *mut f64, usize) -> Status;
    do_step = "fmi3DoStep": fn(Instance3, f64, f64, Bool, *mut Bool, *mut Bool, *mut Bool, *mut f64) -> Status;
    activate_model_partition = "fmi3ActivateModelPartition": fn(Instance3, Vr, f64) -> Status;
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn declares_the_75_functions_of_fmi3_function_types() {
        // Expected value: fmi3FunctionTypes.h of FMI 3.0 declares 75 functions; one
        // field per `= "fmi3` in the table above.
        let source = include_str!("fmi3.rs");
        let table = source.split("mod tests").next().unwrap_or("");
        assert_eq!(table.matches("= \"fmi3").count(), 75);
    }
}
