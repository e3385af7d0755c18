//! What the pid crate's layer tests share (each test file includes this module).

use robofmu_fmi::core::{DefaultExperiment, ModelInfo};

/// The `ModelInfo` of a test model: no continuous states, event indicators, log
/// categories or directional derivatives; default experiment 0..1 s by 0.1 s.
pub const fn test_info(
    name: &'static str,
    guid: &'static str,
    description: &'static str,
) -> ModelInfo {
    ModelInfo {
        model_name: name,
        model_identifier: name,
        guid,
        description,
        default_experiment: DefaultExperiment {
            start_time: 0.0,
            stop_time: 1.0,
            tolerance: 1e-6,
            step_size: 0.1,
        },
        number_of_continuous_states: 0,
        number_of_event_indicators: 0,
        provides_directional_derivative: false,
        max_output_derivative_order: 0,
        log_categories: &[],
    }
}
