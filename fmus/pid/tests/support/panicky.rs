//! A model whose step panics, to prove that unwinds stop at the boundary of either
//! front-end (included by the FMI 2.0 and FMI 3.0 layer tests).

use crate::support::test_info;
use robofmu_fmi::core::{Declaration, Log, Model, ModelInfo, StepOutcome, Variability};

#[derive(Clone, Default)]
pub struct Panicky;

static PANICKY_INFO: ModelInfo = test_info("Panicky", "{panicky}", "panics in doStep");

impl Model for Panicky {
    const INFO: &'static ModelInfo = &PANICKY_INFO;
    const VARIABLES: &'static [Declaration<Self>] =
        &[Declaration::real("k", "a parameter", |_, _| 1.0)
            .parameter(Variability::Fixed)
            .start_real(&[1.0])
            .set_real(|_, _, _| Ok(()))];
    fn set_time(&mut self, _time: f64) {}
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        panic!("deliberate test panic")
    }
}
