//! A family of arrays: the declarations a model keeps once per channel, axis or joint,
//! all of one length, their elements labelled alike ("Channel 2: ..." in FMI 2.0), the
//! parameters followed by one hook. What a model would otherwise restate in each of its
//! per-channel declarations (`.array(n).at(vr).label("Channel")`, the variability, the
//! hook after a write) is said once, in the family:
//!
//! ```
//! use robofmu_fmi::prelude::*;
//! #[derive(Default)]
//! struct Pid { kp: [f64; 3], limited: [bool; 3], setpoint: [f64; 3], integral: [f64; 3] }
//! impl Pid {
//!     fn sync(&mut self, _channel: usize) {}
//! }
//! const CHANNELS: Family<Pid> = Family::new(3, "Channel").after_set(Pid::sync);
//! static VARIABLES: &[Declaration<Pid>] = &[
//!     CHANNELS.tunable("Kp", 1, &[1.0], |m, c| &mut m.kp[c]),
//!     CHANNELS.flag("limitOutput", 11, Variability::Fixed, |m, c| &mut m.limited[c]),
//!     CHANNELS.input("setpoint", 21, &[1.0, 0.5, 0.0], |m, c| &mut m.setpoint[c]),
//!     CHANNELS.state("integral", 31, |m, c| &mut m.integral[c]),
//! ];
//! # fn main() { assert_eq!(VARIABLES[0].size(), 3); }
//! ```
//!
//! The declarations are ordinary [`Declaration`]s: every further builder method applies
//! (`.describe`, `.start_real`, `.real_range`, `.input_derivative`, ...). A family
//! `.sized_by(k)` a structural parameter is resizable (FMI 3.0, `core::structural`):
//! each of its arrays has the size set in Configuration Mode, its length the default.
//! [`Element::role`] looks an element up in a table of (declaration, role), the way a
//! model maps the variables of a directional derivative to the signals of its law.

use super::attributes::Variability;
use super::declare::{AfterSet, Declaration, Get, Place};
use super::hooks::Element;

/// Arrays of `length` elements labelled `label`; the parameters among them run
/// `after_set` after every accepted write (see the module documentation).
pub struct Family<M: 'static> {
    length: usize,
    label: &'static str,
    after_set: Option<AfterSet<M>>,
    /// `Some(k)`: resizable, its length the structural parameter `Model::STRUCTURAL[k]`.
    sized_by: Option<usize>,
}

impl<M> Clone for Family<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Family<M> {}

impl<M> Family<M> {
    /// Arrays of `length` elements, element i described as "`label` i: ..." in FMI 2.0.
    pub const fn new(length: usize, label: &'static str) -> Self {
        assert!(length > 0, "an array has at least one element");
        Family {
            length,
            label,
            after_set: None,
            sized_by: None,
        }
    }

    /// A resizable family: every array of it is sized by the structural parameter
    /// `Model::STRUCTURAL[k]` (FMI 3.0, `<Dimension valueReference=".."/>`), whose
    /// default must be the family's length; FMI 2.0 and the scalar-only FMI 3.0 view
    /// keep that length.
    pub const fn sized_by(mut self, k: usize) -> Self {
        self.sized_by = Some(k);
        self
    }

    /// Hook of the family's parameters: `f(model, i)` after every accepted write of
    /// element i (a law brought up to date).
    pub const fn after_set(mut self, f: AfterSet<M>) -> Self {
        self.after_set = Some(f);
        self
    }

    /// The number of elements of each array of the family.
    pub const fn length(&self) -> usize {
        self.length
    }

    /// `d` as an array of the family, element 1 at value reference `vr` (element i at
    /// `vr + i - 1`).
    pub const fn member(&self, d: Declaration<M>, vr: u32) -> Declaration<M> {
        self.sized(d.array(self.length).at(vr).label(self.label))
    }

    /// `d` (an array of the family's length) sized as the family is.
    const fn sized(&self, d: Declaration<M>) -> Declaration<M> {
        match self.sized_by {
            Some(k) => d.sized_by(k),
            None => d,
        }
    }

    /// `d` as a parameter array of the family with its hook.
    const fn parameter(&self, d: Declaration<M>, vr: u32, v: Variability) -> Declaration<M> {
        let d = self.member(d, vr).parameter(v);
        match self.after_set {
            Some(f) => d.after_set(f),
            None => d,
        }
    }

    /// A tunable Real parameter kept at `place`, with its start value(s).
    pub const fn tunable(
        &self,
        name: &'static str,
        vr: u32,
        start: &'static [f64],
        place: Place<M, f64>,
    ) -> Declaration<M> {
        let d = self.parameter(Declaration::real_in(name, place), vr, Variability::Tunable);
        d.start_real(start)
    }

    /// A Boolean parameter kept at `place`, of variability `v`, start false.
    pub const fn flag(
        &self,
        name: &'static str,
        vr: u32,
        v: Variability,
        place: Place<M, bool>,
    ) -> Declaration<M> {
        let d = self.parameter(Declaration::boolean_in(name, place), vr, v);
        d.start_boolean(&[false])
    }

    /// A continuous Real input kept at `place`, with its start value(s).
    pub const fn input(
        &self,
        name: &'static str,
        vr: u32,
        start: &'static [f64],
        place: Place<M, f64>,
    ) -> Declaration<M> {
        let d = self.member(Declaration::real_in(name, place), vr);
        d.input().start_real(start)
    }

    /// An output the model computes, read by `get` (its description given with
    /// `.describe`).
    pub const fn output(&self, name: &'static str, vr: u32, get: Get<M, f64>) -> Declaration<M> {
        self.member(Declaration::real(name, "", get), vr).output()
    }

    /// The time derivative of the family's state `state`, read by `get`; its elements
    /// are not labelled (a derivative's description is its own).
    pub const fn derivative(
        &self,
        name: &'static str,
        vr: u32,
        state: Declaration<M>,
        get: Get<M, f64>,
    ) -> Declaration<M> {
        let d = Declaration::real(name, "", get).array(self.length).at(vr);
        self.sized(d.derivative_of(state.name))
    }

    /// A continuous state kept at `place`, start 0.
    pub const fn state(&self, name: &'static str, vr: u32, place: Place<M, f64>) -> Declaration<M> {
        let d = self.member(Declaration::real_in(name, place), vr);
        d.state().start_real(&[0.0])
    }
}

impl Element {
    /// The role that `table` gives this element's declaration, if any.
    pub fn role<M, T: Copy>(self, table: &[(Declaration<M>, T)]) -> Option<T> {
        table.iter().find(|(d, _)| d.is(self)).map(|&(_, t)| t)
    }

    /// [`role`](Self::role), or the error "\"x\" is not `what`".
    pub fn role_in<M, T: Copy>(
        self,
        table: &[(Declaration<M>, T)],
        what: &str,
    ) -> Result<T, String> {
        (self.role(table)).ok_or_else(|| format!("\"{}\" is not {what}", self.name))
    }
}

#[cfg(test)]
mod tests {
    use super::super::attributes::Causality;
    use super::*;

    struct M {
        x: [f64; 2],
        b: [bool; 2],
        hooked: usize,
    }

    fn hook(m: &mut M, _: usize) {
        m.hooked += 1;
    }

    const F: Family<M> = Family::new(2, "Joint").after_set(hook);

    #[test]
    fn members_carry_the_length_label_value_references_and_hook() {
        let k = F.tunable("k", 5, &[1.0], |m, i| &mut m.x[i]);
        assert_eq!(
            (k.length, k.label, k.value_reference),
            (Some(2), Some("Joint"), Some(5))
        );
        assert_eq!(k.variability, Variability::Tunable);
        let mut m = M {
            x: [0.0; 2],
            b: [false; 2],
            hooked: 0,
        };
        (k.after_set.expect("a parameter carries the family's hook"))(&mut m, 1);
        assert_eq!(m.hooked, 1);
        let flag = F.flag("b", 7, Variability::Fixed, |m, i| &mut m.b[i]);
        assert_eq!(flag.variability, Variability::Fixed);
        assert!(flag.after_set.is_some());
        // Inputs and states are no parameters: no hook.
        assert!(
            F.input("u", 9, &[0.0], |m, i| &mut m.x[i])
                .after_set
                .is_none()
        );
        assert!(F.state("s", 11, |m, i| &mut m.x[i]).after_set.is_none());
        let y = F.output("y", 13, |m, i| m.x[i]);
        assert_eq!((y.causality, y.label), (Causality::Output, Some("Joint")));
        // A derivative: no label, no hook, the state named.
        let d = F.derivative(
            "der(s)",
            15,
            F.state("s", 11, |m, i| &mut m.x[i]),
            |m, i| m.x[i],
        );
        assert_eq!(
            (d.length, d.label, d.derivative_of),
            (Some(2), None, Some("s"))
        );
    }

    #[test]
    fn role_finds_the_declaration_of_an_element() {
        const A: Declaration<M> = F.input("a", 1, &[0.0], |m, i| &mut m.x[i]);
        const S: Declaration<M> = F.state("s", 3, |m, i| &mut m.x[i]);
        let table = [(A, 'a'), (S, 's')];
        assert_eq!(
            Element {
                name: "s",
                index: 1
            }
            .role(&table),
            Some('s')
        );
        assert_eq!(
            Element {
                name: "t",
                index: 0
            }
            .role(&table),
            None
        );
    }
}
