//! The evidence every FMU carries (the layered standard FMI-LS-REF 1.0.0-alpha.1 and
//! the experiments format MA-HS-Experiments): under `extra/org.fmi-standard.fmi-ls-ref/`
//! the manifest `fmi-ls-manifest.xml`, the experiments files `smoke-test.exp` (the case
//! at the FMU's defaults, the one folder holding `cross-check.txt`) and `validation.exp`
//! (every other case), and per case its reference CSV, its stimuli CSV and its start
//! values as an SSP parameter set (`parameters.ssv`); and `documentation/fmi-ls-ref.html`
//! (what each experiment checks and how close an importer must come).
//!
//! Everything is generated at packaging time from the case folders the tests use,
//! `tests/references/<Model>/<case>/` (`<Model>_ref.csv`, `<Model>_ref.opt`, an
//! optional `<Model>_input.csv` or `<Model>_in.csv`, `case.json`, `cross-check.txt`):
//! the CSVs are those files' bytes. Each related file's SHA-256 is in the manifest, in an
//! annotation of its `<Related>` element (the schema of FMI-LS-REF has no checksum
//! attribute); each experiment's signal tolerances and event times, from case.json, in an
//! annotation of its `<Experiment>` element. docs/verify.md describes both.

use crate::common::{GENERATION_TOOL, number};
use robofmu_fmi::description::{Description, Value};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The folder of the layered standard inside the FMU.
pub const FOLDER: &str = "extra/org.fmi-standard.fmi-ls-ref";
/// The manifest's path inside the FMU.
pub const MANIFEST: &str = "extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml";
/// The documentation page's path inside the FMU.
pub const DOCUMENTATION: &str = "documentation/fmi-ls-ref.html";
/// The version of FMI-LS-REF the manifest follows.
pub const LS_VERSION: &str = "1.0.0-alpha.1";
const LS_DESCRIPTION: &str =
    "Layered Standard providing information on related files included in an FMU.";
/// The annotation type of a related file's checksum.
pub const CHECKSUM_ANNOTATION: &str = "org.robofmu.checksum";
/// The annotation type of an experiment's tolerances and event times.
pub const VERIFY_ANNOTATION: &str = "org.robofmu.verify";
const SMOKE_TEST: &str = "smoke-test.exp";
const VALIDATION: &str = "validation.exp";

/// One case folder of `tests/references/<Model>/`.
pub struct Case {
    /// The folder's name: the experiment's name.
    pub name: String,
    /// The case at the FMU's defaults (the folder holds `cross-check.txt`, whose
    /// sentence says what the reference is).
    pub smoke: Option<String>,
    pub reference: (String, Vec<u8>),
    pub stimuli: Option<(String, Vec<u8>)>,
    pub start: f64,
    pub stop: f64,
    pub step: f64,
    pub rel_tol: f64,
    /// Start values of case.json, sorted by name.
    pub start_values: Vec<(String, serde_json::Value)>,
    pub event_times: Vec<f64>,
    /// (interface or None for every interface, signal, rule) of case.json.
    pub tolerances: Vec<(Option<String>, String, Rule)>,
}

/// A signal's tolerance as case.json gives it.
pub enum Rule {
    /// |result - reference| <= abs + rel x the reference's range.
    Deviation { abs: f64, rel: f64 },
    /// The FMI cross-check's band around the reference.
    CrossCheck,
}

fn read(path: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))
}

/// The cases of `model` under `references` (`tests/references`), sorted by name: an
/// empty list when the model has no folder there.
pub fn read_cases(references: &Path, model: &str) -> Result<Vec<Case>, String> {
    let dir = references.join(model);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut folders: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    folders.sort();
    let cases = folders
        .iter()
        .map(|f| read_case(f, model))
        .collect::<Result<Vec<_>, _>>()?;
    let smoke = cases.iter().filter(|c| c.smoke.is_some()).count();
    if !cases.is_empty() && smoke != 1 {
        return Err(format!(
            "{}: {smoke} case folders hold cross-check.txt; mark exactly one, the case at \
             the FMU's defaults",
            dir.display()
        ));
    }
    Ok(cases)
}

fn read_case(folder: &Path, model: &str) -> Result<Case, String> {
    let name = folder
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let file = |suffix: &str| format!("{model}{suffix}");
    let reference = (file("_ref.csv"), read(&folder.join(file("_ref.csv")))?);
    let mut stimuli = None;
    for suffix in ["_input.csv", "_in.csv"] {
        let path = folder.join(file(suffix));
        if path.is_file() {
            stimuli = Some((file(suffix), read(&path)?));
        }
    }
    let opt_path = folder.join(file("_ref.opt"));
    let opt = String::from_utf8_lossy(&read(&opt_path)?).into_owned();
    let option = |key: &str| -> Result<f64, String> {
        opt.lines()
            .filter_map(|l| l.split_once(','))
            .find(|(k, _)| k.trim() == key)
            .and_then(|(_, v)| v.trim().parse::<f64>().ok())
            .ok_or_else(|| format!("{}: {key}: missing or not a number", opt_path.display()))
    };
    let smoke_path = folder.join("cross-check.txt");
    let smoke = match smoke_path.is_file() {
        true => Some(
            String::from_utf8_lossy(&read(&smoke_path)?)
                .trim()
                .to_string(),
        ),
        false => None,
    };
    let case_path = folder.join("case.json");
    let json: serde_json::Value = match case_path.is_file() {
        true => serde_json::from_slice(&read(&case_path)?)
            .map_err(|e| format!("{}: not JSON: {e}", case_path.display()))?,
        false => serde_json::Value::Null,
    };
    let bad = |key: &str| format!("{}: {key}: not as docs/verify.md says", case_path.display());
    let start_values = match json.get("start_values") {
        Some(serde_json::Value::Object(m)) => {
            m.iter().map(|(k, v)| (k.clone(), v.clone())).collect()
        }
        None => Vec::new(),
        Some(_) => return Err(bad("start_values")),
    };
    let event_times = match json.get("event_times") {
        Some(serde_json::Value::Array(a)) => a
            .iter()
            .map(|t| t.as_f64().ok_or_else(|| bad("event_times")))
            .collect::<Result<_, _>>()?,
        None => Vec::new(),
        Some(_) => return Err(bad("event_times")),
    };
    let tolerances = match json.get("tolerances") {
        Some(serde_json::Value::Object(m)) => tolerances(m).ok_or_else(|| bad("tolerances"))?,
        None => Vec::new(),
        Some(_) => return Err(bad("tolerances")),
    };
    Ok(Case {
        name,
        smoke,
        reference,
        stimuli,
        start: option("StartTime")?,
        stop: option("StopTime")?,
        step: option("StepSize")?,
        rel_tol: option("RelTol")?,
        start_values,
        event_times,
        tolerances,
    })
}

type Rules = Vec<(Option<String>, String, Rule)>;
type Object = serde_json::Map<String, serde_json::Value>;

/// case.json's tolerances: by signal, or by interface and then by signal.
fn tolerances(m: &Object) -> Option<Rules> {
    let mut rules = Vec::new();
    if !m.is_empty()
        && m.keys()
            .all(|k| k == "CoSimulation" || k == "ModelExchange")
    {
        for (interface, table) in m {
            add_rules(&mut rules, Some(interface), table.as_object()?)?;
        }
    } else {
        add_rules(&mut rules, None, m)?;
    }
    Some(rules)
}

fn add_rules(rules: &mut Rules, interface: Option<&String>, table: &Object) -> Option<()> {
    for (signal, spec) in table {
        let number = |key: &str, o: &Object| o.get(key).map_or(Some(0.0), |v| v.as_f64());
        let rule = match spec {
            serde_json::Value::Number(n) => Rule::Deviation {
                abs: n.as_f64()?,
                rel: 0.0,
            },
            serde_json::Value::String(s) if s == "cross-check" => Rule::CrossCheck,
            serde_json::Value::Object(o) => Rule::Deviation {
                abs: number("abs", o)?,
                rel: number("rel", o)?,
            },
            _ => return None,
        };
        rules.push((interface.cloned(), signal.clone(), rule));
    }
    Some(())
}

/// An XML element, written with its attributes in the order added and its children
/// indented by two spaces.
struct Element {
    name: &'static str,
    attributes: Vec<(&'static str, String)>,
    children: Vec<Element>,
}

impl Element {
    fn new(name: &'static str) -> Element {
        Element {
            name,
            attributes: Vec::new(),
            children: Vec::new(),
        }
    }

    fn attr(mut self, name: &'static str, value: impl ToString) -> Element {
        self.attributes.push((name, value.to_string()));
        self
    }

    fn child(mut self, child: Element) -> Element {
        self.children.push(child);
        self
    }

    fn write(&self, out: &mut String, depth: usize) {
        let indent = "  ".repeat(depth);
        out.push_str(&format!("{indent}<{}", self.name));
        for (name, value) in &self.attributes {
            out.push_str(&format!(" {name}=\"{}\"", quick_xml::escape::escape(value)));
        }
        if self.children.is_empty() {
            out.push_str("/>\n");
            return;
        }
        out.push_str(">\n");
        for child in &self.children {
            child.write(out, depth + 1);
        }
        out.push_str(&format!("{indent}</{}>\n", self.name));
    }

    fn document(&self) -> Vec<u8> {
        let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        self.write(&mut out, 0);
        out.into_bytes()
    }
}

/// `<Annotations><Annotation type=...>` holding `children`.
fn annotation(kind: &str, children: Vec<Element>) -> Element {
    let mut a = Element::new("Annotation").attr("type", kind);
    a.children = children;
    Element::new("Annotations").child(a)
}

/// The lowercase hexadecimal SHA-256 of `bytes`.
pub fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .fold(String::new(), |mut hex, b| {
            let _ = write!(hex, "{b:02x}");
            hex
        })
}

/// The SSP 1.0 parameter set of a case's start values, each typed as the FMU's variable
/// of that name (an element of an FMI 3.0 array, `Kp[1]`, as its FMI 2.0 scalar).
fn parameter_set(d: &Description, case: &Case, source: &str) -> Result<Vec<u8>, String> {
    let mut parameters = Element::new("ssv:Parameters");
    for (name, value) in &case.start_values {
        let scalar = d.scalars.iter().find(|s| &s.name == name).ok_or_else(|| {
            format!(
                "{source}: start_values.{name}: {} has no such variable",
                d.info.model_name
            )
        })?;
        let wrong = || format!("{source}: start_values.{name}: {value} does not fit its type");
        let typed = match scalar.value {
            Value::Real { .. } => {
                Element::new("ssv:Real").attr("value", number(value.as_f64().ok_or_else(wrong)?))
            }
            Value::Integer { .. } => {
                Element::new("ssv:Integer").attr("value", value.as_i64().ok_or_else(wrong)?)
            }
            Value::Boolean { .. } => {
                Element::new("ssv:Boolean").attr("value", value.as_bool().ok_or_else(wrong)?)
            }
        };
        parameters = parameters.child(
            Element::new("ssv:Parameter")
                .attr("name", name)
                .child(typed),
        );
    }
    Ok(Element::new("ssv:ParameterSet")
        .attr(
            "xmlns:ssv",
            "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
        )
        .attr("version", "1.0")
        .attr("name", &case.name)
        .child(parameters)
        .document())
}

fn rule_element(interface: &Option<String>, signal: &str, rule: &Rule) -> Element {
    let mut e = Element::new("Tolerance").attr("signal", signal);
    if let Some(interface) = interface {
        e = e.attr("interface", interface);
    }
    match rule {
        Rule::Deviation { abs, rel } => e.attr("abs", number(*abs)).attr("rel", number(*rel)),
        Rule::CrossCheck => e.attr("rule", "cross-check"),
    }
}

/// What one experiment checks, for its description and the documentation page.
fn experiment_description(d: &Description, case: &Case) -> String {
    let model = d.info.model_name;
    let signals = signal_names(&case.reference.1).join(", ");
    match &case.smoke {
        Some(truth) => format!("{model} at its defaults: {signals} against {truth}"),
        None if case.start_values.is_empty() => format!("{model}: {signals} against the reference"),
        None => {
            let set: Vec<String> = case
                .start_values
                .iter()
                .map(|(n, v)| format!("{n} = {v}"))
                .collect();
            format!(
                "{model} with {}: {signals} against the reference",
                set.join(", ")
            )
        }
    }
}

/// The column names of a CSV's first line, without quotes, `time` left out.
fn signal_names(csv: &[u8]) -> Vec<String> {
    let text = String::from_utf8_lossy(csv);
    let header = text.lines().next().unwrap_or_default();
    header
        .split(',')
        .map(|n| n.trim().trim_matches('"').trim().to_string())
        .filter(|n| n != "time")
        .collect()
}

/// The `<Experiment>` of a case and the related files it names (path under the
/// LS-REF folder, MIME type, role, description, bytes).
fn experiment(d: &Description, case: &Case, files: &mut Vec<Related>) -> Result<Element, String> {
    let mut e = Element::new("Experiment")
        .attr("name", &case.name)
        .attr("description", experiment_description(d, case))
        .attr("tolerance", number(case.rel_tol))
        .child(
            Element::new("TransientSimulation")
                .attr("startTime", number(case.start))
                .attr("stopTime", number(case.stop))
                .attr("stepSize", number(case.step)),
        );
    let folder = &case.name;
    if !case.start_values.is_empty() {
        let source = format!("{folder}/parameters.ssv");
        let bytes = parameter_set(
            d,
            case,
            &format!("tests/references/{}/{folder}/case.json", d.info.model_name),
        )?;
        e = e.child(Element::new("Parameters").attr("source", &source));
        files.push(Related::new(
            source,
            "application/x-ssp-parameter-set",
            "parameter",
            format!("start values of experiment {folder}"),
            bytes,
        ));
    }
    if let Some((name, bytes)) = &case.stimuli {
        let source = format!("{folder}/{name}");
        e = e.child(Element::new("Stimuli").attr("source", &source));
        files.push(Related::new(
            source,
            "text/csv",
            "other",
            format!("stimuli (inputs) of experiment {folder}"),
            bytes.clone(),
        ));
    }
    let source = format!("{folder}/{}", case.reference.0);
    e = e.child(Element::new("References").attr("source", &source));
    files.push(Related::new(
        source,
        "text/csv",
        "result",
        format!("reference result of experiment {folder}"),
        case.reference.1.clone(),
    ));
    let mut verify: Vec<Element> = case
        .tolerances
        .iter()
        .map(|(i, s, r)| rule_element(i, s, r))
        .collect();
    verify.extend(
        case.event_times
            .iter()
            .map(|t| Element::new("Event").attr("time", number(*t))),
    );
    if !verify.is_empty() {
        e = e.child(annotation(VERIFY_ANNOTATION, verify));
    }
    Ok(e)
}

/// A file the manifest lists.
struct Related {
    source: String,
    mime: &'static str,
    role: &'static str,
    description: String,
    bytes: Vec<u8>,
}

impl Related {
    fn new(
        source: String,
        mime: &'static str,
        role: &'static str,
        description: String,
        bytes: Vec<u8>,
    ) -> Related {
        Related {
            source,
            mime,
            role,
            description,
            bytes,
        }
    }
}

/// The experiments file of `cases` named `name`.
fn experiments(
    d: &Description,
    name: String,
    description: &str,
    cases: &[&Case],
    files: &mut Vec<Related>,
) -> Result<Vec<u8>, String> {
    let mut root = Element::new("Experiments")
        .attr("name", name)
        .attr("description", description);
    for case in cases {
        root = root.child(experiment(d, case, files)?);
    }
    Ok(root.document())
}

/// The FMU's entries (path in the archive, bytes) of FMI-LS-REF for `cases`: the
/// manifest, the experiments files and what they name under [`FOLDER`], and
/// [`DOCUMENTATION`]; none when there is no case.
pub fn entries(
    d: &Description,
    cases: &[Case],
    standard: &str,
) -> Result<Vec<(String, Vec<u8>)>, String> {
    if cases.is_empty() {
        return Ok(Vec::new());
    }
    let model = d.info.model_name;
    let mut files = Vec::new();
    let mut sets = Vec::new();
    let smoke: Vec<&Case> = cases.iter().filter(|c| c.smoke.is_some()).collect();
    let validation: Vec<&Case> = cases.iter().filter(|c| c.smoke.is_none()).collect();
    for (file, role, which, group) in [
        (SMOKE_TEST, "experiment/smoke-test", "smoke test", smoke),
        (
            VALIDATION,
            "experiment/validation",
            "validation",
            validation,
        ),
    ] {
        if group.is_empty() {
            continue;
        }
        let mut named = Vec::new();
        let description = format!("the {which} experiments of {model}, from robofmu's tests");
        let bytes = experiments(
            d,
            format!("{model} {which}"),
            &description,
            &group,
            &mut named,
        )?;
        sets.push(Related::new(
            file.to_string(),
            "application/x-ma-hs-experiments",
            role,
            description,
            bytes,
        ));
        files.extend(named);
    }
    let page = page(d, cases, standard);
    let mut related: Vec<Related> = sets;
    related.extend(files);
    related.push(Related::new(
        format!("../../{DOCUMENTATION}"),
        "text/html",
        "document",
        "what each experiment checks and how close an importer must come".to_string(),
        page.clone().into_bytes(),
    ));
    let mut manifest = Element::new("fmiReferences")
        .attr("xmlns:fmi-ls", "http://fmi-standard.org/fmi-ls-manifest")
        .attr("fmi-ls:fmi-ls-name", "org.fmi-standard.fmi-ls-ref")
        .attr("fmi-ls:fmi-ls-version", LS_VERSION)
        .attr("fmi-ls:fmi-ls-description", LS_DESCRIPTION);
    for r in &related {
        manifest = manifest.child(
            Element::new("Related")
                .attr("type", r.mime)
                .attr("source", &r.source)
                .attr("role", r.role)
                .attr("description", &r.description)
                .child(annotation(
                    CHECKSUM_ANNOTATION,
                    vec![
                        Element::new("Checksum")
                            .attr("algorithm", "SHA-256")
                            .attr("value", sha256(&r.bytes)),
                    ],
                )),
        );
    }
    let mut out = vec![(MANIFEST.to_string(), manifest.document())];
    for r in related {
        let path = match r.source.strip_prefix("../../") {
            Some(outside) => outside.to_string(),
            None => format!("{FOLDER}/{}", r.source),
        };
        out.push((path, r.bytes));
    }
    Ok(out)
}

fn escape(text: &str) -> String {
    quick_xml::escape::escape(text).into_owned()
}

/// documentation/fmi-ls-ref.html: every experiment, what it checks, its settings and
/// the tolerance of each signal.
fn page(d: &Description, cases: &[Case], standard: &str) -> String {
    let model = escape(d.info.model_name);
    let mut body = String::new();
    for case in cases {
        let kind = match case.smoke {
            Some(_) => "smoke test (the FMU's defaults)",
            None => "validation",
        };
        let _ = write!(
            body,
            "<h2>{name}: {kind}</h2>\n<p>{what}.</p>\n<p>From {start} s to {stop} s, step {step} s, \
             relative tolerance {rel}; files: <code>{folder}/</code> under \
             <code>{FOLDER}/</code>.</p>\n",
            name = escape(&case.name),
            what = escape(&experiment_description(d, case)),
            start = number(case.start),
            stop = number(case.stop),
            step = number(case.step),
            rel = number(case.rel_tol),
            folder = escape(&case.name),
        );
        body.push_str("<table border=\"1\">\n<tr><th>signal</th><th>interface</th><th>an importer's result must stay within</th></tr>\n");
        let mut rules: Vec<String> = Vec::new();
        for (interface, signal, rule) in &case.tolerances {
            let within = match rule {
                Rule::Deviation { abs, rel: 0.0 } => format!("{} of the reference", number(*abs)),
                Rule::Deviation { abs, rel } => format!(
                    "{} + {} x the reference's range",
                    number(*abs),
                    number(*rel)
                ),
                Rule::CrossCheck => "the FMI cross-check's band around the reference".to_string(),
            };
            rules.push(format!(
                "<tr><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                escape(signal),
                interface.as_deref().unwrap_or("both"),
                within
            ));
        }
        if rules.is_empty() {
            rules.push("<tr><td>every signal</td><td>both</td><td>the FMI cross-check's band around the reference</td></tr>\n".to_string());
        }
        body.push_str(&rules.concat());
        body.push_str("</table>\n");
    }
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{model}: experiments and \
         results</title></head><body>\n<h1>{model}: experiments and results (FMI-LS-REF)</h1>\n\
         <p>This {standard} FMU carries its own evidence, as the layered standard FMI-LS-REF \
         {LS_VERSION} describes: <code>{MANIFEST}</code> lists the experiments files (format \
         MA-HS-Experiments), the parameter sets (SSP 1.0 SSV), the stimuli and the reference \
         results, each with its SHA-256 in an annotation of type \
         <code>{CHECKSUM_ANNOTATION}</code>. Each experiment's annotation of type \
         <code>{VERIFY_ANNOTATION}</code> gives the tolerance of each signal by interface \
         (CoSimulation, ModelExchange) and the times of its events. Column names \
         <code>x[i]</code> name element i of the FMI 3.0 array <code>x</code>. Generated by \
         {GENERATION_TOOL}; <code>cosim verify {model}.fmu</code> runs every experiment.</p>\n\
         {body}</body></html>\n"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_is_the_standards_digest() {
        // Expected: the examples of FIPS 180-2, appendix B.1, and the digest of nothing.
        assert_eq!(
            sha256(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }

    fn write_case(dir: &Path, name: &str, smoke: bool, json: &str) {
        let folder = dir.join("M").join(name);
        std::fs::create_dir_all(&folder).unwrap();
        std::fs::write(folder.join("M_ref.csv"), "\"time\",\"y[1]\"\n0,1\n1,2\n").unwrap();
        std::fs::write(
            folder.join("M_ref.opt"),
            "StartTime, 0.0\nStopTime, 1.0\nStepSize, 0.5\nRelTol, 1e-6\n",
        )
        .unwrap();
        std::fs::write(folder.join("case.json"), json).unwrap();
        if smoke {
            std::fs::write(folder.join("cross-check.txt"), "the closed form.\n").unwrap();
        }
    }

    #[test]
    fn cases_are_read_with_their_rules_and_one_smoke_test() {
        // Expected: the values written into the files above.
        let dir = std::env::temp_dir().join(format!("robofmu-lsref-{}", std::process::id()));
        write_case(
            &dir,
            "a",
            true,
            r#"{"start_values": {"k": 2.5}, "event_times": [0.5],
                "tolerances": {"CoSimulation": {"y[1]": 1e-9},
                               "ModelExchange": {"y[1]": {"abs": 0.1, "rel": 0.01}}}}"#,
        );
        write_case(
            &dir,
            "b",
            false,
            r#"{"tolerances": {"y[1]": "cross-check"}}"#,
        );
        let cases = read_cases(&dir, "M").unwrap();
        assert_eq!(cases.len(), 2);
        let (a, b) = (&cases[0], &cases[1]);
        assert_eq!(a.smoke.as_deref(), Some("the closed form."));
        assert_eq!((a.start, a.stop, a.step, a.rel_tol), (0.0, 1.0, 0.5, 1e-6));
        assert_eq!(a.start_values.len(), 1);
        assert_eq!(a.event_times, vec![0.5]);
        assert!(matches!(
            a.tolerances[1],
            (Some(ref i), ref s, Rule::Deviation { abs: 0.1, rel: 0.01 })
                if i == "ModelExchange" && s == "y[1]"
        ));
        assert!(b.smoke.is_none());
        assert!(matches!(b.tolerances[0], (None, _, Rule::CrossCheck)));
        assert_eq!(signal_names(&a.reference.1), vec!["y[1]"]);
        // A second case marked as the defaults is refused, naming the folder.
        write_case(&dir, "b", true, "{}");
        let e = read_cases(&dir, "M").err().unwrap();
        assert!(e.contains("2 case folders hold cross-check.txt"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
        // No folder for the model: no experiments.
        assert!(read_cases(&dir, "M").unwrap().is_empty());
    }
}
