//! What an FMI 3.0 instance keeps beyond the fields every instance has
//! ([`FmuInstance`](crate::core::frontend::FmuInstance)): the `Extra` of the FMI 3.0
//! front-end.

use super::clocks::Clocks;
use super::intermediate::IntermediateUpdate;
use super::table::Table3;
use std::sync::Arc;

/// What an FMI 3.0 instance keeps beyond the shared fields.
pub struct Fmi3Extra {
    /// The FMI 3.0 view of the core's table (shared, so that a call can hold it while
    /// it changes the instance).
    pub table: Arc<Table3>,
    /// The importer's intermediateUpdate callback (Co-Simulation; None: steps are not
    /// split).
    pub intermediate_update: Option<IntermediateUpdate>,
    /// The model's input clocks (periods, activations).
    pub clocks: Clocks,
}
