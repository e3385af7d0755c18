//! The life of FMI 3.0 instances resized by their structural parameter, for memcheck
//! (scripts/memcheck.sh runs it in robofmu-hostile-lifecycle): for an FMU whose
//! description declares one, on every interface a size refused (0, then fmi3Reset),
//! Configuration Mode with the size doubled, initialization, the arrays read at the new
//! size, 20 steps (CS) or Euler steps over the new state count (ME), an FMU state got,
//! set and freed, its serialization refused, terminate, reset to the default size and
//! free: the vectors grown, shrunk and freed with nothing leaked or read uninitialized.

use super::host::{Instance, Interface3};
use super::lifecycle::{co_simulation_step, running};
use crate::binary::ERROR;
use crate::fmu::Fmu;
use crate::host::Probed;

/// One resized life per interface; Ok(()) for an FMU without structural parameters.
pub fn run(fmu: &Fmu) -> Result<(), String> {
    let Some(&(n, start)) = fmu.description.structural.first() else {
        return Ok(());
    };
    let binary = super::binary::Binary3::open(&fmu.library)?;
    let size = 2 * start;
    let arrays: Vec<u32> = (fmu.description.variables.iter())
        .filter(|v| v.var_type == crate::description::VarType::Real && v.size == start)
        .map(|v| v.vr)
        .collect();
    for interface in Interface3::ALL {
        let inst = Instance::new(&binary, &fmu.description, interface);
        let b = inst.binary;
        // SAFETY: a live instance and well-formed arguments in every call below.
        unsafe {
            inst.expect_ok(
                "fmi3EnterConfigurationMode",
                (b.enter_configuration_mode)(inst.c),
            )?;
            if (b.set_uint64)(inst.c, &n, 1, &0, 1) != ERROR {
                return Err("a size of 0 was accepted".into());
            }
            inst.take_log();
            inst.expect_ok("fmi3Reset", (b.reset)(inst.c))?;
            inst.expect_ok(
                "fmi3EnterConfigurationMode",
                (b.enter_configuration_mode)(inst.c),
            )?;
            inst.expect_ok(
                "fmi3SetUInt64",
                (b.set_uint64)(inst.c, &n, 1, &(size as u64), 1),
            )?;
            inst.expect_ok(
                "fmi3ExitConfigurationMode",
                (b.exit_configuration_mode)(inst.c),
            )?;
            inst.reach(running(interface))?;
            let mut x = vec![0.0; size * arrays.len()];
            let all = (b.get_float64)(
                inst.c,
                arrays.as_ptr(),
                arrays.len(),
                x.as_mut_ptr(),
                x.len(),
            );
            inst.expect_ok("fmi3GetFloat64 at the new size", all)?;
            for k in 0..20 {
                let t = k as f64 * 1e-3;
                if interface.is_me() {
                    let mut states = 0;
                    inst.expect_ok(
                        "fmi3GetNumberOfContinuousStates",
                        (b.get_number_of_continuous_states)(inst.c, &mut states),
                    )?;
                    let mut dx = vec![0.0; states];
                    inst.expect_ok(
                        "fmi3GetContinuousStateDerivatives",
                        (b.get_continuous_state_derivatives)(inst.c, dx.as_mut_ptr(), states),
                    )?;
                    inst.expect_ok("fmi3SetTime", (b.set_time)(inst.c, t + 1e-3))?;
                } else {
                    co_simulation_step(&inst, t, 1e-3)?;
                }
            }
            let (s, state) = inst.get_state();
            inst.expect_ok("fmi3GetFMUState", s)?;
            inst.expect_ok("fmi3SetFMUState", (b.set_fmu_state)(inst.c, state))?;
            let mut bytes = 0;
            if (b.serialized_size)(inst.c, state, &mut bytes) != ERROR {
                return Err("a resized FMU state was serialized".into());
            }
            inst.take_log();
            inst.expect_ok("fmi3Reset", (b.reset)(inst.c))?;
            inst.release_state(state);
            inst.reach(running(interface))?;
        }
    }
    drop(binary);
    Ok(())
}
