//! The importer's intermediateUpdate callback (FMI 3.0 Co-Simulation, section 4.2.4),
//! called by a split fmi3DoStep at its intermediate points.

use super::types::{
    FMI3_FALSE, FMI3_TRUE, Fmi3Boolean, Fmi3InstanceEnvironment, Fmi3IntermediateUpdateCallback,
    fmi3_bool,
};

/// The callback with the instance environment it is called with.
#[derive(Clone, Copy)]
pub struct IntermediateUpdate {
    pub function: Fmi3IntermediateUpdateCallback,
    pub environment: Fmi3InstanceEnvironment,
}

// The environment pointer is the host's opaque token, handed back only to the host's
// own callback, from the thread that called fmi3DoStep.
unsafe impl Send for IntermediateUpdate {}

impl IntermediateUpdate {
    /// The callback, if the host passed one.
    pub fn new(
        function: Option<Fmi3IntermediateUpdateCallback>,
        environment: Fmi3InstanceEnvironment,
    ) -> Option<Self> {
        function.map(|function| IntermediateUpdate {
            function,
            environment,
        })
    }

    /// Calls the importer at the intermediate point `time`, after a finished
    /// sub-interval: it may get outputs and set inputs (intermediateVariableGetAllowed
    /// and intermediateVariableSetRequested). Some(t): with `can_return_early`, it asked
    /// the step to return early, at the first intermediate point at or after t (a
    /// time not after `time`, or not a number, means at once).
    ///
    /// # Safety
    /// No reference into the instance may be live: the importer calls back into it.
    pub unsafe fn call(&self, time: f64, can_return_early: bool) -> Option<f64> {
        let mut requested: Fmi3Boolean = FMI3_FALSE;
        let mut at = time;
        // SAFETY: the host's fmi3IntermediateUpdateCallback with its environment; the
        // two outputs live until it returns.
        unsafe {
            (self.function)(
                self.environment,
                time,
                FMI3_TRUE,
                FMI3_TRUE,
                FMI3_TRUE,
                fmi3_bool(can_return_early),
                &mut requested,
                &mut at,
            )
        };
        (can_return_early && requested != FMI3_FALSE).then_some(at.max(time))
    }
}
