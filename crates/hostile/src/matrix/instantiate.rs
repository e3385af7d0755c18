//! Instantiation with arguments the standard forbids (FMI 2.0 2.1.5, FMI 3.0
//! 2.3.1): missing callbacks, null or empty names, a null or foreign GUID
//! (instantiation token), an unknown fmuType or an interface the FMU does not
//! provide. The FMU returns NULL; when a logger was given, it says why. The
//! observed status is OK for an instance and Error for NULL. The functions and
//! their arguments differ between the standards: the rows are
//! `seam::Tables::instantiations`.

use super::Case;
use super::seam::Standard;
use crate::Loaded;

pub fn cases<I: Standard>(l: &Loaded, m: usize) -> Vec<Case> {
    (I::tables().instantiations)(l, m)
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
