//! The value references of Pss3Plant: a vector variable's group plus i = 1..3, the
//! scalars on their own.

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
