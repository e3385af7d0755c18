//! The checked-in modelDescription/fmi3/PID.xml must equal what the FMI 3.0 front-end
//! generates from the variable table. Regenerate with
//! `UPDATE_MODEL_DESCRIPTION=1 cargo test --release -p robofmu-pid-fmu --test model_description_fmi3`.

use robofmu_fmi_build::fmi3::check_checked_in;
use robofmu_pid_fmu::Pid;

#[test]
fn checked_in_fmi3_model_description_matches_the_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../modelDescription/fmi3");
    check_checked_in::<Pid>(&dir).unwrap();
}
