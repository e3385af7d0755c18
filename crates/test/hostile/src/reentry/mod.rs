//! A host that calls back, reuses addresses, forges states and shares an instance
//! between threads (issue 20), through the packaged binaries: the probes of
//! `calls` (calls from the log callback), `reuse` (handles whose memory comes back,
//! requiredIntermediateVariables), `threads` (a second thread on a busy instance)
//! and `crate::forged` (re-sealed edited states, times that overflow or stand
//! still), registered in [`cases`] for both standards and every model. Each probe
//! returns what it saw (Ok) or why the FMU failed it (Err); `tests/reentry.rs` runs
//! them in forked children, `robofmu-hostile-reentry` in one process under valgrind.

pub mod api;
pub mod calls;
pub mod host;
pub mod reuse;
pub mod status;
pub mod threads;

use crate::binary::{Status, status_name};
use crate::forged;
use api::{Api, Handle};
use host::Host;

/// What a probe saw, or why the FMU failed it.
pub type Outcome = Result<String, String>;

/// Err naming `what`, the status and the log unless `got` is `want`.
pub fn expect(got: Status, want: Status, what: &str, host: &Host) -> Result<(), String> {
    if got == want {
        return Ok(());
    }
    Err(format!(
        "{what} returned {got} ({}), expected {}: {}",
        status_name(got),
        status_name(want),
        host.log_text()
    ))
}

/// A Co-Simulation instance of `api` initialized at t = 0, its handle in `host`.
pub fn started(api: &dyn Api, host: &Host) -> Result<Handle, String> {
    let h = api.instantiate(host);
    if h.is_null() {
        return Err(format!("instantiate refused: {}", host.log_text()));
    }
    host.handle.set(h);
    expect(api.initialize(h, 0.0), OK_STATUS, "initialize", host)?;
    Ok(h)
}

const OK_STATUS: Status = crate::binary::OK;

/// What a case runs on one FMU.
pub type Probe = Box<dyn Fn(&dyn Api) -> Outcome + Sync>;

/// One probe: its class, its name and what it runs.
pub struct Case {
    pub class: &'static str,
    pub name: String,
    pub run: Probe,
}

/// Which FMUs a probe applies to.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Scope {
    All,
    /// FMI 3.0 only (intermediateUpdate, requiredIntermediateVariables).
    Fmi3,
    /// FMI 3.0 models with an eventIndicators variable.
    Fmi3Indicators,
}

type Entry = (&'static str, &'static str, fn(&dyn Api) -> Outcome, Scope);

/// The fixed probes: class, name, probe, scope.
const PROBES: [Entry; 16] = [
    (
        "callbacks",
        "logger frees on Error",
        calls::free_on_error,
        Scope::All,
    ),
    (
        "callbacks",
        "logger frees at the DoStep logCalls line",
        calls::free_at_do_step_line,
        Scope::All,
    ),
    (
        "callbacks",
        "logger resets on Error",
        calls::reset_on_error,
        Scope::All,
    ),
    (
        "callbacks",
        "logger sets an FMU state on Error",
        calls::set_state_on_error,
        Scope::All,
    ),
    (
        "callbacks",
        "logger calls a getter inside DoStep",
        calls::getter_at_do_step_line,
        Scope::All,
    ),
    (
        "reuse",
        "freed instance, new one at its address",
        reuse::freed_instance,
        Scope::All,
    ),
    (
        "reuse",
        "freed FMU state, new one at its address",
        reuse::freed_state,
        Scope::All,
    ),
    (
        "reuse",
        "intermediateUpdate frees and re-instantiates",
        reuse::freed_in_intermediate_update,
        Scope::Fmi3,
    ),
    (
        "reuse",
        "requiredIntermediateVariables garbage, n = 2^60",
        reuse::garbage_required_variables,
        Scope::Fmi3,
    ),
    (
        "threads",
        "second thread inside a call, then free",
        threads::second_thread_then_free,
        Scope::All,
    ),
    (
        "threads",
        "another thread inside when intermediateUpdate returns",
        threads::get_while_resuming,
        Scope::Fmi3,
    ),
    ("time", "step to +inf", forged::step_to_infinity, Scope::All),
    (
        "time",
        "step that does not advance the time",
        forged::step_that_does_not_advance,
        Scope::All,
    ),
    (
        "status",
        "the experiment's tolerance",
        status::tolerances,
        Scope::All,
    ),
    (
        "status",
        "refused parameters: Discard with their reason",
        status::refused_parameters,
        Scope::All,
    ),
    (
        "status",
        "GetFloat64(eventIndicators) as GetEventIndicators",
        status::event_indicators_agree,
        Scope::Fmi3Indicators,
    ),
];

/// Every probe for the FMU of `api` (the forged states depend on its parameters).
pub fn cases(api: &dyn Api) -> Vec<Case> {
    let fmi3 = api.fmi3().is_some();
    let indicators = api
        .description()
        .variables
        .iter()
        .any(|v| v.name == "eventIndicators");
    let applies = |scope| match scope {
        Scope::All => true,
        Scope::Fmi3 => fmi3,
        Scope::Fmi3Indicators => fmi3 && indicators,
    };
    let mut all: Vec<Case> = PROBES
        .iter()
        .filter(|(.., scope)| applies(*scope))
        .map(|&(class, name, run, _)| Case {
            class,
            name: name.into(),
            run: Box::new(run),
        })
        .collect();
    for (name, edit) in forged::edits(api) {
        all.push(Case {
            class: "forged states",
            name,
            run: Box::new(move |api| forged::forged(api, &edit)),
        });
    }
    all
}

/// Every loaded FMU as an [`Api`]: FMI 2.0 then FMI 3.0, models in order.
pub fn apis(loaded: &crate::Loaded) -> Vec<Box<dyn Api + '_>> {
    let two = loaded.fmus.iter().zip(&loaded.binaries);
    let three = loaded.fmus3.iter().zip(&loaded.binaries3);
    let mut all: Vec<Box<dyn Api + '_>> = Vec::new();
    all.extend(two.map(|(fmu, binary)| Box::new(api::Api2 { fmu, binary }) as Box<dyn Api>));
    all.extend(three.map(|(fmu, binary)| Box::new(api::Api3 { fmu, binary }) as Box<dyn Api>));
    all
}

/// Cases, passes and failures per class, in the order classes first appear.
#[derive(Default)]
pub struct Tally(Vec<(&'static str, usize, usize)>);

impl Tally {
    pub fn add(&mut self, class: &'static str, passed: bool) {
        let at = match self.0.iter().position(|(c, ..)| *c == class) {
            Some(at) => at,
            None => {
                self.0.push((class, 0, 0));
                self.0.len() - 1
            }
        };
        self.0[at].1 += 1;
        self.0[at].2 += usize::from(passed);
    }

    pub fn failed(&self) -> usize {
        self.0.iter().map(|(_, n, pass)| n - pass).sum()
    }

    /// The table printed after a run.
    pub fn table(&self) -> String {
        let mut out = format!(
            "{:<16} {:>6} {:>6} {:>6}\n",
            "class", "cases", "pass", "fail"
        );
        for (class, n, pass) in &self.0 {
            out += &format!("{class:<16} {n:>6} {pass:>6} {:>6}\n", n - pass);
        }
        let total: usize = self.0.iter().map(|(_, n, _)| n).sum();
        out + &format!("total cases: {total}")
    }
}
