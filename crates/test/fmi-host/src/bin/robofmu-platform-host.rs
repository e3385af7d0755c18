//! robofmu-platform-host: a minimal FMI 2.0 co-simulation host that runs one
//! reference case against one FMU binary and prints the outputs, one line per
//! communication point. It is cross-built for every platform the FMUs carry
//! (scripts/build-fmus.sh) and run natively, under Wine and under qemu-aarch64 by
//! tests/python/test_platforms.py, which compares the lines of every platform with
//! those of x86_64 Linux. It needs only the standard library, the C runtime and the
//! FMI 2.0 host of this crate (its loader, table and callbacks: dlopen on Linux
//! and macOS, LoadLibraryW on Windows).
//!
//! Usage: `robofmu-platform-host PLAN` where PLAN is a text file written by the test
//! (one directive a line, values separated by single spaces):
//!
//! ```text
//! library <path of the .so/.dll/.dylib>
//! guid <the description's guid>
//! start <t0>
//! stop <t1>
//! step <h>
//! real <vr> <value>          (start values, before initialization; also
//! integer <vr> <value>        `boolean <vr> 0|1`)
//! inputs <vr> <vr> ...        (real inputs, set before every step)
//! at <value> <value> ...      (the inputs' values at t0 + k h, one line per k)
//! outputs <vr> <vr> ...       (real outputs, read at every communication point)
//! ```
//!
//! Output: `t y1 y2 ...` at t0 and after every step, each number in Rust's shortest
//! round-trip form (the same double parses back). Errors: one line on stderr naming
//! the plan or the FMI call (with what the FMU logged), exit 2 (a bad plan) or 1 (the FMU refused a call).

use robofmu_fmi_host::callbacks::Callbacks;
use robofmu_fmi_host::fmi2::Binary;
use robofmu_fmi_host::instance::{Fmi2Instance, Interface};
use std::ffi::c_int;
use std::path::Path;
use std::process::ExitCode;

/// A start value of the plan.
enum Start {
    Real(u32, f64),
    Integer(u32, c_int),
    Boolean(u32, c_int),
}

/// The parsed plan file.
#[derive(Default)]
struct Plan {
    library: String,
    guid: String,
    start: f64,
    stop: f64,
    step: f64,
    starts: Vec<Start>,
    inputs: Vec<u32>,
    rows: Vec<Vec<f64>>,
    outputs: Vec<u32>,
}

fn number<T: std::str::FromStr>(word: &str, line: usize) -> Result<T, String> {
    word.parse()
        .map_err(|_| format!("line {line}: {word:?} is not a number"))
}

fn parse(text: &str) -> Result<Plan, String> {
    let mut plan = Plan::default();
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let (key, rest) = line.split_once(' ').unwrap_or((line, ""));
        let words: Vec<&str> = rest.split(' ').filter(|w| !w.is_empty()).collect();
        let pair = || -> Result<(u32, &str), String> {
            match words.as_slice() {
                [vr, value] => Ok((number(vr, n)?, *value)),
                _ => Err(format!(
                    "line {n}: `{key}` takes a value reference and a value"
                )),
            }
        };
        match key {
            "library" => plan.library = rest.to_string(),
            "guid" => plan.guid = rest.to_string(),
            "start" => plan.start = number(rest, n)?,
            "stop" => plan.stop = number(rest, n)?,
            "step" => plan.step = number(rest, n)?,
            "real" => {
                let (vr, v) = pair()?;
                plan.starts.push(Start::Real(vr, number(v, n)?));
            }
            "integer" => {
                let (vr, v) = pair()?;
                plan.starts.push(Start::Integer(vr, number(v, n)?));
            }
            "boolean" => {
                let (vr, v) = pair()?;
                plan.starts.push(Start::Boolean(vr, number(v, n)?));
            }
            "inputs" => {
                plan.inputs = words
                    .iter()
                    .map(|w| number(w, n))
                    .collect::<Result<_, _>>()?
            }
            "outputs" => {
                plan.outputs = words
                    .iter()
                    .map(|w| number(w, n))
                    .collect::<Result<_, _>>()?
            }
            "at" => plan.rows.push(
                words
                    .iter()
                    .map(|w| number(w, n))
                    .collect::<Result<_, _>>()?,
            ),
            "" => {}
            other => return Err(format!("line {n}: unknown directive {other:?}")),
        }
    }
    let valid = !plan.library.is_empty() && plan.step > 0.0 && plan.stop >= plan.start;
    if !valid {
        return Err("needs `library`, `step` > 0 and `stop` >= `start`".to_string());
    }
    Ok(plan)
}

/// Runs the plan; the output lines.
fn simulate(plan: &Plan) -> Result<Vec<String>, String> {
    let binary = Binary::open(Path::new(&plan.library))?;
    let cs = Interface::CoSimulation;
    let f = Fmi2Instance::new(&binary, "host", cs, &plan.guid, Callbacks::ALL, false)?;
    f.setup_experiment(plan.start, Some(plan.stop))?;
    for s in &plan.starts {
        match *s {
            Start::Real(vr, v) => f.ok("fmi2SetReal", f.set_real(vr, v))?,
            Start::Integer(vr, v) => f.ok("fmi2SetInteger", f.set_integer(vr, v))?,
            Start::Boolean(vr, v) => f.ok("fmi2SetBoolean", f.set_boolean(vr, v != 0))?,
        }
    }
    // SAFETY (both calls): the live instance of this binary.
    let s = unsafe { (binary.enter_initialization_mode)(f.c) };
    f.ok("fmi2EnterInitializationMode", s)?;
    let s = unsafe { (binary.exit_initialization_mode)(f.c) };
    f.ok("fmi2ExitInitializationMode", s)?;
    let steps = ((plan.stop - plan.start) / plan.step).round() as usize;
    let mut lines = Vec::with_capacity(steps + 1);
    for k in 0..=steps {
        let t = plan.start + k as f64 * plan.step;
        if !plan.inputs.is_empty() {
            let row = plan
                .rows
                .get(k)
                .filter(|r| r.len() == plan.inputs.len())
                .ok_or_else(|| {
                    format!(
                        "the plan has no `at` line of {} inputs for step {k}",
                        plan.inputs.len()
                    )
                })?;
            f.ok("fmi2SetReal (inputs)", f.set_reals(&plan.inputs, row))?;
        }
        let (status, y) = f.get_reals(&plan.outputs);
        f.ok("fmi2GetReal", status)?;
        let mut line = format!("{t}");
        for v in &y {
            line.push_str(&format!(" {v}"));
        }
        lines.push(line);
        if k < steps {
            f.ok("fmi2DoStep", f.do_step(t, plan.step))?;
        }
    }
    // SAFETY: as above; the instance is freed when `f` drops.
    let s = unsafe { (binary.terminate)(f.c) };
    f.ok("fmi2Terminate", s)?;
    Ok(lines)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path] = args.as_slice() else {
        eprintln!("robofmu-platform-host: usage: robofmu-platform-host PLAN");
        return ExitCode::from(2);
    };
    let plan = match std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read: {e}"))
        .and_then(|text| parse(&text))
    {
        Ok(plan) => plan,
        Err(e) => {
            eprintln!("robofmu-platform-host: {path}: {e}");
            return ExitCode::from(2);
        }
    };
    match simulate(&plan) {
        Ok(lines) => {
            println!("{}", lines.join("\n"));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("robofmu-platform-host: {}: {e}", plan.library);
            ExitCode::from(1)
        }
    }
}
