//! The bad-input matrix, one for both standards: every case names the call it
//! makes, the status and log text it expects and why (the standard's rule or the
//! project's documented choice). Each case class is written once, generic over
//! the seam `seam::Standard`, and run for FMI 2.0 (`fmi2`: its call tables and
//! reasons) and FMI 3.0 (`fmi3`); classes only one standard has are listed in its
//! tables. Cases run in forked children, grouped per model; a crash fails only the
//! case that caused it.

pub mod fixed;
pub mod fmi2;
pub mod fmi3;
pub mod handles;
pub mod instantiate;
pub mod orders;
pub mod pointers;
pub mod pose;
pub mod references;
pub mod same_named;
pub mod seam;
pub mod serialized;
pub mod states;
pub mod values;
pub mod verdict;

use crate::Loaded;
use crate::binary::{DISCARD, ERROR, OK, Status};
use crate::fmu::Standard;
use crate::host::{Probed, take, unlogged};
use crate::isolate;
use crate::standard_interface::StandardInterface;
pub use verdict::{Verdict, full_name, judge, known_failures, report};

/// What a case expects: one of `statuses`, and `log` (when given) contained in the
/// log lines of the call, compared without case.
pub struct Expect {
    pub statuses: &'static [Status],
    pub log: Option<String>,
}

impl Expect {
    pub fn error(log: &str) -> Expect {
        Expect {
            statuses: &[ERROR],
            log: Some(log.to_string()),
        }
    }
    /// fmi2Error with no log requirement (no trustworthy logger exists).
    pub fn silent_error() -> Expect {
        Expect {
            statuses: &[ERROR],
            log: None,
        }
    }
    /// fmi2Discard; its log line depends on the host enabling logStatusDiscard.
    pub fn discard() -> Expect {
        Expect {
            statuses: &[DISCARD],
            log: None,
        }
    }
    pub fn ok() -> Expect {
        Expect {
            statuses: &[OK],
            log: None,
        }
    }
}

/// What a probe saw: the status, the log of the call and any broken invariant.
pub struct Observed {
    pub status: Status,
    pub log: String,
    pub problem: Option<String>,
}

impl Observed {
    pub fn of(status: Status, log: String) -> Observed {
        Observed {
            status,
            log,
            problem: None,
        }
    }
    pub fn broken(problem: String) -> Observed {
        Observed {
            status: -1,
            log: String::new(),
            problem: Some(problem),
        }
    }
    fn encode(&self) -> String {
        let clean = |s: &str| s.replace('\t', " ");
        format!(
            "{}\t{}\t{}",
            self.status,
            clean(self.problem.as_deref().unwrap_or("")),
            clean(&self.log)
        )
    }
    fn decode(line: &str) -> Observed {
        let mut parts = line.splitn(3, '\t');
        let status = parts.next().and_then(|s| s.parse().ok()).unwrap_or(-1);
        let problem = parts.next().filter(|p| !p.is_empty()).map(str::to_string);
        let log = parts.next().unwrap_or("").to_string();
        Observed {
            status,
            log,
            problem,
        }
    }
}

pub type Probe = Box<dyn Fn(&Loaded) -> Observed>;

pub struct Case {
    pub standard: Standard,
    pub class: &'static str,
    pub model: usize,
    /// The interface's short name ("ME", "CS", "CS+events"), None for instantiation.
    pub interface: Option<&'static str>,
    pub name: String,
    pub expect: Expect,
    pub why: &'static str,
    pub probe: Probe,
}

/// A fresh instance of model `m` brought into `state`, then `call` on it; after
/// the call, the instance must be usable as its standard requires
/// (`StandardInterface::usable_after`).
pub fn on_instance<I: StandardInterface>(
    loaded: &Loaded,
    m: usize,
    interface: I,
    state: I::State,
    call: impl Fn(&I::Instance<'_>) -> Status,
) -> Observed {
    let inst = interface.instance(loaded, m);
    if let Err(e) = I::reach(&inst, state) {
        return Observed::broken(format!("could not reach {state:?}: {e}"));
    }
    let status = call(&inst);
    let log = take(inst.log());
    if let Err(e) = I::usable_after(&inst, status) {
        return Observed::broken(e);
    }
    Observed::of(status, log)
}

impl Case {
    /// A case of class `class` of standard `I` on model `m` and `interface`:
    /// its name, what it expects and why, and its probe.
    pub fn new<I: seam::Standard>(
        (class, model, interface): (&'static str, usize, I),
        name: String,
        (expect, why): (Expect, &'static str),
        probe: impl Fn(&Loaded) -> Observed + 'static,
    ) -> Case {
        Case {
            standard: I::STANDARD,
            class,
            model,
            interface: Some(interface.short()),
            name,
            expect,
            why,
            probe: Box::new(probe),
        }
    }
    /// The class as the report names it: "fmi3 " before the FMI 3.0 classes.
    pub fn label(&self) -> String {
        match self.standard {
            Standard::Fmi2 => self.class.to_string(),
            Standard::Fmi3 => format!("fmi3 {}", self.class),
        }
    }
}

/// Runs the cases, each model's cases in its own sequence of forked children.
pub fn run(loaded: &Loaded, cases: &[Case]) -> Vec<Verdict> {
    let results = isolate::run_cases(cases.len(), &|i| (cases[i].probe)(loaded).encode());
    cases
        .iter()
        .zip(&results)
        .map(|(c, r)| judge(c, r))
        .collect()
}

/// Every case of the matrix, FMI 2.0 then FMI 3.0.
pub fn all_cases(loaded: &Loaded) -> Vec<Case> {
    let mut cases = cases_of::<crate::host::Interface>(loaded);
    cases.extend(cases_of::<crate::fmi3::host::Interface3>(loaded));
    cases
}

/// A builder of the cases of one class for model `m`.
pub type Cases = fn(&Loaded, usize) -> Vec<Case>;

/// The classes of the matrix, each written once for both standards.
fn classes<I: seam::Standard>() -> Vec<Cases> {
    vec![
        pointers::cases::<I>,
        references::cases::<I>,
        values::cases::<I>,
        serialized::cases::<I>,
        orders::cases::<I>,
        handles::cases::<I>,
        states::cases::<I>,
        pose::cases::<I>,
        instantiate::cases::<I>,
        fixed::cases::<I>,
    ]
}

/// The cases of one standard: every class, then the standard's own classes,
/// model by model.
pub fn cases_of<I: seam::Standard>(loaded: &Loaded) -> Vec<Case> {
    let mut all = classes::<I>();
    all.extend_from_slice(I::tables().own_classes);
    (0..crate::fmu::models().len())
        .flat_map(|m| all.iter().flat_map(move |class| class(loaded, m)))
        .collect()
}

/// Like `on_instance`, with well-formed arguments that include a valid FMU state
/// of the instance (taken after reaching `state`, freed after the call).
pub fn with_args<I: StandardInterface>(
    loaded: &Loaded,
    m: usize,
    interface: I,
    state: I::State,
    call: impl Fn(&I::Instance<'_>, &I::Args) -> Status,
) -> Observed {
    on_instance(loaded, m, interface, state, |inst| {
        let (_, fmu_state) = unlogged(inst, || inst.new_state());
        let status = call(inst, &I::args(inst, fmu_state));
        unlogged(inst, || inst.release_state(fmu_state));
        status
    })
}
