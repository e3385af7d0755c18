//! Instantiation with arguments the standard forbids (FMI 2.0 2.1.5, FMI 3.0
//! 2.3.1): a null or empty instance name and a null or foreign GUID
//! (instantiation token), tried with each instantiation function of the standard;
//! and the rows only one standard has (FMI 2.0: missing callbacks, an unknown
//! fmuType; FMI 3.0: no logger, Scheduled Execution). The FMU returns NULL; when a
//! logger was given, it says why. The observed status is OK for an instance and
//! Error for NULL.

use super::seam::{Attempt, Names, Standard};
use super::{Case, Expect};
use crate::Loaded;

/// The rows both standards have: (name, arguments, expected log; None: OK).
fn rows(
    (token, logged): (&'static str, &'static str),
    guid: &str,
) -> Vec<(String, Names, Option<&'static str>)> {
    let ok = Names {
        name: Some("probe"),
        token: Some(guid.to_string()),
    };
    let with = |f: &dyn Fn(&mut Names)| {
        let mut n = ok.clone();
        f(&mut n);
        n
    };
    let foreign = "{00000000-0000-0000-0000-000000000000}";
    vec![
        ("all arguments valid (control)".into(), ok.clone(), None),
        (
            "instanceName = NULL".into(),
            with(&|n| n.name = None),
            Some("instanceName"),
        ),
        (
            "instanceName empty".into(),
            with(&|n| n.name = Some("")),
            Some("instanceName"),
        ),
        (
            format!("{token} = NULL"),
            with(&|n| n.token = None),
            Some(logged),
        ),
        (
            format!("{token} of another model"),
            with(&|n| n.token = Some(foreign.into())),
            Some(logged),
        ),
    ]
}

/// The rows both standards have, for each instantiation function.
fn common<I: Standard>(l: &Loaded, m: usize) -> Vec<Attempt> {
    let table = I::tables().instantiation;
    let guid = &I::description(l, m).guid;
    let mut attempts = Vec::new();
    for &kind in table.kinds {
        for (name, names, log) in rows(table.token, guid) {
            let attempt = table.attempt;
            attempts.push(Attempt {
                interface: kind.map(I::short),
                name,
                expect: log.map_or_else(Expect::ok, Expect::error),
                why: table.why,
                probe: Box::new(move |l| attempt(l, m, kind, &names)),
            });
        }
    }
    attempts
}

pub fn cases<I: Standard>(l: &Loaded, m: usize) -> Vec<Case> {
    let mut attempts = common::<I>(l, m);
    attempts.extend((I::tables().instantiation.own)(l, m));
    attempts
        .into_iter()
        .map(|a| Case {
            standard: I::STANDARD,
            class: "instantiate",
            model: m,
            interface: a.interface,
            name: a.name,
            expect: a.expect,
            why: a.why,
            probe: a.probe,
        })
        .collect()
}
