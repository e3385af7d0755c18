//! The variable table of Pss3Plant: inputs, outputs, state derivatives, parameters.
//!
//! Value references: a vector variable's group below plus i = 1..3.

use super::{Pss3Plant, initial_dependencies, parameters};
use nalgebra::Vector3;
use robofmu::pss3::dynamics::{PlantInputs, PlantOutputs};
use robofmu_fmi::prelude::*;

pub const ACTUATOR_FORCE: u32 = 0;
pub const TORQUE_COMMAND: u32 = 10;
pub const GENERALIZED_FORCE_COMMAND: u32 = 20;
pub const DISTURBANCE_TORQUE: u32 = 30;
pub const THETA: u32 = 100;
pub const OMEGA: u32 = 110;
pub const THETA_DOT: u32 = 120;
pub const OMEGA_DOT: u32 = 130;
pub const YAW_PITCH_ROLL: u32 = 140;
pub const L: u32 = 150;
pub const L_DOT: u32 = 160;
pub const FORCE: u32 = 170;
pub const STOP_FORCE: u32 = 180;
pub const AT_STOP: u32 = 190;
pub const DET_J: u32 = 201;
pub const COND_J: u32 = 202;
pub const KINETIC_ENERGY: u32 = 203;
pub const POTENTIAL_ENERGY: u32 = 204;
pub const GRAVITY_COMPENSATION: u32 = 210;
pub const DER_THETA: u32 = 300;
pub const DER_OMEGA: u32 = 310;

/// Group and component (0..2) of a value reference of a vector variable.
pub fn split(vr: u32) -> (u32, usize) {
    let component = (vr + 9) % 10;
    (vr - component - 1, component as usize)
}

type InputField = fn(&mut PlantInputs) -> &mut Vector3<f64>;

const INPUTS: [(u32, &str, &str, InputField); 4] = [
    (
        ACTUATOR_FORCE,
        "actuatorForce",
        "Force applied by actuator i along its axis u_i",
        |i| &mut i.forces,
    ),
    (
        TORQUE_COMMAND,
        "torqueCommand",
        "Commanded moment about P in {A}, realised by the actuators (f = J^-T tau)",
        |i| &mut i.commanded_torque,
    ),
    (
        GENERALIZED_FORCE_COMMAND,
        "generalizedForceCommand",
        "Commanded generalized force in Euler-angle coordinates (thx, thy, thz), realised \
         by the actuators (tau = E^-T Q, f = J^-T tau)",
        |i| &mut i.generalized_force,
    ),
    (
        DISTURBANCE_TORQUE,
        "disturbanceTorque",
        "External moment on the platform about P in {A} (not through the actuators)",
        |i| &mut i.disturbance_torque,
    ),
];

/// The component of `inputs` that the input with value reference `vr` sets, if `vr`
/// is an input.
pub fn input_component(inputs: &mut PlantInputs, vr: u32) -> Option<&mut f64> {
    let (group, c) = split(vr);
    let (_, _, _, field) = INPUTS.iter().find(|input| input.0 == group)?;
    field(inputs).get_mut(c)
}

type VectorOutput = fn(&PlantOutputs) -> Vector3<f64>;

/// A vector output read from `PlantOutputs`.
struct PlantOutput {
    group: u32,
    name: &'static str,
    unit: &'static str,
    display: Option<&'static str>,
    description: &'static str,
    get: VectorOutput,
    depends: Depends,
}

/// What an output or state derivative depends on (ModelStructure dependencies).
#[derive(Clone, Copy)]
enum Depends {
    /// The Euler angles only (a function of the pose).
    Theta,
    /// The continuous states (pose and angular velocity).
    States,
    /// The states and every input (through the accelerations).
    StatesAndInputs,
    /// The pose and the actuator commands (the realised actuator force).
    ThetaAndCommands,
}

/// The element names `base[1]`, `base[2]`, `base[3]` of a literal `base`.
macro_rules! elements {
    ($base:literal) => {
        [
            concat!($base, "[1]"),
            concat!($base, "[2]"),
            concat!($base, "[3]"),
        ]
    };
}

/// The parts one after the other, in a static table (no allocation at instantiation).
pub const fn concat<const N: usize>(parts: &[&[&'static str]]) -> [&'static str; N] {
    let mut out = [""; N];
    let (mut k, mut p) = (0, 0);
    while p < parts.len() {
        let mut i = 0;
        while i < parts[p].len() {
            out[k] = parts[p][i];
            (k, i) = (k + 1, i + 1);
        }
        p += 1;
    }
    assert!(k == N, "the parts do not fill the table");
    out
}

static THETA_NAMES: [&str; 3] = elements!("theta");
static OMEGA_NAMES: [&str; 3] = elements!("omega");
static COMMAND_NAMES: [&str; 9] = concat(&[
    &elements!("actuatorForce"),
    &elements!("torqueCommand"),
    &elements!("generalizedForceCommand"),
]);
static STATE_NAMES: [&str; 6] = concat(&[&THETA_NAMES, &OMEGA_NAMES]);
static THETA_AND_COMMAND_NAMES: [&str; 12] = concat(&[&THETA_NAMES, &COMMAND_NAMES]);
static STATE_AND_INPUT_NAMES: [&str; 18] = concat(&[
    &STATE_NAMES,
    &COMMAND_NAMES,
    &elements!("disturbanceTorque"),
]);

impl Depends {
    fn names(self) -> &'static [&'static str] {
        match self {
            Depends::Theta => &THETA_NAMES,
            Depends::States => &STATE_NAMES,
            Depends::StatesAndInputs => &STATE_AND_INPUT_NAMES,
            Depends::ThetaAndCommands => &THETA_AND_COMMAND_NAMES,
        }
    }
}

/// Vector outputs read from `PlantOutputs` (omega: its metadata only).
const PLANT_OUTPUTS: [PlantOutput; 6] = [
    PlantOutput {
        group: OMEGA_DOT,
        name: "omegaDot",
        unit: "rad/s2",
        display: Some("deg/s2"),
        description: "Angular acceleration of the platform in {A}",
        get: |o| o.omega_dot,
        depends: Depends::StatesAndInputs,
    },
    PlantOutput {
        group: L,
        name: "l",
        unit: "m",
        display: Some("mm"),
        description: "Actuator displacement",
        get: |o| o.actuator_displacements,
        depends: Depends::Theta,
    },
    PlantOutput {
        group: L_DOT,
        name: "lDot",
        unit: "m/s",
        display: None,
        description: "Actuator velocity",
        get: |o| o.actuator_velocities,
        depends: Depends::States,
    },
    PlantOutput {
        group: FORCE,
        name: "force",
        unit: "N",
        display: None,
        description: "Total actuator force from the inputs (actuatorForce plus the mapped commands), without end-stop forces",
        get: |o| o.actuator_forces,
        depends: Depends::ThetaAndCommands,
    },
    PlantOutput {
        group: STOP_FORCE,
        name: "stopForce",
        unit: "N",
        display: None,
        description: "End-stop force on the actuator along u_i",
        get: |o| o.end_stop_forces,
        depends: Depends::States,
    },
    PlantOutput {
        group: OMEGA,
        name: "omega",
        unit: "rad/s",
        display: Some("deg/s"),
        description: "Angular velocity of the platform in {A} (continuous state)",
        get: |o| o.omega,
        depends: Depends::States,
    },
];

type ScalarOutput = fn(&PlantOutputs) -> f64;

const SCALAR_OUTPUTS: [(u32, &str, Option<&str>, &str, ScalarOutput); 4] = [
    (
        DET_J,
        "detJ",
        Some("m3"),
        "Determinant of the actuator Jacobian J (lDot = J omega)",
        |o| o.jacobian_det,
    ),
    (COND_J, "condJ", None, "2-norm condition number of J", |o| {
        o.jacobian_cond
    }),
    (
        KINETIC_ENERGY,
        "kineticEnergy",
        Some("J"),
        "Kinetic energy of platform, legs and sliders",
        |o| o.kinetic_energy,
    ),
    (
        POTENTIAL_ENERGY,
        "potentialEnergy",
        Some("J"),
        "Potential energy of gravity (zero at the height of C) plus the energy in the \
         end-stop springs",
        |o| o.potential_energy + o.end_stop_energy,
    ),
];

fn vr(group: u32, i: usize) -> u32 {
    group + i as u32 + 1
}

fn inputs(table: &mut Vec<Variable<Pss3Plant>>) {
    for (group, name, description, field) in INPUTS {
        let unit = if group == ACTUATOR_FORCE { "N" } else { "N.m" };
        let read = move |m: &Pss3Plant, i: usize| {
            let mut inputs = m.inputs;
            field(&mut inputs)[i]
        };
        let array = RealArray::new(vr(group, 0), name, 3, description, read)
            .set(move |m, i, v| {
                field(&mut m.inputs)[i] = v;
                Ok(())
            })
            .each(move |v, _| v.unit(unit, None).input().start_real(0.0));
        table.extend(array.variables());
    }
}

/// The output `base[1..3]` read by `get`, with `unit` and display unit `display`, element
/// i depending on `depends(i)`.
fn vector_output(
    group: u32,
    base: &'static str,
    description: &'static str,
    (unit, display): (&'static str, Option<&'static str>),
    get: impl Fn(&Pss3Plant, usize) -> f64 + Clone + Send + Sync + 'static,
    depends: impl Fn(usize) -> &'static [&'static str] + 'static,
) -> Vec<Variable<Pss3Plant>> {
    RealArray::new(vr(group, 0), base, 3, description, get)
        .each(move |v, i| v.unit(unit, display).output().depends_on(depends(i)))
        .variables()
}

fn state_outputs(table: &mut Vec<Variable<Pss3Plant>>) {
    table.extend(vector_output(
        THETA,
        "theta",
        "Euler angle (thx, thy, thz) of R = Rz Ry Rx (continuous state)",
        ("rad", Some("deg")),
        |m, i| m.current_state().map_or(f64::NAN, |s| s.euler[i]),
        |i| &THETA_NAMES[i..=i],
    ));
    // omega (a state) is read from the state itself, not through the outputs.
    let omega = &PLANT_OUTPUTS[5];
    table.extend(vector_output(
        omega.group,
        omega.name,
        omega.description,
        (omega.unit, omega.display),
        |m, i| m.current_state().map_or(f64::NAN, |s| s.omega[i]),
        |i| &OMEGA_NAMES[i..=i],
    ));
    table.extend(vector_output(
        THETA_DOT,
        "thetaDot",
        "Euler-angle rate",
        ("rad/s", Some("deg/s")),
        |m, i| m.computed(|c| c.euler_rates[i]),
        |_| Depends::States.names(),
    ));
}

fn outputs(table: &mut Vec<Variable<Pss3Plant>>) {
    state_outputs(table);
    plant_vector_output(table, &PLANT_OUTPUTS[0]);
    let names = [
        ("yaw", "Yaw as in the thesis: thx"),
        ("pitch", "Pitch as in the thesis: -thy"),
        ("roll", "Roll as in the thesis: thz"),
    ];
    for (i, (name, description)) in names.into_iter().enumerate() {
        let sign = if i == 1 { -1.0 } else { 1.0 };
        table.push(
            Variable::real(
                vr(YAW_PITCH_ROLL, i),
                name,
                description,
                move |m: &Pss3Plant| m.current_state().map_or(f64::NAN, |s| sign * s.euler[i]),
            )
            .unit("rad", Some("deg"))
            .output()
            .depends_on(&THETA_NAMES[i..=i]),
        );
    }
    for output in &PLANT_OUTPUTS[1..5] {
        plant_vector_output(table, output);
    }
    let at_stop = IntegerArray::new(
        vr(AT_STOP, 0),
        "atStop",
        3,
        "End-stop contact: -1 lower stop, 0 free, +1 upper stop (changes at events)",
        |m: &Pss3Plant, i| m.contact(i),
    )
    .each(|v, _| v.output().depends_on(Depends::Theta.names()));
    table.extend(at_stop.variables());
    for (vr, name, unit, description, get) in SCALAR_OUTPUTS {
        let mut v = Variable::real(vr, name, description, move |m: &Pss3Plant| m.output(get));
        if let Some(unit) = unit {
            v = v.unit(unit, None);
        }
        let depends = if vr == KINETIC_ENERGY {
            Depends::States
        } else {
            Depends::Theta
        };
        table.push(v.output().depends_on(depends.names()));
    }
    table.extend(vector_output(
        GRAVITY_COMPENSATION,
        "gravityCompensation",
        "Euler-angle generalized force G = E^T g(theta) that holds the current pose \
         at rest against gravity (feedforward for generalizedForceCommand)",
        ("N.m", None),
        |m, i| m.computed(|c| c.gravity_compensation[i]),
        |_| Depends::Theta.names(),
    ));
}

fn plant_vector_output(table: &mut Vec<Variable<Pss3Plant>>, output: &PlantOutput) {
    let (get, depends) = (output.get, output.depends);
    table.extend(vector_output(
        output.group,
        output.name,
        output.description,
        (output.unit, output.display),
        move |m, i| m.output(|o| get(o)[i]),
        move |_| depends.names(),
    ));
}

fn derivatives(table: &mut Vec<Variable<Pss3Plant>>) {
    let der_theta = RealArray::derivatives(vr(DER_THETA, 0), "theta", 3, "Euler-angle rate", {
        |m: &Pss3Plant, i| m.computed(|c| c.euler_rates[i])
    })
    .each(|v, _| {
        v.unit("rad/s", Some("deg/s"))
            .depends_on(Depends::States.names())
    });
    let der_omega = RealArray::derivatives(
        vr(DER_OMEGA, 0),
        "omega",
        3,
        "Angular acceleration in {A}",
        |m: &Pss3Plant, i| m.output(|o| o.omega_dot[i]),
    )
    .each(|v, _| {
        v.unit("rad/s2", Some("deg/s2"))
            .depends_on(Depends::StatesAndInputs.names())
    });
    table.extend(
        der_theta
            .variables()
            .into_iter()
            .chain(der_omega.variables()),
    );
}

/// The whole table, sorted by value reference.
pub fn table() -> Vec<Variable<Pss3Plant>> {
    let mut table = Vec::new();
    inputs(&mut table);
    outputs(&mut table);
    derivatives(&mut table);
    table.extend(parameters::variables(&Pss3Plant::new()));
    for v in &mut table {
        let dependencies = initial_dependencies::of(&v.name());
        v.initial_dependencies = dependencies;
    }
    table
}
