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
        crate::core::callback::host("intermediateUpdate", || unsafe {
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
        });
        (can_return_early && requested != FMI3_FALSE).then_some(at.max(time))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    thread_local! {
        /// What the test callback answers: (earlyReturnRequested, earlyReturnTime).
        static ANSWER: Cell<(bool, f64)> = const { Cell::new((false, 0.0)) };
        /// canReturnEarly as the callback received it.
        static OFFERED: Cell<bool> = const { Cell::new(false) };
    }

    unsafe extern "C-unwind" fn answer(
        _environment: Fmi3InstanceEnvironment,
        _time: f64,
        _set_requested: Fmi3Boolean,
        _get_allowed: Fmi3Boolean,
        _finished: Fmi3Boolean,
        can_return_early: Fmi3Boolean,
        requested: *mut Fmi3Boolean,
        at: *mut f64,
    ) {
        let (ask, time) = ANSWER.get();
        OFFERED.set(can_return_early != FMI3_FALSE);
        // SAFETY: `call` passes two live outputs.
        unsafe {
            *requested = fmi3_bool(ask);
            *at = time;
        }
    }

    fn asked(ask: bool, at: f64, can_return_early: bool) -> Option<f64> {
        ANSWER.set((ask, at));
        let callback = IntermediateUpdate::new(Some(answer), std::ptr::null_mut()).unwrap();
        // SAFETY: no instance is involved.
        unsafe { callback.call(0.5, can_return_early) }
    }

    #[test]
    fn an_early_return_counts_only_when_offered_and_never_before_the_point() {
        // Expected values: section 4.2.4: earlyReturnRequested is meaningful only with
        // canReturnEarly; a requested time not after the point (or NaN) means at once.
        assert_eq!(asked(true, 0.7, true), Some(0.7));
        assert!(OFFERED.get());
        assert_eq!(asked(true, 0.2, true), Some(0.5));
        assert_eq!(asked(true, f64::NAN, true), Some(0.5));
        assert_eq!(asked(false, 0.7, true), None);
        assert_eq!(asked(true, 0.7, false), None);
        assert!(!OFFERED.get());
        assert!(IntermediateUpdate::new(None, std::ptr::null_mut()).is_none());
    }
}
