//! One status for a value the model cannot evaluate (issue 20, defect 5): Discard
//! everywhere, with the model's reason.
//!
//! - Initialization Mode: each Real parameter set to a value that ExitInitialization
//!   Mode refuses (tried: 1e6, -1e6, 0; a value the setter refuses is skipped); every
//!   Real read before the exit must then be OK or Discard (never Error, which would
//!   end the instance), and a Discard must give the parameters' reason ("invalid
//!   parameters", as the exit does), not a consequence such as "evaluates to NaN".
//! - Model Exchange (FMI 3.0, models with event indicators): at continuous states the
//!   model cannot evaluate, fmi3GetFloat64 of the event-indicator variable must
//!   answer as fmi3GetEventIndicators does (Discard), not Error.

use super::api::{Api, Handle};
use super::host::Host;
use super::{Outcome, expect};
use crate::binary::{DISCARD, ERROR, OK, Status};
use crate::description::VarType;

/// Values tried for each parameter in Initialization Mode.
const TRIED: [f64; 3] = [1e6, -1e6, 0.0];

/// Reads every Real; Err on an Error, or a Discard without the parameters' reason.
fn reads_discard_with_reason(
    api: &dyn Api,
    h: Handle,
    host: &Host,
    what: &str,
) -> Result<usize, String> {
    let mut discards = 0;
    for v in api.description().of_type(VarType::Real) {
        host.lines.borrow_mut().clear();
        match api.get_real(h, v.vr).0 {
            OK => {}
            DISCARD if host.logged("invalid parameters") => discards += 1,
            s => {
                return Err(format!(
                    "{what}: GetReal(\"{}\") returned {s} before the refused exit: {}",
                    v.name,
                    host.log_text()
                ));
            }
        }
    }
    Ok(discards)
}

pub fn refused_parameters(api: &dyn Api) -> Outcome {
    let parameters: Vec<_> = api
        .description()
        .of_type(VarType::Real)
        .filter(|v| v.is_parameter())
        .collect();
    let (mut refused, mut discards) = (0, 0);
    for v in parameters {
        for x in TRIED {
            let host = Host::new();
            let h = api.instantiate(&host);
            host.handle.set(h);
            let result: Result<(), String> = (|| {
                expect(
                    api.enter_initialization(h, 0.0),
                    OK,
                    "Initialization Mode",
                    &host,
                )?;
                if api.set_real(h, v.vr, x) != OK {
                    return Ok(());
                }
                let what = format!("{} = {x}", v.name);
                let n = reads_discard_with_reason(api, h, &host, &what)?;
                if api.exit_initialization(h) == ERROR {
                    refused += 1;
                    discards += n;
                }
                Ok(())
            })();
            api.free(h);
            result?;
        }
    }
    if refused == 0 {
        return Err("no tried parameter value is refused at ExitInitializationMode".into());
    }
    Ok(format!(
        "{refused} refused parameter sets; {discards} reads Discard with their reason, none Error"
    ))
}

/// Continuous states tried in Model Exchange (angles far outside any assembly).
const STATES: [f64; 4] = [3.0, -3.0, 1e3, 1.5];

pub fn event_indicators_agree(api: &dyn Api) -> Outcome {
    let Some(b) = api.fmi3() else {
        return Err("FMI 3.0 only".into());
    };
    let d = api.description();
    let Some(z) = d.variables.iter().find(|v| v.name == "eventIndicators") else {
        return Err(format!("{} has no eventIndicators variable", d.model_name));
    };
    let (n, nx) = (d.number_of_event_indicators, d.number_of_states);
    let host = Host::new();
    let h = super::api::instantiate_me(b, d, &host);
    let mut discarded = 0;
    let result: Result<(), String> = (|| {
        expect(
            api.initialize(h, 0.0),
            OK,
            "initialize (Model Exchange)",
            &host,
        )?;
        // SAFETY: a live instance; arrays of the model's counts.
        expect(
            unsafe { (b.enter_continuous_time_mode)(h) },
            OK,
            "EnterContinuousTimeMode",
            &host,
        )?;
        for x in STATES {
            let states = vec![x; nx];
            let (mut a, mut c) = (vec![0.0; n], vec![0.0; n]);
            // SAFETY: as above.
            let (set, by_array, by_get) = unsafe {
                (
                    (b.set_continuous_states)(h, states.as_ptr(), nx),
                    (b.get_event_indicators)(h, a.as_mut_ptr(), n),
                    (b.get_float64)(h, &z.vr, 1, c.as_mut_ptr(), n),
                )
            };
            expect(set, OK, "SetContinuousStates", &host)?;
            if by_array != by_get {
                return Err(format!(
                    "states {x}: GetEventIndicators {by_array}, GetFloat64(eventIndicators) {by_get}: {}",
                    host.log_text()
                ));
            }
            discarded += usize::from(by_array == DISCARD);
        }
        Ok(())
    })();
    api.free(h);
    result?;
    if discarded == 0 {
        return Err("no tried state makes the event indicators unevaluable".into());
    }
    Ok(format!("{discarded} unevaluable states: both Discard"))
}

/// The experiment's tolerance (issue 36; docs/interoperability.md, "Tolerance"):
/// (toleranceDefined, tolerance, expected status of fmi2SetupExperiment +
/// fmi2EnterInitializationMode, or fmi3EnterInitializationMode).
const TOLERANCES: [(bool, f64, Status); 8] = [
    (true, 1e-4, OK),
    (true, 1e-300, OK),
    (false, 0.0, OK),
    (false, f64::NAN, OK),
    (true, 0.0, ERROR),
    (true, -1e-6, ERROR),
    (true, f64::NAN, ERROR),
    (true, f64::INFINITY, ERROR),
];

/// Each row of `TOLERANCES` on a fresh instance. The standards give the tolerance a
/// meaning only when it is defined, as the relative tolerance of an error-controlled
/// integration; a defined one that is not a positive finite number is refused with
/// Error and a log line naming it and the fix, a positive one accepted (unused: the
/// FMUs take no tolerance from the importer), an undefined one ignored whatever its
/// value. An accepted one leaves an instance that initializes.
pub fn tolerances(api: &dyn Api) -> Outcome {
    for (defined, tolerance, want) in TOLERANCES {
        let host = Host::new();
        let h = api.instantiate(&host);
        if h.is_null() {
            return Err(format!("instantiate refused: {}", host.log_text()));
        }
        let what = format!("toleranceDefined = {defined}, tolerance = {tolerance:e}");
        let got = api.enter_initialization_with(h, defined.then_some(tolerance), 0.0);
        let result = expect(got, want, &what, &host).and_then(|()| {
            if want == OK {
                return expect(api.exit_initialization(h), OK, &what, &host);
            }
            if host.logged(&format!("tolerance = {tolerance}")) && host.logged("toleranceDefined") {
                Ok(())
            } else {
                Err(format!(
                    "{what}: refused without naming it: {}",
                    host.log_text()
                ))
            }
        });
        api.free(h);
        result?;
    }
    Ok(format!("{} tolerances: as documented", TOLERANCES.len()))
}
