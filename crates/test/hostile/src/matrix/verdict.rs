//! The judge and the report of the matrix: a case's outcome against its
//! expectation and the list of known failures, and the table per class.

use super::{Case, Expect, Observed};
use crate::binary::status_name;
use crate::isolate;

/// Cases known to fail on the FMI layer this suite runs against, by full name
/// (`full_name`), each with the reason. They are reported (not hidden); one that
/// passes is an error, so the list is shrunk as fixes land. Empty since the PID
/// refuses 0 < Tf < 1 ps naming Tf and the plant's start-pose failure names the
/// geometry parameters (issue 12 item 3).
pub fn known_failures() -> Vec<(String, &'static str)> {
    Vec::new()
}

/// Outcome of one case.
pub enum Verdict {
    Pass,
    Fail(String),
    KnownFailure(String),
    FixedKnownFailure,
}

pub fn judge(case: &Case, result: &isolate::CaseResult) -> Verdict {
    let failure = match result {
        Err(death) => Some(death.clone()),
        Ok(line) => {
            let seen = Observed::decode(line);
            mismatch(&case.expect, &seen)
        }
    };
    let name = full_name(case);
    let known = known_failures()
        .into_iter()
        .find(|(known, _)| *known == name);
    match (failure, known) {
        (None, None) => Verdict::Pass,
        (None, Some(_)) => Verdict::FixedKnownFailure,
        (Some(f), None) => Verdict::Fail(f),
        (Some(f), Some((_, reason))) => Verdict::KnownFailure(format!("{f} [{reason}]")),
    }
}

fn mismatch(expect: &Expect, seen: &Observed) -> Option<String> {
    if let Some(p) = &seen.problem {
        return Some(shorten(p));
    }
    if !expect.statuses.contains(&seen.status) {
        let wanted: Vec<String> = expect.statuses.iter().map(|&s| status_name(s)).collect();
        return Some(format!(
            "returned {}, expected {} (log: {})",
            status_name(seen.status),
            wanted.join(" or "),
            shorten(&seen.log)
        ));
    }
    match &expect.log {
        Some(text) if !seen.log.to_lowercase().contains(&text.to_lowercase()) => Some(format!(
            "log lacks \"{text}\" (log: {})",
            if seen.log.is_empty() {
                "empty".into()
            } else {
                shorten(&seen.log)
            }
        )),
        _ => None,
    }
}

fn shorten(log: &str) -> String {
    match log.char_indices().nth(400) {
        Some((i, _)) => format!("{}...", &log[..i]),
        None => log.to_string(),
    }
}

/// "class / model / interface / name", the key of the known-failure list.
pub fn full_name(case: &Case) -> String {
    let interface = case.interface.unwrap_or("--");
    format!(
        "{} / {} / {} / {}",
        case.label(),
        crate::fmu::models()[case.model],
        interface,
        case.name
    )
}

/// Per class: cases, passed, failed, known failures; then every failure with its
/// expectation's reason. Returns the text and whether the suite failed.
pub fn report(cases: &[Case], verdicts: &[Verdict]) -> (String, bool) {
    let key = |c: &Case| (c.standard, c.class);
    let mut classes: Vec<&Case> = Vec::new();
    for c in cases {
        if !classes.iter().any(|k| key(k) == key(c)) {
            classes.push(c);
        }
    }
    let mut text = format!(
        "{:<24} {:>6} {:>6} {:>6} {:>6}  per model ({})\n",
        "class",
        "cases",
        "pass",
        "fail",
        "known",
        crate::fmu::models().join("/")
    );
    let mut details = String::new();
    let mut failed = false;
    for first in classes {
        let (mut n, mut pass, mut fail, mut known) = (0, 0, 0, 0);
        for (c, v) in cases
            .iter()
            .zip(verdicts)
            .filter(|(c, _)| key(c) == key(first))
        {
            n += 1;
            match v {
                Verdict::Pass => pass += 1,
                Verdict::KnownFailure(why) => {
                    known += 1;
                    details += &format!("KNOWN FAILURE {}: {why}\n", full_name(c));
                }
                Verdict::Fail(why) => {
                    fail += 1;
                    details += &format!(
                        "FAIL {}: {why}\n    expected because: {}\n",
                        full_name(c),
                        c.why
                    );
                }
                Verdict::FixedKnownFailure => {
                    fail += 1;
                    details += &format!(
                        "PASSES BUT LISTED AS KNOWN FAILURE (remove it): {}\n",
                        full_name(c)
                    );
                }
            }
        }
        failed |= fail > 0;
        let per_model: Vec<String> = (0..crate::fmu::models().len())
            .map(|m| {
                let count = cases
                    .iter()
                    .filter(|c| key(c) == key(first) && c.model == m)
                    .count();
                count.to_string()
            })
            .collect();
        text += &format!(
            "{:<24} {n:>6} {pass:>6} {fail:>6} {known:>6}  {}\n",
            first.label(),
            per_model.join("/")
        );
    }
    text += &format!("total cases: {}\n", cases.len());
    (details + &text, failed)
}
