//! Structural parameters and resizable arrays through the FMI 3.0 functions
//! (`fmi3::api`, as the exported symbols call them) on a toy model: n channels, each
//! y_i = k_i x_i with the state s_i, ds_i/dt = y_i. Expected values: the law itself
//! (y_i = k_i x_i, dy_i/dx_j = k_i when i = j, else 0), the start values of the
//! declarations for the new elements (`core::structural`: one start for all, or the
//! listed one, else zero), and the rules of FMI 3.0 sections 2.2.x / 3.2 (structural
//! parameters set in Configuration Mode only, entered from Instantiated; nValues
//! counts the current size).

use robofmu_fmi::fmi3::api::{self, DependencyArrays, DerivativeRequest, StepResult};
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::fmi3::types::*;
use robofmu_fmi::prelude::*;
mod support;

use support::{instantiate, last_message};

#[derive(Clone)]
struct Gains {
    k: Vec<f64>,
    x: Vec<f64>,
    s: Vec<f64>,
}

impl Default for Gains {
    fn default() -> Self {
        let mut g = Gains {
            k: Vec::new(),
            x: Vec::new(),
            s: Vec::new(),
        };
        g.resize(2);
        g
    }
}

impl Gains {
    fn resize(&mut self, n: usize) {
        for v in [&mut self.k, &mut self.x, &mut self.s] {
            v.resize(n, f64::NAN);
        }
    }
}

type Decl = Declaration<Gains>;
const CH: Family<Gains> = Family::new(2, "Channel").sized_by(0);
const K: Decl = CH.tunable("k", 1, &[1.5], |m, c| &mut m.k[c]);
const X: Decl = CH.input("x", 11, &[0.5, 0.25], |m, c| &mut m.x[c]);
const Y: Decl = CH.output("y", 21, |m, c| m.k[c] * m.x[c]);
const S: Decl = CH.state("s", 31, |m, c| &mut m.s[c]);
const DS: Decl = CH.derivative("der(s)", 41, S, |m, c| m.k[c] * m.x[c]);
/// y_i reads x_i (its own channel).
static Y_KNOWNS: [Var; 1] = same(&[X]);
static VARIABLES: &[Decl] = &[
    K.describe("gain"),
    X.describe("input"),
    Y.describe("k x").depends_on(&Y_KNOWNS),
    S.describe("integral of y"),
    DS.describe("y"),
];
static STRUCTURAL: &[StructuralParameter<Gains>] = &[StructuralParameter::new(
    "n",
    100,
    "number of channels",
    [2, 8],
    |m| m.k.len(),
    Gains::resize,
)];
static INFO: ModelInfo = ModelInfo::new(
    "Gains",
    "{0d6b7a52-19e4-4c8e-8f3a-5b1e2c7d9a40}",
    "n gains",
    [0.0, 1.0, 1e-6, 0.1],
);

fn partial(m: &Gains, unknown: Element, known: Element) -> Result<f64, String> {
    let same = unknown.index == known.index;
    Ok(if same && X.is(known) {
        m.k[unknown.index]
    } else {
        0.0
    })
}

impl Model for Gains {
    const INFO: &'static ModelInfo = &INFO;
    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;
    const STRUCTURAL: &'static [StructuralParameter<Self>] = STRUCTURAL;
    const JACOBIAN: Option<Jacobian<Self>> = Some(Jacobian::Partial(partial));
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
}

const N: u32 = 100;

struct Fmu(Fmi3Instance);

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { api::free_instance::<Gains>(self.0) }
    }
}

impl Fmu {
    fn new(interface: Interface) -> Fmu {
        Fmu(instantiate::<Gains>(
            interface,
            c"{0d6b7a52-19e4-4c8e-8f3a-5b1e2c7d9a40}",
        ))
    }

    fn cs() -> Fmu {
        Fmu::new(Interface::CoSimulation {
            event_mode_used: false,
            early_return_allowed: false,
        })
    }

    fn set_n(&self, n: u64) -> Fmi3Status {
        unsafe { api::set_uint64::<Gains>(self.0, &N, 1, &n, 1) }
    }

    fn n(&self) -> u64 {
        let mut n = 0;
        let s = unsafe { api::get_uint64::<Gains>(self.0, &N, 1, &mut n, 1) };
        assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
        n
    }

    /// Configuration Mode, n set, back to Instantiated.
    fn configure(&self, n: u64) {
        let ok = Fmi3Status::Ok;
        assert_eq!(
            unsafe { api::enter_configuration_mode::<Gains>(self.0) },
            ok
        );
        assert_eq!(self.set_n(n), ok, "{}", last_message());
        assert_eq!(self.n(), n);
        assert_eq!(unsafe { api::exit_configuration_mode::<Gains>(self.0) }, ok);
    }

    fn initialize(&self) {
        let s = unsafe { api::enter_initialization_mode::<Gains>(self.0, 0, 0.0, 0.0, 0, 0.0) };
        assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
        let s = unsafe { api::exit_initialization_mode::<Gains>(self.0) };
        assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
    }

    fn get(&self, vr: u32, n: usize) -> (Fmi3Status, Vec<f64>) {
        let mut v = vec![f64::NAN; n];
        let s = unsafe { api::get_float64::<Gains>(self.0, &vr, 1, v.as_mut_ptr(), n) };
        (s, v)
    }

    fn set(&self, vr: u32, v: &[f64]) -> Fmi3Status {
        unsafe { api::set_float64::<Gains>(self.0, &vr, 1, v.as_ptr(), v.len()) }
    }

    fn step(&self, t: f64, h: f64) -> Fmi3Status {
        let (mut a, mut b, mut c, mut d) = (0, 0, 0, 0.0);
        unsafe {
            api::do_step::<Gains>(
                self.0,
                t,
                h,
                FMI3_TRUE,
                StepResult {
                    event_handling_needed: &mut a,
                    terminate_simulation: &mut b,
                    early_return: &mut c,
                    last_successful_time: &mut d,
                },
            )
        }
    }
}

#[test]
fn a_resized_family_is_read_and_written_at_its_new_size() {
    let f = Fmu::cs();
    f.configure(5);
    f.initialize();
    // New elements: k's one start value (1.5); x's listed starts, zero past them.
    assert_eq!(f.get(1, 5), (Fmi3Status::Ok, vec![1.5; 5]));
    assert_eq!(
        f.get(11, 5),
        (Fmi3Status::Ok, vec![0.5, 0.25, 0.0, 0.0, 0.0])
    );
    assert_eq!(f.set(11, &[1.0, 2.0, 3.0, 4.0, 5.0]), Fmi3Status::Ok);
    assert_eq!(f.set(1, &[1.0, 2.0, 3.0, 4.0, 5.0]), Fmi3Status::Ok);
    // y_i = k_i x_i = i^2.
    assert_eq!(
        f.get(21, 5),
        (Fmi3Status::Ok, vec![1.0, 4.0, 9.0, 16.0, 25.0])
    );
    // d y / d x: diag(k).
    let (unknowns, knowns) = ([21u32], [11u32]);
    let seed = [1.0, 1.0, 1.0, 1.0, 1.0];
    let mut out = [f64::NAN; 5];
    let s = unsafe {
        api::get_directional_derivative::<Gains>(
            f.0,
            DerivativeRequest {
                unknowns: unknowns.as_ptr(),
                n_unknowns: 1,
                knowns: knowns.as_ptr(),
                n_knowns: 1,
                seed: seed.as_ptr(),
                n_seed: 5,
                sensitivity: out.as_mut_ptr(),
                n_sensitivity: 5,
            },
        )
    };
    assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
    assert_eq!(out, [1.0, 2.0, 3.0, 4.0, 5.0]);
    // The FMU state carries the size; its byte form holds the default size only.
    let mut state: Fmi3FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::get_fmu_state::<Gains>(f.0, &mut state) },
        Fmi3Status::Ok
    );
    let mut size = 0;
    let s = unsafe { api::serialized_fmu_state_size::<Gains>(f.0, state, &mut size) };
    assert_eq!(s, Fmi3Status::Error);
    assert!(
        last_message().contains("default sizes only"),
        "{}",
        last_message()
    );
    // The old size is refused, nothing written.
    let g = Fmu::cs();
    g.configure(5);
    g.initialize();
    assert_eq!(g.set(11, &[9.0, 9.0]), Fmi3Status::Error);
    assert!(last_message().contains("nValues = 2"), "{}", last_message());
    assert_eq!(g.get(11, 5).1, vec![0.5, 0.25, 0.0, 0.0, 0.0]);
    assert_eq!(g.get(11, 2).0, Fmi3Status::Error);
}

#[test]
fn a_resized_model_exchange_instance_has_as_many_states() {
    let f = Fmu::new(Interface::ModelExchange);
    f.configure(7);
    f.initialize();
    let mut n = 0;
    let s = unsafe { api::get_number_of_continuous_states::<Gains>(f.0, &mut n) };
    assert_eq!((s, n), (Fmi3Status::Ok, 7));
    let mut dx = [f64::NAN; 7];
    let s = unsafe { api::get_continuous_state_derivatives::<Gains>(f.0, dx.as_mut_ptr(), 7) };
    assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
    // k = 1.5, x = 0.5, 0.25, then 0.
    assert_eq!(dx, [0.75, 0.375, 0.0, 0.0, 0.0, 0.0, 0.0]);
}

#[test]
fn a_co_simulation_step_runs_at_the_new_size_and_a_reset_restores_the_default() {
    let f = Fmu::cs();
    f.configure(3);
    f.initialize();
    assert_eq!(f.step(0.0, 0.1), Fmi3Status::Ok, "{}", last_message());
    assert_eq!(f.n(), 3);
    assert_eq!(unsafe { api::reset::<Gains>(f.0) }, Fmi3Status::Ok);
    f.initialize();
    assert_eq!(f.n(), 2);
    assert_eq!(f.get(1, 2), (Fmi3Status::Ok, vec![1.5, 1.5]));
}

#[test]
fn structural_parameters_are_refused_outside_configuration_mode_and_range() {
    // Set in Instantiated: refused, naming Configuration Mode.
    let f = Fmu::cs();
    assert_eq!(f.set_n(4), Fmi3Status::Error);
    assert!(
        last_message().contains("Configuration Mode"),
        "{}",
        last_message()
    );
    // 0 and 10^9: refused, the size kept (readable in the Error state).
    for bad in [0, 1_000_000_000, u64::MAX] {
        let f = Fmu::cs();
        assert_eq!(
            unsafe { api::enter_configuration_mode::<Gains>(f.0) },
            Fmi3Status::Ok
        );
        assert_eq!(f.set_n(bad), Fmi3Status::Error);
        assert!(
            last_message().contains("outside 1..=8"),
            "{}",
            last_message()
        );
        assert_eq!(f.n(), 2);
    }
    // Enter from Step Mode (Reconfiguration Mode): refused with the reason.
    let f = Fmu::cs();
    f.initialize();
    let s = unsafe { api::enter_configuration_mode::<Gains>(f.0) };
    assert_eq!(s, Fmi3Status::Error);
    assert!(
        last_message().contains("Reconfiguration Mode"),
        "{}",
        last_message()
    );
    // Exit without entering, enter twice, initialize in Configuration Mode: refused.
    let f = Fmu::cs();
    assert_eq!(
        unsafe { api::exit_configuration_mode::<Gains>(f.0) },
        Fmi3Status::Error
    );
    let f = Fmu::cs();
    assert_eq!(
        unsafe { api::enter_configuration_mode::<Gains>(f.0) },
        Fmi3Status::Ok
    );
    assert_eq!(
        unsafe { api::enter_configuration_mode::<Gains>(f.0) },
        Fmi3Status::Error
    );
    let f = Fmu::cs();
    assert_eq!(
        unsafe { api::enter_configuration_mode::<Gains>(f.0) },
        Fmi3Status::Ok
    );
    let s = unsafe { api::enter_initialization_mode::<Gains>(f.0, 0, 0.0, 0.0, 0, 0.0) };
    assert_eq!(s, Fmi3Status::Error);
    // A Float64 array set in Configuration Mode: refused.
    let f = Fmu::cs();
    assert_eq!(
        unsafe { api::enter_configuration_mode::<Gains>(f.0) },
        Fmi3Status::Ok
    );
    assert_eq!(f.set(1, &[1.0, 1.0]), Fmi3Status::Error);
}

#[test]
fn dependencies_follow_the_size() {
    // Expected: y_i depends on x_i only (declared per channel), at 5 channels too;
    // der(s)_i declares none, so it depends on every element of every known: x and s,
    // 5 elements each, for each of its 5 elements.
    let f = Fmu::new(Interface::ModelExchange);
    f.configure(5);
    f.initialize();
    let mut n = 0;
    let s = unsafe { api::get_number_of_variable_dependencies::<Gains>(f.0, 21, &mut n) };
    assert_eq!((s, n), (Fmi3Status::Ok, 5), "{}", last_message());
    let (mut of_y, mut known, mut of_known) = ([0usize; 5], [0u32; 5], [0usize; 5]);
    let mut kinds = [Fmi3DependencyKind::Independent; 5];
    let s = unsafe {
        api::get_variable_dependencies::<Gains>(
            f.0,
            21,
            DependencyArrays {
                element_indices_of_dependent: of_y.as_mut_ptr(),
                independents: known.as_mut_ptr(),
                element_indices_of_independents: of_known.as_mut_ptr(),
                dependency_kinds: kinds.as_mut_ptr(),
                n_dependencies: 5,
            },
        )
    };
    assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
    assert_eq!(
        (of_y, known, of_known),
        ([1, 2, 3, 4, 5], [11; 5], [1, 2, 3, 4, 5])
    );
    let s = unsafe { api::get_number_of_variable_dependencies::<Gains>(f.0, 41, &mut n) };
    assert_eq!((s, n), (Fmi3Status::Ok, 5 * 10), "{}", last_message());
}
