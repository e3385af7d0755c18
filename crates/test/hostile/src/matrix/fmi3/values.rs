//! The FMI 3.0 rows of the scalar-argument cases of the value class
//! (`matrix::values`): times, step sizes, tolerances, continuous states and seeds
//! set to values the standard or the project refuses.

use crate::binary::ERROR;
use crate::description::Description;
use crate::fmi3::host::{Interface3, State3};
use crate::matrix::seam;

type Applies = fn(&Description, Interface3) -> bool;
type Scalar = seam::ScalarRow<Interface3>;

pub fn scalar_arguments() -> Vec<Scalar> {
    let any: Applies = |_, _| true;
    let me: Applies = |_, i| i.is_me();
    let me_states: Applies = |d, i| i.is_me() && d.number_of_states > 0;
    let cs: Applies = |_, i| i == Interface3::CoSimulation;
    let partials: Applies = |d, _| !d.state_derivative_pairs().is_empty();
    vec![
        (
            "fmi3EnterInitializationMode",
            "startTime = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, f64::NAN, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "startTime = inf",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, f64::INFINITY, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "tolerance = -1",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 1, -1.0, 0.0, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "tolerance = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 1, f64::NAN, 0.0, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "stopTime = -1 < startTime",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, 0.0, 1, -1.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "stopTime = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, 0.0, 1, f64::NAN) },
        ),
        (
            "fmi3SetDebugLogging",
            "categories = [\"noSuchCategory\"]",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.set_debug_logging)(i.c, 1, 1, &c"noSuchCategory".as_ptr()) },
        ),
        (
            "fmi3SetTime",
            "time = NaN",
            State3::ContinuousTimeMode,
            me,
            |i| unsafe { (i.binary.set_time)(i.c, f64::NAN) },
        ),
        (
            "fmi3SetTime",
            "time = inf",
            State3::ContinuousTimeMode,
            me,
            |i| unsafe { (i.binary.set_time)(i.c, f64::INFINITY) },
        ),
        (
            "fmi3SetContinuousStates",
            "x[0] = NaN",
            State3::ContinuousTimeMode,
            me_states,
            |i| unsafe {
                let n = i.description.number_of_states;
                let mut x = vec![0.0; n];
                (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n);
                if let Some(first) = x.first_mut() {
                    *first = f64::NAN;
                }
                (i.binary.set_continuous_states)(i.c, x.as_ptr(), n)
            },
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = NaN",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, f64::NAN).status,
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = inf",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, f64::INFINITY).status,
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = -1 ms",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, -1e-3).status,
        ),
        (
            "fmi3DoStep",
            "currentCommunicationPoint = NaN",
            State3::StepMode,
            cs,
            |i| i.do_step(f64::NAN, 1e-3).status,
        ),
        (
            "fmi3DoStep",
            "currentCommunicationPoint = 1 s, the FMU is at 0 s",
            State3::StepMode,
            cs,
            |i| i.do_step(1.0, 1e-3).status,
        ),
        (
            "fmi3GetDirectionalDerivative",
            "seed = NaN",
            State3::InitializationMode,
            partials,
            |i| unsafe {
                let d = i.description;
                let Some(&(x, dx)) = d.state_derivative_pairs().first() else {
                    return ERROR;
                };
                let seed = vec![f64::NAN; d.elements(&[x])];
                let mut out = vec![0.0; d.elements(&[dx])];
                (i.binary.get_directional_derivative)(
                    i.c,
                    &dx,
                    1,
                    &x,
                    1,
                    seed.as_ptr(),
                    seed.len(),
                    out.as_mut_ptr(),
                    out.len(),
                )
            },
        ),
    ]
}
