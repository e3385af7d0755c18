//! `const` helpers for a model's static tables: a declaration slice or a dependency list
//! put together from named parts, so that each part is written once.

use super::declare::Declaration;
use super::hooks::Var;

/// The parts one after the other, in a static table of length N; a length that does not
/// add up is a compile error in the `static` (`fill` only fills the array before it is
/// overwritten).
///
/// ```
/// use robofmu_fmi::prelude::*;
/// const A: [Var; 1] = [Var::Time];
/// static BOTH: [Var; 2] = concat(&[&A, &A], Var::Time);
/// assert_eq!(BOTH.len(), 2);
/// ```
pub const fn concat<T: Copy, const N: usize>(parts: &[&[T]], fill: T) -> [T; N] {
    let mut out = [fill; N];
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

/// Every element of each declaration ([`Declaration::var`]), one entry per declaration.
pub const fn every<M, const N: usize>(declarations: &[Declaration<M>; N]) -> [Var; N] {
    let mut out = [Var::Time; N];
    let mut k = 0;
    while k < N {
        out[k] = declarations[k].var();
        k += 1;
    }
    out
}

/// For each declaration, the element with the dependent element's own index: of an
/// array the element of that index ([`Declaration::same`]), a scalar itself
/// ([`Declaration::var`]); `u[c]` on `same(&[KP, SETPOINT])` depends on `Kp[c]` and
/// `setpoint[c]`.
pub const fn same<M, const N: usize>(declarations: &[Declaration<M>; N]) -> [Var; N] {
    let mut out = [Var::Time; N];
    let mut k = 0;
    while k < N {
        out[k] = match declarations[k].length {
            Some(_) => declarations[k].same(),
            None => declarations[k].var(),
        };
        k += 1;
    }
    out
}
