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
//! the plan or the FMI call, exit 2 (a bad plan) or 1 (the FMU refused a call).

use robofmu_fmi_host::fmi2::{Binary, CallbackFunctions, OK, Status};
use std::ffi::{CString, c_char, c_int, c_void};
use std::path::Path;
use std::process::ExitCode;

const CO_SIMULATION: c_int = 1;

/// Prints the FMU's log lines on stderr. Non-variadic stand-in for the variadic
/// fmi2CallbackLogger: the five fixed arguments are passed the same way on x86_64
/// (System V and Windows) and aarch64 Linux, and the message is printed unformatted.
extern "C" fn logger(
    _env: *mut c_void,
    instance: *const c_char,
    status: Status,
    category: *const c_char,
    message: *const c_char,
) {
    let text = |p: *const c_char| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: the FMU passes NUL-terminated strings, alive during the call.
            unsafe { std::ffi::CStr::from_ptr(p) }
                .to_string_lossy()
                .into_owned()
        }
    };
    eprintln!(
        "[{} status {status} {}] {}",
        text(instance),
        text(category),
        text(message)
    );
}

extern "C" fn allocate(n: usize, size: usize) -> *mut c_void {
    // SAFETY: calloc accepts any sizes and returns null on failure.
    unsafe { libc::calloc(n, size) }
}

extern "C" fn release(p: *mut c_void) {
    // SAFETY: the FMU frees only what `allocate` returned (or null).
    unsafe { libc::free(p) }
}

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
    let f = Binary::open(Path::new(&plan.library))?;
    let functions = CallbackFunctions {
        logger: logger as *const c_void,
        allocate_memory: allocate as *const c_void,
        free_memory: release as *const c_void,
        step_finished: std::ptr::null(),
        component_environment: std::ptr::null_mut(),
    };
    let name = CString::new("host").expect("no NUL");
    let guid = CString::new(plan.guid.as_str()).map_err(|e| e.to_string())?;
    let resources = CString::new("").expect("no NUL");
    // SAFETY (every call of an `f` function below): the FMI 2.0 functions of the loaded
    // binary, called as the standard says: NUL-terminated strings, callbacks alive
    // until the end of this function, the instance `c` from fmi2Instantiate until
    // fmi2FreeInstance, each array as long as the count passed with it.
    let c = unsafe {
        (f.instantiate)(
            name.as_ptr(),
            CO_SIMULATION,
            guid.as_ptr(),
            resources.as_ptr(),
            &functions,
            0,
            0,
        )
    };
    if c.is_null() {
        return Err("fmi2Instantiate returned NULL".to_string());
    }
    let check = |status: Status, call: &str| {
        if status == OK {
            Ok(())
        } else {
            Err(format!("{call} returned status {status}"))
        }
    };
    check(
        unsafe { (f.setup_experiment)(c, 0, 0.0, plan.start, 1, plan.stop) },
        "fmi2SetupExperiment",
    )?;
    for s in &plan.starts {
        let (status, call) = match *s {
            Start::Real(vr, v) => (unsafe { (f.set_real)(c, &vr, 1, &v) }, "fmi2SetReal"),
            Start::Integer(vr, v) => (unsafe { (f.set_integer)(c, &vr, 1, &v) }, "fmi2SetInteger"),
            Start::Boolean(vr, v) => (unsafe { (f.set_boolean)(c, &vr, 1, &v) }, "fmi2SetBoolean"),
        };
        check(status, call)?;
    }
    check(
        unsafe { (f.enter_initialization_mode)(c) },
        "fmi2EnterInitializationMode",
    )?;
    check(
        unsafe { (f.exit_initialization_mode)(c) },
        "fmi2ExitInitializationMode",
    )?;
    let steps = ((plan.stop - plan.start) / plan.step).round() as usize;
    let mut lines = Vec::with_capacity(steps + 1);
    let mut y = vec![0.0; plan.outputs.len()];
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
            check(
                unsafe { (f.set_real)(c, plan.inputs.as_ptr(), row.len(), row.as_ptr()) },
                "fmi2SetReal (inputs)",
            )?;
        }
        check(
            unsafe { (f.get_real)(c, plan.outputs.as_ptr(), y.len(), y.as_mut_ptr()) },
            "fmi2GetReal",
        )?;
        let mut line = format!("{t}");
        for v in &y {
            line.push_str(&format!(" {v}"));
        }
        lines.push(line);
        if k < steps {
            check(unsafe { (f.do_step)(c, t, plan.step, 1) }, "fmi2DoStep")?;
        }
    }
    check(unsafe { (f.terminate)(c) }, "fmi2Terminate")?;
    unsafe { (f.free_instance)(c) };
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
